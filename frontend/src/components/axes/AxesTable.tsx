import { ActionIcon, Badge, Center, Loader, Stack, Table, Text, Tooltip } from "@mantine/core";
import { IconTool } from "@tabler/icons-react";
import type { AxisSummary } from "../../api/types";
import { useAxisList, useAxisVars, useErrorInfo } from "../../hooks/useLive";
import { axisState, axisTypeLabel, axisUnits, stateColor } from "../../lib/format";
import { openAxisTab } from "../../store/tabs";
import { Num } from "../common/Num";

function ErrorCell({ code }: { code: string }) {
  const info = useErrorInfo(code);
  if (code === "0000") {
    return (
      <Text span size="xs" c="dimmed" className="num">
        0000
      </Text>
    );
  }
  return (
    <Tooltip label={info ? `${info.name}: ${info.correction}` : "Unknown ErrorID"} multiline w={360} withArrow>
      <Text span size="xs" c="red" fw={700} className="num">
        {code}
      </Text>
    </Tooltip>
  );
}

/** One row; it subscribes to its own axis so that the table does not re-render as a whole. */
function AxisRow({ axis }: { axis: AxisSummary }) {
  const v = useAxisVars(axis.name);
  const u = axisUnits(axis.units);
  const state = v ? axisState(v.Status) : axis.state;
  const servo = v ? v.DrvStatus.ServoOn : axis.servo_on;
  const code = v ? (v.MFaultLvl.Active ? v.MFaultLvl.Code : "0000") : axis.error_code;
  return (
    <Table.Tr
      data-testid={`axis-row-${axis.name}`}
      onDoubleClick={() => openAxisTab(axis.name)}
      title="Double-click to open the test run of this axis"
    >
      <Table.Td>
        <Text size="xs" fw={600}>
          {axis.name}
        </Text>
      </Table.Td>
      <Table.Td className="num">{axis.number}</Table.Td>
      <Table.Td>{axisTypeLabel(axis.type)}</Table.Td>
      <Table.Td className="num">{axis.node_address ?? "—"}</Table.Td>
      <Table.Td>
        <Badge size="sm" variant="light" color={stateColor(state)} style={{ textTransform: "none" }}
          data-testid={`axis-state-${axis.name}`}>
          {state}
        </Badge>
      </Table.Td>
      <Table.Td>
        <Badge size="sm" variant={servo ? "filled" : "outline"} color={servo ? "teal" : "gray"}
          data-testid={`axis-servo-${axis.name}`}>
          {servo ? "ON" : "OFF"}
        </Badge>
      </Table.Td>
      <Table.Td className="num">
        <Num value={v ? v.Cmd.Pos : axis.cmd_pos} unit={u.pos} testId={`axis-cmdpos-${axis.name}`} />
      </Table.Td>
      <Table.Td className="num">
        <Num value={v ? v.Act.Pos : axis.act_pos} unit={u.pos} testId={`axis-actpos-${axis.name}`} />
      </Table.Td>
      <Table.Td className="num">
        <Num value={v ? v.Cmd.Vel : axis.cmd_vel} unit={u.vel} testId={`axis-cmdvel-${axis.name}`} />
      </Table.Td>
      <Table.Td className="num">
        <Num value={v ? v.Act.Vel : axis.act_vel} unit={u.vel} testId={`axis-actvel-${axis.name}`} />
      </Table.Td>
      <Table.Td className="num" data-testid={`axis-error-${axis.name}`}>
        <ErrorCell code={code} />
      </Table.Td>
      <Table.Td>
        <Tooltip label="Open test run">
          <ActionIcon size="sm" aria-label={`Open test run of ${axis.name}`} onClick={() => openAxisTab(axis.name)}
            data-testid={`axis-open-${axis.name}`}>
            <IconTool size={14} />
          </ActionIcon>
        </Tooltip>
      </Table.Td>
    </Table.Tr>
  );
}

/** The "Axes" overview: every axis of the project with live values. */
export function AxesTable() {
  const { status, axes, error } = useAxisList();
  if (status === "loading") {
    return (
      <Center h={160}>
        <Loader size="sm" />
      </Center>
    );
  }
  if (status === "error" && axes.length === 0) {
    return (
      <Center h={160}>
        <Text size="sm" c="red">
          Cannot load the axes: {error}
        </Text>
      </Center>
    );
  }
  if (axes.length === 0) {
    return (
      <Center h={160}>
        <Stack gap={4} align="center">
          <Text size="sm" fw={600}>
            No axes
          </Text>
          <Text size="xs" c="dimmed">
            This project has no axes. Add axes to the project document (project.json) and reopen it.
          </Text>
        </Stack>
      </Center>
    );
  }
  return (
    <Table striped highlightOnHover stickyHeader withColumnBorders data-testid="axes-table" miw={980}>
      <Table.Thead>
        <Table.Tr>
          <Table.Th>Axis</Table.Th>
          <Table.Th className="num">No.</Table.Th>
          <Table.Th>Type</Table.Th>
          <Table.Th className="num">Node</Table.Th>
          <Table.Th>State</Table.Th>
          <Table.Th>Servo</Table.Th>
          <Table.Th className="num">Command position</Table.Th>
          <Table.Th className="num">Actual position</Table.Th>
          <Table.Th className="num">Command velocity</Table.Th>
          <Table.Th className="num">Actual velocity</Table.Th>
          <Table.Th className="num">Error</Table.Th>
          <Table.Th w={36} />
        </Table.Tr>
      </Table.Thead>
      <Table.Tbody>
        {axes.map((a) => (
          <AxisRow key={a.name} axis={a} />
        ))}
      </Table.Tbody>
    </Table>
  );
}
