import { ActionIcon, Alert, Badge, Group, NumberInput, Table, Text, Tooltip } from "@mantine/core";
import { IconAlertTriangle, IconArrowDown, IconArrowUp, IconLock, IconTrash } from "@tabler/icons-react";
import { Fragment } from "react";
import type { DeviceDescription, PdoOut, SlaveOut } from "../../api/types";
import { byteBits, hex, hexH, objKey, sizeText } from "../../lib/hex";
import { type ObjectInfo, assignOf, bitsOf, dirOfPdo, objId, pdoStarts } from "../../lib/pdo";
import { type EntryDraft, type PdoEditor, moveEntry, removeEntry, setBitLen } from "../../store/pdoEditor";
import { Panel } from "../common/Panel";
import { AddEntryPopover } from "./AddEntryPopover";

interface RowProps {
  node: number;
  pdo: PdoOut;
  row: number;
  count: number;
  e: EntryDraft;
  bit: number;
  info: ObjectInfo | undefined;
  emulated: boolean | undefined;
  editable: boolean;
  disabled: boolean;
  selected: boolean;
  errors: string[];
  onSelect: () => void;
}

function EntryRow({ node, pdo, row, count, e, bit, info, emulated, editable, disabled, selected, errors, onSelect }: RowProps) {
  const pad = e.index === 0;
  const mismatch = !pad && info !== undefined && info.bit_len > 0 && info.bit_len !== e.bit_len;
  const testId = pad ? `pdo-entry-pad-${row}` : `pdo-entry-${hex(e.index)}-${hex(e.subindex, 2)}`;
  return (
    <Fragment>
      <Table.Tr
        className="pdo-entry-row"
        data-testid={testId}
        data-row={row}
        data-selected={selected ? "true" : undefined}
        data-invalid={errors.length ? "true" : undefined}
        onClick={onSelect}
      >
        <Table.Td className="num" c="dimmed">{row + 1}</Table.Td>
        <Table.Td className="num">{objKey(e.index, e.subindex)}</Table.Td>
        <Table.Td>
          {pad ? (
            <Text size="xs" c="dimmed" fs="italic">Padding</Text>
          ) : (
            <Group gap={4} wrap="nowrap">
              <Text size="xs" truncate="end" title={info?.name}>{info?.name || "(not in the dictionary)"}</Text>
              {emulated === false && (
                <Tooltip label="The emulated device does not model this object: it travels as zeros" openDelay={200}>
                  <Badge size="xs" variant="outline" color="gray" radius="xs" px={3} style={{ flex: "none" }}>not emulated</Badge>
                </Tooltip>
              )}
            </Group>
          )}
        </Table.Td>
        <Table.Td>
          <Text size="xs" ff="monospace">{pad ? "" : (info?.data_type ?? "")}</Text>
        </Table.Td>
        <Table.Td className="num">
          {editable ? (
            <Group gap={4} wrap="nowrap" justify="flex-end">
              {mismatch && (
                <Tooltip label={`The object dictionary gives ${info?.bit_len} bits`}>
                  <IconAlertTriangle size={13} color="var(--mantine-color-orange-6)" />
                </Tooltip>
              )}
              <NumberInput
                size="xs"
                w={52}
                value={e.bit_len}
                min={1}
                max={64}
                allowDecimal={false}
                allowNegative={false}
                disabled={disabled}
                error={errors.length > 0 || e.bit_len < 1 || e.bit_len > 64}
                onChange={(v) => setBitLen(node, pdo.index, row, typeof v === "number" ? v : Number(v) || 0)}
                onClick={(ev) => ev.stopPropagation()}
                aria-label={`Bit length of entry ${row + 1}`}
                data-testid="entry-bits"
                styles={{ input: { textAlign: "right", height: 22, minHeight: 22, paddingRight: 6, fontVariantNumeric: "tabular-nums" } }}
              />
            </Group>
          ) : (
            e.bit_len
          )}
        </Table.Td>
        <Table.Td className="num">{byteBits(bit)}</Table.Td>
        <Table.Td className="num" c="dimmed">{sizeText(e.bit_len)}</Table.Td>
        <Table.Td>
          {editable && (
            <Group gap={0} wrap="nowrap" justify="flex-end" onClick={(ev) => ev.stopPropagation()}>
              <ActionIcon size="sm" disabled={disabled || row === 0} onClick={() => moveEntry(node, pdo.index, row, -1)}
                aria-label={`Move entry ${row + 1} up`} data-testid="entry-up">
                <IconArrowUp size={13} />
              </ActionIcon>
              <ActionIcon size="sm" disabled={disabled || row === count - 1} onClick={() => moveEntry(node, pdo.index, row, 1)}
                aria-label={`Move entry ${row + 1} down`} data-testid="entry-down">
                <IconArrowDown size={13} />
              </ActionIcon>
              <ActionIcon size="sm" color="red" disabled={disabled} onClick={() => removeEntry(node, pdo.index, row)}
                aria-label={`Delete entry ${row + 1}`} data-testid="entry-delete">
                <IconTrash size={13} />
              </ActionIcon>
            </Group>
          )}
        </Table.Td>
      </Table.Tr>
      {errors.map((msg, k) => (
        <Table.Tr key={k} className="pdo-entry-error">
          <Table.Td />
          <Table.Td colSpan={7}>
            <Text size="11px" c="red.7" data-testid={`pdo-entry-error-${row}`} role="alert">
              {msg}
            </Text>
          </Table.Td>
        </Table.Tr>
      ))}
    </Fragment>
  );
}

interface Props {
  node: number;
  slave: SlaveOut;
  device: DeviceDescription | null;
  ed: PdoEditor;
  objects: ReadonlyMap<string, ObjectInfo>;
  selectedRow: number | null;
  onSelectRow: (row: number | null) => void;
}

/** The entries of the selected PDO: object, name, type, bit length, offset in the image, size; editable unless fixed. */
export function PdoEntries({ node, slave, device, ed, objects, selectedRow, onSelectRow }: Props) {
  const dir = dirOfPdo(ed.selected);
  const pdo = (dir === "rx" ? slave.rx_pdos : slave.tx_pdos).find((p) => p.index === ed.selected);
  if (!pdo) return null;
  const rows = ed.draft.entries[pdo.index] ?? [];
  const assigned = assignOf(ed.draft, dir).includes(pdo.index);
  const start = assigned ? (pdoStarts(ed.draft, dir).get(pdo.index) ?? 0) : 0;
  const maxEntries = device?.max_entries_per_pdo ?? 254;
  // Whether the emulator models an object is known for what is applied (unassigned PDOs show their defaults).
  const applied = new Map(pdo.assigned ? pdo.entries.map((e) => [objId(e.index, e.subindex), e.emulated]) : []);
  const editable = !pdo.fixed;
  const pdoIssues = ed.issues.filter((i) => i.target.kind === "pdo" && i.target.pdo === pdo.index);
  const rowErrors = (row: number) =>
    ed.issues.filter((i) => i.target.kind === "entry" && i.target.pdo === pdo.index && i.target.row === row).map((i) => i.msg);
  const after = selectedRow !== null && selectedRow < rows.length ? selectedRow : null;
  const addBlocked = pdo.fixed
    ? `${hexH(pdo.index)} is fixed: its entries cannot be changed`
    : rows.length >= maxEntries
      ? `${hexH(pdo.index)} takes at most ${maxEntries} entries`
      : ed.applying
        ? "Applying…"
        : null;
  let bit = start;

  return (
    <Panel
      testId="pdo-entries"
      bodyPadding={0}
      title={
        <Group gap={8} wrap="nowrap" style={{ minWidth: 0 }}>
          <span className="num" style={{ textTransform: "none" }}>{hex(pdo.index)}h</span>
          <Text span size="xs" fw={600} tt="none" c="dark" truncate="end">{pdo.name}</Text>
          {pdo.fixed && (
            <Badge size="xs" color="gray" variant="light" leftSection={<IconLock size={10} />} style={{ textTransform: "none" }}
              data-testid="pdo-fixed">
              fixed
            </Badge>
          )}
          {!assigned && (
            <Badge size="xs" color="gray" variant="outline" style={{ textTransform: "none" }}>not assigned</Badge>
          )}
        </Group>
      }
      right={
        <AddEntryPopover node={node} pdo={pdo.index} dir={dir} objects={objects} draft={ed.draft} after={after}
          disabledReason={addBlocked} />
      }
    >
      {pdoIssues.map((i, k) => (
        <Alert key={k} color="red" variant="light" py={4} px={8} radius={0} data-testid="pdo-mapping-error"
          icon={<IconAlertTriangle size={14} />}>
          <Text size="xs">{i.msg}</Text>
        </Alert>
      ))}
      <Table highlightOnHover data-testid="pdo-entry-table" className="pdo-entry-table" layout="fixed">
        <Table.Thead>
          <Table.Tr>
            <Table.Th w={30} className="num">#</Table.Th>
            <Table.Th w={96}>Index:Sub</Table.Th>
            <Table.Th>Name</Table.Th>
            <Table.Th w={84}>Data type</Table.Th>
            <Table.Th w={82} className="num">Bit length</Table.Th>
            <Table.Th w={64} className="num">
              <Tooltip label={assigned ? "Offset in the slave's image of this direction (bytes.bits)" : "Offset within this PDO (bytes.bits): it is not assigned"}>
                <span>Offset</span>
              </Tooltip>
            </Table.Th>
            <Table.Th w={74} className="num">Size</Table.Th>
            <Table.Th w={editable ? 84 : 8} />
          </Table.Tr>
        </Table.Thead>
        <Table.Tbody>
          {rows.length === 0 && (
            <Table.Tr>
              <Table.Td colSpan={8}>
                <Text size="xs" c="dimmed" ta="center" py={6}>No entries{editable ? ": add objects from the dictionary" : ""}.</Text>
              </Table.Td>
            </Table.Tr>
          )}
          {rows.map((e, row) => {
            const here = bit;
            bit += e.bit_len;
            return (
              <EntryRow key={e.key} node={node} pdo={pdo} row={row} count={rows.length} e={e} bit={here}
                info={objects.get(objId(e.index, e.subindex))} emulated={e.index ? applied.get(objId(e.index, e.subindex)) : undefined}
                editable={editable} disabled={ed.applying} selected={selectedRow === row} errors={rowErrors(row)}
                onSelect={() => onSelectRow(selectedRow === row ? null : row)} />
            );
          })}
        </Table.Tbody>
      </Table>
      <Group justify="space-between" px={8} py={4} className="pdo-entry-footer">
        <Text size="11px" c="dimmed" data-testid="pdo-entry-summary">
          {rows.length} entr{rows.length === 1 ? "y" : "ies"}{editable ? ` (at most ${maxEntries})` : ""} · {bitsOf(rows)} bits
          = {sizeText(bitsOf(rows))}
        </Text>
        {editable && (
          <Text size="11px" c="dimmed">Click a row to insert after it.</Text>
        )}
      </Group>
    </Panel>
  );
}
