import { Center, Loader, ScrollArea, Stack, Table, Text } from "@mantine/core";
import { useAxisList } from "../../hooks/useLive";
import { unitLabel } from "../../lib/format";
import { useGroup } from "../../store/groupCommands";
import { Panel } from "../common/Panel";
import { GroupControls, LastGroupInstruction } from "./GroupControls";
import { GroupMoveForm } from "./GroupMoveForm";
import { RobotJogPanel } from "./RobotJogPanel";
import { ControlGuard } from "../control/ControlGuard";

const LOGICAL = ["A0", "A1", "A2", "A3"];

/** Command positions of the composition axes (from GET /api/v1/groups). */
export function GroupPositions({ axes, cmd }: { axes: string[]; cmd: number[] }) {
  const list = useAxisList().axes;
  const unit = (name: string) => unitLabel(list.find((x) => x.name === name)?.units);
  return (
    <Table withRowBorders={false} verticalSpacing={1} horizontalSpacing={4} fz="xs">
      <Table.Tbody>
        {axes.map((a, k) => (
          <Table.Tr key={a} data-testid={`group-pos-${LOGICAL[k]}`}>
            <Table.Td>
              <Text size="xs" fw={600} span>
                {LOGICAL[k]}
              </Text>{" "}
              <Text size="xs" c="dimmed" span>
                {a}
              </Text>
            </Table.Td>
            <Table.Td ta="right" ff="monospace">
              {cmd[k] !== undefined ? cmd[k].toFixed(3) : "—"}{" "}
              <span className="unit">{unit(a)}</span>
            </Table.Td>
          </Table.Tr>
        ))}
      </Table.Tbody>
    </Table>
  );
}

/** The test run of an axes group: state, positions, state instructions, moves; the Cartesian jog for a robot. */
export function GroupTestRun({ name }: { name: string }) {
  const group = useGroup(name);
  if (!group) {
    return (
      <Center p="xl">
        <Loader size="sm" />
      </Center>
    );
  }
  const robot = group.kinematics !== null;
  return (
    <ScrollArea h="100%" data-testid={`group-testrun-${name}`}>
      <Stack gap={10} p="sm" maw={760}>
        <ControlGuard>
        <Panel title={`${group.name} · ${group.composition} · ${robot ? "Delta3 robot" : "interpolation"}`}>
          <Stack gap={8}>
            <GroupControls group={group} />
            <Text size="xs" c="dimmed">
              Command positions {robot ? "[°] (ACS)" : ""}
            </Text>
            <GroupPositions axes={group.axes} cmd={group.cmd_pos} />
          </Stack>
        </Panel>
        {robot ? (
          <Panel title="Cartesian jog (MC_RobotJog, MC Studio extension)">
            <RobotJogPanel group={group} />
          </Panel>
        ) : (
          <Panel title="Move (linear / circular interpolation)">
            <GroupMoveForm group={group} />
          </Panel>
        )}
        <Panel title="Last group instruction">
          <LastGroupInstruction group={name} />
          <Text size="xs" c="dimmed">
            Instructions issued from this tab and the 3D view appear here.
          </Text>
        </Panel>
        </ControlGuard>
      </Stack>
    </ScrollArea>
  );
}
