import { Button, Group, NumberInput, SegmentedControl, SimpleGrid, Stack, Text, Tooltip } from "@mantine/core";
import { IconPlayerPlay, IconPlayerStop, IconTarget } from "@tabler/icons-react";
import { useState } from "react";
import { useFb } from "../../hooks/useLive";
import { notifyError } from "../../lib/notify";
import type { NumValue } from "../../store/forms";
import { num } from "../../store/forms";
import {
  type GroupInfo,
  moveToPose,
  robotJogPress,
  robotJogRelease,
  runDemo,
  stopDemo,
  useGroupCommands,
} from "../../store/groupCommands";
import { HoldButton } from "../testrun/HoldButton";
import { ErrorCode } from "./GroupControls";

const READY_POINT = [0, 0, -300];

function JogReadout({ id }: { id: number | null }) {
  const fb = useFb(id);
  if (!fb) return null;
  const o = fb.outputs;
  const p = Array.isArray(o.CommandPosition) ? (o.CommandPosition as number[]) : null;
  return (
    <Stack gap={2} data-testid="robot-jog-status">
      <Group gap={8} wrap="nowrap">
        <Text size="xs" c={o.Active === true ? "blue" : "dimmed"} fw={o.Active === true ? 600 : 400}>
          {o.Active === true ? `moving ${Number(o.CommandVelocity ?? 0).toFixed(1)} mm/s` : "idle"}
        </Text>
        {o.AtBoundary === true && (
          <Text size="xs" c="orange" fw={600} data-testid="robot-jog-boundary">
            at the workspace boundary
          </Text>
        )}
      </Group>
      {p && o.Busy === true && (
        <Text size="xs" ff="monospace" c="dimmed">
          cmd {p.map((v) => v.toFixed(2)).join(", ")} mm
        </Text>
      )}
      <ErrorCode code={typeof o.WarningID === "string" ? o.WarningID : "0000"} testId="robot-jog-warning" />
      <ErrorCode code={typeof o.ErrorID === "string" ? o.ErrorID : "0000"} testId="robot-jog-error" />
    </Stack>
  );
}

/**
 * Cartesian jog of a Delta3 TCP (MC_RobotJog, an MC Studio extension): hold ±X/±Y/±Z; a dead-man lease stops the
 * robot when the browser goes away. Plus the way into the workspace (MC_GroupSyncMoveAbsolute to the inverse
 * kinematics of a ready point) and the pick-and-place demo.
 */
export function RobotJogPanel({ group }: { group: GroupInfo }) {
  const cmds = useGroupCommands(group.name);
  const [vel, setVel] = useState<NumValue>(50);
  const [cs, setCs] = useState<"1" | "3">("1");
  const [csid, setCsid] = useState<NumValue>(0);
  const [readyBusy, setReadyBusy] = useState(false);
  const demo = cmds.demo !== null;

  const press = (dir: string) => {
    const v = num(vel);
    const id = num(csid);
    if (v === null || v <= 0 || id === null) {
      notifyError("Cartesian jog", new Error("enter a positive speed"));
      return;
    }
    robotJogPress(group.name, dir, { velocity: v, acceleration: v * 10, coordSystem: Number(cs), csid: id });
  };
  const release = () => robotJogRelease(group.name);
  const btn = (dir: string) => (
    <HoldButton key={dir} testId={`robot-jog-${dir[0] === "+" ? "plus" : "minus"}-${dir[1].toLowerCase()}`}
      label={`Jog ${dir} (hold)`} held={cmds.jogHeld === dir} disabled={demo}
      onPress={() => press(dir)} onRelease={release}>
      {dir}
    </HoldButton>
  );

  return (
    <Stack gap={8} data-testid={`robot-jog-${group.name}`}>
      <Group gap={6} align="flex-end" wrap="nowrap">
        <NumberInput size="xs" label="Speed" rightSection={<Text size="10px" c="dimmed">mm/s</Text>}
          rightSectionWidth={44} value={vel} onChange={setVel} min={0.1} max={1000} w={100}
          data-testid="robot-jog-speed" />
        <SegmentedControl size="xs" value={cs} onChange={(v) => setCs(v as "1" | "3")}
          data={[{ value: "1", label: "MCS" }, { value: "3", label: "UCS" }]} data-testid="robot-jog-cs" />
        {cs === "3" && (
          <NumberInput size="xs" label="CSID" value={csid} onChange={setCsid} min={0} max={15} w={60} />
        )}
      </Group>
      <SimpleGrid cols={3} spacing={4} verticalSpacing={4}>
        {btn("+X")}
        {btn("+Y")}
        {btn("+Z")}
        {btn("-X")}
        {btn("-Y")}
        {btn("-Z")}
      </SimpleGrid>
      <JogReadout id={cmds.jogId} />
      <Group gap={4} wrap="wrap">
        <Tooltip label="MC_GroupSyncMoveAbsolute to the inverse kinematics of (0, 0, −300) mm, then MC_GroupStop"
          openDelay={400} multiline w={240}>
          <Button size="compact-xs" variant="default" leftSection={<IconTarget size={13} />} loading={readyBusy}
            disabled={demo} data-testid={`robot-ready-${group.name}`}
            onClick={async () => {
              setReadyBusy(true);
              await moveToPose(group.name, READY_POINT);
              setReadyBusy(false);
            }}>
            Ready pose
          </Button>
        </Tooltip>
        {!demo ? (
          <Tooltip label="Pick and place between (−150, −100, −400) and (150, 100, −400) mm with the conveyor running"
            openDelay={400} multiline w={240}>
            <Button size="compact-xs" color="teal" leftSection={<IconPlayerPlay size={13} />}
              data-testid={`robot-demo-run-${group.name}`}
              onClick={() => void runDemo(group.name, group.axes)}>
              Run demo sequence
            </Button>
          </Tooltip>
        ) : (
          <Button size="compact-xs" color="red" leftSection={<IconPlayerStop size={13} />}
            data-testid={`robot-demo-stop-${group.name}`} onClick={() => stopDemo(group.name)}>
            Stop demo
          </Button>
        )}
      </Group>
      {demo && (
        <Text size="xs" c="teal" data-testid={`robot-demo-status-${group.name}`}>
          Demo: {cmds.demo} · {cmds.demoCycles} cycles
        </Text>
      )}
    </Stack>
  );
}
