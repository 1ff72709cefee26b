/**
 * Cam tables: the project's list (GET /api/v1/cams) and one editor state per open cam table.
 *
 * An editor holds the nodes and property being edited (as typed: numbers or raw text), the state last saved (for the
 * unsaved-changes dot), and the latest generation (POST /cams/generate, debounced while typing): the profile to plot,
 * the characteristic values and the continuity warnings, or the field errors of an invalid input. Saving is
 * PUT /cams/{name} with the source (the backend saves it to the project and downloads it into the controller).
 */
import { api, ApiError, unwrap } from "../api/client";
import type { components } from "../api/schema";
import type { Loadable } from "./catalog";
import { createStore, useStore } from "./createStore";
import type { NumValue } from "./forms";
import { closeTab, camTabKey } from "./tabs";

type S = components["schemas"];
export type CamInfo = S["CamInfo"];
export type CamOut = S["CamOut"];
export type CamGenerateOut = S["CamGenerateOut"];
export type CamSegmentOut = S["CamSegmentOut"];
export type CamJumpOut = S["CamJumpOut"];
type CamSourceIn = S["CamSource-Input"];
type CamNodeIn = S["CamNode-Input"];

export const CURVES = [
  ["_mcConstantLine", "Dwell (constant line)"],
  ["_mcStraightLine", "Straight line"],
  ["_mcParabolic", "Parabolic"],
  ["_mcModifiedConstantVel", "Modified constant velocity"],
  ["_mcModifiedTrapezoid", "Modified trapezoid"],
  ["_mcModifiedSine", "Modified sine"],
  ["_mcCycloidal", "Cycloidal"],
  ["_mcTrapeclloid", "Trapecloid"],
  ["_mcReverseTrapeclloid", "Reverse trapecloid"],
  ["_mcSimpleHarmonic", "Simple harmonic"],
  ["_mcDoubleHarmonic", "Double harmonic"],
  ["_mcReverseDoubleHarmonic", "Reverse double harmonic"],
  ["_mcNC2Curve", "NC2 (unverified)"],
  ["_mcPolynomic3", "Polynomial, cubic"],
  ["_mcPolynomic5", "Polynomial, quintic"],
] as const;

export const curveLabel = (c: string): string => CURVES.find(([k]) => k === c)?.[1] ?? c;
export const usesConnectingVel = (c: string): boolean => c === "_mcPolynomic3" || c === "_mcPolynomic5";
export const usesConnectingAcc = (c: string): boolean => c === "_mcPolynomic5";

export interface NodeRow {
  Phase: NumValue;
  Distance: NumValue;
  Curve: string;
  ConnectingVelEnable: boolean;
  ConnectingVel: NumValue;
  ConnectingAccEnable: boolean;
  ConnectingAcc: NumValue;
  PhasePitch: NumValue;
}

export interface CamDraft {
  nodes: NodeRow[];
  CycleTime: NumValue;
  InitVel: NumValue;
  InitAcc: NumValue;
  /** "" = the last node's phase / CycleTime */
  masterVelocity: NumValue;
  periodic: boolean;
  description: string;
}

export interface CamEditorState {
  status: "loading" | "ready" | "error";
  error?: string;
  /** null: the table was imported as points (no nodes to edit) */
  draft: CamDraft | null;
  saved: string;
  info: CamOut | null;
  /** Points of an imported table (for its plot) */
  points: { phase: number[]; distance: number[] } | null;
  result: CamGenerateOut | null;
  generating: boolean;
  /** Field problems of the last generation: path ("nodes[2].Phase", "property.CycleTime") → message */
  issues: Record<string, string>;
  saving: boolean;
}

export const camListStore = createStore<Loadable<CamInfo[]>>({ status: "loading", data: [] });
export const camEditorStore = createStore<Record<string, CamEditorState>>({});

const message = (err: unknown): string => (err instanceof Error ? err.message : String(err));

export async function loadCamList(): Promise<void> {
  try {
    const data = await unwrap(api.GET("/api/v1/cams"));
    camListStore.set({ status: "ready", data });
  } catch (err) {
    camListStore.set((s) => ({ ...s, status: s.data.length ? "ready" : "error", error: message(err) }));
  }
}

export function useCamList(): Loadable<CamInfo[]> {
  return useStore(camListStore, (s) => s);
}

export function useCamEditor(name: string): CamEditorState | undefined {
  return useStore(camEditorStore, (s) => s[name]);
}

function patch(name: string, p: Partial<CamEditorState>): void {
  camEditorStore.set((s) => (s[name] ? { ...s, [name]: { ...s[name], ...p } } : s));
}

const num = (v: NumValue): number | null => {
  if (typeof v === "number") return Number.isFinite(v) ? v : null;
  if (v.trim() === "") return null;
  const n = Number(v);
  return Number.isFinite(n) ? n : null;
};

function draftOf(info: CamOut): CamDraft | null {
  const src = info.source;
  if (!src) return null;
  return {
    nodes: src.nodes.map((n) => ({
      Phase: n.Phase,
      Distance: n.Distance,
      Curve: String(n.Curve),
      ConnectingVelEnable: n.ConnectingVelEnable,
      ConnectingVel: n.ConnectingVel,
      ConnectingAccEnable: n.ConnectingAccEnable,
      ConnectingAcc: n.ConnectingAcc,
      PhasePitch: n.PhasePitch,
    })),
    CycleTime: src.property?.CycleTime ?? 1,
    InitVel: src.property?.InitVel ?? 0,
    InitAcc: src.property?.InitAcc ?? 0,
    masterVelocity: src.master_velocity ?? "",
    periodic: src.periodic,
    description: info.description,
  };
}

/** The source to send, or the field problems of values that are not numbers yet. */
export function sourceOf(d: CamDraft): { source: CamSourceIn | null; issues: Record<string, string> } {
  const issues: Record<string, string> = {};
  const need = (path: string, v: NumValue): number => {
    const n = num(v);
    if (n === null) issues[path] = "enter a number";
    return n ?? 0;
  };
  const nodes: CamNodeIn[] = d.nodes.map((n, i) => ({
    Phase: need(`nodes[${i}].Phase`, n.Phase),
    Distance: n.Curve === "_mcConstantLine" ? (num(n.Distance) ?? 0) : need(`nodes[${i}].Distance`, n.Distance),
    Curve: n.Curve as CamNodeIn["Curve"],
    ConnectingVelEnable: n.ConnectingVelEnable,
    ConnectingVel: n.ConnectingVelEnable ? need(`nodes[${i}].ConnectingVel`, n.ConnectingVel) : (num(n.ConnectingVel) ?? 0),
    ConnectingAccEnable: n.ConnectingAccEnable,
    ConnectingAcc: n.ConnectingAccEnable ? need(`nodes[${i}].ConnectingAcc`, n.ConnectingAcc) : (num(n.ConnectingAcc) ?? 0),
    PhasePitch: need(`nodes[${i}].PhasePitch`, n.PhasePitch),
  }));
  const mv = num(d.masterVelocity);
  const source: CamSourceIn = {
    property: {
      CycleTime: need("property.CycleTime", d.CycleTime),
      InitVel: need("property.InitVel", d.InitVel),
      InitAcc: need("property.InitAcc", d.InitAcc),
    },
    nodes,
    master_velocity: mv !== null && mv > 0 ? mv : null,
    periodic: d.periodic,
  };
  return { source: Object.keys(issues).length ? null : source, issues };
}

const snapshot = (d: CamDraft | null): string => JSON.stringify(d);

export async function openCamEditor(name: string, force = false): Promise<void> {
  if (camEditorStore.get()[name] && !force) return;
  camEditorStore.set((s) => ({
    ...s,
    [name]: s[name] ?? {
      status: "loading", draft: null, saved: "null", info: null, points: null, result: null, generating: false,
      issues: {}, saving: false,
    },
  }));
  try {
    const info = await unwrap(api.GET("/api/v1/cams/{name}", { params: { path: { name }, query: { points: true } } }));
    const draft = draftOf(info);
    const points = draft ? null : { phase: info.phase ?? [], distance: info.distance ?? [] };
    patch(name, { status: "ready", info: { ...info, phase: null, distance: null }, draft, saved: snapshot(draft), points,
      issues: {}, result: null });
    if (draft) scheduleGenerate(name, 0);
  } catch (err) {
    patch(name, { status: "error", error: message(err) });
  }
}

export function isDirty(e: CamEditorState | undefined): boolean {
  return !!e && e.status === "ready" && snapshot(e.draft) !== e.saved;
}

export function useCamDirty(name: string): boolean {
  return useStore(camEditorStore, (s) => isDirty(s[name]));
}

// ------------------------------------------------------------------ editing

export function editDraft(name: string, fn: (d: CamDraft) => CamDraft): void {
  const e = camEditorStore.get()[name];
  if (!e?.draft) return;
  patch(name, { draft: fn(e.draft) });
  scheduleGenerate(name);
}

export function setNode(name: string, i: number, p: Partial<NodeRow>): void {
  editDraft(name, (d) => ({ ...d, nodes: d.nodes.map((n, k) => (k === i ? { ...n, ...p } : n)) }));
}

export function addNode(name: string): void {
  editDraft(name, (d) => {
    const last = d.nodes[d.nodes.length - 1];
    const lastPhase = last ? (num(last.Phase) ?? 0) : 0;
    const span = d.nodes.length > 1 ? lastPhase - (num(d.nodes[d.nodes.length - 2].Phase) ?? 0) : 90;
    const node: NodeRow = {
      Phase: +(lastPhase + (span > 0 ? span : 90)).toFixed(3),
      Distance: 0,
      Curve: "_mcModifiedSine",
      ConnectingVelEnable: false,
      ConnectingVel: 0,
      ConnectingAccEnable: false,
      ConnectingAcc: 0,
      PhasePitch: last ? last.PhasePitch : 0.1,
    };
    return { ...d, nodes: [...d.nodes, node] };
  });
}

export function removeNode(name: string, i: number): void {
  editDraft(name, (d) => (d.nodes.length > 1 ? { ...d, nodes: d.nodes.filter((_, k) => k !== i) } : d));
}

export function revertCam(name: string): void {
  const e = camEditorStore.get()[name];
  if (!e) return;
  patch(name, { draft: JSON.parse(e.saved) as CamDraft | null });
  scheduleGenerate(name, 0);
}

// ------------------------------------------------------------------ generation (debounced)

const timers = new Map<string, ReturnType<typeof setTimeout>>();
const seq = new Map<string, number>();
export const PLOT_POINTS = 2000;

function issuesFrom(err: unknown): Record<string, string> {
  const out: Record<string, string> = {};
  if (err instanceof ApiError && err.issues.length) {
    for (const i of err.issues) out[i.field || "nodes"] = i.msg;
    // the manual's ErrorID, where the backend gives one
    if (Array.isArray(err.detail)) {
      for (const d of err.detail as { loc?: unknown[]; code?: string; msg?: string }[]) {
        const i = err.issues.find((x) => x.msg === d.msg);
        if (i && d.code) out[i.field || "nodes"] = `${d.msg} [${d.code}]`;
      }
    }
  } else {
    out["nodes"] = message(err);
  }
  return out;
}

export function scheduleGenerate(name: string, delayMs = 250): void {
  const t = timers.get(name);
  if (t !== undefined) clearTimeout(t);
  timers.set(name, setTimeout(() => void generateNow(name), delayMs));
}

async function generateNow(name: string): Promise<void> {
  timers.delete(name);
  const e = camEditorStore.get()[name];
  if (!e?.draft) return;
  const { source, issues } = sourceOf(e.draft);
  if (!source) {
    patch(name, { issues, generating: false });
    return;
  }
  const n = (seq.get(name) ?? 0) + 1;
  seq.set(name, n);
  patch(name, { generating: true });
  try {
    const result = await unwrap(api.POST("/api/v1/cams/generate", { body: { ...source, max_points: PLOT_POINTS } }));
    if (seq.get(name) !== n) return;
    patch(name, { result, issues: {}, generating: false });
  } catch (err) {
    if (seq.get(name) !== n) return;
    patch(name, { issues: issuesFrom(err), generating: false });
  }
}

// ------------------------------------------------------------------ saving, creating, deleting, CSV

export async function saveCam(name: string): Promise<void> {
  const e = camEditorStore.get()[name];
  if (!e?.draft || !e.info) return;
  const { source, issues } = sourceOf(e.draft);
  if (!source) {
    patch(name, { issues });
    throw new Error("some values are not numbers yet");
  }
  patch(name, { saving: true });
  try {
    const info = await unwrap(api.PUT("/api/v1/cams/{name}", {
      params: { path: { name } },
      body: { description: e.draft.description, size: e.info.size ?? null, source },
    }));
    const draft = camEditorStore.get()[name]?.draft ?? e.draft;
    patch(name, { info, saved: snapshot(e.draft), saving: false, draft });
    void loadCamList();
  } catch (err) {
    patch(name, { saving: false });
    if (err instanceof ApiError && err.status === 422) patch(name, { issues: issuesFrom(err) });
    throw err;
  }
}

const NO_CONNECTION = { ConnectingVelEnable: false, ConnectingVel: 0, ConnectingAccEnable: false, ConnectingAcc: 0 };

export const DEFAULT_SOURCE: CamSourceIn = {
  property: { CycleTime: 1, InitVel: 0, InitAcc: 0 },
  nodes: [
    { Phase: 180, Distance: 100, Curve: "_mcModifiedSine", PhasePitch: 0.1, ...NO_CONNECTION },
    { Phase: 360, Distance: 0, Curve: "_mcModifiedSine", PhasePitch: 0.1, ...NO_CONNECTION },
  ],
  master_velocity: null,
  periodic: true,
};

export async function createCam(name: string): Promise<void> {
  await unwrap(api.PUT("/api/v1/cams/{name}", {
    params: { path: { name } },
    body: { description: "", size: null, source: DEFAULT_SOURCE },
  }));
  await loadCamList();
}

export async function deleteCam(name: string): Promise<void> {
  await unwrap(api.DELETE("/api/v1/cams/{name}", { params: { path: { name } } }));
  closeTab(camTabKey(name));
  camEditorStore.set((s) => {
    const next = { ...s };
    delete next[name];
    return next;
  });
  await loadCamList();
}

/** Replace the table's data with a CSV file's points (the table loses its nodes). */
export async function importCamCsv(name: string, text: string): Promise<CamOut> {
  const res = await fetch(`/api/v1/cams/${encodeURIComponent(name)}/csv`, {
    method: "PUT",
    headers: { "content-type": "text/csv" },
    body: text,
  });
  const body: unknown = await res.json().catch(() => null);
  if (!res.ok) {
    const detail = typeof body === "object" && body !== null && "detail" in body ? (body as { detail: unknown }).detail : body;
    throw new ApiError(res.status, detail);
  }
  await openCamEditor(name, true);
  void loadCamList();
  return body as CamOut;
}

export const camCsvUrl = (name: string): string => `/api/v1/cams/${encodeURIComponent(name)}/csv`;
