import { Button, Divider, Group, Modal, SegmentedControl, Text, Tooltip } from "@mantine/core";
import { IconPlayerSkipForward, IconRefresh, IconSettingsAutomation } from "@tabler/icons-react";
import { useState } from "react";
import { api, unwrap } from "../../api/client";
import type { ControllerMode } from "../../api/types";
import { useLive } from "../../hooks/useLive";
import { notifyError, notifyOk } from "../../lib/notify";
import { ControlGuard } from "../control/ControlGuard";
import { ControlStatus } from "../control/ControlStatus";
import { ProjectBar } from "../project/ProjectBar";
import { HelpPopover } from "./HelpPopover";
import { Readouts } from "./Readouts";
import { WsIndicator } from "./WsIndicator";

const MODES: { value: ControllerMode; label: string }[] = [
  { value: "realtime", label: "Realtime" },
  { value: "fast", label: "Fast" },
  { value: "paused", label: "Paused" },
];

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
          data-testid="controller-reset" aria-label="Reset controller" px={10}>
          <Text span inherit visibleFrom="xl">
            Reset
          </Text>
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
          {/* below 1408 px (Mantine xl) the header needs the room for the project and control buttons */}
          <Text fw={700} size="md" style={{ whiteSpace: "nowrap" }} visibleFrom="xl">
            MC Studio
          </Text>
        </Group>
        <Divider orientation="vertical" />
        <ProjectBar />
        <Divider orientation="vertical" />
        <ControlGuard hint={false}>
          <ModeSwitch />
          <StepButtons />
          <ResetController />
        </ControlGuard>
        <Divider orientation="vertical" />
        <ControlStatus />
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
