/**
 * Test-run control shared between browsers (backend api/control.py, docs/shared-control.md).
 *
 * One client at a time holds control; the others watch read-only. This page is a client with the id `CLIENT_ID`
 * (sent with every REST request and on the WebSocket). The state arrives with the WebSocket (`hello`, `control`
 * messages and every snapshot). Control is taken automatically by the first test-run action while nobody holds it,
 * or with the Take button (forcing it from another holder); it ends with Release, a forced take by someone else, or
 * when this page goes away.
 */
import { CLIENT_ID, api, onApiStatus, unwrap } from "../api/client";
import type { ControlState } from "../api/types";
import { notifyError, notifyOk } from "../lib/notify";
import { createStore } from "./createStore";

const NAME_KEY = "mcstudio.clientName";

export interface ControlStoreState {
  /** The last state the server sent (null before the first). */
  state: ControlState | null;
  /** This page's display name as the server knows it. */
  myName: string | null;
  /** An API request was refused for want of the access token (401). */
  tokenRequired: boolean;
}

export const controlStore = createStore<ControlStoreState>({ state: null, myName: null, tokenRequired: false });

/** The display name the user chose (localStorage), or null for the server's default ("browser 2 · 10.0.0.7"). */
export function chosenName(): string | null {
  try {
    const n = localStorage.getItem(NAME_KEY);
    return n && n.trim() ? n.trim().slice(0, 48) : null;
  } catch {
    return null;
  }
}

type LostListener = () => void;
const lostListeners = new Set<LostListener>();

/** Called when this page loses control to somebody else (its held jogs must be forgotten: the server stopped them). */
export function onControlLost(listener: LostListener): () => void {
  lostListeners.add(listener);
  return () => lostListeners.delete(listener);
}

/** Apply a state from the server (WebSocket `control` message or snapshot). */
export function applyControl(next: ControlState): void {
  const prev = controlStore.get().state;
  if (prev && next.version < prev.version) return; // an older snapshot (cached) after a newer control message
  if (prev && prev.version === next.version) return;
  controlStore.set((s) => ({ ...s, state: next }));
  const wasMine = prev?.holder?.id === CLIENT_ID;
  const isMine = next.holder?.id === CLIENT_ID;
  if (wasMine && !isMine) {
    for (const l of [...lostListeners]) l();
    if (next.holder) {
      notifyError("Test-run control", new Error(`${next.holder.name} took test-run control: this page is read-only now`));
    }
  }
}

export function setMyName(name: string): void {
  controlStore.set((s) => ({ ...s, myName: name }));
}

export async function takeControl(force: boolean): Promise<boolean> {
  try {
    const out = await unwrap(api.POST("/api/v1/control/take", { body: { force, name: chosenName() } }));
    applyControl(out);
    return true;
  } catch (err) {
    notifyError("Take control", err);
    return false;
  }
}

export async function releaseControl(): Promise<void> {
  try {
    const out = await unwrap(api.POST("/api/v1/control/release"));
    applyControl(out);
    notifyOk("Control released", "Other browsers may take test-run control now.");
  } catch (err) {
    notifyError("Release control", err);
  }
}

/** Remember the display name and tell the server (with the next take, and by reconnecting the WebSocket). */
export function storeName(name: string): void {
  try {
    if (name.trim()) localStorage.setItem(NAME_KEY, name.trim().slice(0, 48));
    else localStorage.removeItem(NAME_KEY);
  } catch {
    // private mode: the name lasts as long as the page
  }
}

let started = false;

/** Watch API answers: a 401 means the studio needs its access token (docs/shared-control.md). */
export function startControl(): void {
  if (started) return;
  started = true;
  onApiStatus((status) => {
    if (status === 401 && !controlStore.get().tokenRequired) controlStore.set((s) => ({ ...s, tokenRequired: true }));
  });
}
