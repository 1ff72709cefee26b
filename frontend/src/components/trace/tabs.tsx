/** The data trace tab of the workspace (`trace`), opened from the project tree. */
import { Text } from "@mantine/core";
import { IconTimeline } from "@tabler/icons-react";
import { tabsStore } from "../../store/tabs";
import type { EthercatTab } from "../ethercat/tabs";
import { TraceView } from "./TraceView";

export const TAB_TRACE = "trace";

export function openTraceTab(): void {
  tabsStore.set((s) => ({ open: s.open.includes(TAB_TRACE) ? s.open : [...s.open, TAB_TRACE], active: TAB_TRACE }));
}

/** What the workspace shows for the data trace tab key, or null for any other tab. */
export function traceTab(key: string): EthercatTab | null {
  if (key !== TAB_TRACE) return null;
  return {
    icon: <IconTimeline size={14} />,
    title: (
      <Text span size="13px">
        Data trace
      </Text>
    ),
    testId: "tab-trace",
    closeLabel: "Close the data trace",
    closeTestId: "tab-close-trace",
    panel: <TraceView />,
  };
}
