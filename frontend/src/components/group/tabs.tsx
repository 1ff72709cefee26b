/** The group test-run tabs of the workspace: one per axes group (`group:<name>`). */
import { Text } from "@mantine/core";
import { IconTopologyStar } from "@tabler/icons-react";
import { tabsStore } from "../../store/tabs";
import type { EthercatTab } from "../ethercat/tabs";
import { GroupTestRun } from "./GroupTestRun";

export const groupTabKey = (name: string): string => `group:${name}`;
export const groupOfTab = (key: string): string | null => (key.startsWith("group:") ? key.slice(6) : null);

export function openGroupTab(name: string): void {
  const key = groupTabKey(name);
  tabsStore.set((s) => ({ open: s.open.includes(key) ? s.open : [...s.open, key], active: key }));
}

/** What the workspace shows for a group test-run tab key, or null for any other tab. */
export function groupTab(key: string): EthercatTab | null {
  const name = groupOfTab(key);
  if (name === null) return null;
  return {
    icon: <IconTopologyStar size={14} />,
    title: (
      <Text span size="13px">
        Group: {name}
      </Text>
    ),
    testId: `tab-group-${name}`,
    closeLabel: `Close the test run of ${name}`,
    closeTestId: `tab-close-group-${name}`,
    panel: <GroupTestRun name={name} />,
  };
}
