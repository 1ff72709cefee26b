import { Anchor, Badge, Button, Group, Menu, Text, Tooltip } from "@mantine/core";
import {
  IconArrowBackUp,
  IconChevronDown,
  IconDeviceFloppy,
  IconFileCode,
  IconFilePlus,
  IconFolderOpen,
  IconCopy,
} from "@tabler/icons-react";
import { useCallback, useEffect, useRef, useState } from "react";
import { useLive } from "../../hooks/useLive";
import { notifyError, notifyOk } from "../../lib/notify";
import { NewProjectDialog } from "./NewProjectDialog";
import { OpenProjectDialog } from "./OpenProjectDialog";
import { RevertDialog } from "./RevertDialog";
import { SaveAsDialog } from "./SaveAsDialog";
import { saveProject, schemaUrl } from "./projectApi";

type Dialog = "new" | "open" | "save-as" | "revert" | null;

/** The project's name and its unsaved-changes badge; the browser tab's title carries a dot while there are some. */
function ProjectName({ name, dirty }: { name: string | null; dirty: boolean }) {
  useEffect(() => {
    document.title = name ? `${dirty ? "● " : ""}${name} — MC Studio` : "MC Studio";
  }, [name, dirty]);
  return (
    <Group gap={6} wrap="nowrap" maw={260} data-testid="project-name" data-dirty={dirty ? "true" : "false"}>
      <Text size="sm" fw={600} truncate="end" title={name ?? undefined}>
        {name ?? "—"}
      </Text>
      {dirty && (
        <Tooltip label="The project in the controller differs from the saved file: Save (Ctrl+S) to keep it">
          <Badge color="orange" variant="light" size="sm" style={{ textTransform: "none", flex: "none" }}
            leftSection={<span className="dot dot-modified" />} data-testid="project-dirty">
            Unsaved
          </Badge>
        </Tooltip>
      )}
    </Group>
  );
}

/** Warn before the page is closed or reloaded while the project has unsaved changes. */
function useBeforeUnload(dirty: boolean): void {
  useEffect(() => {
    if (!dirty) return;
    const onBeforeUnload = (e: BeforeUnloadEvent) => {
      e.preventDefault();
      e.returnValue = ""; // older browsers need it set to show their dialog
    };
    window.addEventListener("beforeunload", onBeforeUnload);
    return () => window.removeEventListener("beforeunload", onBeforeUnload);
  }, [dirty]);
}

/**
 * Project toolbar: name with the unsaved-changes badge, Save (Ctrl+S) and the Project menu — New from a template,
 * Open, Save as, Revert, and the JSON Schema of project.json for editors.
 */
export function ProjectBar() {
  const name = useLive((s) => s.controller?.project ?? null);
  const dirty = useLive((s) => s.controller?.project_dirty ?? false);
  const [dialog, setDialog] = useState<Dialog>(null);
  const [saving, setSaving] = useState(false);
  const savingRef = useRef(false);
  useBeforeUnload(dirty);

  const save = useCallback(async () => {
    if (savingRef.current) return;
    savingRef.current = true;
    setSaving(true);
    try {
      notifyOk("Project saved", await saveProject());
    } catch (err) {
      notifyError("Save project", err);
    } finally {
      savingRef.current = false;
      setSaving(false);
    }
  }, []);

  useEffect(() => {
    const onKey = (e: KeyboardEvent) => {
      if ((e.ctrlKey || e.metaKey) && !e.altKey && !e.shiftKey && e.key.toLowerCase() === "s") {
        e.preventDefault(); // not the browser's "save page"
        void save();
      }
    };
    window.addEventListener("keydown", onKey);
    return () => window.removeEventListener("keydown", onKey);
  }, [save]);

  const close = () => setDialog(null);
  return (
    <>
      <ProjectName name={name} dirty={dirty} />
      <Group gap={4} wrap="nowrap">
        <Tooltip label="Save the project to its folder (Ctrl+S)">
          <Button variant={dirty ? "filled" : "default"} leftSection={<IconDeviceFloppy size={14} />} loading={saving}
            onClick={() => void save()} data-testid="save-project">
            Save
          </Button>
        </Tooltip>
        <Menu position="bottom-start" withinPortal shadow="md" width={250}>
          <Menu.Target>
            <Button variant="default" rightSection={<IconChevronDown size={14} />} data-testid="project-menu">
              Project
            </Button>
          </Menu.Target>
          <Menu.Dropdown>
            <Menu.Item leftSection={<IconFilePlus size={16} />} onClick={() => setDialog("new")}
              data-testid="project-menu-new">
              New from template…
            </Menu.Item>
            <Menu.Item leftSection={<IconFolderOpen size={16} />} onClick={() => setDialog("open")}
              data-testid="project-menu-open">
              Open…
            </Menu.Item>
            <Menu.Divider />
            <Menu.Item leftSection={<IconDeviceFloppy size={16} />} onClick={() => void save()}
              rightSection={<Text size="xs" c="dimmed">Ctrl+S</Text>} data-testid="project-menu-save">
              Save
            </Menu.Item>
            <Menu.Item leftSection={<IconCopy size={16} />} onClick={() => setDialog("save-as")}
              data-testid="project-menu-save-as">
              Save as…
            </Menu.Item>
            <Menu.Item leftSection={<IconArrowBackUp size={16} />} onClick={() => setDialog("revert")}
              data-testid="project-menu-revert"
              title="Reload project.json from its folder (also after editing it in another editor)">
              Revert to saved…
            </Menu.Item>
            <Menu.Divider />
            <Menu.Item leftSection={<IconFileCode size={16} />} component="a" href={schemaUrl()} target="_blank"
              rel="noreferrer" data-testid="project-menu-schema">
              JSON Schema of project.json
            </Menu.Item>
            <Menu.Label>
              For editors: add{" "}
              <Anchor size="xs" component="span" ff="monospace">
                "$schema"
              </Anchor>{" "}
              (docs/project-format.md)
            </Menu.Label>
          </Menu.Dropdown>
        </Menu>
      </Group>
      <NewProjectDialog opened={dialog === "new"} onClose={close} dirty={dirty} />
      <OpenProjectDialog opened={dialog === "open"} onClose={close} dirty={dirty} />
      <SaveAsDialog opened={dialog === "save-as"} onClose={close} current={name ?? ""} />
      <RevertDialog opened={dialog === "revert"} onClose={close} dirty={dirty} />
    </>
  );
}
