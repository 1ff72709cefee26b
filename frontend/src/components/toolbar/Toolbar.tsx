import { ActionIcon, Box, Button, Divider, Group, Menu, Modal, SegmentedControl, Text, Tooltip } from "@mantine/core";
import {
  IconDeviceFloppy,
  IconFolderOpen,
  IconPlayerSkipForward,
  IconRefresh,
  IconSettingsAutomation,
} from "@tabler/icons-react";
import { useState } from "react";
import { api, unwrap } from "../../api/client";
import type { ControllerMode, ProjectInfo } from "../../api/types";
import { useLive } from "../../hooks/useLive";
import { notifyError, notifyOk } from "../../lib/notify";
import { HelpPopover } from "./HelpPopover";
import { Readouts } from "./Readouts";
import { WsIndicator } from "./WsIndicator";

const MODES: { value: ControllerMode; label: string }[] = [
  { value: "realtime", label: "Realtime" },
  { value: "fast", label: "Fast" },
  { value: "paused", label: "Paused" },
];

function ProjectName() {
  const name = useLive((s) => s.controller?.project ?? null);
  const dirty = useLive((s) => s.controller?.project_dirty ?? false);
  return (
    <Group gap={6} wrap="nowrap" maw={220} data-testid="project-name">
      <Text size="sm" fw={600} truncate="end" title={name ?? undefined}>
        {name ?? "—"}
      </Text>
      {dirty && (
        <Tooltip label="Unsaved changes">
          <Box
            data-testid="project-dirty"
            w={8}
            h={8}
            style={{ borderRadius: "50%", background: "var(--mantine-color-orange-6)", flex: "none" }}
          />
        </Tooltip>
      )}
    </Group>
  );
}

function SaveButton() {
  const [busy, setBusy] = useState(false);
  const dirty = useLive((s) => s.controller?.project_dirty ?? false);
  const save = async () => {
    setBusy(true);
    try {
      const out = await unwrap(api.POST("/api/v1/project/save"));
      notifyOk("Project saved", out.path);
    } catch (err) {
      notifyError("Save project", err);
    } finally {
      setBusy(false);
    }
  };
  return (
    <Button
      variant={dirty ? "filled" : "default"}
      leftSection={<IconDeviceFloppy size={14} />}
      loading={busy}
      onClick={save}
      data-testid="save-project"
    >
      Save
    </Button>
  );
}

function OpenProjectMenu() {
  const [projects, setProjects] = useState<ProjectInfo[] | null>(null);
  const load = async () => {
    try {
      setProjects(await unwrap(api.GET("/api/v1/projects")));
    } catch (err) {
      notifyError("List projects", err);
    }
  };
  const open = async (name: string) => {
    try {
      const p = await unwrap(api.POST("/api/v1/projects/open", { body: { name } }));
      notifyOk("Project opened", p.name);
    } catch (err) {
      notifyError("Open project", err);
    }
  };
  return (
    <Menu position="bottom-start" onOpen={() => void load()} withinPortal shadow="md">
      <Menu.Target>
        <Tooltip label="Open project">
          <ActionIcon aria-label="Open project" data-testid="open-project">
            <IconFolderOpen size={18} />
          </ActionIcon>
        </Tooltip>
      </Menu.Target>
      <Menu.Dropdown miw={240}>
        <Menu.Label>Projects folder</Menu.Label>
        {projects === null && <Menu.Item disabled>Loading…</Menu.Item>}
        {projects?.length === 0 && <Menu.Item disabled>No projects found</Menu.Item>}
        {projects?.map((p) => (
          <Menu.Item
            key={p.name}
            disabled={!p.valid || p.current}
            onClick={() => void open(p.name)}
            rightSection={p.current ? <Text size="xs" c="dimmed">open</Text> : undefined}
          >
            <Text size="sm">{p.title}</Text>
            <Text size="xs" c={p.valid ? "dimmed" : "red"}>
              {p.valid ? p.name : (p.error ?? "invalid")}
            </Text>
          </Menu.Item>
        ))}
      </Menu.Dropdown>
    </Menu>
  );
}

function ModeSwitch() {
  const mode = useLive((s) => s.controller?.mode ?? null);
  const setMode = async (m: string) => {
    try {
      await unwrap(api.PUT("/api/v1/controller/mode", { body: { mode: m as ControllerMode } }));
    } catch (err) {
      notifyError("Controller mode", err);
    }
  };
  return (
    <SegmentedControl
      data={MODES}
      value={mode ?? ""}
      onChange={(m) => void setMode(m)}
      disabled={mode === null}
      data-testid="mode-switch"
      color={mode === "paused" ? "orange" : mode === "fast" ? "violet" : "blue"}
    />
  );
}

function StepButtons() {
  const mode = useLive((s) => s.controller?.mode ?? null);
  const period = useLive((s) => s.controller?.period_s ?? 0.001);
  const [busy, setBusy] = useState(false);
  if (mode !== "paused") return null;
  const perSecond = Math.max(1, Math.round(1 / period));
  const step = async (cycles: number) => {
    setBusy(true);
    try {
      await unwrap(api.POST("/api/v1/controller/step", { body: { cycles } }));
    } catch (err) {
      notifyError("Step", err);
    } finally {
      setBusy(false);
    }
  };
  return (
    <Group gap={4} wrap="nowrap">
      <Button.Group>
        <Button variant="default" onClick={() => void step(1)} disabled={busy} data-testid="step-1"
          leftSection={<IconPlayerSkipForward size={13} />}>
          1
        </Button>
        <Button variant="default" onClick={() => void step(100)} disabled={busy} data-testid="step-100">
          100
        </Button>
        <Button variant="default" onClick={() => void step(perSecond)} disabled={busy} data-testid="step-1s"
          title={`${perSecond} cycles`}>
          1 s
        </Button>
      </Button.Group>
    </Group>
  );
}

function ResetController() {
  const [open, setOpen] = useState(false);
  const [busy, setBusy] = useState(false);
  const reset = async () => {
    setBusy(true);
    try {
      await unwrap(api.POST("/api/v1/controller/reset"));
      notifyOk("Controller reset", "The project was reloaded into a fresh controller (cycle 0).");
      setOpen(false);
    } catch (err) {
      notifyError("Reset controller", err);
    } finally {
      setBusy(false);
    }
  };
  return (
    <>
      <Tooltip label="Reset controller (reload the project, cycle 0)">
        <Button variant="default" color="red" leftSection={<IconRefresh size={14} />} onClick={() => setOpen(true)}
          data-testid="controller-reset">
          Reset
        </Button>
      </Tooltip>
      <Modal opened={open} onClose={() => setOpen(false)} title="Reset the controller?" size="sm" centered>
        <Text size="sm">
          The project is reloaded into a fresh controller at cycle 0, like a download. All function-block instances
          are removed and every axis is disabled (servo OFF).
        </Text>
        <Group justify="flex-end" mt="md" gap="xs">
          <Button variant="default" onClick={() => setOpen(false)}>
            Cancel
          </Button>
          <Button color="red" loading={busy} onClick={() => void reset()} data-testid="controller-reset-confirm">
            Reset controller
          </Button>
        </Group>
      </Modal>
    </>
  );
}

/** The header: product, project, controller mode and stepping, live read-outs, connection. */
export function Toolbar() {
  return (
    <Group h="100%" px="sm" gap="sm" wrap="nowrap" justify="space-between">
      <Group gap="sm" wrap="nowrap" style={{ minWidth: 0 }}>
        <Group gap={6} wrap="nowrap">
          <IconSettingsAutomation size={22} color="var(--mantine-color-blue-6)" />
          <Text fw={700} size="md" style={{ whiteSpace: "nowrap" }}>
            MC Studio
          </Text>
        </Group>
        <Divider orientation="vertical" />
        <ProjectName />
        <Group gap={4} wrap="nowrap">
          <SaveButton />
          <OpenProjectMenu />
        </Group>
        <Divider orientation="vertical" />
        <ModeSwitch />
        <StepButtons />
        <ResetController />
      </Group>
      <Group gap="sm" wrap="nowrap">
        <Readouts />
        <Divider orientation="vertical" />
        <WsIndicator />
        <HelpPopover />
      </Group>
    </Group>
  );
}
