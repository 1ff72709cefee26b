import { ActionIcon, Box, Button, Group, Loader, Modal, NavLink, Text, TextInput, Tooltip } from "@mantine/core";
import { IconChartDots, IconPlus, IconTimeline, IconTrash } from "@tabler/icons-react";
import { type MouseEvent, useEffect, useState } from "react";
import { notifyError } from "../../lib/notify";
import { createCam, loadCamList, useCamDirty, useCamList, type CamInfo } from "../../store/cams";
import { useStore } from "../../store/createStore";
import { onEpoch, onReconnect } from "../../store/live";
import { camTabKey, openCamTab, tabsStore } from "../../store/tabs";
import { DeleteCamModal } from "./DeleteCamModal";

const IDENT = /^[A-Za-z_][A-Za-z0-9_]{0,62}$/;

function CamEntry({ cam, active, onDelete }: { cam: CamInfo; active: boolean; onDelete: () => void }) {
  const dirty = useCamDirty(cam.name);
  return (
    <Box style={{ display: "flex", alignItems: "center" }}>
      <NavLink
        style={{ flex: 1, minWidth: 0 }}
        data-testid={`nav-cam-${cam.name}`}
        active={active}
        onClick={() => openCamTab(cam.name)}
        label={
          <Text size="xs" fw={600} truncate="end" title={cam.description || cam.name}>
            {cam.name}
            {dirty && <span className="tab-dirty" title="Unsaved changes" />}
          </Text>
        }
        description={
          <Text size="10px" c="dimmed" truncate="end">
            {cam.point_count} points · {cam.generated ? `${cam.nodes} nodes` : "imported"}
          </Text>
        }
        leftSection={<IconChartDots size={14} />}
        py={3}
        pl={8}
        pr={4}
      />
      <Tooltip label={`Delete ${cam.name}`} position="right" openDelay={300}>
        <ActionIcon size="sm" variant="subtle" color="gray" aria-label={`Delete cam table ${cam.name}`}
          data-testid={`nav-cam-delete-${cam.name}`} onClick={onDelete} mr={2}>
          <IconTrash size={13} />
        </ActionIcon>
      </Tooltip>
    </Box>
  );
}

function NewCamModal({ opened, onClose, existing }: { opened: boolean; onClose: () => void; existing: string[] }) {
  const [name, setName] = useState("");
  const [busy, setBusy] = useState(false);
  const taken = existing.some((n) => n.toLowerCase() === name.toLowerCase());
  const error = name && !IDENT.test(name) ? "An identifier: a letter or _, then letters, digits or _"
    : taken ? "A cam table of this name exists" : undefined;
  const create = async () => {
    if (!name || error) return;
    setBusy(true);
    try {
      await createCam(name);
      openCamTab(name);
      setName("");
      onClose();
    } catch (err) {
      notifyError(`Create ${name}`, err);
    } finally {
      setBusy(false);
    }
  };
  return (
    <Modal opened={opened} onClose={onClose} title="New cam table" size="sm" centered>
      <TextInput label="Name (cam data variable)" value={name} onChange={(e) => setName(e.currentTarget.value)}
        error={error} data-autofocus data-testid="cam-new-name" placeholder="MyCam1"
        onKeyDown={(e) => e.key === "Enter" && void create()} />
      <Text size="xs" c="dimmed" mt={6}>
        Starts as a modified-sine rise and return over 360 master units; edit its nodes in the cam editor.
      </Text>
      <Group justify="flex-end" mt="md" gap={8}>
        <Button variant="default" onClick={onClose}>Cancel</Button>
        <Button onClick={create} disabled={!name || !!error} loading={busy} data-testid="cam-new-create">Create</Button>
      </Group>
    </Modal>
  );
}

/** The "Cam tables" branch of the project tree: each table opens its cam editor; add and delete tables. */
export function CamTreeNode() {
  const { status, data } = useCamList();
  const active = useStore(tabsStore, (s) => s.active);
  const [adding, setAdding] = useState(false);
  const [deleting, setDeleting] = useState<string | null>(null);

  useEffect(() => {
    void loadCamList();
    const offEpoch = onEpoch(() => void loadCamList());
    const offReconnect = onReconnect(() => void loadCamList());
    return () => {
      offEpoch();
      offReconnect();
    };
  }, []);

  return (
    <>
      <NavLink
        label={<Text size="xs" fw={600}>Cam tables{status === "ready" ? ` (${data.length})` : ""}</Text>}
        leftSection={<IconTimeline size={15} />}
        defaultOpened
        childrenOffset={8}
        py={3}
        data-testid="nav-cams"
        rightSection={
          <ActionIcon size="sm" variant="subtle" color="gray" component="span" role="button"
            aria-label="New cam table" data-testid="nav-cam-add"
            onClick={(e: MouseEvent) => {
              e.stopPropagation();
              setAdding(true);
            }}>
            <IconPlus size={14} />
          </ActionIcon>
        }
        disableRightSectionRotation
      >
        {status === "loading" && (
          <Box px="sm" py={4}>
            <Loader size="xs" />
          </Box>
        )}
        {status === "ready" && data.length === 0 && (
          <Text size="xs" c="dimmed" px="sm" py={4}>No cam tables yet: add one with +.</Text>
        )}
        {data.map((c) => (
          <CamEntry key={c.name} cam={c} active={active === camTabKey(c.name)} onDelete={() => setDeleting(c.name)} />
        ))}
      </NavLink>
      <NewCamModal opened={adding} onClose={() => setAdding(false)} existing={data.map((c) => c.name)} />
      <DeleteCamModal name={deleting} onClose={() => setDeleting(null)} />
    </>
  );
}
