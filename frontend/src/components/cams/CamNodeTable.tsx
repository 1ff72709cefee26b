import { ActionIcon, Checkbox, NumberInput, Select, Table, Text, Tooltip } from "@mantine/core";
import { IconAlertTriangle, IconPlus, IconTrash } from "@tabler/icons-react";
import type { NumValue } from "../../store/forms";
import {
  CURVES,
  type CamJumpOut,
  type CamSegmentOut,
  type NodeRow,
  addNode,
  removeNode,
  setNode,
  usesConnectingAcc,
  usesConnectingVel,
} from "../../store/cams";

const CURVE_OPTIONS = CURVES.map(([value, label]) => ({ value, label }));

function fmt(v: number | null | undefined, digits = 4): string {
  if (v === null || v === undefined || !Number.isFinite(v)) return "—";
  const a = Math.abs(v);
  if (a !== 0 && (a >= 1e6 || a < 1e-3)) return v.toExponential(2);
  return String(+v.toPrecision(digits));
}

interface CellProps {
  value: NumValue;
  onChange: (v: NumValue) => void;
  error?: string;
  testId: string;
  label: string;
  disabled?: boolean;
  w?: number;
}

function Cell({ value, onChange, error, testId, label, disabled, w = 82 }: CellProps) {
  return (
    <NumberInput
      size="xs"
      w={w}
      value={value}
      onChange={onChange}
      aria-label={label}
      data-testid={testId}
      disabled={disabled}
      error={error ? true : undefined}
      title={error}
      hideControls
      allowDecimal
      thousandSeparator={false}
      autoComplete="off"
      styles={{ input: { textAlign: "right", fontVariantNumeric: "tabular-nums", paddingInline: 6 } }}
    />
  );
}

interface Props {
  name: string;
  nodes: NodeRow[];
  issues: Record<string, string>;
  segments: CamSegmentOut[] | null;
  jumps: CamJumpOut[];
}

/**
 * The cam nodes, one row per segment (it ends at the node): phase, distance, curve, phase pitch, the connecting
 * conditions of the polynomials; then the segment's characteristic values (dimensionless Vm/Am/Jm and the maxima
 * in command units at the master velocity) and the continuity warnings at its end.
 */
export function CamNodeTable({ name, nodes, issues, segments, jumps }: Props) {
  return (
    <Table className="cam-node-table" withTableBorder withColumnBorders verticalSpacing={2} horizontalSpacing={4}
      data-testid="cam-node-table">
      <Table.Thead>
        <Table.Tr>
          <Table.Th>#</Table.Th>
          <Table.Th>Phase</Table.Th>
          <Table.Th>Distance</Table.Th>
          <Table.Th>Curve</Table.Th>
          <Table.Th>Pitch</Table.Th>
          <Table.Th title="ConnectingVel (cubic and quintic): end velocity [units/s]">Conn. vel</Table.Th>
          <Table.Th title="ConnectingAcc (quintic): end acceleration [units/s²]">Conn. acc</Table.Th>
          <Table.Th title="Dimensionless maxima of the law: velocity, acceleration, jerk">Vm · Am · Jm</Table.Th>
          <Table.Th title="Maxima at the master velocity [units/s, units/s², units/s³]">v max · a max · j max</Table.Th>
          <Table.Th />
        </Table.Tr>
      </Table.Thead>
      <Table.Tbody>
        {nodes.map((n, i) => {
          const seg = segments?.find((s) => s.node === i) ?? null;
          const rowJumps = jumps.filter((j) => j.node === i);
          const err = (f: string) => issues[`nodes[${i}].${f}`];
          const rowErr = issues[`nodes[${i}]`];
          const vel = usesConnectingVel(n.Curve);
          const acc = usesConnectingAcc(n.Curve);
          const dwell = n.Curve === "_mcConstantLine";
          const problems = Object.entries(issues).filter(([k]) => k === `nodes[${i}]` || k.startsWith(`nodes[${i}].`));
          return (
            <Table.Tr key={i} data-testid={`cam-node-${i}`} data-warning={rowJumps.length ? "true" : "false"}
              data-error={problems.length ? "true" : "false"}>
              <Table.Td><Text size="xs" c="dimmed">{i}</Text></Table.Td>
              <Table.Td>
                <Cell value={n.Phase} onChange={(v) => setNode(name, i, { Phase: v })} error={err("Phase")}
                  testId={`cam-node-${i}-phase`} label={`Phase of node ${i}`} />
              </Table.Td>
              <Table.Td>
                <Cell value={n.Distance} onChange={(v) => setNode(name, i, { Distance: v })} error={err("Distance")}
                  testId={`cam-node-${i}-distance`} label={`Distance of node ${i}`} disabled={dwell} />
              </Table.Td>
              <Table.Td>
                <Select size="xs" w={168} data={CURVE_OPTIONS} value={n.Curve} allowDeselect={false}
                  onChange={(v) => v && setNode(name, i, { Curve: v })} aria-label={`Curve of node ${i}`}
                  data-testid={`cam-node-${i}-curve`} error={err("Curve") ? true : undefined}
                  comboboxProps={{ withinPortal: true }} />
              </Table.Td>
              <Table.Td>
                <Cell value={n.PhasePitch} onChange={(v) => setNode(name, i, { PhasePitch: v })} w={62}
                  error={err("PhasePitch")} testId={`cam-node-${i}-pitch`} label={`Phase pitch of node ${i}`} />
              </Table.Td>
              <Table.Td>
                {vel ? (
                  <div style={{ display: "flex", alignItems: "center", gap: 4 }}>
                    <Checkbox size="xs" checked={n.ConnectingVelEnable} aria-label={`ConnectingVelEnable of node ${i}`}
                      onChange={(e) => setNode(name, i, { ConnectingVelEnable: e.currentTarget.checked })} />
                    <Cell value={n.ConnectingVel} onChange={(v) => setNode(name, i, { ConnectingVel: v })} w={64}
                      disabled={!n.ConnectingVelEnable} error={err("ConnectingVel")}
                      testId={`cam-node-${i}-cvel`} label={`ConnectingVel of node ${i}`} />
                  </div>
                ) : <Text size="xs" c="dimmed" ta="center">—</Text>}
              </Table.Td>
              <Table.Td>
                {acc ? (
                  <div style={{ display: "flex", alignItems: "center", gap: 4 }}>
                    <Checkbox size="xs" checked={n.ConnectingAccEnable} aria-label={`ConnectingAccEnable of node ${i}`}
                      onChange={(e) => setNode(name, i, { ConnectingAccEnable: e.currentTarget.checked })} />
                    <Cell value={n.ConnectingAcc} onChange={(v) => setNode(name, i, { ConnectingAcc: v })} w={64}
                      disabled={!n.ConnectingAccEnable} error={err("ConnectingAcc")}
                      testId={`cam-node-${i}-cacc`} label={`ConnectingAcc of node ${i}`} />
                  </div>
                ) : <Text size="xs" c="dimmed" ta="center">—</Text>}
              </Table.Td>
              <Table.Td data-testid={`cam-node-${i}-dim`}>
                <Text size="xs" ff="monospace" style={{ whiteSpace: "nowrap" }}>
                  {seg ? (seg.Vm === null ? "no rise" : `${fmt(seg.Vm)} · ${fmt(seg.Am)} · ${fmt(seg.Jm)}`) : "—"}
                </Text>
              </Table.Td>
              <Table.Td data-testid={`cam-node-${i}-max`}>
                <Text size="xs" ff="monospace" style={{ whiteSpace: "nowrap" }}
                  title={seg?.accel_jump_inside ? "The acceleration jumps inside this law: the jerk is unbounded" : undefined}>
                  {seg ? `${fmt(seg.v_max)} · ${fmt(seg.a_max)} · ${seg.accel_jump_inside ? "∞" : fmt(seg.j_max)}` : "—"}
                </Text>
              </Table.Td>
              <Table.Td>
                <div style={{ display: "flex", alignItems: "center", gap: 2 }}>
                  {(rowJumps.length > 0 || problems.length > 0 || rowErr) && (
                    <Tooltip multiline w={300} withArrow
                      label={[...problems.map(([k, m]) => `${k}: ${m}`), ...rowJumps.map((j) => j.message)].join("\n")}>
                      <IconAlertTriangle size={15} color={problems.length ? "var(--mantine-color-red-7)"
                        : "var(--mantine-color-orange-6)"} data-testid={`cam-node-${i}-warning`} />
                    </Tooltip>
                  )}
                  <ActionIcon size="sm" variant="subtle" color="gray" aria-label={`Remove node ${i}`}
                    disabled={nodes.length <= 1} onClick={() => removeNode(name, i)} data-testid={`cam-node-${i}-remove`}>
                    <IconTrash size={13} />
                  </ActionIcon>
                </div>
              </Table.Td>
            </Table.Tr>
          );
        })}
        <Table.Tr>
          <Table.Td colSpan={10}>
            <ActionIcon size="sm" variant="subtle" aria-label="Add a node" onClick={() => addNode(name)}
              data-testid="cam-node-add" disabled={nodes.length >= 359}>
              <IconPlus size={14} />
            </ActionIcon>
          </Table.Td>
        </Table.Tr>
      </Table.Tbody>
    </Table>
  );
}
