import { Box, Tabs, Text } from "@mantine/core";
import { IconBox, IconTable, IconTool, IconX } from "@tabler/icons-react";
import { useEffect, useState } from "react";
import { useAxisList } from "../hooks/useLive";
import { useStore } from "../store/createStore";
import { TAB_3D, TAB_AXES, activateTab, axisTabKey, closeAxisTab, pruneAxisTabs, tabsStore } from "../store/tabs";
import { AxesTable } from "./axes/AxesTable";
import { AxisTestRun } from "./testrun/AxisTestRun";
import { VizView } from "./viz/VizView";

function CloseTab({ axis }: { axis: string }) {
  return (
    <span
      className="tab-close"
      role="button"
      tabIndex={-1}
      aria-label={`Close test run of ${axis}`}
      data-testid={`tab-close-${axis}`}
      onMouseDown={(e) => e.stopPropagation()}
      onClick={(e) => {
        e.stopPropagation();
        closeAxisTab(axis);
      }}
    >
      <IconX size={12} />
    </span>
  );
}

/** The editor area: the axes overview, one test-run tab per opened axis, and the 3D view. */
export function Workspace() {
  const { axes: openAxes, active } = useStore(tabsStore, (s) => s);
  const { status, axes } = useAxisList();
  // The viser iframe stays mounted once opened (hidden while another tab is active) so the scene keeps its camera.
  const [vizMounted, setVizMounted] = useState(false);

  useEffect(() => {
    if (active === TAB_3D) setVizMounted(true);
  }, [active]);

  useEffect(() => {
    if (status === "ready") pruneAxisTabs(axes.map((a) => a.name));
  }, [status, axes]);

  return (
    <Box style={{ flex: 1, minHeight: 0, display: "flex", flexDirection: "column", background: "white" }}>
      <Tabs
        value={active}
        onChange={(v) => v && activateTab(v)}
        keepMounted={false}
        className="editor-tabs"
        style={active === TAB_3D ? { flex: "none" } : undefined}
        variant="default"
        radius={0}
        styles={{ tab: { paddingTop: 7, paddingBottom: 7, fontSize: 13 }, panel: { flex: 1, minHeight: 0, overflow: "auto" } }}
      >
        <Tabs.List>
          <Tabs.Tab value={TAB_AXES} leftSection={<IconTable size={14} />} data-testid="tab-axes">
            Axes
          </Tabs.Tab>
          <Tabs.Tab value={TAB_3D} leftSection={<IconBox size={14} />} data-testid="tab-3d">
            3D
          </Tabs.Tab>
          {openAxes.map((a) => (
            <Tabs.Tab
              key={a}
              value={axisTabKey(a)}
              leftSection={<IconTool size={14} />}
              rightSection={<CloseTab axis={a} />}
              data-testid={`tab-axis-${a}`}
              onAuxClick={(e) => {
                if (e.button === 1) closeAxisTab(a);
              }}
            >
              <Text span size="13px">
                Test run: {a}
              </Text>
            </Tabs.Tab>
          ))}
        </Tabs.List>

        <Tabs.Panel value={TAB_AXES}>
          <AxesTable />
        </Tabs.Panel>
        {openAxes.map((a) => (
          <Tabs.Panel key={a} value={axisTabKey(a)}>
            <AxisTestRun axis={a} />
          </Tabs.Panel>
        ))}
      </Tabs>
      {vizMounted && (
        <Box style={{ flex: 1, minHeight: 0, display: active === TAB_3D ? "flex" : "none" }}>
          <VizView />
        </Box>
      )}
    </Box>
  );
}
