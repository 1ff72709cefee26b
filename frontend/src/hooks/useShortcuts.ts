import { useEffect } from "react";
import { stopAxis } from "../store/commands";
import { axisForms, num } from "../store/forms";
import { axisOfTab, tabsStore } from "../store/tabs";

/** Keyboard shortcuts (listed in the toolbar's "?" popover). */
export const SHORTCUTS: { keys: string; action: string }[] = [
  { keys: "Esc", action: "Stop the axis of the active test-run tab (MC_Stop)" },
  { keys: "Space / Enter (held)", action: "Jog while a jog button has the focus" },
  { keys: "Enter", action: "Execute the move form whose field has the focus" },
];

export function useShortcuts(): void {
  useEffect(() => {
    const onKey = (e: KeyboardEvent) => {
      if (e.key !== "Escape" || e.repeat) return;
      const axis = axisOfTab(tabsStore.get().active);
      if (axis === null) return;
      const dec = num(axisForms(axis).absDeceleration);
      void stopAxis(axis, dec !== null && dec > 0 ? dec : 500);
    };
    window.addEventListener("keydown", onKey);
    return () => window.removeEventListener("keydown", onKey);
  }, []);
}
