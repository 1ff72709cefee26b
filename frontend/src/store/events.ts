/**
 * The controller's event log: loaded with GET /api/v1/events, then extended by the WebSocket snapshots.
 * New faults also pop a notification (lib/notifyEvents.tsx).
 */
import { api, unwrap } from "../api/client";
import type { EventOut } from "../api/types";
import { isFault } from "../lib/format";
import { notifyFaults } from "../lib/notifyEvents";
import { createStore } from "./createStore";
import { onEpoch, onReconnect, onWsEvents } from "./live";

export interface EventsState {
  status: "loading" | "ready" | "error";
  /** Oldest first. */
  events: EventOut[];
  /** Highest seq seen (the log keeps counting after a clear). */
  lastSeq: number;
}

const MAX_EVENTS = 2000;

export const eventsStore = createStore<EventsState>({ status: "loading", events: [], lastSeq: 0 });

function merge(incoming: EventOut[], notify: boolean): void {
  const st = eventsStore.get();
  const have = new Set(st.events.map((e) => e.seq));
  const fresh = incoming.filter((e) => !have.has(e.seq));
  if (!fresh.length) {
    if (st.status !== "ready") eventsStore.set({ ...st, status: "ready" });
    return;
  }
  const events = st.events.concat(fresh).sort((a, b) => a.seq - b.seq);
  if (events.length > MAX_EVENTS) events.splice(0, events.length - MAX_EVENTS);
  const lastSeq = Math.max(st.lastSeq, ...fresh.map((e) => e.seq));
  eventsStore.set({ status: "ready", events, lastSeq });
  if (notify) notifyFaults(fresh.filter((x) => x.seq > st.lastSeq && isFault(x.level)));
}

/** "Show in event log": the event the log should reveal (a new nonce each request, so the same seq works twice). */
export const eventFocusStore = createStore<{ seq: number; nonce: number } | null>(null);

export function focusEvent(seq: number): void {
  eventFocusStore.set({ seq, nonce: (eventFocusStore.get()?.nonce ?? 0) + 1 });
}

async function fetchSince(since: number, notify: boolean): Promise<void> {
  try {
    const list = await unwrap(api.GET("/api/v1/events", { params: { query: { since } } }));
    merge(list, notify);
  } catch {
    const st = eventsStore.get();
    if (st.status === "loading") eventsStore.set({ ...st, status: "error" });
  }
}

let started = false;

export function startEvents(): void {
  if (started) return;
  started = true;
  void fetchSince(0, false);
  onWsEvents((evs) => merge(evs, true));
  // Catch up on what happened while the socket was down.
  onReconnect(() => void fetchSince(eventsStore.get().lastSeq, true));
  // A new controller numbers its events from 1 again.
  onEpoch(() => {
    eventsStore.set({ status: "loading", events: [], lastSeq: 0 });
    void fetchSince(0, false);
  });
}

/** DELETE /api/v1/events, then empty the local list. */
export async function clearEvents(): Promise<void> {
  await unwrap(api.DELETE("/api/v1/events"));
  eventsStore.set((s) => ({ ...s, events: [] }));
}
