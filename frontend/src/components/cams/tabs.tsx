/** The cam editor tabs of the workspace: one per open cam table (`cam:<name>`). */
import { Text } from "@mantine/core";
import { IconChartDots } from "@tabler/icons-react";
import { useCamDirty } from "../../store/cams";
import { camOfTab } from "../../store/tabs";
import type { EthercatTab } from "../ethercat/tabs";
import { CamEditor } from "./CamEditor";

function CamTabTitle({ name }: { name: string }) {
  const dirty = useCamDirty(name);
  return (
    <Text span size="13px" data-dirty={dirty ? "true" : "false"}>
      Cam: {name}
      {dirty && <span className="tab-dirty" title="Unsaved changes" data-testid={`tab-dirty-cam-${name}`} />}
    </Text>
  );
}

/** What the workspace shows for a cam editor tab key, or null for any other tab. */
export function camTab(key: string): EthercatTab | null {
  const name = camOfTab(key);
  if (name === null) return null;
  return {
    icon: <IconChartDots size={14} />,
    title: <CamTabTitle name={name} />,
    testId: `tab-cam-${name}`,
    closeLabel: `Close the cam editor of ${name}`,
    closeTestId: `tab-close-cam-${name}`,
    panel: <CamEditor name={name} />,
  };
}
