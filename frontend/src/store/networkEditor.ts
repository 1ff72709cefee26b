/**
 * The network configuration editor of the EtherCAT view: a draft per slave (name, node address, position in the wiring
 * order, start-up SDO list, commissioning drill) and one for the master settings, kept outside React so that they
 * survive polling and switching tabs. Apply sends one edit through `applyNetwork` (store/network.ts); the problems of
 * a 422 are placed on the fields of the form that made the edit (`ethercat.slaves[k].startup_sdos[2].index` → that
 * cell; a node address already in use, reported on the other slave, and `axes[i].node_address` of the slave's axis →
 * the node address field); a 409 says that an axis is moving.
 */
import type { EtherCATMasterConfig, StartupSdo } from "../api/types";
import { hex } from "../lib/hex";
import { notifyOk } from "../lib/notify";
import { createStore } from "./createStore";
import type { NumValue } from "./forms";
import {
  type AxisRef,
  type NetConfig,
  type NetIssue,
  type SlaveConfig,
  DEFAULT_EMULATION,
  applyNetwork,
  axisOfNode,
} from "./network";
import { pdoEditorStore } from "./pdoEditor";
import { retargetPdoTab } from "./tabs";

export type SlaveTab = "general" | "sdo" | "drill";

export const SDO_SIZES = ["8", "16", "32", "64"] as const;
export type SdoSize = (typeof SDO_SIZES)[number];

export interface SdoDraft {
  /** Stable React key of the row. */
  key: number;
  /** Object index in hex, as typed (`6065`, `6065h`, `0x6065`). */
  index: string;
  subindex: NumValue;
  /** Decimal, or hex with `0x` / `h`; may be negative. */
  value: string;
  bit_len: SdoSize;
  abort_on_error: boolean;
  comment: string;
}

export interface SlaveDraft {
  name: string;
  node_address: NumValue;
  /** Position in the wiring order, 0-based. */
  position: number;
  /** Move the axis that uses this slave to the new node address along with it. */
  moveAxis: boolean;
  startup_sdos: SdoDraft[];
  connected: boolean;
  wired_device: string | null;
  encoder_velocity: NumValue;
}

/** A problem of a form: its field (`node_address`, `startup_sdos[2].value`, `emulation.wired_device`; "" = none). */
export interface FieldIssue {
  field: string;
  msg: string;
  /** Where the API located it (empty for the studio's own checks). */
  path: string;
}

export interface Refusal {
  status: number | null;
  message: string;
}

export interface SlaveEditor {
  /** Node address of the slave as the controller has it. */
  node: number;
  open: boolean;
  tab: SlaveTab;
  base: SlaveConfig;
  basePosition: number;
  draft: SlaveDraft;
  dirty: boolean;
  issues: FieldIssue[];
  refusal: Refusal | null;
  applying: boolean;
}

export const slaveEditorStore = createStore<Readonly<Record<number, SlaveEditor>>>({});

let nextKey = 1;

// ------------------------------------------------------------------ values

/** `6065`, `6065h`, `0x6065` → 0x6065 (null when it is not hex). */
export function parseHexIndex(text: string): number | null {
  const t = text.trim().replace(/h$/i, "").replace(/^0x/i, "");
  if (!/^[0-9a-f]{1,4}$/i.test(t)) return null;
  return parseInt(t, 16);
}

/** `-5`, `5000`, `0x1F`, `1Fh` → the integer (null when it is none, or beyond what a JSON number carries exactly). */
export function parseSdoValue(text: string): number | null {
  const t = text.trim().replace(/_/g, "");
  let v: number;
  if (/^-?\d+$/.test(t)) v = Number(t);
  else if (/^-?0x[0-9a-f]+$/i.test(t)) v = (t.startsWith("-") ? -1 : 1) * parseInt(t.replace(/^-?0x/i, ""), 16);
  else if (/^-?[0-9a-f]+h$/i.test(t)) v = (t.startsWith("-") ? -1 : 1) * parseInt(t.replace(/^-/, "").slice(0, -1), 16);
  else return null;
  return Number.isSafeInteger(v) ? v : null;
}

function sdoDraft(s: StartupSdo): SdoDraft {
  return {
    key: nextKey++,
    index: hex(s.index),
    subindex: s.subindex ?? 0,
    value: String(s.value),
    bit_len: String(s.bit_len ?? 32) as SdoSize,
    abort_on_error: s.abort_on_error ?? true,
    comment: s.comment ?? "",
  };
}

export function newSdoRow(): SdoDraft {
  return { key: nextKey++, index: "", subindex: 0, value: "0", bit_len: "32", abort_on_error: true, comment: "" };
}

function draftOf(cfg: SlaveConfig, position: number): SlaveDraft {
  return {
    name: cfg.name,
    node_address: cfg.node_address,
    position,
    moveAxis: true,
    startup_sdos: cfg.startup_sdos.map(sdoDraft),
    connected: cfg.emulation.connected,
    wired_device: cfg.emulation.wired_device,
    encoder_velocity: cfg.emulation.encoder_velocity,
  };
}

/** What decides whether a draft differs from what the controller runs (row keys and the axis option aside). */
function signature(d: SlaveDraft): string {
  const num = (v: NumValue) => String(v).trim();
  return JSON.stringify([
    d.name,
    num(d.node_address),
    d.position,
    d.connected,
    d.wired_device,
    num(d.encoder_velocity),
    d.startup_sdos.map((s) => [
      parseHexIndex(s.index) ?? s.index.trim(),
      num(s.subindex),
      parseSdoValue(s.value) ?? s.value.trim(),
      s.bit_len,
      s.abort_on_error,
      s.comment,
    ]),
  ]);
}

const isInt = (v: NumValue): v is number => typeof v === "number" && Number.isInteger(v);

function fits(value: number, bits: number): boolean {
  if (bits >= 64) return true;
  return value >= -(2 ** (bits - 1)) && value <= 2 ** bits - 1;
}

/** The studio's own checks of a slave draft (the controller's stay authoritative). */
export function slaveDraftProblems(d: SlaveDraft): FieldIssue[] {
  const out: FieldIssue[] = [];
  const add = (field: string, msg: string) => out.push({ field, msg, path: "" });
  if (d.name.length > 63) add("name", "at most 63 characters");
  if (!isInt(d.node_address) || d.node_address < 1 || d.node_address > 65534) add("node_address", "an integer from 1 to 65534");
  d.startup_sdos.forEach((s, i) => {
    const idx = parseHexIndex(s.index);
    if (idx === null) add(`startup_sdos[${i}].index`, "the object index in hex, e.g. 6065");
    else if (idx < 0x1000) add(`startup_sdos[${i}].index`, "from 1000h to FFFFh");
    if (!isInt(s.subindex) || s.subindex < 0 || s.subindex > 255) add(`startup_sdos[${i}].subindex`, "0 to 255");
    const v = parseSdoValue(s.value);
    if (v === null) add(`startup_sdos[${i}].value`, "an integer (decimal, or hex as 0x1F / 1Fh)");
    else if (!fits(v, Number(s.bit_len))) add(`startup_sdos[${i}].value`, `does not fit in ${s.bit_len} bits`);
    if (s.comment.length > 200) add(`startup_sdos[${i}].comment`, "at most 200 characters");
  });
  if (typeof d.encoder_velocity !== "number" || Math.abs(d.encoder_velocity) > 1e9) {
    add("emulation.encoder_velocity", "a number within ±1e9 pulse/s");
  }
  return out;
}

/** The slave the draft describes, on top of the slave as the controller has it now (its device and PDO map kept). */
function slaveFromDraft(current: SlaveConfig, d: SlaveDraft): SlaveConfig {
  return {
    ...current,
    name: d.name,
    node_address: Number(d.node_address),
    startup_sdos: d.startup_sdos.map((s) => ({
      index: parseHexIndex(s.index) ?? 0,
      subindex: Number(s.subindex),
      value: parseSdoValue(s.value) ?? 0,
      bit_len: Number(s.bit_len) as StartupSdo["bit_len"],
      abort_on_error: s.abort_on_error,
      comment: s.comment,
    })),
    emulation: {
      ...DEFAULT_EMULATION,
      connected: d.connected,
      wired_device: d.wired_device,
      encoder_velocity: Number(d.encoder_velocity),
    },
  };
}

/** Which tab of the slave editor shows a field. */
export function tabOfField(field: string): SlaveTab {
  if (field.startsWith("startup_sdos")) return "sdo";
  if (field.startsWith("emulation")) return "drill";
  return "general";
}

// ------------------------------------------------------------------ placing the controller's problems

/**
 * A problem of the controller as the form of slave `k` (in what was sent) shows it: on its own fields; a node address
 * it now shares with another slave (reported on that one when it comes later) and a problem of the axis that used
 * the slave (by its node before or after the edit) on its node address field; anything else without a field.
 */
export function placeSlaveIssue(i: NetIssue, body: NetConfig, k: number, oldNode: number | null): FieldIssue {
  const newNode = body.slaves[k]?.node_address ?? null;
  if (i.slave === k) {
    const field = i.field.startsWith("pdo") ? "" : i.field;
    return { field, msg: i.msg, path: i.path };
  }
  if (i.slave !== null && i.field === "node_address" && i.node !== null && i.node === newNode) {
    const other = body.slaves[i.slave];
    return {
      field: "node_address",
      msg: `node address ${newNode} is already used by ${other?.name || `slave ${i.slave + 1}`} (position ${i.slave + 1})`,
      path: i.path,
    };
  }
  if (i.axis !== null && i.axisNode !== null && (i.axisNode === oldNode || i.axisNode === newNode)) {
    return { field: "node_address", msg: `${i.axis}: ${i.msg}`, path: i.path };
  }
  const where = i.slave !== null ? `${body.slaves[i.slave]?.name || `slave ${i.slave + 1}`}: ` : i.axis ? `${i.axis}: ` : "";
  return { field: "", msg: where + i.msg, path: i.path };
}

// ------------------------------------------------------------------ slave editors

function patch(node: number, fn: (ed: SlaveEditor) => Partial<SlaveEditor>): void {
  slaveEditorStore.set((s) => {
    const ed = s[node];
    if (!ed) return s;
    return { ...s, [node]: { ...ed, ...fn(ed) } };
  });
}

function fresh(cfg: SlaveConfig, position: number, keep?: Pick<SlaveEditor, "open" | "tab">): SlaveEditor {
  const draft = draftOf(cfg, position);
  return {
    node: cfg.node_address,
    open: keep?.open ?? false,
    tab: keep?.tab ?? "general",
    base: cfg,
    basePosition: position,
    draft,
    dirty: false,
    issues: [],
    refusal: null,
    applying: false,
  };
}

/** Start editing, or follow what the controller now has: an unchanged draft is replaced, a changed one kept. */
export function syncSlaveEditor(cfg: SlaveConfig, position: number): void {
  const node = cfg.node_address;
  slaveEditorStore.set((s) => {
    const ed = s[node];
    if (!ed) return { ...s, [node]: fresh(cfg, position) };
    if (ed.base === cfg && ed.basePosition === position) return s;
    if (!ed.dirty) return { ...s, [node]: { ...fresh(cfg, position, ed), issues: ed.issues, refusal: ed.refusal } };
    const dirty = signature(ed.draft) !== signature(draftOf(cfg, position));
    return { ...s, [node]: { ...ed, base: cfg, basePosition: position, dirty } };
  });
}

export function toggleSlaveEditor(cfg: SlaveConfig, position: number, open?: boolean, tab?: SlaveTab): void {
  syncSlaveEditor(cfg, position);
  patch(cfg.node_address, (ed) => ({ open: open ?? !ed.open, tab: tab ?? ed.tab }));
}

export function setSlaveTab(node: number, tab: SlaveTab): void {
  patch(node, () => ({ tab }));
}

/** Change the draft; the controller's problems with the fields touched are dropped. */
export function editSlave(node: number, fn: (d: SlaveDraft) => SlaveDraft, touched?: (field: string) => boolean): void {
  patch(node, (ed) => {
    const draft = fn(ed.draft);
    const dirty = signature(draft) !== signature(draftOf(ed.base, ed.basePosition));
    const issues = touched ? ed.issues.filter((i) => !i.field || !touched(i.field)) : ed.issues;
    return { draft, dirty, issues, refusal: null };
  });
}

export function setSlaveField<K extends keyof SlaveDraft>(node: number, key: K, value: SlaveDraft[K]): void {
  const field = key === "connected" || key === "wired_device" || key === "encoder_velocity" ? `emulation.${key}` : key;
  editSlave(node, (d) => ({ ...d, [key]: value }), (f) => f === field);
}

export function setSdo<K extends keyof SdoDraft>(node: number, row: number, key: K, value: SdoDraft[K]): void {
  editSlave(
    node,
    (d) => ({ ...d, startup_sdos: d.startup_sdos.map((s, i) => (i === row ? { ...s, [key]: value } : s)) }),
    (f) => f === `startup_sdos[${row}].${key}` || f === `startup_sdos[${row}]`,
  );
}

/** Rows move: the controller's problems with the SDO list no longer point at the right rows. */
const anySdo = (f: string) => f.startsWith("startup_sdos");

export function addSdo(node: number, after: number | null = null): void {
  editSlave(
    node,
    (d) => {
      const rows = [...d.startup_sdos];
      rows.splice(after === null ? rows.length : after + 1, 0, newSdoRow());
      return { ...d, startup_sdos: rows };
    },
    anySdo,
  );
}

export function removeSdo(node: number, row: number): void {
  editSlave(node, (d) => ({ ...d, startup_sdos: d.startup_sdos.filter((_, i) => i !== row) }), anySdo);
}

export function moveSdo(node: number, row: number, by: -1 | 1): void {
  editSlave(
    node,
    (d) => {
      const to = row + by;
      if (to < 0 || to >= d.startup_sdos.length) return d;
      const rows = [...d.startup_sdos];
      [rows[row], rows[to]] = [rows[to], rows[row]];
      return { ...d, startup_sdos: rows };
    },
    anySdo,
  );
}

export function revertSlave(node: number): void {
  patch(node, (ed) => ({ draft: draftOf(ed.base, ed.basePosition), dirty: false, issues: [], refusal: null }));
}

/** Forget the editors of slaves that are no longer in the network. */
export function pruneSlaveEditors(existing: readonly number[]): void {
  slaveEditorStore.set((s) => {
    const gone = Object.keys(s).map(Number).filter((n) => !existing.includes(n));
    if (!gone.length) return s;
    const next = { ...s };
    for (const n of gone) if (!next[n].applying) delete next[n];
    return next;
  });
}

/** Apply the slave's draft (PUT /api/v1/ethercat, or PUT /api/v1/project when its axis moves along). */
export async function applySlave(node: number, axes: readonly AxisRef[]): Promise<boolean> {
  const ed = slaveEditorStore.get()[node];
  if (!ed || ed.applying || slaveDraftProblems(ed.draft).length) return false;
  patch(node, () => ({ applying: true, refusal: null }));
  const d = ed.draft;
  const newNode = Number(d.node_address);
  const axis = axisOfNode(axes, node);
  const moveAxes = d.moveAxis && axis && newNode !== node ? { [axis.name]: newNode } : undefined;
  let k = -1;
  let sent: NetConfig | null = null;
  const res = await applyNetwork(
    (cfg) => {
      const at = cfg.slaves.findIndex((s) => s.node_address === node);
      if (at < 0) throw new Error(`no slave with node address ${node} in the network any more`);
      const slave = slaveFromDraft(cfg.slaves[at], d);
      const slaves = cfg.slaves.filter((_, i) => i !== at);
      k = Math.max(0, Math.min(d.position, slaves.length));
      slaves.splice(k, 0, slave);
      sent = { ...cfg, slaves };
      return sent;
    },
    { moveAxes },
  );
  if (res.ok) {
    const cfg = res.config.slaves[k];
    slaveEditorStore.set((s) => {
      const next = { ...s };
      delete next[node];
      next[newNode] = fresh(cfg, k, { open: ed.open, tab: ed.tab });
      return next;
    });
    if (newNode !== node) {
      retargetPdoTab(node, newNode);
      pdoEditorStore.set((s) => {
        if (!(node in s)) return s;
        const next = { ...s };
        delete next[node];
        return next;
      });
    }
    const moved = moveAxes && axis ? `; ${axis.name} now uses node ${newNode}` : "";
    notifyOk("Applied — the controller restarted at cycle 0; save the project to keep it", `${cfg.name || `Node ${newNode}`}${moved}`);
    return true;
  }
  if (res.status === 422 && res.issues.length) {
    const body = sent as NetConfig | null;
    // The slave's own problems first: a field shows the first problem placed on it.
    const issues = res.issues
      .map((i) => (body ? placeSlaveIssue(i, body, k, node) : { field: "", msg: i.msg, path: i.path }))
      .sort((a, b) => Number(a.path.startsWith("axes")) - Number(b.path.startsWith("axes")));
    const first = issues.find((i) => i.field);
    patch(node, (e) => ({ applying: false, issues, tab: first ? tabOfField(first.field) : e.tab }));
    return false;
  }
  patch(node, () => ({ applying: false, issues: [], refusal: { status: res.status, message: res.message } }));
  return false;
}

// ------------------------------------------------------------------ master settings

export interface MasterDraft {
  dc_enabled: boolean;
  sync_offset_pct: NumValue;
  auto_restart_slaves: boolean;
}

export interface MasterEditor {
  open: boolean;
  draft: MasterDraft;
  issues: FieldIssue[];
  refusal: Refusal | null;
  applying: boolean;
}

const CLOSED_MASTER: MasterEditor = {
  open: false,
  draft: { dc_enabled: true, sync_offset_pct: 20, auto_restart_slaves: true },
  issues: [],
  refusal: null,
  applying: false,
};

export const masterEditorStore = createStore<MasterEditor>(CLOSED_MASTER);

export function openMasterEditor(settings: EtherCATMasterConfig): void {
  masterEditorStore.set({
    ...CLOSED_MASTER,
    open: true,
    draft: {
      dc_enabled: settings.dc_enabled ?? true,
      sync_offset_pct: settings.sync_offset_pct ?? 20,
      auto_restart_slaves: settings.auto_restart_slaves ?? true,
    },
  });
}

export function closeMasterEditor(): void {
  masterEditorStore.set(CLOSED_MASTER);
}

export function setMasterField<K extends keyof MasterDraft>(key: K, value: MasterDraft[K]): void {
  masterEditorStore.set((m) => ({
    ...m,
    draft: { ...m.draft, [key]: value },
    issues: m.issues.filter((i) => i.field !== key),
    refusal: null,
  }));
}

export function masterDraftProblems(d: MasterDraft): FieldIssue[] {
  const v = d.sync_offset_pct;
  if (!isInt(v) || v < 0 || v > 80) return [{ field: "sync_offset_pct", msg: "an integer from 0 to 80 %", path: "" }];
  return [];
}

export async function applyMaster(): Promise<boolean> {
  const m = masterEditorStore.get();
  if (m.applying || masterDraftProblems(m.draft).length) return false;
  masterEditorStore.set({ ...m, applying: true, refusal: null });
  const master = {
    dc_enabled: m.draft.dc_enabled,
    sync_offset_pct: Number(m.draft.sync_offset_pct),
    auto_restart_slaves: m.draft.auto_restart_slaves,
  };
  const res = await applyNetwork((cfg) => ({ ...cfg, master }), { keepImplicit: true });
  if (res.ok) {
    masterEditorStore.set(CLOSED_MASTER);
    notifyOk("Applied — the controller restarted at cycle 0; save the project to keep it", "EtherCAT master settings");
    return true;
  }
  if (res.status === 422 && res.issues.length) {
    const issues = res.issues.map((i) => {
      const field = i.field.startsWith("master.") ? i.field.slice(7) : "";
      return { field, msg: i.msg, path: i.path };
    });
    masterEditorStore.set((s) => ({ ...s, applying: false, issues }));
    return false;
  }
  masterEditorStore.set((s) => ({ ...s, applying: false, issues: [], refusal: { status: res.status, message: res.message } }));
  return false;
}

// ------------------------------------------------------------------ add and remove slaves

export interface NewSlave {
  device: string;
  node_address: number;
  name: string;
  /** Position in the wiring order (0-based; the end when past it). */
  position: number;
}

export type EditOutcome = { ok: true } | { ok: false; issues: FieldIssue[]; refusal: Refusal | null };

/** Add a slave (the device's default PDO map, no start-up SDOs, on the wire). */
export async function addSlave(n: NewSlave): Promise<EditOutcome> {
  let k = -1;
  let sent: NetConfig | null = null;
  const res = await applyNetwork((cfg) => {
    const slaves = [...cfg.slaves];
    k = Math.max(0, Math.min(n.position, slaves.length));
    slaves.splice(k, 0, {
      node_address: n.node_address,
      name: n.name,
      device: n.device,
      pdo: null,
      startup_sdos: [],
      emulation: { ...DEFAULT_EMULATION },
    });
    sent = { ...cfg, slaves };
    return sent;
  });
  if (res.ok) {
    notifyOk("Slave added — the controller restarted at cycle 0; save the project to keep it", `${n.name || "Slave"} at node ${n.node_address}`);
    return { ok: true };
  }
  if (res.status === 422 && res.issues.length && sent) {
    return { ok: false, issues: res.issues.map((i) => placeSlaveIssue(i, sent as NetConfig, k, null)), refusal: null };
  }
  return { ok: false, issues: [], refusal: { status: res.status, message: res.message } };
}

/** Remove a slave from the network. */
export async function removeSlave(node: number): Promise<EditOutcome> {
  let sent: NetConfig | null = null;
  const res = await applyNetwork((cfg) => {
    if (!cfg.slaves.some((s) => s.node_address === node)) {
      throw new Error(`no slave with node address ${node} in the network any more`);
    }
    sent = { ...cfg, slaves: cfg.slaves.filter((s) => s.node_address !== node) };
    return sent;
  });
  if (res.ok) {
    slaveEditorStore.set((s) => {
      if (!(node in s)) return s;
      const next = { ...s };
      delete next[node];
      return next;
    });
    retargetPdoTab(node, null);
    notifyOk("Slave removed — the controller restarted at cycle 0; save the project to keep it", `Node ${node}`);
    return { ok: true };
  }
  if (res.status === 422 && res.issues.length) {
    return {
      ok: false,
      issues: res.issues.map((i) => ({
        field: "",
        msg: i.axis ? `${i.axis}: ${i.msg}` : i.slave !== null && sent ? `${(sent as NetConfig).slaves[i.slave]?.name ?? ""}: ${i.msg}` : i.msg,
        path: i.path,
      })),
      refusal: null,
    };
  }
  return { ok: false, issues: [], refusal: { status: res.status, message: res.message } };
}
