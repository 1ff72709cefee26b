/** Which editor tabs are open: the fixed "Axes" overview and "3D" tabs, and one test-run tab per opened axis. */
import { createStore } from "./createStore";

export const TAB_AXES = "axes";
export const TAB_3D = "3d";
export const axisTabKey = (axis: string): string => `axis:${axis}`;
export const axisOfTab = (key: string): string | null => (key.startsWith("axis:") ? key.slice(5) : null);

export interface TabsState {
  /** Axis names with an open test-run tab, in opening order. */
  axes: string[];
  active: string;
}

export const tabsStore = createStore<TabsState>({ axes: [], active: TAB_AXES });

export function openAxisTab(axis: string): void {
  tabsStore.set((s) => ({
    axes: s.axes.includes(axis) ? s.axes : [...s.axes, axis],
    active: axisTabKey(axis),
  }));
}

export function closeAxisTab(axis: string): void {
  tabsStore.set((s) => {
    const i = s.axes.indexOf(axis);
    if (i < 0) return s;
    const axes = s.axes.filter((a) => a !== axis);
    let active = s.active;
    if (active === axisTabKey(axis)) {
      const neighbour = axes[Math.min(i, axes.length - 1)];
      active = neighbour ? axisTabKey(neighbour) : TAB_AXES;
    }
    return { axes, active };
  });
}

export function activateTab(key: string): void {
  tabsStore.set((s) => (s.active === key ? s : { ...s, active: key }));
}

/** Close the tabs of axes that no longer exist (another project was opened). */
export function pruneAxisTabs(existing: readonly string[]): void {
  tabsStore.set((s) => {
    const axes = s.axes.filter((a) => existing.includes(a));
    if (axes.length === s.axes.length) return s;
    const activeAxis = axisOfTab(s.active);
    const active = activeAxis !== null && !axes.includes(activeAxis) ? TAB_AXES : s.active;
    return { axes, active };
  });
}
