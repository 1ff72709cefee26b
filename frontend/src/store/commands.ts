/**
 * MC commands with PLC semantics, issued from the test-run panel.
 *
 * - One-shot instructions (moves, MC_Stop, MC_Reset) start on a rising edge of Execute that the controller must see
 *   in a cycle, so every button press creates a new instance with `Execute: true`. Its outputs are watched in the
 *   snapshots; when it has ended (Done / CommandAborted / Failure) it is deleted (MC_Stop: Execute is first set
 *   FALSE, since the axis stays in Stopping while an MC_Stop has Execute TRUE). An instance that ended with Error is
 *   kept so that its ErrorID stays visible, until the user resets or issues another command on that axis.
 * - Servo: one MC_Power instance per axis whose Enable is patched.
 * - Jog: one MC_MoveJog instance per axis with a 0.5 s dead-man lease. While a jog button is held the enable is set
 *   once and heartbeats renew the lease every 100 ms over the WebSocket; if they stop (tab closed, network lost) the
 *   backend drops the enable and the axis decelerates.
 * - Override: one MC_SetOverride instance per axis, created on first use (Enable TRUE); Enable and VelFactor are
 *   patched as the slider moves, at most ~9 PATCH requests a second (the latest value always goes out).
 */
import { ApiError, api, unwrap } from "../api/client";
import type { FBOut } from "../api/types";
import { notifyError } from "../lib/notify";
import { onControlLost } from "./control";
import { createStore } from "./createStore";
import { liveStore, onEpoch, onFrame, sendHeartbeat } from "./live";

export type JogDir = "plus" | "minus";
type Outputs = Record<string, unknown>;

export interface LastInstruction {
  id: number;
  type: string;
  outputs: Outputs;
  /** The instance no longer exists in the controller (outputs are those last seen). */
  gone: boolean;
}

export interface AxisCommands {
  last: LastInstruction | null;
  powerId: number | null;
  jogId: number | null;
  jogHeld: JogDir | null;
  /** The MC_SetOverride instance of the axis, and what the user set (sent throttled). */
  overrideId: number | null;
  overrideEnable: boolean;
  overrideFactor: number;
}

const EMPTY: AxisCommands = {
  last: null,
  powerId: null,
  jogId: null,
  jogHeld: null,
  overrideId: null,
  overrideEnable: false,
  overrideFactor: 100,
};

/** React-facing state, by axis name. */
export const commandsStore = createStore<Readonly<Record<string, AxisCommands>>>({});

export function axisCommands(state: Readonly<Record<string, AxisCommands>>, axis: string): AxisCommands {
  return state[axis] ?? EMPTY;
}

function patchAxis(axis: string, patch: Partial<AxisCommands>): void {
  commandsStore.set((s) => ({ ...s, [axis]: { ...axisCommands(s, axis), ...patch } }));
}

// ------------------------------------------------------------------ one-shot instances

interface Tracked {
  id: number;
  axis: string;
  type: string;
  /** running: watched; error: ended with Error, kept until reset / next command; closing: being deleted. */
  state: "running" | "error" | "closing";
}

const tracked = new Map<number, Tracked>();

function bool(outputs: Outputs, name: string): boolean {
  return outputs[name] === true;
}

async function deleteFb(id: number): Promise<void> {
  try {
    await unwrap(api.DELETE("/api/v1/fb/{fb_id}", { params: { path: { fb_id: id } } }));
  } catch (err) {
    if (!(err instanceof ApiError && err.status === 404)) throw err;
  }
}

async function close(t: Tracked): Promise<void> {
  if (t.state === "closing") return;
  t.state = "closing";
  try {
    if (t.type === "MC_Stop") {
      // The axis stays in Stopping while an MC_Stop has Execute TRUE: release it before removing the instance.
      try {
        await unwrap(
          api.PATCH("/api/v1/fb/{fb_id}", { params: { path: { fb_id: t.id } }, body: { inputs: { Execute: false } } }),
        );
      } catch (err) {
        if (!(err instanceof ApiError && err.status === 404)) throw err;
      }
    }
    await deleteFb(t.id);
  } catch (err) {
    notifyError(`Remove ${t.type} #${t.id}`, err);
  } finally {
    tracked.delete(t.id);
  }
}

function evaluate(t: Tracked, outputs: Outputs): void {
  if (t.state !== "running") return;
  if (bool(outputs, "Error")) {
    t.state = "error";
    return;
  }
  if (bool(outputs, "Done") || bool(outputs, "CommandAborted") || bool(outputs, "Failure")) void close(t);
}

function setLast(axis: string, out: FBOut, gone = false): void {
  patchAxis(axis, { last: { id: out.id, type: out.type, outputs: out.outputs, gone } });
}

/** Delete the instances of this axis that ended with Error (their ErrorID was shown until now). */
async function dropErrored(axis: string): Promise<void> {
  await Promise.all([...tracked.values()].filter((t) => t.axis === axis && t.state === "error").map((t) => close(t)));
}

/**
 * Issue a one-shot instruction on an axis: a new instance with Execute TRUE. Returns false when the request was
 * rejected (the reason is shown as a notification).
 */
export async function issue(axis: string, type: string, inputs: Record<string, unknown>): Promise<boolean> {
  await dropErrored(axis);
  try {
    const out = await unwrap(
      api.POST("/api/v1/fb", { body: { type, inputs: { ...inputs, Axis: axis, Execute: true }, lease_s: null } }),
    );
    const t: Tracked = { id: out.id, axis, type, state: "running" };
    tracked.set(out.id, t);
    setLast(axis, out);
    // Outputs of the first call (unless paused); later ones arrive with the snapshots.
    const live = liveStore.get().fbs[String(out.id)];
    evaluate(t, live ? live.outputs : out.outputs);
    return true;
  } catch (err) {
    notifyError(type, err);
    return false;
  }
}

/** MC_Reset on the axis (after removing instances that ended with Error). */
export function resetAxis(axis: string): Promise<boolean> {
  return issue(axis, "MC_Reset", {});
}

export function stopAxis(axis: string, deceleration: number, jerk = 0): Promise<boolean> {
  return issue(axis, "MC_Stop", { Deceleration: deceleration, Jerk: jerk });
}

// ------------------------------------------------------------------ servo (MC_Power)

function adopt(axis: string, type: string): number | null {
  const fbs = liveStore.get().fbs;
  for (const key of Object.keys(fbs)) {
    const fb = fbs[key];
    if (fb.type === type && fb.inputs.Axis === axis && !tracked.has(fb.id)) return fb.id;
  }
  return null;
}

export async function setServo(axis: string, enable: boolean): Promise<void> {
  let id = axisCommands(commandsStore.get(), axis).powerId ?? adopt(axis, "MC_Power");
  try {
    if (id !== null) {
      try {
        await unwrap(
          api.PATCH("/api/v1/fb/{fb_id}", { params: { path: { fb_id: id } }, body: { inputs: { Enable: enable } } }),
        );
        patchAxis(axis, { powerId: id });
        return;
      } catch (err) {
        if (!(err instanceof ApiError && err.status === 404)) throw err;
        id = null;
      }
    }
    const out = await unwrap(
      api.POST("/api/v1/fb", { body: { type: "MC_Power", inputs: { Axis: axis, Enable: enable }, lease_s: null } }),
    );
    patchAxis(axis, { powerId: out.id });
  } catch (err) {
    notifyError(enable ? "Servo ON" : "Servo OFF", err);
  }
}

// ------------------------------------------------------------------ jog (MC_MoveJog with a dead-man lease)

export const JOG_LEASE_S = 0.5;
const HEARTBEAT_MS = 100;

interface JogState {
  /** What the user holds now. */
  want: JogDir | null;
  /** What the controller was last told (null after a release or before the first press). */
  sent: JogDir | null;
  velocity: number;
  acceleration: number;
  chain: Promise<void>;
}

const jogs = new Map<string, JogState>();
let heartbeatTimer: ReturnType<typeof setInterval> | undefined;

function jogState(axis: string): JogState {
  let j = jogs.get(axis);
  if (!j) {
    j = { want: null, sent: null, velocity: 0, acceleration: 0, chain: Promise.resolve() };
    jogs.set(axis, j);
  }
  return j;
}

function heldJogIds(): number[] {
  const ids: number[] = [];
  for (const [axis, j] of jogs) {
    const id = axisCommands(commandsStore.get(), axis).jogId;
    if (j.want !== null && id !== null) ids.push(id);
  }
  return ids;
}

function updateHeartbeat(): void {
  const any = [...jogs.values()].some((j) => j.want !== null);
  if (any && heartbeatTimer === undefined) {
    heartbeatTimer = setInterval(() => sendHeartbeat(heldJogIds()), HEARTBEAT_MS);
  } else if (!any && heartbeatTimer !== undefined) {
    clearInterval(heartbeatTimer);
    heartbeatTimer = undefined;
  }
}

async function syncJog(axis: string): Promise<void> {
  const j = jogState(axis);
  const want = j.want;
  if (want === null && j.sent === null) return;
  const inputs = {
    PositiveEnable: want === "plus",
    NegativeEnable: want === "minus",
    Velocity: j.velocity,
    Acceleration: j.acceleration,
    Deceleration: j.acceleration,
  };
  let id = axisCommands(commandsStore.get(), axis).jogId ?? adopt(axis, "MC_MoveJog");
  try {
    if (id !== null) {
      try {
        await unwrap(api.PATCH("/api/v1/fb/{fb_id}", { params: { path: { fb_id: id } }, body: { inputs } }));
        patchAxis(axis, { jogId: id });
      } catch (err) {
        if (!(err instanceof ApiError && err.status === 404)) throw err;
        id = null;
      }
    }
    if (id === null) {
      if (want === null) {
        j.sent = null;
        return;
      }
      const out = await unwrap(
        api.POST("/api/v1/fb", {
          body: { type: "MC_MoveJog", inputs: { Axis: axis, ...inputs }, lease_s: JOG_LEASE_S },
        }),
      );
      patchAxis(axis, { jogId: out.id });
    }
    j.sent = want;
  } catch (err) {
    j.sent = null;
    if (j.want !== null) {
      j.want = null;
      patchAxis(axis, { jogHeld: null });
      updateHeartbeat();
    } else if (err instanceof ApiError && err.status === 423) {
      return; // a release after control passed to another client: the server already dropped the enable
    }
    notifyError("Jog", err);
  }
}

function queueJog(axis: string): void {
  const j = jogState(axis);
  j.chain = j.chain.then(() => syncJog(axis));
}

/** A jog button went down: PATCH the enable once, then keep the lease alive with heartbeats until release. */
export function jogPress(axis: string, dir: JogDir, velocity: number, acceleration: number): void {
  const j = jogState(axis);
  if (j.want === dir) return;
  j.want = dir;
  j.velocity = velocity;
  j.acceleration = acceleration;
  patchAxis(axis, { jogHeld: dir });
  updateHeartbeat();
  queueJog(axis);
}

/** The jog button was released (pointer up/leave/cancel, key up, blur): drop the enable. */
export function jogRelease(axis: string): void {
  const j = jogs.get(axis);
  if (!j || j.want === null) return;
  j.want = null;
  patchAxis(axis, { jogHeld: null });
  updateHeartbeat();
  queueJog(axis);
}

export function releaseAllJogs(): void {
  for (const [axis, j] of jogs) if (j.want !== null) jogRelease(axis);
}

/** Control passed to another client: the server dropped this page's jog enables; forget what is held here. */
function forgetJogs(): void {
  for (const [axis, j] of jogs) {
    if (j.want === null && j.sent === null) continue;
    j.want = null;
    j.sent = null;
    patchAxis(axis, { jogHeld: null });
  }
  updateHeartbeat();
}

// ------------------------------------------------------------------ override (MC_SetOverride)

const OVERRIDE_MIN_INTERVAL_MS = 110; // ≤ 10 PATCH requests a second, with a margin

interface OverrideSync {
  /** What the controller was last told (null: nothing yet, or the instance is gone). */
  sent: { enable: boolean; factor: number } | null;
  busy: boolean;
  timer: ReturnType<typeof setTimeout> | undefined;
  lastAt: number;
}

const overrides = new Map<string, OverrideSync>();

function overrideSync(axis: string): OverrideSync {
  let o = overrides.get(axis);
  if (!o) {
    o = { sent: null, busy: false, timer: undefined, lastAt: 0 };
    overrides.set(axis, o);
  }
  return o;
}

function scheduleOverride(axis: string): void {
  const o = overrideSync(axis);
  if (o.busy || o.timer !== undefined) return;
  const wait = Math.max(0, o.lastAt + OVERRIDE_MIN_INTERVAL_MS - Date.now());
  o.timer = setTimeout(() => {
    o.timer = undefined;
    void flushOverride(axis);
  }, wait);
}

async function flushOverride(axis: string): Promise<void> {
  const o = overrideSync(axis);
  const c = axisCommands(commandsStore.get(), axis);
  const want = { enable: c.overrideEnable, factor: c.overrideFactor };
  if (o.sent && o.sent.enable === want.enable && o.sent.factor === want.factor) return;
  o.busy = true;
  o.lastAt = Date.now();
  const inputs = { Enable: want.enable, VelFactor: want.factor };
  let id = c.overrideId ?? adopt(axis, "MC_SetOverride");
  try {
    if (id !== null) {
      try {
        await unwrap(api.PATCH("/api/v1/fb/{fb_id}", { params: { path: { fb_id: id } }, body: { inputs } }));
        patchAxis(axis, { overrideId: id });
      } catch (err) {
        if (!(err instanceof ApiError && err.status === 404)) throw err;
        id = null;
      }
    }
    if (id === null) {
      const out = await unwrap(
        api.POST("/api/v1/fb", { body: { type: "MC_SetOverride", inputs: { Axis: axis, ...inputs }, lease_s: null } }),
      );
      patchAxis(axis, { overrideId: out.id });
    }
  } catch (err) {
    notifyError("Override (MC_SetOverride)", err);
  } finally {
    // Also after a failure: the same value is not retried, the next change is.
    o.sent = want;
    o.busy = false;
    const now = axisCommands(commandsStore.get(), axis);
    if (now.overrideEnable !== want.enable || now.overrideFactor !== want.factor) scheduleOverride(axis);
  }
}

/**
 * Set the velocity override of an axis (MC_SetOverride VelFactor in %, Enable). The value shows at once; the
 * instance is created on first use and patched at most every 110 ms.
 */
export function setOverride(axis: string, change: { enable?: boolean; factor?: number }): void {
  const cur = axisCommands(commandsStore.get(), axis);
  patchAxis(axis, {
    overrideEnable: change.enable ?? cur.overrideEnable,
    overrideFactor: change.factor ?? cur.overrideFactor,
  });
  scheduleOverride(axis);
}

// ------------------------------------------------------------------ wiring

let started = false;

export function startCommands(): void {
  if (started) return;
  started = true;
  onControlLost(forgetJogs);
  onFrame((_snap, state) => {
    for (const t of [...tracked.values()]) {
      const out = state.fbs[String(t.id)];
      if (!out) {
        if (t.state !== "closing") tracked.delete(t.id);
        continue;
      }
      evaluate(t, out.outputs);
    }
    // Keep the "last instruction" read-out of each axis current (frozen once its instance is gone).
    const cmds = commandsStore.get();
    for (const axis of Object.keys(cmds)) {
      const last = cmds[axis].last;
      if (!last || last.gone) continue;
      const out = state.fbs[String(last.id)];
      if (!out) patchAxis(axis, { last: { ...last, gone: true } });
      else if (JSON.stringify(out.outputs) !== JSON.stringify(last.outputs)) setLast(axis, out);
    }
  });
  onEpoch(() => {
    // The controller was replaced: its instances (and their ids) are gone.
    tracked.clear();
    for (const o of overrides.values()) if (o.timer !== undefined) clearTimeout(o.timer);
    overrides.clear();
    for (const j of jogs.values()) {
      j.want = null;
      j.sent = null;
    }
    updateHeartbeat();
    commandsStore.set({});
  });
  window.addEventListener("blur", releaseAllJogs);
  document.addEventListener("visibilitychange", () => {
    if (document.visibilityState === "hidden") releaseAllJogs();
  });
}
