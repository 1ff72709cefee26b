/**
 * Axes-group test run over /api/v1/fb, with the same PLC semantics as the axis test run (store/commands.ts):
 *
 * - State: GET /api/v1/groups polled every 200 ms while a group panel is shown (`useGroups`).
 * - One-shot group instructions (MC_GroupEnable/Disable/Reset/Stop/ImmediateStop, MC_MoveLinear, MC_MoveCircular2D)
 *   are new instances with Execute TRUE, removed once they end (MC_GroupStop: Execute first set FALSE, the group stays
 *   Stopping while it is TRUE); an instance that ended with Error is kept so its ErrorID stays visible.
 * - Cartesian jog of a robot: one MC_RobotJog instance per group (MC Studio extension) with a 1.5 s dead-man lease,
 *   renewed by WebSocket heartbeats while a jog button is held.
 * - The pick-and-place demo: MC_RobotJog in Mode 1 (go to) with the lease renewed while the sequence runs, the
 *   conveyor on MC_MoveVelocity; stopping drops the enable (the robot decelerates) and stops the conveyor.
 */
import { useEffect } from "react";
import { ApiError, api, unwrap } from "../api/client";
import type { FBOut } from "../api/types";
import { notifyError } from "../lib/notify";
import { issue, setServo, stopAxis } from "./commands";
import { createStore, useStore } from "./createStore";
import { liveStore, onEpoch, onFrame, sendHeartbeat } from "./live";

type Outputs = Record<string, unknown>;

export interface GroupInfo {
  name: string;
  number: number;
  composition: string;
  axes: string[];
  state: string;
  ready: boolean;
  error_code: string;
  kinematics: string | null;
  cmd_pos: number[];
}

// ------------------------------------------------------------------ group list (polled)

export const groupsStore = createStore<{ groups: GroupInfo[]; error: string | null; loaded: boolean }>({
  groups: [],
  error: null,
  loaded: false,
});

const POLL_MS = 200;
let pollUsers = 0;
let pollTimer: ReturnType<typeof setInterval> | undefined;
let polling = false;

export async function refreshGroups(): Promise<void> {
  if (polling) return;
  polling = true;
  try {
    const groups = (await unwrap(api.GET("/api/v1/groups"))) as GroupInfo[];
    groupsStore.set({ groups, error: null, loaded: true });
  } catch (err) {
    groupsStore.set((s) => ({ ...s, error: err instanceof Error ? err.message : String(err), loaded: true }));
  } finally {
    polling = false;
  }
}

/** The project's axes groups, polled while a component using them is mounted. */
export function useGroups(): { groups: GroupInfo[]; error: string | null; loaded: boolean } {
  useEffect(() => {
    pollUsers += 1;
    if (pollTimer === undefined) {
      void refreshGroups();
      pollTimer = setInterval(() => {
        if (document.visibilityState === "visible") void refreshGroups();
      }, POLL_MS);
    }
    return () => {
      pollUsers -= 1;
      if (pollUsers === 0 && pollTimer !== undefined) {
        clearInterval(pollTimer);
        pollTimer = undefined;
      }
    };
  }, []);
  return useStore(groupsStore, (s) => s);
}

export function useGroup(name: string): GroupInfo | undefined {
  const { groups } = useGroups();
  return groups.find((g) => g.name === name);
}

// ------------------------------------------------------------------ per-group command state

export interface LastGroupInstruction {
  id: number;
  type: string;
  outputs: Outputs;
  gone: boolean;
}

export interface GroupCommands {
  last: LastGroupInstruction | null;
  jogId: number | null;
  /** The held jog button ("+X", "-Z" …) or null. */
  jogHeld: string | null;
  /** The pick-and-place demo: what it is doing now, null when not running. */
  demo: string | null;
  demoCycles: number;
}

const EMPTY: GroupCommands = { last: null, jogId: null, jogHeld: null, demo: null, demoCycles: 0 };

export const groupCommandsStore = createStore<Readonly<Record<string, GroupCommands>>>({});

export function groupCommands(s: Readonly<Record<string, GroupCommands>>, group: string): GroupCommands {
  return s[group] ?? EMPTY;
}

export function useGroupCommands(group: string): GroupCommands {
  return useStore(groupCommandsStore, (s) => groupCommands(s, group));
}

function patchGroup(group: string, patch: Partial<GroupCommands>): void {
  groupCommandsStore.set((s) => ({ ...s, [group]: { ...groupCommands(s, group), ...patch } }));
}

interface Tracked {
  id: number;
  group: string;
  type: string;
  state: "running" | "error" | "closing";
}

const tracked = new Map<number, Tracked>();

async function deleteFb(id: number): Promise<void> {
  try {
    await unwrap(api.DELETE("/api/v1/fb/{fb_id}", { params: { path: { fb_id: id } } }));
  } catch (err) {
    if (!(err instanceof ApiError && err.status === 404)) throw err;
  }
}

async function patchFb(id: number, inputs: Record<string, unknown>): Promise<void> {
  await unwrap(api.PATCH("/api/v1/fb/{fb_id}", { params: { path: { fb_id: id } }, body: { inputs } }));
}

async function close(t: Tracked): Promise<void> {
  if (t.state === "closing") return;
  t.state = "closing";
  try {
    if (t.type === "MC_GroupStop") {
      try {
        await patchFb(t.id, { Execute: false });
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

function evaluate(t: Tracked, o: Outputs): void {
  if (t.state !== "running") return;
  if (o.Error === true) {
    t.state = "error";
    return;
  }
  if (o.Done === true || o.CommandAborted === true || o.Failure === true) void close(t);
}

/** Issue a one-shot group instruction (a new instance with Execute TRUE). False when the request was refused. */
export async function issueGroup(group: string, type: string, inputs: Record<string, unknown> = {}): Promise<boolean> {
  await Promise.all([...tracked.values()].filter((t) => t.group === group && t.state === "error").map((t) => close(t)));
  try {
    const out = await unwrap(
      api.POST("/api/v1/fb", { body: { type, inputs: { ...inputs, AxesGroup: group, Execute: true }, lease_s: null } }),
    );
    const t: Tracked = { id: out.id, group, type, state: "running" };
    tracked.set(out.id, t);
    patchGroup(group, { last: { id: out.id, type, outputs: out.outputs, gone: false } });
    const live = liveStore.get().fbs[String(out.id)];
    evaluate(t, live ? live.outputs : out.outputs);
    return true;
  } catch (err) {
    notifyError(type, err);
    return false;
  }
}

onFrame((_snap, state) => {
  for (const t of tracked.values()) {
    const fb: FBOut | undefined = state.fbs[String(t.id)];
    if (!fb) continue;
    evaluate(t, fb.outputs);
  }
  // the "last instruction" of each group follows its instance's outputs
  const all = groupCommandsStore.get();
  let changed = false;
  const next: Record<string, GroupCommands> = { ...all };
  for (const [group, c] of Object.entries(all)) {
    if (!c.last || c.last.gone) continue;
    const fb = state.fbs[String(c.last.id)];
    if (fb && fb.outputs !== c.last.outputs) {
      next[group] = { ...c, last: { ...c.last, outputs: fb.outputs } };
      changed = true;
    } else if (!fb && !tracked.has(c.last.id)) {
      next[group] = { ...c, last: { ...c.last, gone: true } };
      changed = true;
    }
  }
  if (changed) groupCommandsStore.set(next);
});

onEpoch(() => {
  tracked.clear();
  jogs.clear();
  demos.clear();
  groupCommandsStore.set({});
});

/** Servo ON/OFF of every composition axis (one MC_Power per axis, shared with the axis test run). */
export async function setGroupServo(axes: string[], on: boolean): Promise<void> {
  await Promise.all(axes.map((a) => setServo(a, on)));
}

export const enableGroup = (g: string) => issueGroup(g, "MC_GroupEnable");
export const disableGroup = (g: string) => issueGroup(g, "MC_GroupDisable");
export const resetGroup = (g: string) => issueGroup(g, "MC_GroupReset");
export const stopGroup = (g: string, deceleration: number) => issueGroup(g, "MC_GroupStop", { Deceleration: deceleration });
export const immediateStopGroup = (g: string) => issueGroup(g, "MC_GroupImmediateStop");

// ------------------------------------------------------------------ Cartesian jog (MC_RobotJog, dead-man lease)

/**
 * 1.5 s rather than the axis jog's 0.5 s: next to the 3D view a software-rendered WebGL frame can hold the page's
 * main thread for several 100 ms (measured in headless Chromium: 100 ms timers firing every ~0.7 s), and a lease
 * shorter than that gap would stop the robot while the button is still held.
 */
export const ROBOT_JOG_LEASE_S = 1.5;
const HEARTBEAT_MS = 100;

export interface JogSettings {
  velocity: number;
  acceleration: number;
  /** 1 = MCS, 3 = UCS */
  coordSystem: number;
  csid: number;
}

interface JogState {
  want: string | null;
  chain: Promise<void>;
}

const jogs = new Map<string, JogState>();
const leased = new Set<number>();
let heartbeatTimer: ReturnType<typeof setInterval> | undefined;

function updateHeartbeat(): void {
  if (leased.size > 0 && heartbeatTimer === undefined) {
    heartbeatTimer = setInterval(() => sendHeartbeat([...leased]), HEARTBEAT_MS);
  } else if (leased.size === 0 && heartbeatTimer !== undefined) {
    clearInterval(heartbeatTimer);
    heartbeatTimer = undefined;
  }
}

const DIRS: Record<string, number[]> = {
  "+X": [1, 0, 0], "-X": [-1, 0, 0], "+Y": [0, 1, 0], "-Y": [0, -1, 0], "+Z": [0, 0, 1], "-Z": [0, 0, -1],
};

/** The group's MC_RobotJog instance (created with Enable FALSE on first use). */
async function jogInstance(group: string, inputs: Record<string, unknown>): Promise<number> {
  const id = groupCommands(groupCommandsStore.get(), group).jogId;
  if (id !== null) {
    try {
      await patchFb(id, inputs);
      return id;
    } catch (err) {
      if (!(err instanceof ApiError && err.status === 404)) throw err;
    }
  }
  const out = await unwrap(
    api.POST("/api/v1/fb", {
      body: { type: "MC_RobotJog", inputs: { AxesGroup: group, ...inputs }, lease_s: ROBOT_JOG_LEASE_S },
    }),
  );
  patchGroup(group, { jogId: out.id });
  return out.id;
}

async function syncJog(group: string, settings: JogSettings): Promise<void> {
  const j = jogs.get(group);
  if (!j) return;
  const want = j.want;
  try {
    const inputs: Record<string, unknown> = want
      ? {
          Enable: true, Mode: 0, Direction: DIRS[want], Velocity: settings.velocity,
          Acceleration: settings.acceleration, CoordSystem: settings.coordSystem, CSID: settings.csid,
        }
      : { Enable: false };
    if (!want && groupCommands(groupCommandsStore.get(), group).jogId === null) return;
    const id = await jogInstance(group, inputs);
    if (want) leased.add(id);
    else leased.delete(id);
    updateHeartbeat();
  } catch (err) {
    j.want = null;
    patchGroup(group, { jogHeld: null });
    notifyError("Cartesian jog (MC_RobotJog)", err);
  }
}

export function robotJogPress(group: string, dir: string, settings: JogSettings): void {
  let j = jogs.get(group);
  if (!j) {
    j = { want: null, chain: Promise.resolve() };
    jogs.set(group, j);
  }
  if (j.want === dir) return;
  j.want = dir;
  patchGroup(group, { jogHeld: dir });
  const jj = j;
  jj.chain = jj.chain.then(() => syncJog(group, settings));
}

export function robotJogRelease(group: string): void {
  const j = jogs.get(group);
  if (!j || j.want === null) return;
  j.want = null;
  patchGroup(group, { jogHeld: null });
  j.chain = j.chain.then(() => syncJog(group, { velocity: 0, acceleration: 0, coordSystem: 1, csid: 0 }));
}

/**
 * One step (inching) of the TCP: MC_RobotJog Mode 2 moves `distance` mm along the direction of the chosen frame from
 * Enable↑ and stops (InPosition, or AtBoundary at the workspace boundary); then the enable drops and the group is
 * Standby again. The lease is renewed while the step runs; a press during a step is ignored (D93).
 */
export async function robotJogStep(group: string, dir: string, settings: JogSettings & { distance: number }): Promise<void> {
  let j = jogs.get(group);
  if (!j) {
    j = { want: null, chain: Promise.resolve() };
    jogs.set(group, j);
  }
  if (j.want !== null) return;
  j.want = dir;
  patchGroup(group, { jogHeld: dir });
  let id: number | null = null;
  try {
    const prev = groupCommands(groupCommandsStore.get(), group).jogId;
    if (prev !== null && fbOut(prev)?.Busy === true) {
      await jogInstance(group, { Enable: false });
      await waitFor(() => fbOut(prev)?.Busy !== true, 3000);
    }
    id = await jogInstance(group, {
      Enable: true, Mode: 2, Direction: DIRS[dir], Distance: settings.distance, Velocity: settings.velocity,
      Acceleration: settings.acceleration, CoordSystem: settings.coordSystem, CSID: settings.csid,
    });
    leased.add(id);
    updateHeartbeat();
    const sid = id;
    // Enable↑ is seen in the next period: wait for the step to start, then for its end
    await waitFor(() => fbOut(sid)?.Busy === true || fbOut(sid)?.Error === true, 2000);
    const end = () => {
      const o = fbOut(sid);
      return o?.InPosition === true || o?.AtBoundary === true || o?.Error === true || o?.CommandAborted === true
        || o?.Busy !== true;
    };
    await waitFor(end, 30000);
  } catch (err) {
    notifyError("Cartesian jog step (MC_RobotJog)", err);
  } finally {
    if (id !== null) {
      leased.delete(id);
      updateHeartbeat();
      try {
        await patchFb(id, { Enable: false });
      } catch {
        /* the lease drops the enable anyway */
      }
    }
    j.want = null;
    patchGroup(group, { jogHeld: null });
  }
}

// ------------------------------------------------------------------ ready pose and the pick-and-place demo

function sleep(ms: number): Promise<void> {
  return new Promise((r) => setTimeout(r, ms));
}

/** Wait until `pred` holds for the latest snapshot/poll; false on timeout or when `alive()` turns false. */
/**
 * Wait until `pred` holds, at most `timeoutMs` of the controller's simulated time: a machine that runs slower than
 * real time (a loaded PC, a large project) gets the same number of control periods as a fast one. A wall-clock cap of
 * six times the timeout (at least 30 s) ends the wait when the controller does not run at all (paused, gone).
 */
async function waitFor(pred: () => boolean, timeoutMs: number, alive: () => boolean = () => true): Promise<boolean> {
  const simNow = () => liveStore.get().controller?.time_s ?? null;
  const simStart = simNow();
  const started = Date.now();
  const wallEnd = started + Math.max(6 * timeoutMs, 30000);
  while (Date.now() < wallEnd) {
    if (!alive()) return false;
    if (pred()) return true;
    const t = simNow();
    const elapsedMs = simStart !== null && t !== null ? (t - simStart) * 1000 : Date.now() - started; // no snapshot: wall
    if (elapsedMs > timeoutMs) break;
    await sleep(50);
  }
  return pred();
}

const groupState = (g: string) => groupsStore.get().groups.find((x) => x.name === g);
const fbOut = (id: number) => liveStore.get().fbs[String(id)]?.outputs;

/**
 * Move the robot's arms to the inverse kinematics of `point` (MCS, mm) — the way into the workspace from the zero pose
 * (which lies above it). As on the controller, single-axis positioning of the robot's axes needs the group disabled
 * (§9.9): the group is disabled, the three axes move with MC_MoveAbsolute at a moderate speed (no step, so the drives
 * follow without following-error warnings), and the group is enabled again if it was.
 */
export async function moveToPose(group: string, point: number[]): Promise<boolean> {
  const made: number[] = [];
  try {
    const inv = await unwrap(
      api.POST("/api/v1/groups/{name}/kinematics/inverse", { params: { path: { name: group } }, body: { position: point } }),
    );
    const angles = (inv as { axes: number[] }).axes;
    const info = groupState(group);
    if (!info) throw new Error(`no group ${group}`);
    const wasEnabled = info.state !== "Disabled";
    if (wasEnabled) {
      await disableGroup(group);
      if (!(await waitFor(() => groupState(group)?.state === "Disabled", 5000))) throw new Error("the group did not disable");
    }
    for (let k = 0; k < info.axes.length; k++) {
      const out = await unwrap(
        api.POST("/api/v1/fb", {
          body: {
            type: "MC_MoveAbsolute",
            inputs: { Axis: info.axes[k], Execute: true, Position: angles[k], Velocity: READY_VELOCITY,
              Acceleration: READY_ACCELERATION, Deceleration: READY_ACCELERATION },
            lease_s: null,
          },
        }),
      );
      made.push(out.id);
    }
    const settled = () => made.every((id) => fbOut(id)?.Done === true || fbOut(id)?.Error === true
      || fbOut(id)?.CommandAborted === true);
    const ok = await waitFor(settled, 15000) && made.every((id) => fbOut(id)?.Done === true);
    if (wasEnabled) {
      await enableGroup(group);
      await waitFor(() => groupState(group)?.state === "Standby", 5000);
    }
    return ok;
  } catch (err) {
    notifyError("Move to the ready pose", err);
    return false;
  } finally {
    await Promise.all(made.map((id) => deleteFb(id)));
  }
}

const READY_VELOCITY = 60; // °/s of each arm
const READY_ACCELERATION = 600; // °/s²

export interface DemoConfig {
  conveyor: string;
  conveyorVelocity: number;
  velocity: number;
  acceleration: number;
  /** Pick and place points (MCS, mm) and the approach height above them. */
  pick: number[];
  place: number[];
  approach: number;
}

export const DEMO_DEFAULTS: DemoConfig = {
  conveyor: "MC_Axis007",
  conveyorVelocity: 100,
  velocity: 400,
  acceleration: 4000,
  pick: [-150, -100, -400],
  place: [150, 100, -400],
  approach: 70,
};

interface DemoRun {
  stop: boolean;
}

const demos = new Map<string, DemoRun>();

export function demoRunning(group: string): boolean {
  return demos.has(group);
}

/** Ask the demo to stop: the go-to enable drops (the robot decelerates), the conveyor stops. */
export function stopDemo(group: string): void {
  const run = demos.get(group);
  if (run) run.stop = true;
}

/**
 * The pick-and-place demo: servo ON, the group enabled, into the workspace, the conveyor running, then the TCP
 * goes above the pick point, down, up, above the place point, down, up … until `stopDemo`.
 */
export async function runDemo(group: string, axes: string[], cfg: DemoConfig = DEMO_DEFAULTS): Promise<void> {
  if (demos.has(group)) return;
  const run: DemoRun = { stop: false };
  demos.set(group, run);
  const alive = () => !run.stop;
  const status = (s: string) => patchGroup(group, { demo: s });
  let jogId: number | null = null;
  try {
    status("servo ON");
    await setGroupServo([...axes, cfg.conveyor], true);
    await waitFor(() => axes.every((a) => liveStore.get().axes[a]?.Status?.Standstill === true), 5000, alive);
    await refreshGroups();
    if (groupState(group)?.state === "ErrorStop") await resetGroup(group);
    if (groupState(group)?.state !== "Standby") {
      status("enabling the group");
      await enableGroup(group);
      await waitFor(() => groupState(group)?.state === "Standby", 5000, alive);
    }
    if (!alive()) return;
    status("conveyor");
    await issue(cfg.conveyor, "MC_MoveVelocity", {
      Velocity: cfg.conveyorVelocity, Acceleration: 500, Deceleration: 500, Direction: "_mcPositiveDirection",
    });
    const above = (p: number[]) => [p[0], p[1], p[2] + cfg.approach];
    const route = [above(cfg.pick), cfg.pick, above(cfg.pick), above(cfg.place), cfg.place, above(cfg.place)];
    status("to the ready pose");
    // into the workspace first if the TCP is outside (the zero pose is above it): the first point of the route
    const inputs = {
      Enable: true, Mode: 1, TargetPosition: route[0], Velocity: cfg.velocity, Acceleration: cfg.acceleration,
      CoordSystem: 1,
    };
    jogId = await jogInstance(group, inputs);
    leased.add(jogId);
    updateHeartbeat();
    await sleep(100);
    if (fbOut(jogId)?.Error === true) {
      // 6701: the TCP is outside the workspace — reset, bring it in with the ACS, and start again
      await resetGroup(group);
      await waitFor(() => groupState(group)?.state === "Standby", 3000, alive);
      await patchFb(jogId, { Enable: false });
      if (!(await moveToPose(group, route[0]))) throw new Error("cannot reach the ready pose");
      await waitFor(() => groupState(group)?.state === "Standby", 3000, alive);
      await patchFb(jogId, inputs);
    }
    let k = 0;
    let cycles = 0;
    while (alive()) {
      const id = jogId;
      const ok = await waitFor(() => fbOut(id)?.InPosition === true || fbOut(id)?.Error === true
        || fbOut(id)?.CommandAborted === true, 15000, alive);
      if (!alive()) break;
      const o = fbOut(id);
      if (!ok || o?.Error === true || o?.CommandAborted === true) {
        throw new Error(o?.Error === true ? `MC_RobotJog ErrorID ${String(o.ErrorID)}` : "the robot stopped");
      }
      k = (k + 1) % route.length;
      if (k === 0) {
        cycles += 1;
        patchGroup(group, { demoCycles: cycles });
      }
      status(["above the pick point", "picking", "lifting", "above the place point", "placing", "lifting"][k]);
      await sleep(k === 2 || k === 5 ? 150 : 0); // a short dwell at the pick and place points
      await patchFb(id, { TargetPosition: route[k] });
      // the new target is taken in the next period: wait until a snapshot shows InPosition FALSE
      await waitFor(() => fbOut(id)?.InPosition !== true, 2000, alive);
    }
  } catch (err) {
    notifyError("Pick-and-place demo", err);
  } finally {
    if (jogId !== null) {
      leased.delete(jogId);
      updateHeartbeat();
      try {
        await patchFb(jogId, { Enable: false });
      } catch {
        /* the lease drops the enable anyway */
      }
    }
    await stopAxis(cfg.conveyor, 500);
    demos.delete(group);
    patchGroup(group, { demo: null });
  }
}
