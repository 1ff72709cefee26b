/** Hooks that subscribe components to slices of the live data (re-rendering only when their slice changes). */
import type { AxisSummary, AxisVariables, ControllerStatus, ErrorInfo, FBOut } from "../api/types";
import { axesStore, errorsStore } from "../store/catalog";
import { type AxisCommands, axisCommands, commandsStore } from "../store/commands";
import { useStore } from "../store/createStore";
import { type LiveState, type WsStatus, liveStore } from "../store/live";

/** Any slice of the live state; the selector must return a primitive or a reference held by the state. */
export function useLive<R>(selector: (s: LiveState) => R): R {
  return useStore(liveStore, selector);
}

export function useWsStatus(): WsStatus {
  return useLive((s) => s.ws);
}

export function useController(): ControllerStatus | null {
  return useLive((s) => s.controller);
}

export function useAxisVars(name: string): AxisVariables | undefined {
  return useLive((s) => s.axes[name]);
}

export function useFb(id: number | null | undefined): FBOut | undefined {
  return useLive((s) => (id === null || id === undefined ? undefined : s.fbs[String(id)]));
}

export function useAxisList(): { status: "loading" | "ready" | "error"; axes: AxisSummary[]; error?: string } {
  const st = useStore(axesStore, (s) => s);
  return { status: st.status, axes: st.data, error: st.error };
}

export function useAxisSummary(name: string): AxisSummary | undefined {
  return useStore(axesStore, (s) => s.data.find((a) => a.name === name));
}

export function useErrorInfo(code: string | null | undefined): ErrorInfo | undefined {
  return useStore(errorsStore, (s) => (code ? s.data.get(code.toUpperCase()) : undefined));
}

export function useAxisCommands(axis: string): AxisCommands {
  return useStore(commandsStore, (s) => axisCommands(s, axis));
}
