/**
 * Which editor tabs are open: the fixed "Axes" overview and "3D" tabs, then per axis a test-run tab (`axis:<name>`)
 * and an axis settings tab (`settings:<name>`), the EtherCAT network view (`ethercat`), the device library
 * (`devices`) and per slave a PDO map editor (`pdo:<node address>`), in opening order.
 */
import { createStore } from "./createStore";

export const TAB_AXES = "axes";
export const TAB_3D = "3d";
export const axisTabKey = (axis: string): string => `axis:${axis}`;
export const settingsTabKey = (axis: string): string => `settings:${axis}`;
/** The axis of a test-run tab (null for any other tab). */
export const axisOfTab = (key: string): string | null => (key.startsWith("axis:") ? key.slice(5) : null);
/** The axis of a settings tab (null for any other tab). */
export const settingsAxisOfTab = (key: string): string | null => (key.startsWith("settings:") ? key.slice(9) : null);
export const TAB_ETHERCAT = "ethercat";
export const TAB_DEVICES = "devices";
export const pdoTabKey = (node: number): string => `pdo:${node}`;
/** The slave (node address) of a PDO map tab (null for any other tab). */
export const pdoNodeOfTab = (key: string): number | null => (key.startsWith("pdo:") ? Number(key.slice(4)) : null);

export const camTabKey = (name: string): string => `cam:${name}`;
/** The cam table of a cam editor tab (null for any other tab). */
export const camOfTab = (key: string): string | null => (key.startsWith("cam:") ? key.slice(4) : null);

export interface TabsState {
  /** Keys of the open tabs besides "Axes" and "3D" (axis test run and settings, EtherCAT), in opening order. */
  open: string[];
  active: string;
}

export const tabsStore = createStore<TabsState>({ open: [], active: TAB_AXES });

function openTab(key: string): void {
  tabsStore.set((s) => ({ open: s.open.includes(key) ? s.open : [...s.open, key], active: key }));
}

export function openAxisTab(axis: string): void {
  openTab(axisTabKey(axis));
}

export function openSettingsTab(axis: string): void {
  openTab(settingsTabKey(axis));
}

export function openEthercatTab(): void {
  openTab(TAB_ETHERCAT);
}

export function openDevicesTab(): void {
  openTab(TAB_DEVICES);
}

export function openCamTab(name: string): void {
  openTab(camTabKey(name));
}

export function openPdoTab(node: number): void {
  openTab(pdoTabKey(node));
}

/** A slave got another node address (its PDO map tab follows it) or left the network (`to` null: the tab closes). */
export function retargetPdoTab(from: number, to: number | null): void {
  const key = pdoTabKey(from);
  if (to === null) {
    closeTab(key);
    return;
  }
  const next = pdoTabKey(to);
  tabsStore.set((s) => {
    if (!s.open.includes(key)) return s;
    const open = s.open.filter((k) => k !== next).map((k) => (k === key ? next : k));
    return { open, active: s.active === key ? next : s.active };
  });
}

export function closeTab(key: string): void {
  tabsStore.set((s) => {
    const i = s.open.indexOf(key);
    if (i < 0) return s;
    const open = s.open.filter((k) => k !== key);
    const active = s.active === key ? (open[Math.min(i, open.length - 1)] ?? TAB_AXES) : s.active;
    return { open, active };
  });
}

export function closeAxisTab(axis: string): void {
  closeTab(axisTabKey(axis));
}

export function activateTab(key: string): void {
  tabsStore.set((s) => (s.active === key ? s : { ...s, active: key }));
}

/** Close the tabs of axes that no longer exist (another project was opened). */
export function pruneAxisTabs(existing: readonly string[]): void {
  tabsStore.set((s) => {
    const keep = (k: string) => {
      const axis = axisOfTab(k) ?? settingsAxisOfTab(k);
      return axis === null || existing.includes(axis);
    };
    const open = s.open.filter(keep);
    if (open.length === s.open.length) return s;
    return { open, active: keep(s.active) ? s.active : TAB_AXES };
  });
}
