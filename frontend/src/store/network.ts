/**
 * Editing the EtherCAT network: the configuration (the project's `ethercat` section) and PUT /api/v1/ethercat.
 *
 * The configuration comes from GET /api/v1/project → `.ethercat`. A project without a slave list uses implicit slaves
 * (one built-in device per axis); the list is then built from GET /api/v1/ethercat (node address, name, device, default
 * PDO map), so that the first slave edit makes the network explicit without changing anything else.
 *
 * Every edit is applied on the configuration as the controller has it at that moment (fetched again just before the
 * PUT), so that an edit never undoes another one (a PDO map applied meanwhile). The controller validates the whole
 * project: a 422 lists problems with `path` such as `ethercat.slaves[3].node_address` or `axes[1].node_address`; they
 * are returned with the slave they concern (its index in what was sent) and the field, and the editors place them on
 * their fields. Applying restarts the controller like a download (409 while an axis moves).
 *
 * One edit needs more than the `ethercat` section: a new node address for a slave that an axis uses (the axis refers
 * to its slave by node address). That edit moves the axis along and goes to PUT /api/v1/project with both changes, so
 * that the controller never sees the one without the other.
 */
import { useEffect } from "react";
import { ApiError, api, formatLoc, unwrap } from "../api/client";
import type {
  EtherCATMasterConfig,
  EtherCATOut,
  EtherCATSlaveConfig,
  Project,
  SlaveEmulation,
  SlavePdoConfig,
  StartupSdo,
} from "../api/types";
import type { Loadable } from "./catalog";
import { createStore, useStore } from "./createStore";
import { ethercatStore } from "./ethercat";
import { onEpoch, onReconnect } from "./live";

/** A slave as the configuration lists it, every field present. */
export interface SlaveConfig {
  node_address: number;
  name: string;
  device: string;
  pdo: SlavePdoConfig | null;
  startup_sdos: StartupSdo[];
  emulation: Required<SlaveEmulation>;
}

export interface NetConfig {
  master: EtherCATMasterConfig;
  slaves: SlaveConfig[];
}

export interface AxisRef {
  name: string;
  node_address: number | null;
  /** `_mcServo`, `_mcEncdr`, `_mcVirServo`, `_mcVirEncdr`. */
  type: string;
}

export interface NetworkConfig {
  config: NetConfig;
  /** The project lists its slaves (else they are the implicit ones, as the controller runs them). */
  explicit: boolean;
  /** The project's axes and their node addresses, in project order (to place `axes[i]` problems). */
  axes: readonly AxisRef[];
  /** The controller's primary period = the EtherCAT cycle [µs]. */
  cycle_time_us: number;
}

export const networkConfigStore = createStore<Loadable<NetworkConfig | null>>({ status: "loading", data: null });

export const DEFAULT_EMULATION: Required<SlaveEmulation> = { connected: true, wired_device: null, encoder_velocity: 0 };

const DEFAULT_SDO = { subindex: 0, bit_len: 32, abort_on_error: true, comment: "" } as const;

function slaveConfig(s: EtherCATSlaveConfig): SlaveConfig {
  return {
    node_address: s.node_address,
    name: s.name ?? "",
    device: s.device,
    pdo: s.pdo ?? null,
    startup_sdos: (s.startup_sdos ?? []).map((x) => ({ ...DEFAULT_SDO, ...x })),
    emulation: { ...DEFAULT_EMULATION, ...(s.emulation ?? {}), wired_device: s.emulation?.wired_device ?? null },
  };
}

function message(err: unknown): string {
  return err instanceof Error ? err.message : String(err);
}

interface Current {
  nc: NetworkConfig;
  project: Project;
}

async function fetchCurrent(): Promise<Current> {
  const [project, net] = await Promise.all([unwrap(api.GET("/api/v1/project")), unwrap(api.GET("/api/v1/ethercat"))]);
  ethercatStore.set({ status: "ready", data: net });
  const given = project.ethercat?.slaves ?? [];
  const master = { ...net.master.settings, ...(project.ethercat?.master ?? {}) };
  const slaves = given.length
    ? given.map(slaveConfig)
    : net.slaves.map((s) => slaveConfig({ node_address: s.node_address, name: s.name, device: s.device_id, pdo: null }));
  const axes = (project.axes ?? []).map((a) => ({
    name: a.name,
    node_address: a.node_address ?? null,
    type: String(a.type ?? "_mcServo"),
  }));
  return {
    nc: { config: { master, slaves }, explicit: given.length > 0, axes, cycle_time_us: net.master.cycle_time_us },
    project,
  };
}

/** The configuration as the controller has it now (explicit: the implicit slaves listed). */
export async function fetchNetworkConfig(): Promise<NetworkConfig> {
  return (await fetchCurrent()).nc;
}

let inflight: Promise<void> | null = null;

export function loadNetworkConfig(): Promise<void> {
  if (inflight) return inflight;
  inflight = (async () => {
    try {
      const data = await fetchNetworkConfig();
      networkConfigStore.set({ status: "ready", data });
    } catch (err) {
      networkConfigStore.set((s) => ({ ...s, status: s.data ? "ready" : "error", error: message(err) }));
    } finally {
      inflight = null;
    }
  })();
  return inflight;
}

let users = 0;
let started = false;

/** The network configuration, loaded while a component uses it (and again whenever the controller was replaced). */
export function useNetworkConfig(): Loadable<NetworkConfig | null> {
  const st = useStore(networkConfigStore, (s) => s);
  useEffect(() => {
    if (!started) {
      started = true;
      const reload = () => {
        if (users > 0) void loadNetworkConfig();
      };
      onEpoch(reload);
      onReconnect(reload);
    }
    users++;
    void loadNetworkConfig();
    return () => {
      users--;
    };
  }, []);
  return st;
}

/** One slave's configuration (an object of the store: safe as a `useStore` selection). */
export function useSlaveConfig(node: number): SlaveConfig | undefined {
  return useStore(networkConfigStore, (s) => s.data?.config.slaves.find((x) => x.node_address === node));
}

// ------------------------------------------------------------------ apply

export interface NetIssue {
  /** Where the API located it, without the leading `ethercat.`, e.g. `slaves[3].startup_sdos[0].index`. */
  path: string;
  /** The message, with `ethercat.slaves[k]` replaced by that slave's name and node. */
  msg: string;
  /** Index in the slave list that was sent, when the problem is about a slave. */
  slave: number | null;
  /** Node address of that slave (in what was sent). */
  node: number | null;
  /** The field within the slave (`node_address`, `startup_sdos[0].index`) or the master (`master.sync_offset_pct`);
   * "" when the whole slave or nothing specific is meant. */
  field: string;
  /** For `axes[i]` problems: the axis and the node address it had before the edit. */
  axis: string | null;
  axisNode: number | null;
}

export type ApplyOutcome =
  | { ok: true; out: EtherCATOut; config: NetConfig }
  | { ok: false; status: number | null; message: string; issues: NetIssue[] };

interface DetailItem {
  loc?: (string | number)[];
  msg?: string;
  path?: string;
}

function slaveLabel(body: NetConfig, k: number): string {
  const s = body.slaves[k];
  return s ? `${s.name || `slave ${k + 1}`} (node ${s.node_address})` : `slave ${k + 1}`;
}

/** `ethercat.slaves[3].node_address` → slave 3 and its field; `axes[1].node_address` → the axis (and its node). */
export function issueOf(rawPath: string, msg: string, body: NetConfig, axes: readonly AxisRef[]): NetIssue {
  const path = rawPath.replace(/^(body\.)?ethercat\./, "");
  const text = msg
    .replace(/^Value error, /, "")
    .replace(/ethercat\.slaves\[(\d+)\]/g, (_, k: string) => slaveLabel(body, Number(k)))
    .replace(/\baxes\[(\d+)\]/g, (m: string, k: string) => axes[Number(k)]?.name ?? m);
  const base = { path, msg: text, slave: null, node: null, field: "", axis: null, axisNode: null };
  const s = /^slaves\[(\d+)\](?:\.(.*))?$/.exec(path);
  if (s) {
    const k = Number(s[1]);
    return { ...base, slave: k, node: body.slaves[k]?.node_address ?? null, field: s[2] ?? "" };
  }
  const a = /^axes\[(\d+)\]/.exec(path);
  if (a) {
    const axis = axes[Number(a[1])];
    return { ...base, axis: axis?.name ?? null, axisNode: axis?.node_address ?? null, field: "axis" };
  }
  return { ...base, field: path };
}

function issuesOf(detail: unknown, body: NetConfig, axes: readonly AxisRef[]): NetIssue[] {
  if (!Array.isArray(detail)) {
    return [{ path: "", msg: String(detail), slave: null, node: null, field: "", axis: null, axisNode: null }];
  }
  return (detail as DetailItem[]).map((d) =>
    issueOf(typeof d.path === "string" ? d.path : formatLoc(d.loc ?? []), d.msg ?? "invalid", body, axes),
  );
}

export interface ApplyOptions {
  /** Axes to move to another node address with this edit (axis name → new node address): PUT /api/v1/project. */
  moveAxes?: Readonly<Record<string, number>>;
  /** Keep an implicit network implicit (master settings only). */
  keepImplicit?: boolean;
}

/**
 * Change the configuration and PUT it. `change` gets a copy of the configuration as the controller has it now and
 * returns the one to apply (it may throw an Error to refuse, e.g. when its slave is gone).
 */
export async function applyNetwork(
  change: (cfg: NetConfig, current: NetworkConfig) => NetConfig,
  opts: ApplyOptions = {},
): Promise<ApplyOutcome> {
  let current: Current;
  let body: NetConfig;
  try {
    current = await fetchCurrent();
    body = change(structuredClone(current.nc.config), current.nc);
  } catch (err) {
    return { ok: false, status: err instanceof ApiError ? err.status : null, message: message(err), issues: [] };
  }
  const sent: NetConfig = opts.keepImplicit && !current.nc.explicit ? { ...body, slaves: [] } : body;
  const moves = Object.entries(opts.moveAxes ?? {});
  try {
    let out: EtherCATOut;
    if (moves.length) {
      const doc = structuredClone(current.project);
      doc.ethercat = sent;
      doc.axes = (doc.axes ?? []).map((a) => {
        const to = opts.moveAxes?.[a.name];
        return to === undefined ? a : { ...a, node_address: to };
      });
      await unwrap(api.PUT("/api/v1/project", { body: doc as unknown as Record<string, unknown> }));
      out = await unwrap(api.GET("/api/v1/ethercat"));
    } else {
      out = await unwrap(api.PUT("/api/v1/ethercat", { body: sent }));
    }
    ethercatStore.set({ status: "ready", data: out });
    const axes = current.nc.axes.map((a) => {
      const to = opts.moveAxes?.[a.name];
      return to === undefined ? a : { ...a, node_address: to };
    });
    networkConfigStore.set({
      status: "ready",
      data: { ...current.nc, config: body, explicit: sent.slaves.length > 0, axes },
    });
    void loadNetworkConfig();
    return { ok: true, out, config: body };
  } catch (err) {
    if (err instanceof ApiError && err.status === 422) {
      return { ok: false, status: 422, message: err.message, issues: issuesOf(err.detail, body, current.nc.axes) };
    }
    return { ok: false, status: err instanceof ApiError ? err.status : null, message: message(err), issues: [] };
  }
}

/** The title of a refusal that is not a list of field problems. */
export function refusalTitle(status: number | null): string {
  if (status === 409) return "Not applied: an axis is moving (409)";
  return `Not applied${status ? ` (${status})` : ""}`;
}

/** The text of a refusal (the title says what a 409 means; the controller names the moving axes). */
export function refusalText(_status: number | null, msg: string): string {
  return msg ? msg.charAt(0).toUpperCase() + msg.slice(1) : "";
}

// ------------------------------------------------------------------ defaults for a new slave

/** The smallest node address above those in use (or the first free one from 1 when that is past the end). */
export function nextFreeNode(used: readonly number[]): number {
  const set = new Set(used);
  const next = (used.length ? Math.max(...used) : 0) + 1;
  if (next <= 65534) return next;
  let n = 1;
  while (set.has(n)) n++;
  return n;
}

/** `10` → `E010`: the default name of a slave. */
export function defaultSlaveName(node: number): string {
  return `E${String(node).padStart(3, "0")}`;
}

/** The axis that uses a node address, if any. */
export function axisOfNode(axes: readonly AxisRef[], node: number): AxisRef | undefined {
  return axes.find((a) => a.node_address === node);
}

/** "servo axis", "encoder axis", … for an axis type. */
export function axisTypeText(type: string): string {
  switch (type) {
    case "_mcServo":
      return "servo axis";
    case "_mcEncdr":
      return "encoder axis";
    case "_mcVirServo":
      return "virtual servo axis";
    case "_mcVirEncdr":
      return "virtual encoder axis";
    default:
      return "axis";
  }
}
