/**
 * The live connection: one WebSocket to /api/v1/ws for the whole app, reconnecting with backoff.
 *
 * Snapshots (WsSnapshot) replace `liveStore`'s state at the subscribed rate; components subscribe to the slices
 * they need (see hooks/useLive.ts). Per-axis history for the charts is kept outside React state, in ring buffers
 * that `onFrame` listeners read.
 */
import { CLIENT_ID } from "../api/client";
import type {
  AxisVariables,
  ControlState,
  ControllerStatus,
  EventOut,
  FBOut,
  WsHeartbeat,
  WsPing,
  WsSnapshot,
  WsSubscribe,
} from "../api/types";
import { applyControl, chosenName, controlStore, setMyName } from "./control";
import { createStore } from "./createStore";

export type WsStatus = "connecting" | "live" | "offline";

export interface LiveState {
  ws: WsStatus;
  /** Controller status of the latest snapshot (null before the first). */
  controller: ControllerStatus | null;
  /** `_sAXIS_REF` variables by axis name, of the latest snapshot. */
  axes: Readonly<Record<string, AxisVariables>>;
  /** Function-block instances by id, of the latest snapshot. */
  fbs: Readonly<Record<string, FBOut>>;
  /** Bumped whenever the controller was replaced (reset, project opened): instance ids and event seqs restart. */
  epoch: number;
  /** Number of snapshots received. */
  frame: number;
}

export const liveStore = createStore<LiveState>({
  ws: "connecting",
  controller: null,
  axes: {},
  fbs: {},
  epoch: 0,
  frame: 0,
});

// ------------------------------------------------------------------ frame listeners (non-React consumers)

type FrameListener = (snap: WsSnapshot, state: LiveState) => void;
const frameListeners = new Set<FrameListener>();

/** Called after each snapshot was applied to the store. */
export function onFrame(listener: FrameListener): () => void {
  frameListeners.add(listener);
  return () => frameListeners.delete(listener);
}

type EpochListener = (epoch: number) => void;
const epochListeners = new Set<EpochListener>();

/** Called when the controller was replaced (a new epoch: cycle restarted, old instances are gone). */
export function onEpoch(listener: EpochListener): () => void {
  epochListeners.add(listener);
  return () => epochListeners.delete(listener);
}

type EventsListener = (events: EventOut[]) => void;
const eventsListeners = new Set<EventsListener>();

/** Events carried by snapshots (new since the previous frame). */
export function onWsEvents(listener: EventsListener): () => void {
  eventsListeners.add(listener);
  return () => eventsListeners.delete(listener);
}

type OpenListener = () => void;
const openListeners = new Set<OpenListener>();

/** Called each time the socket (re)connects, to catch up on what was missed while offline. */
export function onReconnect(listener: OpenListener): () => void {
  openListeners.add(listener);
  return () => openListeners.delete(listener);
}

// ------------------------------------------------------------------ chart history

/** Samples of one axis over the last HISTORY_S seconds of simulated time. */
export interface AxisHistory {
  t: number[];
  cmdPos: number[];
  actPos: number[];
  cmdVel: number[];
}

export const HISTORY_S = 12;
const history = new Map<string, AxisHistory>();

export function axisHistory(name: string): AxisHistory {
  let h = history.get(name);
  if (!h) {
    h = { t: [], cmdPos: [], actPos: [], cmdVel: [] };
    history.set(name, h);
  }
  return h;
}

function recordHistory(snap: WsSnapshot): void {
  const t = snap.controller.time_s;
  for (const a of snap.axes) {
    const h = axisHistory(a.name);
    const last = h.t.length ? h.t[h.t.length - 1] : -Infinity;
    if (t <= last) continue;
    h.t.push(t);
    h.cmdPos.push(a.variables.Cmd.Pos);
    h.actPos.push(a.variables.Act.Pos);
    h.cmdVel.push(a.variables.Cmd.Vel);
    let drop = 0;
    while (drop < h.t.length && h.t[drop] < t - HISTORY_S) drop++;
    if (drop > 0) {
      h.t.splice(0, drop);
      h.cmdPos.splice(0, drop);
      h.actPos.splice(0, drop);
      h.cmdVel.splice(0, drop);
    }
  }
}

// ------------------------------------------------------------------ the socket

const SUBSCRIBE: WsSubscribe = { type: "subscribe", rate_hz: 30, axes: null, fbs: null, events: true };
const STALE_MS = 3500; // the server sends at least one snapshot a second
const PING_MS = 2000; // the server drops a client it has not heard from for 10 s (decision D117)

let socket: WebSocket | null = null;
let started = false;
let attempt = 0;
let lastMessageAt = 0;
let reconnectTimer: ReturnType<typeof setTimeout> | undefined;

function wsUrl(): string {
  const q = new URLSearchParams({ client: CLIENT_ID });
  const name = chosenName();
  if (name) q.set("name", name);
  return `${location.protocol === "https:" ? "wss" : "ws"}://${location.host}/api/v1/ws?${q}`;
}

function applySnapshot(snap: WsSnapshot): void {
  const prev = liveStore.get();
  const pc = prev.controller;
  // The server's epoch increments whenever the controller is replaced (reset, configuration applied, project opened).
  const replaced = pc !== null && snap.controller.epoch !== pc.epoch;
  if (replaced) history.clear();
  recordHistory(snap);
  const axes: Record<string, AxisVariables> = {};
  for (const a of snap.axes) axes[a.name] = a.variables;
  const next: LiveState = {
    ws: "live",
    controller: snap.controller,
    axes,
    fbs: snap.fbs,
    epoch: replaced ? prev.epoch + 1 : prev.epoch,
    frame: prev.frame + 1,
  };
  liveStore.set(next);
  if (replaced) for (const l of [...epochListeners]) l(next.epoch);
  if (snap.control) applyControl(snap.control);
  if (snap.events.length) for (const l of [...eventsListeners]) l(snap.events);
  for (const l of [...frameListeners]) l(snap, next);
}

function scheduleReconnect(): void {
  if (reconnectTimer !== undefined) return;
  const delay = Math.min(5000, 300 * 2 ** Math.min(attempt, 5));
  attempt += 1;
  reconnectTimer = setTimeout(() => {
    reconnectTimer = undefined;
    connect();
  }, delay);
}

function connect(): void {
  const sock = new WebSocket(wsUrl());
  socket = sock;
  if (liveStore.get().ws !== "offline") liveStore.set((s) => ({ ...s, ws: "connecting" }));
  sock.onopen = () => {
    attempt = 0;
    lastMessageAt = Date.now();
    sock.send(JSON.stringify(SUBSCRIBE));
    for (const l of [...openListeners]) l();
  };
  sock.onmessage = (msg: MessageEvent<string>) => {
    lastMessageAt = Date.now();
    let data: unknown;
    try {
      data = JSON.parse(msg.data);
    } catch {
      return;
    }
    if (typeof data !== "object" || data === null) return;
    const type = (data as { type?: unknown }).type;
    if (type === "snapshot") {
      applySnapshot(data as WsSnapshot);
    } else if (type === "control") {
      applyControl(data as ControlState);
    } else if (type === "hello") {
      // a new connection (perhaps to a restarted server, whose control versions start again)
      controlStore.set((s) => ({ ...s, state: null }));
      setMyName((data as { client: { name: string } }).client.name);
    }
  };
  sock.onclose = () => {
    if (socket === sock) socket = null;
    liveStore.set((s) => ({ ...s, ws: "offline" }));
    scheduleReconnect();
  };
  sock.onerror = () => {
    // onclose follows and schedules the reconnect
  };
}

/** Reconnect now (e.g. to tell the server a new display name). */
export function reconnectLive(): void {
  if (socket) socket.close();
}

/** Open the live connection (idempotent; the connection lives as long as the page). */
export function startLive(): void {
  if (started) return;
  started = true;
  connect();
  // "Still here": keeps this page's test-run control while it has nothing else to say.
  const ping: WsPing = { type: "ping" };
  setInterval(() => {
    if (socket && socket.readyState === WebSocket.OPEN) socket.send(JSON.stringify(ping));
  }, PING_MS);
  // Watchdog: a socket that went silent (suspended laptop, dead proxy) is closed and reopened.
  setInterval(() => {
    if (socket && socket.readyState === WebSocket.OPEN && Date.now() - lastMessageAt > STALE_MS) {
      socket.close();
    }
  }, 1000);
}

/** Send a heartbeat that renews the dead-man leases of these instances; false when offline. */
export function sendHeartbeat(fbs: number[]): boolean {
  if (!socket || socket.readyState !== WebSocket.OPEN || fbs.length === 0) return false;
  const msg: WsHeartbeat = { type: "heartbeat", fbs };
  socket.send(JSON.stringify(msg));
  return true;
}
