/** The EtherCAT tabs of the workspace: network view, device library and a PDO map editor per slave. */
import { Text } from "@mantine/core";
import { IconBooks, IconNetwork, IconTableOptions } from "@tabler/icons-react";
import type { ReactNode } from "react";
import { useStore } from "../../store/createStore";
import { useSlave } from "../../store/ethercat";
import { pdoEditorStore } from "../../store/pdoEditor";
import { TAB_DEVICES, TAB_ETHERCAT, pdoNodeOfTab } from "../../store/tabs";
import { DeviceLibrary } from "./DeviceLibrary";
import { NetworkView } from "./NetworkView";
import { PdoEditor } from "./PdoEditor";

export interface EthercatTab {
  icon: ReactNode;
  title: ReactNode;
  testId: string;
  closeLabel: string;
  closeTestId: string;
  panel: ReactNode;
}

function PdoTabTitle({ node }: { node: number }) {
  const name = useSlave(node)?.name ?? `node ${node}`;
  const dirty = useStore(pdoEditorStore, (s) => s[node]?.dirty ?? false);
  return (
    <Text span size="13px" data-dirty={dirty ? "true" : "false"}>
      PDO map: {name}
      {dirty && <span className="tab-dirty" title="Unsaved changes" data-testid={`tab-dirty-pdo-${node}`} />}
    </Text>
  );
}

/** What the workspace shows for an EtherCAT tab key, or null for any other tab. */
export function ethercatTab(key: string): EthercatTab | null {
  if (key === TAB_ETHERCAT) {
    return {
      icon: <IconNetwork size={14} />,
      title: <Text span size="13px">EtherCAT</Text>,
      testId: "tab-ethercat",
      closeLabel: "Close the EtherCAT network view",
      closeTestId: "tab-close-ethercat",
      panel: <NetworkView />,
    };
  }
  if (key === TAB_DEVICES) {
    return {
      icon: <IconBooks size={14} />,
      title: <Text span size="13px">Device library</Text>,
      testId: "tab-devices",
      closeLabel: "Close the device library",
      closeTestId: "tab-close-devices",
      panel: <DeviceLibrary />,
    };
  }
  const node = pdoNodeOfTab(key);
  if (node !== null) {
    return {
      icon: <IconTableOptions size={14} />,
      title: <PdoTabTitle node={node} />,
      testId: `tab-pdo-${node}`,
      closeLabel: `Close the PDO map of node ${node}`,
      closeTestId: `tab-close-pdo-${node}`,
      panel: <PdoEditor node={node} />,
    };
  }
  return null;
}
