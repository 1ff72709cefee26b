import { Button, Group, NumberInput, Popover, SegmentedControl, Select, Stack, Text, Tooltip } from "@mantine/core";
import { IconPlus } from "@tabler/icons-react";
import { useMemo, useState } from "react";
import { hex, hexH } from "../../lib/hex";
import { type Dir, type ObjectInfo, assignOf } from "../../lib/pdo";
import { type PdoDraft, addEntry } from "../../store/pdoEditor";

interface Props {
  node: number;
  pdo: number;
  dir: Dir;
  objects: ReadonlyMap<string, ObjectInfo>;
  draft: PdoDraft;
  /** Insert after this row (at the end when null). */
  after: number | null;
  /** Why nothing can be added, or null. */
  disabledReason: string | null;
}

/** Where each object is mapped in the draft (this PDO, or another assigned PDO of the direction). */
function mappedIn(draft: PdoDraft, dir: Dir, pdo: number): Map<string, number> {
  const out = new Map<string, number>();
  for (const idx of new Set([pdo, ...assignOf(draft, dir)])) {
    for (const e of draft.entries[idx] ?? []) if (e.index) out.set(`${e.index}:${e.subindex}`, idx);
  }
  return out;
}

/** Add an object of the device's dictionary that may be mapped in this direction, or a padding gap. */
export function AddEntryPopover({ node, pdo, dir, objects, draft, after, disabledReason }: Props) {
  const [opened, setOpened] = useState(false);
  const [mode, setMode] = useState<"object" | "padding">("object");
  const [pick, setPick] = useState<string | null>(null);
  const [padBits, setPadBits] = useState<number | string>(8);
  const flag = dir === "rx" ? "R" : "T";

  const options = useMemo(() => {
    const used = mappedIn(draft, dir, pdo);
    const list: { value: string; label: string; disabled: boolean }[] = [];
    const keys = [...objects.keys()].sort((a, b) => {
      const [ai, as] = a.split(":").map(Number);
      const [bi, bs] = b.split(":").map(Number);
      return ai - bi || as - bs;
    });
    for (const k of keys) {
      const o = objects.get(k);
      if (!o || !o.mapping.includes(flag) || !o.bit_len) continue;
      const [index, sub] = k.split(":").map(Number);
      const where = used.get(k);
      list.push({
        value: k,
        label: `${hex(index)}h:${hex(sub, 2)}h  ${o.name} · ${o.data_type || "?"} · ${o.bit_len} bit${where !== undefined ? ` (mapped in ${hexH(where)})` : ""}`,
        disabled: where !== undefined,
      });
    }
    return list;
  }, [objects, draft, dir, pdo, flag]);

  const bits = typeof padBits === "number" ? padBits : Number(padBits);
  const padOk = Number.isInteger(bits) && bits >= 1 && bits <= 64;
  const chosen = pick ? objects.get(pick) : undefined;
  const canAdd = mode === "padding" ? padOk : chosen !== undefined;

  const add = () => {
    if (mode === "padding") {
      if (!padOk) return;
      addEntry(node, pdo, { index: 0, subindex: 0, bit_len: bits }, after);
    } else {
      if (!pick || !chosen) return;
      const [index, subindex] = pick.split(":").map(Number);
      addEntry(node, pdo, { index, subindex, bit_len: chosen.bit_len }, after);
      setPick(null);
    }
    setOpened(false);
  };

  return (
    <Popover opened={opened} onChange={setOpened} position="bottom-end" shadow="md" width={440} trapFocus withinPortal>
      <Popover.Target>
        <Tooltip label={disabledReason ?? (after !== null ? `Insert after entry ${after + 1}` : "Append an entry")}
          openDelay={300}>
          <Button size="compact-xs" variant="light" leftSection={<IconPlus size={13} />} disabled={disabledReason !== null}
            onClick={() => setOpened((o) => !o)} data-testid="pdo-add-entry">
            Add entry
          </Button>
        </Tooltip>
      </Popover.Target>
      <Popover.Dropdown data-testid="pdo-add-dialog">
        <Stack gap={8}>
          <Text size="xs" fw={700}>
            Add to {hexH(pdo)} {after !== null ? `after entry ${after + 1}` : "at the end"}
          </Text>
          <SegmentedControl fullWidth value={mode} onChange={(v) => setMode(v === "padding" ? "padding" : "object")}
            data={[{ value: "object", label: "Object" }, { value: "padding", label: "Padding" }]}
            data-testid="pdo-add-mode" />
          {mode === "object" ? (
            <Select
              size="xs"
              searchable
              placeholder={`Objects mappable into ${dir === "rx" ? "RxPDOs (R)" : "TxPDOs (T)"}`}
              data={options}
              value={pick}
              onChange={setPick}
              nothingFoundMessage="No object of the dictionary matches"
              maxDropdownHeight={240}
              comboboxProps={{ withinPortal: false }}
              styles={{ option: { fontSize: 12, fontFamily: "var(--mantine-font-family-monospace)" } }}
              data-testid="pdo-add-object"
            />
          ) : (
            <NumberInput label="Gap [bit]" value={padBits} onChange={setPadBits} min={1} max={64} allowDecimal={false}
              error={padOk ? undefined : "1–64 bits"} data-testid="pdo-add-padding-bits" w={120} />
          )}
          <Group justify="flex-end" gap={6}>
            <Button variant="default" size="compact-xs" onClick={() => setOpened(false)}>Cancel</Button>
            <Button size="compact-xs" disabled={!canAdd} onClick={add} data-testid="pdo-add-confirm">Add</Button>
          </Group>
        </Stack>
      </Popover.Dropdown>
    </Popover>
  );
}
