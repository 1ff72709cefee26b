import { Alert, Badge, Box, Button, Center, Group, List, Loader, ScrollArea, Stack, Text, Tooltip } from "@mantine/core";
import { IconAlertTriangle, IconArrowBackUp, IconCheck, IconInfoCircle, IconRestore, IconTableOptions } from "@tabler/icons-react";
import { useEffect, useMemo, useState } from "react";
import type { DeviceDescription, SlaveOut } from "../../api/types";
import { hexH } from "../../lib/hex";
import { assignOf, dirOfPdo, draftProblems, objectTable, pdoStarts } from "../../lib/pdo";
import { useStore } from "../../store/createStore";
import { useDevice, useEthercat, useEthercatPoll, useSlave } from "../../store/ethercat";
import {
  type PdoEditor as Editor,
  applyPdo,
  changeCount,
  issuePlace,
  pdoEditorStore,
  resetToDefault,
  revertPdo,
  syncPdoEditor,
} from "../../store/pdoEditor";
import { EsmBadge } from "./EsmBadge";
import { PdoAssignment } from "./PdoAssignment";
import { PdoEntries } from "./PdoEntries";
import { type ImageHighlight, ProcessImage } from "./ProcessImage";

function Header({ slave, device, ed, problems }: {
  slave: SlaveOut;
  device: DeviceDescription | null;
  ed: Editor;
  problems: string[];
}) {
  const node = slave.node_address;
  const changes = changeCount(ed);
  const hasIssues = ed.issues.length > 0 || ed.refusal !== null;
  return (
    <Group justify="space-between" wrap="wrap" gap="6px 12px" px="sm" py={6} className="settings-header">
      <Group gap={10} wrap="nowrap" style={{ minWidth: 0, flex: "1 1 260px" }}>
        <IconTableOptions size={20} color="var(--mantine-color-gray-6)" style={{ flex: "none" }} />
        <Stack gap={0} style={{ minWidth: 0 }}>
          <Group gap={8} wrap="nowrap">
            <Text fw={700} size="md" truncate="end">
              {slave.name} <Text span fw={400} c="dimmed" size="sm">· PDO map</Text>
            </Text>
            <EsmBadge state={slave.state} size="xs" testId="pdo-slave-state" />
          </Group>
          <Text size="xs" c="dimmed" truncate="end">
            {slave.device_name} · node {node} · product {hexH(slave.product_code, 8)}
            {slave.axis ? ` · axis ${slave.axis}` : ""}
          </Text>
        </Stack>
      </Group>
      <Group gap={8} wrap="nowrap" ml="auto">
        {ed.dirty ? (
          <Badge color="orange" variant="light" style={{ textTransform: "none" }} data-testid="pdo-dirty">
            {changes} unsaved change{changes === 1 ? "" : "s"}
          </Badge>
        ) : (
          <Badge color="gray" variant="light" style={{ textTransform: "none" }} data-testid="pdo-clean">
            No changes
          </Badge>
        )}
        <Tooltip label={device ? "The device description's default assignment and mapping (then Apply)" : "Loading the device description…"}>
          <Button variant="default" leftSection={<IconRestore size={14} />} disabled={!device || ed.applying}
            onClick={() => device && resetToDefault(node, device)} data-testid="pdo-reset-default">
            Reset to device default
          </Button>
        </Tooltip>
        <Button variant="default" leftSection={<IconArrowBackUp size={14} />} disabled={(!ed.dirty && !hasIssues) || ed.applying}
          onClick={() => revertPdo(node)} data-testid="pdo-revert">
          Revert
        </Button>
        <Tooltip
          label={problems.length ? `Cannot apply: ${problems.join("; ")}` : ed.dirty ? "Restart the controller with this PDO map" : "Nothing changed"}
          multiline maw={360}
        >
          <Button leftSection={<IconCheck size={14} />} disabled={!ed.dirty || problems.length > 0} loading={ed.applying}
            onClick={() => void applyPdo(node, slave.name)} data-testid="pdo-apply">
            Apply
          </Button>
        </Tooltip>
      </Group>
    </Group>
  );
}

function Problems({ ed, problems }: { ed: Editor; problems: string[] }) {
  if (ed.refusal) {
    return (
      <Alert color="orange" variant="light" py={6} icon={<IconAlertTriangle size={16} />} data-testid="pdo-refusal"
        title={ed.refusal.status === 409 ? "Not applied: an axis is moving (409)" : `Not applied${ed.refusal.status ? ` (${ed.refusal.status})` : ""}`}>
        <Text size="xs">{ed.refusal.message}</Text>
      </Alert>
    );
  }
  if (ed.issues.length) {
    return (
      <Alert color="red" variant="light" py={6} icon={<IconAlertTriangle size={16} />} data-testid="pdo-issues"
        title={`The controller refused this PDO map (${ed.issues.length} problem${ed.issues.length === 1 ? "" : "s"})`}>
        <ScrollArea.Autosize mah={80} type="auto">
          <Stack gap={2}>
            {ed.issues.map((i, k) => (
              <Text size="xs" key={k} data-testid="pdo-issue">
                {issuePlace(i.target) && <Text span ff="monospace" size="xs" fw={600}>{issuePlace(i.target)}: </Text>}
                {i.msg}
              </Text>
            ))}
          </Stack>
        </ScrollArea.Autosize>
      </Alert>
    );
  }
  if (problems.length) {
    return (
      <Alert color="yellow" variant="light" py={6} icon={<IconAlertTriangle size={16} />} data-testid="pdo-client-problems"
        title="Correct this before applying">
        <List size="xs" spacing={0}>
          {problems.map((p, k) => <List.Item key={k}>{p}</List.Item>)}
        </List>
      </Alert>
    );
  }
  return null;
}

function EditorBody({ slave, ed }: { slave: SlaveOut; ed: Editor }) {
  const node = slave.node_address;
  const device = useDevice(slave.device_id);
  const objects = useMemo(() => objectTable(slave, device), [slave, device]);
  const problems = useMemo(() => draftProblems(ed.draft, slave, device), [ed.draft, slave, device]);
  const [selectedRow, setSelectedRow] = useState<number | null>(null);
  useEffect(() => setSelectedRow(null), [ed.selected]);

  // The selected entry in the live image: only while the draft is what the controller runs.
  let highlight: ImageHighlight | null = null;
  const dir = dirOfPdo(ed.selected);
  const rows = ed.draft.entries[ed.selected] ?? [];
  if (!ed.dirty && selectedRow !== null && selectedRow < rows.length && assignOf(ed.draft, dir).includes(ed.selected)) {
    const bit = (pdoStarts(ed.draft, dir).get(ed.selected) ?? 0) + rows.slice(0, selectedRow).reduce((n, e) => n + e.bit_len, 0);
    highlight = { dir, bit, bits: rows[selectedRow].bit_len };
  }

  return (
    <Box style={{ height: "100%", display: "flex", flexDirection: "column", minHeight: 0 }} data-testid={`pdo-editor-${node}`}>
      <Header slave={slave} device={device} ed={ed} problems={problems} />
      <Stack gap={6} px={8} pt={6} style={{ flex: "none" }}>
        <Group gap={6} wrap="nowrap" className="settings-notice">
          <IconInfoCircle size={14} color="var(--mantine-color-blue-6)" style={{ flex: "none" }} />
          <Text size="xs" c="gray.7">
            Applying restarts the controller with the new process data (cycle 0), only while all axes are stopped.
            Save the project to keep it.
          </Text>
        </Group>
        <Problems ed={ed} problems={problems} />
      </Stack>
      <div className="ecat-scroll">
        <div className="pdo-grid">
          <Stack gap={8}>
            <PdoAssignment node={node} dir="rx" slave={slave} device={device} ed={ed} />
            <PdoAssignment node={node} dir="tx" slave={slave} device={device} ed={ed} />
            <ProcessImage node={node} highlight={highlight}
              note={ed.dirty ? "The map the controller runs (the edits are not applied yet)." : "Click an entry to highlight its bytes; bytes that just changed are blue."} />
          </Stack>
          <PdoEntries node={node} slave={slave} device={device} ed={ed} objects={objects} selectedRow={selectedRow}
            onSelectRow={setSelectedRow} />
        </div>
      </div>
    </Box>
  );
}

/** The PDO map editor of one slave: assignment, mapping, Apply / Reset to default, and the live process image. */
export function PdoEditor({ node }: { node: number }) {
  useEthercatPoll(500);
  const { status, error } = useEthercat();
  const slave = useSlave(node);
  const ed = useStore(pdoEditorStore, (s) => s[node]);

  useEffect(() => {
    if (slave) syncPdoEditor(node, slave);
  }, [node, slave]);

  if (!slave || !ed) {
    return (
      <Center h={160}>
        {status === "loading" || (slave && !ed) ? (
          <Loader size="sm" />
        ) : (
          <Text size="sm" c={status === "error" ? "red" : "dimmed"}>
            {status === "error" ? `Cannot load the EtherCAT network: ${error}` : `No slave with node address ${node} in the network.`}
          </Text>
        )}
      </Center>
    );
  }
  return <EditorBody slave={slave} ed={ed} />;
}
