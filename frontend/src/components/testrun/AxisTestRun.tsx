import { ActionIcon, Badge, Box, Button, Center, Group, Loader, NativeSelect, Stack, Text, Tooltip } from "@mantine/core";
import { IconAlertOctagon, IconHandStop, IconPower, IconRotateClockwise2, IconSettings } from "@tabler/icons-react";
import { type KeyboardEvent, type FocusEvent, type ReactNode, useMemo, useState } from "react";
import type { AxisSummary } from "../../api/types";
import { useAxisList, useAxisSummary, useLive } from "../../hooks/useLive";
import { type AxisUnits, axisState, axisTypeLabel, axisUnits, stateColor } from "../../lib/format";
import { type JogDir, issue, jogRelease, resetAxis, setServo, stopAxis } from "../../store/commands";
import { axisForms, num, setFormField, useAxisForms } from "../../store/forms";
import { openSettingsTab } from "../../store/tabs";
import { AxisChart } from "./AxisChart";
import { HomingPanel } from "./HomingPanel";
import { JogPanel, startJog } from "./JogPanel";
import { LastInstructionPanel } from "./LastInstructionPanel";
import { AxisErrorPanel, PositionPanel, StatusPanel } from "./LivePanels";
import { MoveForms } from "./MoveForms";
import { OverridePanel } from "./OverridePanel";
import { ControlGuard } from "../control/ControlGuard";

const STOP_MODES = [
  { value: "1", label: "StopMode 1" },
  { value: "2", label: "StopMode 2" },
  { value: "3", label: "StopMode 3" },
];

function Labeled({ label, children }: { label: string; children: ReactNode }) {
  return (
    <Stack gap={0} style={{ flex: "none" }}>
      <Text size="10px" c="dimmed" tt="uppercase">
        {label}
      </Text>
      {children}
    </Stack>
  );
}

function HomedBadge({ axis }: { axis: string }) {
  const homed = useLive((s) => s.axes[axis]?.Details.Homed ?? null);
  return (
    <Labeled label="Home">
      <Tooltip label="Details.Homed: home is defined">
        <Badge size="lg" variant={homed ? "filled" : "outline"} color={homed ? "teal" : "orange"} miw={92}
          style={{ textTransform: "none" }}>
          <span data-testid="homed" data-active={homed ? "true" : "false"}>
            {homed === null ? "—" : homed ? "Homed" : "Not homed"}
          </span>
        </Badge>
      </Tooltip>
    </Labeled>
  );
}

/** MC_ImmediateStop with the chosen StopMode: the axis goes to ErrorStop (5485) until Reset. */
function ImmediateStop({ axis }: { axis: string }) {
  const mode = useAxisForms(axis).immediateStopMode;
  const [busy, setBusy] = useState(false);
  const run = async () => {
    setBusy(true);
    await issue(axis, "MC_ImmediateStop", { StopMode: Number(axisForms(axis).immediateStopMode) });
    setBusy(false);
  };
  return (
    <Group gap={0} wrap="nowrap">
      <Tooltip
        label="StopMode — 1: immediate stop · 2: immediate stop and following error reset · 3: free-run stop (servo OFF)"
        multiline
        w={260}
      >
        <NativeSelect
          aria-label="Immediate stop mode"
          data={STOP_MODES}
          value={mode}
          onChange={(e) => setFormField(axis, "immediateStopMode", e.currentTarget.value)}
          data-testid="immediate-stop-mode"
          w={116}
          styles={{ input: { borderTopRightRadius: 0, borderBottomRightRadius: 0, borderRight: 0 } }}
        />
      </Tooltip>
      <Tooltip label="MC_ImmediateStop: stop at once; the axis goes to ErrorStop (5485), Reset clears it">
        <Button data-testid="immediate-stop-button" color="red.8" leftSection={<IconAlertOctagon size={14} />}
          loading={busy} onClick={() => void run()} style={{ borderTopLeftRadius: 0, borderBottomLeftRadius: 0 }}>
          Immediate stop
        </Button>
      </Tooltip>
    </Group>
  );
}

function HeaderBar({ axis }: { axis: AxisSummary }) {
  const name = axis.name;
  const state = useLive((s) => (s.axes[name] ? axisState(s.axes[name].Status) : null));
  const servoOn = useLive((s) => s.axes[name]?.DrvStatus.ServoOn ?? null);
  const [servoBusy, setServoBusy] = useState(false);
  const [stopBusy, setStopBusy] = useState(false);
  const [resetBusy, setResetBusy] = useState(false);

  const toggleServo = async () => {
    setServoBusy(true);
    await setServo(name, !servoOn);
    setServoBusy(false);
  };
  const stop = async () => {
    const dec = num(axisForms(name).absDeceleration);
    setStopBusy(true);
    await stopAxis(name, dec ?? 0);
    setStopBusy(false);
  };
  const reset = async () => {
    setResetBusy(true);
    await resetAxis(name);
    setResetBusy(false);
  };

  return (
    <Group justify="space-between" wrap="wrap" gap="6px 12px" px="sm" py={6} className="panel testrun-header">
      <Group gap="md" wrap="nowrap" style={{ minWidth: 0, flex: "1 1 auto" }}>
        <Stack gap={0} style={{ minWidth: 0 }}>
          <Group gap={4} wrap="nowrap">
            <Text fw={700} size="md" truncate="end">
              {name}
            </Text>
            <Tooltip label="Axis settings">
              <ActionIcon size="sm" color="gray" aria-label={`Axis settings of ${name}`} onClick={() => openSettingsTab(name)}
                data-testid="open-settings">
                <IconSettings size={15} />
              </ActionIcon>
            </Tooltip>
          </Group>
          <Text size="xs" c="dimmed" truncate="end" title={axis.node_address !== null ? `EtherCAT node ${axis.node_address}` : undefined}>
            Axis {axis.number} · {axisTypeLabel(axis.type)}
            {axis.node_address !== null ? ` · node ${axis.node_address}` : ""}
          </Text>
        </Stack>
        <Stack gap={0} style={{ flex: "none" }}>
          <Text size="10px" c="dimmed" tt="uppercase">
            State
          </Text>
          <Badge size="lg" variant="light" color={stateColor(state ?? "")} style={{ textTransform: "none" }} miw={110}>
            <span data-testid="axis-state">{state ?? "—"}</span>
          </Badge>
        </Stack>
        <Stack gap={0} style={{ flex: "none" }}>
          <Text size="10px" c="dimmed" tt="uppercase">
            Servo
          </Text>
          <Badge size="lg" variant={servoOn ? "filled" : "outline"} color={servoOn ? "teal" : "gray"} miw={56}>
            <span data-testid="servo-status">{servoOn === null ? "—" : servoOn ? "ON" : "OFF"}</span>
          </Badge>
        </Stack>
        <HomedBadge axis={name} />
      </Group>
      <Group gap={6} wrap="nowrap" ml="auto">
        <Button
          data-testid="servo-toggle"
          leftSection={<IconPower size={14} />}
          color={servoOn ? "gray" : "teal"}
          variant={servoOn ? "default" : "filled"}
          loading={servoBusy}
          disabled={servoOn === null}
          onClick={() => void toggleServo()}
          miw={112}
        >
          {servoOn ? "Servo OFF" : "Servo ON"}
        </Button>
        <Tooltip label="MC_Stop with the deceleration of the absolute move (Esc)">
          <Button data-testid="stop-button" color="red" leftSection={<IconHandStop size={14} />} loading={stopBusy}
            onClick={() => void stop()}>
            Stop
          </Button>
        </Tooltip>
        <ImmediateStop axis={name} />
        <Tooltip label="MC_Reset: clear the axis error">
          <Button data-testid="reset-button" variant="default" leftSection={<IconRotateClockwise2 size={14} />}
            loading={resetBusy} onClick={() => void reset()}>
            Reset
          </Button>
        </Tooltip>
      </Group>
    </Group>
  );
}

const ARROW_JOG: Record<string, JogDir> = { ArrowLeft: "minus", ArrowRight: "plus" };

/** Keys typed into a field (or a slider) are the field's, not a jog. */
function ownsArrows(t: EventTarget | null): boolean {
  if (!(t instanceof HTMLElement)) return false;
  return t.isContentEditable || ["INPUT", "TEXTAREA", "SELECT"].includes(t.tagName) || t.getAttribute("role") === "slider";
}

function TestRunBody({ axis, units }: { axis: AxisSummary; units: AxisUnits }) {
  const name = axis.name;
  // ← / → held = hold-to-jog while the test run has the focus; key up, leaving the panel and window blur
  // (commands.ts releaseAllJogs) stop it
  const keyDown = (e: KeyboardEvent<HTMLDivElement>) => {
    const dir = ARROW_JOG[e.key];
    if (!dir || ownsArrows(e.target) || e.altKey || e.ctrlKey || e.metaKey) return;
    e.preventDefault();
    if (!e.repeat) startJog(name, dir);
  };
  const keyUp = (e: KeyboardEvent<HTMLDivElement>) => {
    if (ARROW_JOG[e.key]) jogRelease(name);
  };
  const blur = (e: FocusEvent<HTMLDivElement>) => {
    if (!(e.relatedTarget instanceof Node && e.currentTarget.contains(e.relatedTarget))) jogRelease(name);
  };
  return (
    <Stack gap={8} p={8} data-testid={`testrun-${axis.name}`} tabIndex={-1} onKeyDown={keyDown} onKeyUp={keyUp}
      onBlur={blur} style={{ outline: "none" }}>
      <HeaderBar axis={axis} />
      <Box style={{ display: "flex", gap: 8, alignItems: "flex-start", flexWrap: "wrap" }}>
        <Stack gap={8} style={{ flex: "1 1 600px", minWidth: 560 }}>
          <JogPanel axis={axis.name} units={units} />
          <MoveForms axis={axis.name} units={units} />
          <OverridePanel axis={axis.name} />
          <HomingPanel axis={axis.name} units={units} />
          <LastInstructionPanel axis={axis.name} />
        </Stack>
        <Stack gap={8} style={{ flex: "1 1 420px", minWidth: 400 }}>
          <PositionPanel axis={axis.name} units={units} />
          <AxisErrorPanel axis={axis.name} />
          <AxisChart axis={axis.name} units={units} />
          <StatusPanel axis={axis.name} />
        </Stack>
      </Box>
    </Stack>
  );
}

/**
 * The MC test-run panel of one axis: servo, jog and inching, moves, override, homing, stop / immediate stop / reset,
 * live status and a trend chart.
 */
export function AxisTestRun({ axis }: { axis: string }) {
  const summary = useAxisSummary(axis);
  const { status } = useAxisList();
  const hasLive = useLive((s) => s.axes[axis] !== undefined);
  const unitDisplay = summary?.units;
  const units = useMemo(() => axisUnits(unitDisplay), [unitDisplay]);
  if (!summary) {
    return (
      <Center h={160}>
        {status === "loading" ? <Loader size="sm" /> : <Text size="sm">No axis named {axis} in this project.</Text>}
      </Center>
    );
  }
  if (!hasLive) {
    return (
      <Center h={160}>
        <Stack align="center" gap={4}>
          <Loader size="sm" />
          <Text size="xs" c="dimmed">
            Waiting for live data…
          </Text>
        </Stack>
      </Center>
    );
  }
  return (
    <ControlGuard>
      <TestRunBody axis={summary} units={units} />
    </ControlGuard>
  );
}
