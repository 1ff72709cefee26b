/**
 * Slow-changing data fetched over REST: the axis list (GET /axes, refetched when the controller is replaced or the
 * socket reconnects), the ErrorID catalogue (GET /errors), where the 3D view runs (GET /viz), the instruction
 * catalogue (GET /fb-types: inputs, enumerators) and the project document's JSON Schema (GET /project/schema).
 */
import { api, unwrap } from "../api/client";
import type { AxisSummary, ErrorInfo, FBType, VizInfo } from "../api/types";
import type { JsonSchema } from "../lib/schema";
import { createStore } from "./createStore";
import { onEpoch, onReconnect } from "./live";

export interface Loadable<T> {
  status: "loading" | "ready" | "error";
  data: T;
  error?: string;
}

export const axesStore = createStore<Loadable<AxisSummary[]>>({ status: "loading", data: [] });
export const errorsStore = createStore<Loadable<ReadonlyMap<string, ErrorInfo>>>({ status: "loading", data: new Map() });
export const vizStore = createStore<Loadable<VizInfo | null>>({ status: "loading", data: null });
export const fbTypesStore = createStore<Loadable<ReadonlyMap<string, FBType>>>({ status: "loading", data: new Map() });
export const projectSchemaStore = createStore<Loadable<JsonSchema | null>>({ status: "loading", data: null });

function message(err: unknown): string {
  return err instanceof Error ? err.message : String(err);
}

export async function loadAxes(): Promise<void> {
  try {
    const data = await unwrap(api.GET("/api/v1/axes"));
    axesStore.set({ status: "ready", data });
  } catch (err) {
    axesStore.set((s) => ({ ...s, status: s.status === "ready" ? "ready" : "error", error: message(err) }));
  }
}

async function loadErrors(): Promise<void> {
  try {
    const list = await unwrap(api.GET("/api/v1/errors"));
    errorsStore.set({ status: "ready", data: new Map(list.map((e) => [e.code.toUpperCase(), e])) });
  } catch (err) {
    errorsStore.set((s) => ({ ...s, status: "error", error: message(err) }));
  }
}

async function loadViz(): Promise<void> {
  try {
    const data = await unwrap(api.GET("/api/v1/viz"));
    vizStore.set({ status: "ready", data });
  } catch (err) {
    vizStore.set((s) => ({ ...s, status: "error", error: message(err) }));
  }
}

async function loadFbTypes(): Promise<void> {
  try {
    const list = await unwrap(api.GET("/api/v1/fb-types"));
    fbTypesStore.set({ status: "ready", data: new Map(list.map((t) => [t.name, t])) });
  } catch (err) {
    fbTypesStore.set((s) => ({ ...s, status: "error", error: message(err) }));
  }
}

async function loadProjectSchema(): Promise<void> {
  try {
    const data = await unwrap(api.GET("/api/v1/project/schema"));
    projectSchemaStore.set({ status: "ready", data: data as JsonSchema });
  } catch (err) {
    projectSchemaStore.set((s) => ({ ...s, status: "error", error: message(err) }));
  }
}

let started = false;

export function startCatalog(): void {
  if (started) return;
  started = true;
  void loadAxes();
  void loadErrors();
  void loadViz();
  void loadFbTypes();
  void loadProjectSchema();
  onEpoch(() => void loadAxes());
  onReconnect(() => {
    void loadAxes();
    if (errorsStore.get().status !== "ready") void loadErrors();
    if (vizStore.get().status !== "ready") void loadViz();
    if (fbTypesStore.get().status !== "ready") void loadFbTypes();
    if (projectSchemaStore.get().status !== "ready") void loadProjectSchema();
  });
}
