/**
 * The settings of the axes (GET /api/v1/axes/{name} → config), fetched on demand, by axis name. Every loaded entry is
 * refetched when the controller was replaced (settings applied, project opened) or the socket reconnects.
 */
import { useEffect } from "react";
import { api, unwrap } from "../api/client";
import type { AxisConfig } from "../api/types";
import type { Loadable } from "./catalog";
import { createStore, useStore } from "./createStore";
import { onEpoch, onReconnect } from "./live";

type Entry = Loadable<AxisConfig | null>;

export const axisConfigStore = createStore<Readonly<Record<string, Entry>>>({});

const inflight = new Map<string, Promise<AxisConfig | null>>();

function setEntry(axis: string, entry: Entry): void {
  axisConfigStore.set((s) => ({ ...s, [axis]: entry }));
}

/** Fetch the settings of an axis (concurrent calls share one request); null when it failed (see the entry). */
export function loadAxisConfig(axis: string): Promise<AxisConfig | null> {
  const pending = inflight.get(axis);
  if (pending) return pending;
  const p = (async () => {
    try {
      const detail = await unwrap(api.GET("/api/v1/axes/{name}", { params: { path: { name: axis } } }));
      setEntry(axis, { status: "ready", data: detail.config });
      return detail.config;
    } catch (err) {
      const prev = axisConfigStore.get()[axis];
      setEntry(axis, {
        status: "error",
        data: prev?.data ?? null,
        error: err instanceof Error ? err.message : String(err),
      });
      return null;
    } finally {
      inflight.delete(axis);
    }
  })();
  inflight.set(axis, p);
  return p;
}

/** Store the settings the API returned after a successful PUT. */
export function putAxisConfig(axis: string, config: AxisConfig): void {
  setEntry(axis, { status: "ready", data: config });
}

/** The settings of an axis, loading them on first use. */
export function useAxisConfig(axis: string): Entry | undefined {
  const entry = useStore(axisConfigStore, (s) => s[axis]);
  useEffect(() => {
    if (axisConfigStore.get()[axis] === undefined) void loadAxisConfig(axis);
  }, [axis]);
  return entry;
}

let started = false;

export function startAxisConfig(): void {
  if (started) return;
  started = true;
  const reloadAll = () => {
    for (const axis of Object.keys(axisConfigStore.get())) void loadAxisConfig(axis);
  };
  onEpoch(reloadAll);
  onReconnect(reloadAll);
}
