import { Box, Button, Group, Modal, Tabs, Text } from "@mantine/core";
import { IconBox, IconSettings, IconTable, IconTool, IconX } from "@tabler/icons-react";
import { useEffect, useState } from "react";
import { useAxisList } from "../hooks/useLive";
import { useStore } from "../store/createStore";
import { discardSettings, pruneSettings, settingsStore } from "../store/settings";
import {
  TAB_3D,
  TAB_AXES,
  activateTab,
  axisOfTab,
  closeTab,
  pruneAxisTabs,
  settingsAxisOfTab,
  settingsTabKey,
  tabsStore,
} from "../store/tabs";
import { AxesTable } from "./axes/AxesTable";
import { camTab } from "./cams/tabs";
import { ethercatTab } from "./ethercat/tabs";
import { groupTab } from "./group/tabs";
import { AxisSettings } from "./settings/AxisSettings";
import { AxisTestRun } from "./testrun/AxisTestRun";
import { traceTab } from "./trace/tabs";
import { VizView } from "./viz/VizView";
import { OfflineBanner } from "./OfflineBanner";

function CloseTab({ label, testId, onClose }: { label: string; testId: string; onClose: () => void }) {
  return (
    <span
      className="tab-close"
      role="button"
      tabIndex={-1}
      aria-label={label}
      data-testid={testId}
      onMouseDown={(e) => e.stopPropagation()}
      onClick={(e) => {
        e.stopPropagation();
        onClose();
      }}
    >
      <IconX size={12} />
    </span>
  );
}

function SettingsTabTitle({ axis }: { axis: string }) {
  const dirty = useStore(settingsStore, (s) => s[axis]?.dirty ?? false);
  return (
    <Text span size="13px" data-dirty={dirty ? "true" : "false"}>
      Settings: {axis}
      {dirty && <span className="tab-dirty" title="Unsaved changes" data-testid={`tab-dirty-${axis}`} />}
    </Text>
  );
}

/** Asks before a settings tab with unsaved changes is closed. */
function DiscardModal({ axis, onClose }: { axis: string | null; onClose: () => void }) {
  return (
    <Modal opened={axis !== null} onClose={onClose} title="Discard unsaved settings?" size="sm" centered>
      <Text size="sm">
        The settings of <b>{axis}</b> have changes that were not applied. Close the tab and discard them?
      </Text>
      <Group justify="flex-end" mt="md" gap={8}>
        <Button variant="default" onClick={onClose} data-testid="discard-cancel">
          Keep editing
        </Button>
        <Button
          color="red"
          data-testid="discard-confirm"
          onClick={() => {
            if (axis !== null) {
              discardSettings(axis);
              closeTab(settingsTabKey(axis));
            }
            onClose();
          }}
        >
          Discard
        </Button>
      </Group>
    </Modal>
  );
}

/**
 * The editor area: the axes overview, the 3D view, per axis its test-run and settings tabs, and the EtherCAT tabs
 * (network view, device library, PDO map per slave).
 */
export function Workspace() {
  const { open, active } = useStore(tabsStore, (s) => s);
  const { status, axes } = useAxisList();
  // The viser iframe stays mounted once opened (hidden while another tab is active) so the scene keeps its camera.
  const [vizMounted, setVizMounted] = useState(false);
  const [confirmAxis, setConfirmAxis] = useState<string | null>(null);

  useEffect(() => {
    if (active === TAB_3D) setVizMounted(true);
  }, [active]);

  useEffect(() => {
    if (status === "ready") {
      const names = axes.map((a) => a.name);
      pruneAxisTabs(names);
      pruneSettings(names);
    }
  }, [status, axes]);

  const close = (key: string) => {
    const settingsAxis = settingsAxisOfTab(key);
    if (settingsAxis !== null) {
      if (settingsStore.get()[settingsAxis]?.dirty) {
        setConfirmAxis(settingsAxis);
        return;
      }
      discardSettings(settingsAxis);
    }
    closeTab(key);
  };

  return (
    <Box style={{ flex: 1, minHeight: 0, display: "flex", flexDirection: "column", background: "white" }}>
      <OfflineBanner />
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
          {open.map((key) => {
            const ec = ethercatTab(key) ?? camTab(key) ?? groupTab(key) ?? traceTab(key);
            if (ec) {
              return (
                <Tabs.Tab key={key} value={key} leftSection={ec.icon} data-testid={ec.testId}
                  rightSection={<CloseTab label={ec.closeLabel} testId={ec.closeTestId} onClose={() => close(key)} />}
                  onAuxClick={(e) => {
                    if (e.button === 1) close(key);
                  }}>
                  {ec.title}
                </Tabs.Tab>
              );
            }
            const runAxis = axisOfTab(key);
            const setAxis = settingsAxisOfTab(key);
            const axis = runAxis ?? setAxis ?? key;
            const isSettings = setAxis !== null;
            return (
              <Tabs.Tab
                key={key}
                value={key}
                leftSection={isSettings ? <IconSettings size={14} /> : <IconTool size={14} />}
                rightSection={
                  <CloseTab
                    label={isSettings ? `Close settings of ${axis}` : `Close test run of ${axis}`}
                    testId={isSettings ? `tab-close-settings-${axis}` : `tab-close-${axis}`}
                    onClose={() => close(key)}
                  />
                }
                data-testid={isSettings ? `tab-axis-settings-${axis}` : `tab-axis-${axis}`}
                onAuxClick={(e) => {
                  if (e.button === 1) close(key);
                }}
              >
                {isSettings ? (
                  <SettingsTabTitle axis={axis} />
                ) : (
                  <Text span size="13px">
                    Test run: {axis}
                  </Text>
                )}
              </Tabs.Tab>
            );
          })}
        </Tabs.List>

        <Tabs.Panel value={TAB_AXES}>
          <AxesTable />
        </Tabs.Panel>
        {open.map((key) => {
          const ec = ethercatTab(key) ?? camTab(key) ?? groupTab(key) ?? traceTab(key);
          if (ec) {
            return (
              <Tabs.Panel key={key} value={key} style={{ overflow: "hidden" }}>
                {ec.panel}
              </Tabs.Panel>
            );
          }
          const runAxis = axisOfTab(key);
          const setAxis = settingsAxisOfTab(key);
          return (
            <Tabs.Panel key={key} value={key} style={setAxis !== null ? { overflow: "hidden" } : undefined}>
              {runAxis !== null && <AxisTestRun axis={runAxis} />}
              {setAxis !== null && <AxisSettings axis={setAxis} />}
            </Tabs.Panel>
          );
        })}
      </Tabs>
      {vizMounted && (
        <Box style={{ flex: 1, minHeight: 0, display: active === TAB_3D ? "flex" : "none" }}>
          <VizView active={active === TAB_3D} />
        </Box>
      )}
      <DiscardModal axis={confirmAxis} onClose={() => setConfirmAxis(null)} />
    </Box>
  );
}
