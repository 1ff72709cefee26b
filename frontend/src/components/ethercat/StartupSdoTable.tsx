import { ActionIcon, Button, Checkbox, Group, NumberInput, Select, Table, Text, TextInput, Tooltip } from "@mantine/core";
import { IconArrowDown, IconArrowUp, IconPlus, IconTrash } from "@tabler/icons-react";
import { Fragment, useMemo } from "react";
import type { DeviceDescription, SlaveOut } from "../../api/types";
import { hexH } from "../../lib/hex";
import { useDevice } from "../../store/ethercat";
import {
  type FieldIssue,
  SDO_SIZES,
  type SdoDraft,
  type SdoSize,
  addSdo,
  moveSdo,
  parseHexIndex,
  removeSdo,
  setSdo,
} from "../../store/networkEditor";

const CELL = { input: { height: 24, minHeight: 24, fontSize: 12 } };
const MONO = { input: { ...CELL.input, fontFamily: "var(--mantine-font-family-monospace)" } };

interface ObjectHint {
  text: string;
  tone: "name" | "warn";
}

function objectHint(device: DeviceDescription | null, row: SdoDraft): ObjectHint | null {
  const index = parseHexIndex(row.index);
  if (index === null || !device) return null;
  const sub = typeof row.subindex === "number" ? row.subindex : 0;
  const objects = device.objects ?? [];
  const obj = objects.find((o) => o.index === index && o.subindex === sub);
  if (!obj) {
    const any = objects.some((o) => o.index === index);
    return { text: any ? `no subindex ${sub} in ${hexH(index)}` : "not in the device's object dictionary", tone: "warn" };
  }
  const ro = obj.access.toLowerCase() === "ro";
  return { text: `${obj.name} · ${obj.data_type}${ro ? " · read-only" : ""}`, tone: ro ? "warn" : "name" };
}

interface RowProps {
  node: number;
  row: number;
  count: number;
  s: SdoDraft;
  hint: ObjectHint | null;
  errors: FieldIssue[];
  disabled: boolean;
}

function SdoRow({ node, row, count, s, hint, errors, disabled }: RowProps) {
  const has = (f: string) => errors.some((e) => e.field === `startup_sdos[${row}].${f}`);
  return (
    <Fragment>
      <Table.Tr data-testid={`sdo-row-${row}`} data-invalid={errors.length ? "true" : undefined} className="sdo-row">
        <Table.Td className="num" c="dimmed">{row + 1}</Table.Td>
        <Table.Td>
          <TextInput size="xs" w={76} value={s.index} onChange={(e) => setSdo(node, row, "index", e.currentTarget.value)}
            placeholder="6065" aria-label={`Index of line ${row + 1} (hex)`} data-testid="sdo-index" error={has("index")}
            rightSection={<Text size="xs" c="dimmed">h</Text>} rightSectionWidth={16} disabled={disabled} styles={MONO} />
        </Table.Td>
        <Table.Td>
          <NumberInput size="xs" w={54} value={s.subindex} onChange={(v) => setSdo(node, row, "subindex", v)}
            allowDecimal={false} allowNegative={false} hideControls aria-label={`Subindex of line ${row + 1}`}
            data-testid="sdo-subindex" error={has("subindex")} disabled={disabled} styles={CELL} />
        </Table.Td>
        <Table.Td style={{ maxWidth: 200 }}>
          {hint && (
            <Text size="11px" c={hint.tone === "warn" ? "orange.8" : "dimmed"} truncate="end" title={hint.text}
              data-testid="sdo-object">
              {hint.text}
            </Text>
          )}
        </Table.Td>
        <Table.Td>
          <TextInput size="xs" w={116} value={s.value} onChange={(e) => setSdo(node, row, "value", e.currentTarget.value)}
            aria-label={`Value of line ${row + 1}`} data-testid="sdo-value" error={has("value")} disabled={disabled}
            styles={{ input: { ...MONO.input, textAlign: "right" } }} />
        </Table.Td>
        <Table.Td>
          <Select size="xs" w={74} data={SDO_SIZES.map((b) => ({ value: b, label: `${b} bit` }))} value={s.bit_len}
            onChange={(v) => v && setSdo(node, row, "bit_len", v as SdoSize)} allowDeselect={false}
            aria-label={`Size of line ${row + 1}`} data-testid="sdo-size" error={has("bit_len")} disabled={disabled}
            comboboxProps={{ withinPortal: true }} styles={CELL} />
        </Table.Td>
        <Table.Td ta="center">
          <Tooltip label="Abort on error: a failed write stops the slave's start-up in Pre-Op" openDelay={400}>
            <Checkbox size="xs" checked={s.abort_on_error} onChange={(e) => setSdo(node, row, "abort_on_error", e.currentTarget.checked)}
              aria-label={`Abort on error, line ${row + 1}`} data-testid="sdo-abort" disabled={disabled}
              style={{ display: "inline-block" }} />
          </Tooltip>
        </Table.Td>
        <Table.Td>
          <TextInput size="xs" value={s.comment} onChange={(e) => setSdo(node, row, "comment", e.currentTarget.value)}
            aria-label={`Comment of line ${row + 1}`} data-testid="sdo-comment" error={has("comment")} disabled={disabled}
            miw={120} styles={CELL} />
        </Table.Td>
        <Table.Td>
          <Group gap={0} wrap="nowrap" justify="flex-end">
            <ActionIcon size="sm" disabled={disabled || row === 0} onClick={() => moveSdo(node, row, -1)}
              aria-label={`Move line ${row + 1} up`} data-testid="sdo-up">
              <IconArrowUp size={13} />
            </ActionIcon>
            <ActionIcon size="sm" disabled={disabled || row === count - 1} onClick={() => moveSdo(node, row, 1)}
              aria-label={`Move line ${row + 1} down`} data-testid="sdo-down">
              <IconArrowDown size={13} />
            </ActionIcon>
            <ActionIcon size="sm" color="red" disabled={disabled} onClick={() => removeSdo(node, row)}
              aria-label={`Delete line ${row + 1}`} data-testid="sdo-delete">
              <IconTrash size={13} />
            </ActionIcon>
          </Group>
        </Table.Td>
      </Table.Tr>
      {errors.length > 0 && (
        <Table.Tr className="pdo-entry-error">
          <Table.Td />
          <Table.Td colSpan={8}>
            {errors.map((e, k) => (
              <Text key={k} size="11px" c="red.7" data-testid={`sdo-error-${row}`} role="alert"
                data-field-error="true">
                {e.field.replace(/^startup_sdos\[\d+\]\.?/, "").replace("bit_len", "size") || "line"}: {e.msg}
              </Text>
            ))}
          </Table.Td>
        </Table.Tr>
      )}
    </Fragment>
  );
}

/** The last start-up of the slave as the master logged it: 1C12h/1C13h and each SDO line, an abort in red. */
function StartupLog({ slave }: { slave: SlaveOut }) {
  if (!slave.startup_log.length) return null;
  return (
    <div className="sdo-log" data-testid={`sdo-log-${slave.node_address}`}>
      <Text size="10px" c="dimmed" tt="uppercase" fw={600} style={{ letterSpacing: "0.03em" }}>
        Last start-up (Pre-Op downloads)
      </Text>
      {slave.startup_log.map((line, k) => (
        <Text key={k} size="11px" ff="monospace" c={line.includes("abort") ? "red.7" : "gray.7"} lh={1.45}>
          {line}
        </Text>
      ))}
    </div>
  );
}

/** The start-up parameter list of a slave: SDO writes in Pre-Op, in order (TwinCAT's "Startup", Sysmac's
 * initialization parameters). */
export function StartupSdoTable({ node, slave, rows, issues, disabled }: {
  node: number;
  slave: SlaveOut;
  rows: readonly SdoDraft[];
  issues: readonly FieldIssue[];
  disabled: boolean;
}) {
  const device = useDevice(slave.device_id);
  const hints = useMemo(() => rows.map((r) => objectHint(device, r)), [rows, device]);
  const rowIssues = (i: number) =>
    issues.filter((x) => x.field === `startup_sdos[${i}]` || x.field.startsWith(`startup_sdos[${i}].`));
  return (
    <div className="sdo-grid">
      <div style={{ minWidth: 0 }}>
        <Table className="sdo-table" verticalSpacing={3} horizontalSpacing={6} data-testid={`sdo-table-${node}`}>
          <Table.Thead>
            <Table.Tr>
              <Table.Th w={28}>#</Table.Th>
              <Table.Th>Index</Table.Th>
              <Table.Th>Sub</Table.Th>
              <Table.Th>Object</Table.Th>
              <Table.Th>Value</Table.Th>
              <Table.Th>Size</Table.Th>
              <Table.Th ta="center" title="Abort on error">Abort</Table.Th>
              <Table.Th>Comment</Table.Th>
              <Table.Th w={72} />
            </Table.Tr>
          </Table.Thead>
          <Table.Tbody>
            {rows.map((s, i) => (
              <SdoRow key={s.key} node={node} row={i} count={rows.length} s={s} hint={hints[i]} errors={rowIssues(i)}
                disabled={disabled} />
            ))}
            {rows.length === 0 && (
              <Table.Tr>
                <Table.Td colSpan={9}>
                  <Text size="xs" c="dimmed" py={4} data-testid={`sdo-empty-${node}`}>
                    No start-up parameters: the master only downloads the PDO assignment and mapping in Pre-Op.
                  </Text>
                </Table.Td>
              </Table.Tr>
            )}
          </Table.Tbody>
        </Table>
        <Group gap={8} mt={4}>
          <Button size="compact-xs" variant="light" leftSection={<IconPlus size={13} />} onClick={() => addSdo(node)}
            disabled={disabled} data-testid={`sdo-add-${node}`}>
            Add line
          </Button>
          <Text size="11px" c="dimmed">
            Written in order in Pre-Op, after the PDO map. Values: decimal, or hex as 0x1F or 1Fh.
          </Text>
        </Group>
      </div>
      <StartupLog slave={slave} />
    </div>
  );
}
