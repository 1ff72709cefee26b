/**
 * Cam test run: a slave axis cams on a master axis that runs at constant velocity, through the /fb REST API —
 * servo ON for both (MC_Power, adopted if the test-run tab already made one), MC_CamIn (starting at the master's
 * present position, periodic or once) and MC_MoveVelocity of the master; Stop issues MC_Stop on both axes and deletes
 * the instances it created once they are stopped (so the table is free to be saved again, D45).
 */
import { api, unwrap } from "../api/client";
import { setServo } from "./commands";
import { createStore, useStore } from "./createStore";
import { liveStore } from "./live";

export interface CamRun {
  status: "idle" | "starting" | "running" | "stopping";
  master: string;
  slave: string;
  camInId: number | null;
  ids: number[];
  /** master position where the cam table's phase 0 is */
  startPosition: number;
  error?: string;
}

export const camRunStore = createStore<Record<string, CamRun>>({});

export function useCamRun(name: string): CamRun | undefined {
  return useStore(camRunStore, (s) => s[name]);
}

function patch(name: string, p: Partial<CamRun>): void {
  camRunStore.set((s) => ({ ...s, [name]: { ...(s[name] ?? { status: "idle", master: "", slave: "", camInId: null,
    ids: [], startPosition: 0 }), ...p } }));
}

const pause = (ms: number) => new Promise((r) => setTimeout(r, ms));

/** Wait (a bounded number of polls) until `ok` holds for the live snapshot. */
async function until(ok: () => boolean, what: string, polls = 100): Promise<void> {
  for (let i = 0; i < polls; i++) {
    if (ok()) return;
    await pause(50);
  }
  throw new Error(`timed out waiting for ${what}`);
}

async function post(type: string, inputs: Record<string, unknown>): Promise<number> {
  const out = await unwrap(api.POST("/api/v1/fb", { body: { type, inputs, lease_s: null } }));
  return out.id;
}

async function remove(id: number): Promise<void> {
  try {
    await unwrap(api.DELETE("/api/v1/fb/{fb_id}", { params: { path: { fb_id: id } } }));
  } catch {
    // already gone
  }
}

export async function startCamRun(name: string, opts: { master: string; slave: string; velocity: number;
  acceleration: number; periodic: boolean }): Promise<void> {
  const { master, slave } = opts;
  patch(name, { status: "starting", master, slave, error: undefined, ids: [], camInId: null });
  const ids: number[] = [];
  try {
    if (master === slave) throw new Error("choose two different axes for master and slave");
    await setServo(master, true);
    await setServo(slave, true);
    const on = (a: string) => liveStore.get().axes[a]?.Status.Standstill === true;
    await until(() => on(master) && on(slave), "servo ON and standstill of both axes");
    const startPosition = liveStore.get().axes[master]?.Cmd.Pos ?? 0;
    const camIn = await post("MC_CamIn", {
      Master: master, Slave: slave, CamTable: name, Execute: true, Periodic: opts.periodic,
      StartMode: "_mcRelativePosition", StartPosition: startPosition, MasterStartDistance: 0,
    });
    ids.push(camIn);
    patch(name, { camInId: camIn, ids: [...ids], startPosition });
    ids.push(await post("MC_MoveVelocity", {
      Axis: master, Execute: true, Velocity: opts.velocity, Acceleration: opts.acceleration,
      Deceleration: opts.acceleration, Direction: "_mcPositiveDirection",
    }));
    patch(name, { status: "running", ids: [...ids] });
  } catch (err) {
    await Promise.all(ids.map(remove));
    patch(name, { status: "idle", ids: [], camInId: null, error: err instanceof Error ? err.message : String(err) });
    throw err;
  }
}

export async function stopCamRun(name: string, deceleration: number): Promise<void> {
  const run = camRunStore.get()[name];
  if (!run) return;
  patch(name, { status: "stopping" });
  const ids = [...run.ids];
  try {
    const stops = [
      await post("MC_Stop", { Axis: run.master, Execute: true, Deceleration: deceleration }),
      await post("MC_Stop", { Axis: run.slave, Execute: true, Deceleration: deceleration * 10 }),
    ];
    ids.push(...stops);
    const done = (id: number) => {
      const fb = liveStore.get().fbs[String(id)];
      return !!fb && (fb.outputs.Done === true || fb.outputs.Error === true);
    };
    await until(() => stops.every(done), "the axes to stop", 200);
    // MC_Stop holds its axis in Stopping while Execute is TRUE (even after Done): drop Execute before deleting the
    // instances, else the axes stay Stopping and refuse the next motion
    await Promise.all(stops.map((id) => unwrap(api.PATCH("/api/v1/fb/{fb_id}", {
      params: { path: { fb_id: id } }, body: { inputs: { Execute: false } } }))));
    const rest = (a: string) => liveStore.get().axes[a]?.Status.Stopping === false;
    await until(() => rest(run.master) && rest(run.slave), "the axes to leave Stopping", 100);
  } catch (err) {
    patch(name, { error: err instanceof Error ? err.message : String(err) });
  } finally {
    await Promise.all(ids.map(remove));
    patch(name, { status: "idle", ids: [], camInId: null });
  }
}
