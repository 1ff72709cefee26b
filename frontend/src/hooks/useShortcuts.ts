import { useEffect } from "react";
import { stopAxis } from "../store/commands";
import { axisForms, num } from "../store/forms";
import { liveStore } from "../store/live";
import { axisOfTab, tabsStore } from "../store/tabs";

/** Keyboard shortcuts (listed in the toolbar's "?" popover; README "Keyboard shortcuts"). */
export const SHORTCUTS: { keys: string; action: string }[] = [
  { keys: "Esc", action: "Stop the axis of the active test-run tab (MC_Stop at the absolute move's deceleration)" },
  { keys: "Shift + Esc", action: "Stop every moving axis that is not in an axes group (MC_Stop), from any tab" },
  { keys: "← / → (held)", action: "Jog − / + while the test-run tab has the focus (click its background); stops on release" },
  { keys: "Space / Enter (held)", action: "Jog while a jog button has the focus" },
  { keys: "Enter", action: "Execute the move form whose field has the focus" },
];

function deceleration(axis: string): number {
  const dec = num(axisForms(axis).absDeceleration);
  return dec !== null && dec > 0 ? dec : 500;
}

/** MC_Stop on every axis that moves on its own (Discrete, Continuous, Synchronized, Homing); not group members. */
export function stopAllAxes(): void {
  const axes = liveStore.get().axes;
  for (const name of Object.keys(axes)) {
    const s = axes[name].Status;
    if (s.Discrete || s.Continuous || s.Synchronized || s.Homing) void stopAxis(name, deceleration(name));
  }
}

export function useShortcuts(): void {
  useEffect(() => {
    const onKey = (e: KeyboardEvent) => {
      if (e.key !== "Escape" || e.repeat) return;
      if (e.shiftKey) {
        stopAllAxes();
        return;
      }
      const axis = axisOfTab(tabsStore.get().active);
      if (axis === null) return;
      void stopAxis(axis, deceleration(axis));
    };
    window.addEventListener("keydown", onKey);
    return () => window.removeEventListener("keydown", onKey);
  }, []);
}
