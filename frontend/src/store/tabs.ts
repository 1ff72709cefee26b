/**
 * Which editor tabs are open: the fixed "Axes" overview and "3D" tabs, then per axis a test-run tab (`axis:<name>`)
 * and an axis settings tab (`settings:<name>`), in opening order.
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

export interface TabsState {
  /** Keys of the open axis tabs (test run and settings), in opening order. */
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
