/**
 * The EtherCAT network (GET /api/v1/ethercat), polled while a view needs it, and the device library
 * (GET /api/v1/devices, GET /api/v1/devices/{id}).
 *
 * Views declare how fresh they need the network with `useEthercatPoll(ms)`; the poller runs at the shortest
 * interval asked for and stops when nothing asks. Commands that change the network (faults, reconnect, PDO apply)
 * refresh it at once.
 */
import { useEffect } from "react";
import { api, unwrap } from "../api/client";
import type { DeviceDescription, DeviceSummary, EtherCATOut, FaultIn, FaultOut, SlaveOut } from "../api/types";
import type { Loadable } from "./catalog";
import { createStore, useStore } from "./createStore";
import { onEpoch, onReconnect } from "./live";

export const ethercatStore = createStore<Loadable<EtherCATOut | null>>({ status: "loading", data: null });

function message(err: unknown): string {
  return err instanceof Error ? err.message : String(err);
}

let inflight: Promise<void> | null = null;

/** Fetch the network now (concurrent calls share one request). */
export function loadEthercat(): Promise<void> {
  if (inflight) return inflight;
  inflight = (async () => {
    try {
      const data = await unwrap(api.GET("/api/v1/ethercat"));
      ethercatStore.set({ status: "ready", data });
    } catch (err) {
      ethercatStore.set((s) => ({ ...s, status: s.data ? "ready" : "error", error: message(err) }));
    } finally {
      inflight = null;
    }
  })();
  return inflight;
}

/** Put one slave as a command returned it into the network (until the next poll). */
export function putSlave(slave: SlaveOut): void {
  ethercatStore.set((s) => {
    if (!s.data) return s;
    const slaves = s.data.slaves.map((x) => (x.node_address === slave.node_address ? slave : x));
    return { ...s, data: { ...s.data, slaves } };
  });
}

// ------------------------------------------------------------------ polling on demand

const demands = new Map<number, number>();
let nextDemand = 1;
let timer: ReturnType<typeof setInterval> | undefined;
let timerMs = 0;

function reschedule(): void {
  const ms = demands.size ? Math.min(...demands.values()) : 0;
  if (ms === timerMs) return;
  if (timer !== undefined) clearInterval(timer);
  timer = undefined;
  timerMs = ms;
  if (ms > 0) {
    timer = setInterval(() => {
      if (document.visibilityState === "visible") void loadEthercat();
    }, ms);
  }
}

/** Keep the network at most `intervalMs` old while the calling component is mounted. */
export function useEthercatPoll(intervalMs: number): void {
  useEffect(() => {
    const id = nextDemand++;
    demands.set(id, intervalMs);
    reschedule();
    void loadEthercat();
    return () => {
      demands.delete(id);
      reschedule();
    };
  }, [intervalMs]);
}

export function useEthercat(): Loadable<EtherCATOut | null> {
  return useStore(ethercatStore, (s) => s);
}

export function useSlave(node: number): SlaveOut | undefined {
  return useStore(ethercatStore, (s) => s.data?.slaves.find((x) => x.node_address === node));
}

// ------------------------------------------------------------------ commands

/** POST /api/v1/faults (a commissioning drill); the network is refreshed afterwards. */
export async function injectFault(kind: FaultIn["kind"], node: number, code = 0x2310): Promise<FaultOut> {
  try {
    return await unwrap(
      api.POST("/api/v1/faults", { body: { kind, node_address: node, code, persistent: false, value: 0 } }),
    );
  } finally {
    void loadEthercat();
  }
}

/** POST /api/v1/ethercat/slaves/{address}/connect (the reconnect command). */
export async function connectSlave(node: number): Promise<SlaveOut> {
  try {
    const slave = await unwrap(
      api.POST("/api/v1/ethercat/slaves/{address}/connect", { params: { path: { address: node } } }),
    );
    putSlave(slave);
    return slave;
  } finally {
    void loadEthercat();
  }
}

// ------------------------------------------------------------------ device library

export const devicesStore = createStore<Loadable<DeviceSummary[]>>({ status: "loading", data: [] });
export const deviceDetailStore = createStore<Readonly<Record<string, Loadable<DeviceDescription | null>>>>({});

export async function loadDevices(): Promise<void> {
  try {
    const data = await unwrap(api.GET("/api/v1/devices"));
    devicesStore.set({ status: "ready", data });
  } catch (err) {
    devicesStore.set((s) => ({ ...s, status: s.status === "ready" ? "ready" : "error", error: message(err) }));
  }
}

export function useDevices(): Loadable<DeviceSummary[]> {
  const st = useStore(devicesStore, (s) => s);
  useEffect(() => {
    void loadDevices();
  }, []);
  return st;
}

async function loadDevice(id: string): Promise<void> {
  try {
    const data = await unwrap(api.GET("/api/v1/devices/{device_id}", { params: { path: { device_id: id } } }));
    deviceDetailStore.set((s) => ({ ...s, [id]: { status: "ready", data } }));
  } catch (err) {
    deviceDetailStore.set((s) => ({ ...s, [id]: { status: "error", data: null, error: message(err) } }));
  }
}

/** The full description of a library device (PDOs, object dictionary), loaded on first use. */
export function useDevice(id: string | null | undefined): DeviceDescription | null {
  const entry = useStore(deviceDetailStore, (s) => (id ? s[id] : undefined));
  useEffect(() => {
    if (id && deviceDetailStore.get()[id] === undefined) {
      deviceDetailStore.set((s) => ({ ...s, [id]: { status: "loading", data: null } }));
      void loadDevice(id);
    }
  }, [id]);
  return entry?.data ?? null;
}

let started = false;

export function startEthercat(): void {
  if (started) return;
  started = true;
  // A new controller (PDO applied, project opened, reset) has a new network.
  onEpoch(() => {
    if (demands.size) void loadEthercat();
    // Another project may bring other ESI files.
    if (devicesStore.get().status !== "loading") void loadDevices();
  });
  onReconnect(() => {
    if (demands.size) void loadEthercat();
  });
}
