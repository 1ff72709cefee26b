import { Badge, Box, Button, Center, Group, Loader, Stack, Text, Tooltip } from "@mantine/core";
import { IconHandStop, IconPower, IconRotateClockwise2 } from "@tabler/icons-react";
import { useMemo, useState } from "react";
import type { AxisSummary } from "../../api/types";
import { useAxisList, useAxisSummary, useLive } from "../../hooks/useLive";
import { type AxisUnits, axisState, axisTypeLabel, axisUnits, stateColor } from "../../lib/format";
import { resetAxis, setServo, stopAxis } from "../../store/commands";
import { axisForms, num } from "../../store/forms";
import { AxisChart } from "./AxisChart";
import { JogPanel } from "./JogPanel";
import { LastInstructionPanel } from "./LastInstructionPanel";
import { AxisErrorPanel, PositionPanel, StatusPanel } from "./LivePanels";
import { MoveForms } from "./MoveForms";

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
    <Group justify="space-between" wrap="nowrap" gap="sm" px="sm" py={6} className="panel">
      <Group gap="md" wrap="nowrap" style={{ minWidth: 0 }}>
        <Stack gap={0} style={{ minWidth: 0 }}>
          <Text fw={700} size="md" truncate="end">
            {name}
          </Text>
          <Text size="xs" c="dimmed" style={{ whiteSpace: "nowrap" }}>
            Axis {axis.number} · {axisTypeLabel(axis.type)}
            {axis.node_address !== null ? ` · EtherCAT node ${axis.node_address}` : ""}
          </Text>
        </Stack>
        <Stack gap={0}>
          <Text size="10px" c="dimmed" tt="uppercase">
            State
          </Text>
          <Badge size="lg" variant="light" color={stateColor(state ?? "")} style={{ textTransform: "none" }} miw={110}>
            <span data-testid="axis-state">{state ?? "—"}</span>
          </Badge>
        </Stack>
        <Stack gap={0}>
          <Text size="10px" c="dimmed" tt="uppercase">
            Servo
          </Text>
          <Badge size="lg" variant={servoOn ? "filled" : "outline"} color={servoOn ? "teal" : "gray"} miw={56}>
            <span data-testid="servo-status">{servoOn === null ? "—" : servoOn ? "ON" : "OFF"}</span>
          </Badge>
        </Stack>
      </Group>
      <Group gap={6} wrap="nowrap">
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

function TestRunBody({ axis, units }: { axis: AxisSummary; units: AxisUnits }) {
  return (
    <Stack gap={8} p={8} data-testid={`testrun-${axis.name}`}>
      <HeaderBar axis={axis} />
      <Box style={{ display: "flex", gap: 8, alignItems: "flex-start", flexWrap: "wrap" }}>
        <Stack gap={8} style={{ flex: "1 1 600px", minWidth: 560 }}>
          <JogPanel axis={axis.name} units={units} />
          <MoveForms axis={axis.name} units={units} />
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

/** The MC test-run panel of one axis: servo, jog, moves, stop/reset, live status and a trend chart. */
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
  return <TestRunBody axis={summary} units={units} />;
}
