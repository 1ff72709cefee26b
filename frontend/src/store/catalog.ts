/**
 * Slow-changing data fetched over REST: the axis list (GET /axes, refetched when the controller is replaced or the
 * socket reconnects), the ErrorID catalogue (GET /errors) and where the 3D view runs (GET /viz).
 */
import { api, unwrap } from "../api/client";
import type { AxisSummary, ErrorInfo, VizInfo } from "../api/types";
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

let started = false;

export function startCatalog(): void {
  if (started) return;
  started = true;
  void loadAxes();
  void loadErrors();
  void loadViz();
  onEpoch(() => void loadAxes());
  onReconnect(() => {
    void loadAxes();
    if (errorsStore.get().status !== "ready") void loadErrors();
    if (vizStore.get().status !== "ready") void loadViz();
  });
}
