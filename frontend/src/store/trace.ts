/**
 * The data trace tab: the draft settings, the variable catalog (GET /api/v1/traces/variables), the running trace and
 * its latest samples (polled while it records), and the settings saved in the project (GET/PUT /project/traces).
 */
import { api, unwrap } from "../api/client";
import type { components } from "../api/schema";
import { createStore } from "./createStore";
import { onEpoch } from "./live";

type S = components["schemas"];
export type TraceSettings = S["TraceSettings"];
export type TraceVariable = S["TraceVariable"];
export type TraceTrigger = S["TraceTrigger"];
export type TraceData = S["TraceData"];
export type TraceCatalog = S["TraceCatalog"];
export type TraceTarget = S["TraceTarget"];

export const MAX_POINTS = 2000;
const POLL_MS = 250;

export interface TraceState {
  draft: TraceSettings;
  catalog: TraceCatalog | null;
  catalogError: string | null;
  traceId: number | null;
  data: TraceData | null;
  error: string | null;
  saved: TraceSettings[];
  busy: boolean;
}

export const DEFAULT_SETTINGS: TraceSettings = {
  name: "Trace",
  variables: [{ kind: "axis", target: "MC_Axis000", name: "Cmd.Vel" }],
  sampling_periods: 1,
  samples: 10000,
  mode: "single",
  trigger: null,
};

export const traceStore = createStore<TraceState>({
  draft: DEFAULT_SETTINGS,
  catalog: null,
  catalogError: null,
  traceId: null,
  data: null,
  error: null,
  saved: [],
  busy: false,
});

/** `kind|target|name`: the key of a variable in selects and lists. */
export const varKey = (v: TraceVariable): string => `${v.kind}|${v.target}|${v.name}`;
export function parseVarKey(key: string): TraceVariable {
  const [kind, target, ...rest] = key.split("|");
  return { kind: kind as TraceVariable["kind"], target, name: rest.join("|") };
}

export function setDraft(update: Partial<TraceSettings>): void {
  traceStore.set((s) => ({ ...s, draft: { ...s.draft, ...update } }));
}

export async function loadCatalog(): Promise<void> {
  try {
    const catalog = await unwrap(api.GET("/api/v1/traces/variables"));
    traceStore.set((s) => ({ ...s, catalog, catalogError: null }));
  } catch (err) {
    traceStore.set((s) => ({ ...s, catalogError: err instanceof Error ? err.message : String(err) }));
  }
}

export async function loadSaved(): Promise<void> {
  try {
    const saved = await unwrap(api.GET("/api/v1/project/traces"));
    traceStore.set((s) => ({ ...s, saved }));
  } catch {
    /* the list stays as it was */
  }
}

let timer: ReturnType<typeof setTimeout> | null = null;

function schedulePoll(): void {
  if (timer !== null) clearTimeout(timer);
  timer = setTimeout(() => void poll(), POLL_MS);
}

/** Read the trace (decimated for the chart); keeps polling while it records. */
export async function poll(): Promise<void> {
  timer = null;
  const id = traceStore.get().traceId;
  if (id === null) return;
  try {
    const data = await unwrap(
      api.GET("/api/v1/traces/{trace_id}", { params: { path: { trace_id: id }, query: { max_points: MAX_POINTS } } }),
    );
    if (traceStore.get().traceId !== id) return;
    traceStore.set((s) => ({ ...s, data, error: null }));
    if (data.state === "waiting" || data.state === "triggered" || data.state === "running") schedulePoll();
  } catch (err) {
    if (traceStore.get().traceId !== id) return;
    traceStore.set((s) => ({ ...s, error: err instanceof Error ? err.message : String(err) }));
  }
}

/** Configure and start a trace with the draft settings (the previous trace of this tab is deleted). */
export async function startTrace(): Promise<void> {
  const st = traceStore.get();
  traceStore.set((s) => ({ ...s, busy: true, error: null }));
  try {
    if (st.traceId !== null) {
      await api.DELETE("/api/v1/traces/{trace_id}", { params: { path: { trace_id: st.traceId } } });
    }
    const out = await unwrap(api.POST("/api/v1/traces", { body: st.draft }));
    traceStore.set((s) => ({ ...s, traceId: out.id, data: null, busy: false }));
    await poll();
  } catch (err) {
    traceStore.set((s) => ({ ...s, traceId: null, busy: false, error: err instanceof Error ? err.message : String(err) }));
    throw err;
  }
}

export async function stopTrace(): Promise<void> {
  const id = traceStore.get().traceId;
  if (id === null) return;
  await unwrap(api.POST("/api/v1/traces/{trace_id}/stop", { params: { path: { trace_id: id } } }));
  await poll();
}

export function csvUrl(): string | null {
  const id = traceStore.get().traceId;
  return id === null ? null : `/api/v1/traces/${id}/csv`;
}

/** Put the draft into the project's trace settings (replacing one of the same name); Save writes the file. */
export async function saveDraftToProject(): Promise<void> {
  const { draft, saved } = traceStore.get();
  const list = saved.filter((t) => t.name !== draft.name).concat([draft]);
  const out = await unwrap(api.PUT("/api/v1/project/traces", { body: list }));
  traceStore.set((s) => ({ ...s, saved: out }));
}

onEpoch(() => {
  // a new controller (configuration applied, project opened): its traces and instances are new
  if (timer !== null) clearTimeout(timer);
  timer = null;
  traceStore.set((s) => ({ ...s, traceId: null, data: null, catalog: null }));
  void loadCatalog();
  void loadSaved();
});
