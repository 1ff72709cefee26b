/**
 * The PDO map editor: one draft per slave (by node address), kept outside React so that it survives switching
 * tabs and polling, and so that the tab title can show unsaved changes.
 *
 * The draft holds the assignment (1C12h / 1C13h) and the entries of every PDO of the device. Apply sends
 * PUT /api/v1/ethercat/slaves/{address}/pdo with the assigned PDOs' mappings; the controller validates it against
 * the device description (422 with `path` such as `mappings[0].entries[3].bit_len`, mapped back to the row) and
 * restarts like a download (409 while an axis moves).
 */
import { ApiError, api, formatLoc, unwrap } from "../api/client";
import type { DeviceDescription, SlaveOut, SlavePdoConfig } from "../api/types";
import { hexH } from "../lib/hex";
import { type Dir, type EntryLike, dirOfPdo } from "../lib/pdo";
import { notifyOk } from "../lib/notify";
import { createStore } from "./createStore";
import { loadEthercat, putSlave } from "./ethercat";

export interface EntryDraft extends EntryLike {
  /** Stable React key of the row. */
  key: number;
}

export interface PdoDraft {
  rx_assign: readonly number[];
  tx_assign: readonly number[];
  /** Entries of every PDO of the device, by PDO index. */
  entries: Readonly<Record<number, readonly EntryDraft[]>>;
}

export type IssueTarget =
  | { kind: "assign"; dir: Dir; pdo: number | null }
  | { kind: "pdo"; pdo: number }
  | { kind: "entry"; pdo: number; row: number; field: string | null }
  | { kind: "general" };

export interface PdoIssue {
  target: IssueTarget;
  /** Where the API located it, e.g. `mappings[0].entries[3].bit_len`. */
  path: string;
  msg: string;
}

export interface PdoEditor {
  device: string;
  base: PdoDraft;
  draft: PdoDraft;
  dirty: boolean;
  /** The PDO whose entries are shown. */
  selected: number;
  issues: PdoIssue[];
  refusal: { status: number | null; message: string } | null;
  applying: boolean;
}

export const pdoEditorStore = createStore<Readonly<Record<number, PdoEditor>>>({});

let nextKey = 1;

function entry(e: EntryLike): EntryDraft {
  return { key: nextKey++, index: e.index, subindex: e.subindex, bit_len: e.bit_len };
}

function fromSlave(slave: SlaveOut): PdoDraft {
  const entries: Record<number, EntryDraft[]> = {};
  for (const p of [...slave.rx_pdos, ...slave.tx_pdos]) entries[p.index] = p.entries.map(entry);
  return { rx_assign: slave.rx_assign, tx_assign: slave.tx_assign, entries };
}

function sameEntries(a: readonly EntryLike[] | undefined, b: readonly EntryLike[] | undefined): boolean {
  if (!a || !b) return a === b;
  return a.length === b.length && a.every((e, i) => e.index === b[i].index && e.subindex === b[i].subindex && e.bit_len === b[i].bit_len);
}

function sameList(a: readonly number[], b: readonly number[]): boolean {
  return a.length === b.length && a.every((x, i) => x === b[i]);
}

function sameDraft(a: PdoDraft, b: PdoDraft): boolean {
  if (!sameList(a.rx_assign, b.rx_assign) || !sameList(a.tx_assign, b.tx_assign)) return false;
  const keys = new Set([...Object.keys(a.entries), ...Object.keys(b.entries)].map(Number));
  for (const k of keys) if (!sameEntries(a.entries[k], b.entries[k])) return false;
  return true;
}

function fresh(slave: SlaveOut, selected?: number): PdoEditor {
  const base = fromSlave(slave);
  const first = slave.rx_assign[0] ?? slave.rx_pdos[0]?.index ?? slave.tx_pdos[0]?.index ?? 0;
  const known = selected !== undefined && selected in base.entries;
  return {
    device: slave.device_id,
    base,
    draft: base,
    dirty: false,
    selected: known ? selected : first,
    issues: [],
    refusal: null,
    applying: false,
  };
}

function patch(node: number, fn: (ed: PdoEditor) => Partial<PdoEditor>): void {
  pdoEditorStore.set((s) => {
    const ed = s[node];
    if (!ed) return s;
    return { ...s, [node]: { ...ed, ...fn(ed) } };
  });
}

/** Start editing, or follow what the controller now has: an unchanged draft is replaced, a changed one kept. */
export function syncPdoEditor(node: number, slave: SlaveOut): void {
  pdoEditorStore.set((s) => {
    const ed = s[node];
    if (!ed || ed.device !== slave.device_id) return { ...s, [node]: fresh(slave) };
    const base = fromSlave(slave);
    if (sameDraft(base, ed.base)) return s;
    if (!ed.dirty) return { ...s, [node]: { ...fresh(slave, ed.selected), issues: ed.issues, refusal: ed.refusal } };
    return { ...s, [node]: { ...ed, base, dirty: !sameDraft(ed.draft, base) } };
  });
}

/** Change the draft; issues about what changed are dropped (their rows may have moved). */
function edit(node: number, fn: (d: PdoDraft) => PdoDraft, touched: IssueTarget): void {
  patch(node, (ed) => {
    const draft = fn(ed.draft);
    const issues = ed.issues.filter((i) => !touches(i.target, touched));
    return { draft, dirty: !sameDraft(draft, ed.base), issues, refusal: null };
  });
}

function touches(issue: IssueTarget, touched: IssueTarget): boolean {
  if (issue.kind === "general") return false;
  if (touched.kind === "assign") return issue.kind === "assign" && issue.dir === touched.dir;
  if (touched.kind === "pdo" || touched.kind === "entry") {
    return (issue.kind === "pdo" || issue.kind === "entry") && issue.pdo === touched.pdo;
  }
  return false;
}

/** How many parts differ from what the controller runs: each assignment list and each PDO's entries. */
export function changeCount(ed: PdoEditor): number {
  let n = (sameList(ed.draft.rx_assign, ed.base.rx_assign) ? 0 : 1) + (sameList(ed.draft.tx_assign, ed.base.tx_assign) ? 0 : 1);
  for (const k of Object.keys(ed.draft.entries).map(Number)) if (!sameEntries(ed.draft.entries[k], ed.base.entries[k])) n++;
  return n;
}

export function selectPdo(node: number, pdo: number): void {
  patch(node, () => ({ selected: pdo }));
}

/** Assign or unassign a PDO; a newly assigned PDO takes its place in the device's order. */
export function setAssigned(node: number, pdo: number, on: boolean, deviceOrder: readonly number[]): void {
  const dir = dirOfPdo(pdo);
  edit(
    node,
    (d) => {
      const cur = dir === "rx" ? d.rx_assign : d.tx_assign;
      let next = cur.filter((x) => x !== pdo);
      if (on) {
        const pos = (x: number) => {
          const i = deviceOrder.indexOf(x);
          return i < 0 ? Number.MAX_SAFE_INTEGER : i;
        };
        next = [...next, pdo].sort((a, b) => pos(a) - pos(b));
      }
      return dir === "rx" ? { ...d, rx_assign: next } : { ...d, tx_assign: next };
    },
    { kind: "assign", dir, pdo },
  );
}

function editEntries(node: number, pdo: number, fn: (rows: EntryDraft[]) => EntryDraft[]): void {
  edit(node, (d) => ({ ...d, entries: { ...d.entries, [pdo]: fn([...(d.entries[pdo] ?? [])]) } }), { kind: "pdo", pdo });
}

/** Insert an entry after row `after` (at the end when null). */
export function addEntry(node: number, pdo: number, e: EntryLike, after: number | null): void {
  editEntries(node, pdo, (rows) => {
    rows.splice(after === null ? rows.length : after + 1, 0, entry(e));
    return rows;
  });
}

export function removeEntry(node: number, pdo: number, row: number): void {
  editEntries(node, pdo, (rows) => rows.filter((_, i) => i !== row));
}

export function moveEntry(node: number, pdo: number, row: number, by: -1 | 1): void {
  editEntries(node, pdo, (rows) => {
    const to = row + by;
    if (to < 0 || to >= rows.length) return rows;
    [rows[row], rows[to]] = [rows[to], rows[row]];
    return rows;
  });
}

export function setBitLen(node: number, pdo: number, row: number, bitLen: number): void {
  editEntries(node, pdo, (rows) => rows.map((r, i) => (i === row ? { ...r, bit_len: bitLen } : r)));
}

export function revertPdo(node: number): void {
  patch(node, (ed) => ({ draft: ed.base, dirty: false, issues: [], refusal: null }));
}

/** The device description's default: the PDOs it assigns to a sync manager (or mandatory), default entries. */
export function resetToDefault(node: number, device: DeviceDescription): void {
  patch(node, (ed) => {
    const rx = (device.rx_pdos ?? []).filter((p) => p.sm != null || p.mandatory).map((p) => p.index);
    const tx = (device.tx_pdos ?? []).filter((p) => p.sm != null || p.mandatory).map((p) => p.index);
    const entries: Record<number, readonly EntryDraft[]> = { ...ed.draft.entries };
    for (const p of [...(device.rx_pdos ?? []), ...(device.tx_pdos ?? [])]) {
      const given = p.entries ?? [];
      entries[p.index] = sameEntries(ed.draft.entries[p.index], given)
        ? [...(ed.draft.entries[p.index] ?? [])]
        : given.map((e) => entry({ index: e.index, subindex: e.subindex ?? 0, bit_len: e.bit_len }));
    }
    const draft: PdoDraft = { rx_assign: rx, tx_assign: tx, entries };
    return { draft, dirty: !sameDraft(draft, ed.base), issues: [], refusal: null };
  });
}

// ------------------------------------------------------------------ apply

function bodyOf(d: PdoDraft): SlavePdoConfig {
  return {
    rx_assign: [...d.rx_assign],
    tx_assign: [...d.tx_assign],
    mappings: [...d.rx_assign, ...d.tx_assign].map((index) => ({
      index,
      entries: (d.entries[index] ?? []).map(({ index: i, subindex, bit_len }) => ({ index: i, subindex, bit_len })),
    })),
  };
}

interface DetailItem {
  loc?: (string | number)[];
  msg?: string;
  path?: string;
}

/** `mappings[0].entries[3].bit_len` → the row of the PDO sent first; `rx_assign[1]` → the Rx list. */
export function targetOf(path: string, body: SlavePdoConfig): IssueTarget {
  const a = /^(rx|tx)_assign(?:\[(\d+)\])?/.exec(path);
  if (a) {
    const dir = a[1] as Dir;
    const list = (dir === "rx" ? body.rx_assign : body.tx_assign) ?? [];
    return { kind: "assign", dir, pdo: a[2] !== undefined ? (list[Number(a[2])] ?? null) : null };
  }
  const m = /^mappings\[(\d+)\](?:\.entries\[(\d+)\](?:\.(\w+))?)?/.exec(path);
  if (m) {
    const pdo = body.mappings?.[Number(m[1])]?.index;
    if (pdo === undefined) return { kind: "general" };
    if (m[2] !== undefined) return { kind: "entry", pdo, row: Number(m[2]), field: m[3] ?? null };
    return { kind: "pdo", pdo };
  }
  return { kind: "general" };
}

function issuesOf(detail: unknown, body: SlavePdoConfig): PdoIssue[] {
  if (!Array.isArray(detail)) return [{ target: { kind: "general" }, path: "", msg: String(detail) }];
  return (detail as DetailItem[]).map((d) => {
    const path = typeof d.path === "string" ? d.path : formatLoc(d.loc ?? []);
    const msg = (d.msg ?? "invalid").replace(/^Value error, /, "");
    return { target: targetOf(path, body), path, msg };
  });
}

/** PUT the draft. Returns true when it was applied (the controller restarted). */
export async function applyPdo(node: number, slaveName: string): Promise<boolean> {
  const ed = pdoEditorStore.get()[node];
  if (!ed || ed.applying) return false;
  patch(node, () => ({ applying: true, refusal: null }));
  const body = bodyOf(ed.draft);
  try {
    const slave = await unwrap(
      api.PUT("/api/v1/ethercat/slaves/{address}/pdo", { params: { path: { address: node } }, body }),
    );
    putSlave(slave);
    pdoEditorStore.set((s) => ({ ...s, [node]: fresh(slave, ed.selected) }));
    notifyOk("PDO map applied — the controller restarted at cycle 0", `${slaveName}: save the project to keep it`);
    void loadEthercat();
    return true;
  } catch (err) {
    if (err instanceof ApiError && err.status === 422) {
      patch(node, () => ({ applying: false, issues: issuesOf(err.detail, body) }));
    } else {
      const status = err instanceof ApiError ? err.status : null;
      const message = err instanceof Error ? err.message : String(err);
      patch(node, () => ({ applying: false, issues: [], refusal: { status, message } }));
    }
    return false;
  }
}

/** A readable name of where an issue is, for the summary. */
export function issuePlace(t: IssueTarget): string {
  switch (t.kind) {
    case "assign":
      return `${t.dir === "rx" ? "1C12h" : "1C13h"}${t.pdo !== null ? ` · ${hexH(t.pdo)}` : ""}`;
    case "pdo":
      return hexH(t.pdo);
    case "entry":
      return `${hexH(t.pdo)} · entry ${t.row + 1}`;
    default:
      return "";
  }
}
