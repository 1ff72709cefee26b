import { Alert, Badge, Code, Group, Loader, Paper, ScrollArea, Stack, Table, Text, Title } from "@mantine/core";
import { IconAlertTriangle, IconRobot } from "@tabler/icons-react";
import type { RobotOut } from "../../api/types";
import { useGroup } from "../../store/groupCommands";
import { GroupControls, LastGroupInstruction } from "../group/GroupControls";
import { RobotJogPanel } from "../group/RobotJogPanel";
import { ControlGuard } from "../control/ControlGuard";
import { useRobots } from "./useRobots";

function fmt(v: number | null | undefined, digits = 3): string {
  return v === null || v === undefined ? "—" : v.toFixed(digits);
}

function stateColor(state: string): string {
  if (state === "ErrorStop") return "red";
  if (state === "Disabled") return "dimmed";
  if (state === "Standstill") return "teal.7";
  return "blue.7";
}

function RobotCard({ robot }: { robot: RobotOut }) {
  const k = robot.kinematics;
  return (
    <Stack gap={8} data-testid={`robot-${robot.group}`}>
      <Group gap={6} justify="space-between" wrap="nowrap">
        <Group gap={6} wrap="nowrap">
          <IconRobot size={18} />
          <Text fw={600} data-testid="robot-group">
            {robot.group}
          </Text>
        </Group>
        <Badge size="sm" variant="light" color={robot.alarm ? "red" : "blue"}>
          Delta3
        </Badge>
      </Group>
      {robot.alarm && (
        <Alert color="red" variant="light" p={6} icon={<IconAlertTriangle size={16} />} data-testid="robot-alarm">
          <Text size="xs">
            {robot.alarm.message} (ErrorID {robot.alarm.code})
          </Text>
        </Alert>
      )}
      <Table withRowBorders={false} verticalSpacing={2} horizontalSpacing={4} fz="xs">
        <Table.Thead>
          <Table.Tr>
            <Table.Th>Axis</Table.Th>
            <Table.Th ta="right">Act.Pos [°]</Table.Th>
            <Table.Th>State</Table.Th>
          </Table.Tr>
        </Table.Thead>
        <Table.Tbody>
          {robot.axes.map((a) => (
            <Table.Tr key={a.logical} data-testid={`robot-axis-${a.logical}`}>
              <Table.Td>
                <Text size="xs" fw={600} span>
                  {a.logical}
                </Text>{" "}
                <Text size="xs" c="dimmed" span>
                  {a.name}
                </Text>
              </Table.Td>
              <Table.Td ta="right" ff="monospace">
                {fmt(a.act_pos)}
              </Table.Td>
              <Table.Td>
                <Text size="xs" fw={500} c={stateColor(a.state)}>
                  {a.state}
                  {a.error_code !== "0000" ? ` ${a.error_code}` : ""}
                </Text>
              </Table.Td>
            </Table.Tr>
          ))}
        </Table.Tbody>
      </Table>
      <div>
        <Text size="xs" c="dimmed" mb={2}>
          TCP (feedback, MCS, forward kinematics) [mm]
        </Text>
        {robot.tcp ? (
          <Group gap={10} ff="monospace" data-testid="robot-tcp">
            {(["X", "Y", "Z"] as const).map((n, i) => (
              <Text key={n} size="sm">
                <Text span c="dimmed" size="xs">
                  {n}{" "}
                </Text>
                {fmt(robot.tcp?.[i], 2)}
              </Text>
            ))}
          </Group>
        ) : (
          <Text size="xs" c="red" data-testid="robot-tcp">
            no forward solution ({robot.kin_status})
          </Text>
        )}
      </div>
      <Text size="xs" c="dimmed">
        Rf {k.Rf} · Rm {k.Rm} · Lf {k.Lf} · Lm {k.Lm} mm · θ {k.theta}°
      </Text>
      <RobotTestRun name={robot.group} coordSystems={robot.coord_systems} />
    </Stack>
  );
}

/** The group test run of the robot next to the 3D view: state buttons, Cartesian jog, the demo sequence. */
function RobotTestRun({ name, coordSystems }: { name: string; coordSystems: RobotOut["coord_systems"] }) {
  const group = useGroup(name);
  if (!group) return null;
  return (
    <Stack gap={8} pt={6} style={{ borderTop: "1px solid var(--mantine-color-gray-3)" }} data-testid="robot-testrun">
      <Title order={6}>Test run</Title>
      <ControlGuard>
        <GroupControls group={group} compact />
        <RobotJogPanel group={group} coordSystems={coordSystems} />
      </ControlGuard>
      <LastGroupInstruction group={name} />
    </Stack>
  );
}

/** Status of the project's robots next to the 3D view, or what to do when there is none. */
export function RobotPanel({ active }: { active: boolean }) {
  const { data, error } = useRobots(active);
  return (
    <Paper
      data-testid="robot-panel"
      w={330}
      radius={0}
      p="sm"
      style={{ borderLeft: "1px solid var(--mantine-color-gray-3)", flex: "none", display: "flex", minHeight: 0 }}
    >
      <ScrollArea style={{ flex: 1 }}>
        <Stack gap="md">
          <Title order={6}>Robot</Title>
          {error && (
            <Text size="xs" c="red">
              {error}
            </Text>
          )}
          {!data && !error && <Loader size="xs" />}
          {data && data.robots.length === 0 && (
            <Stack gap={6} data-testid="robot-empty">
              <Text size="sm" fw={600}>
                This project has no robot
              </Text>
              <Text size="xs" c="dimmed">
                The 3D view draws every axes group with Delta3 kinematics. Add one to the project: three servo axes
                in degrees (linear count mode, software limits within ±180°) and a group with composition{" "}
                <Code>_mcXYZ</Code>, its axes as A0, A1, A2, and
              </Text>
              <Code block fz={10}>
                {`"kinematics": {"type": "delta3",
  "Rf": 200, "Rm": 50, "Lf": 350, "Lm": 800,
  "theta": 0, "workspace": {"Zu": -50,
  "Rcy": 300, "Hcy": 250, "Rco": 150, "Hco": 150}}`}
              </Code>
              <Text size="xs" c="dimmed">
                then apply the project (or open the demo project, which has MC_Group000).
              </Text>
            </Stack>
          )}
          {data?.robots.map((r) => <RobotCard key={r.group} robot={r} />)}
        </Stack>
      </ScrollArea>
    </Paper>
  );
}
