import { ActionIcon, Badge, Box, Loader, NavLink, ScrollArea, Text, Tooltip } from "@mantine/core";
import { IconAxisX, IconBox, IconCpu, IconFolder, IconSettings, IconTable, IconTimeline } from "@tabler/icons-react";
import type { AxisSummary } from "../../api/types";
import { useAxisList, useAxisVars, useLive } from "../../hooks/useLive";
import { axisState, axisTypeLabel, stateColor } from "../../lib/format";
import { useStore } from "../../store/createStore";
import {
  TAB_3D,
  activateTab,
  axisTabKey,
  openAxisTab,
  openSettingsTab,
  settingsTabKey,
  tabsStore,
} from "../../store/tabs";
import { CamTreeNode } from "../cams/CamTreeNode";
import { GroupTreeNode } from "../group/GroupTreeNode";
import { TAB_TRACE, openTraceTab } from "../trace/tabs";
import { EthercatTreeNode } from "./EthercatTreeNode";

function StateBadge({ name }: { name: string }) {
  const vars = useAxisVars(name);
  const state = vars ? axisState(vars.Status) : null;
  if (!state) return null;
  return (
    <Badge size="xs" variant="light" color={stateColor(state)} style={{ textTransform: "none" }}>
      {state}
    </Badge>
  );
}

function AxisEntry({ axis, active, settingsActive }: { axis: AxisSummary; active: boolean; settingsActive: boolean }) {
  return (
    <Box style={{ display: "flex", alignItems: "center" }}>
      <NavLink
        style={{ flex: 1, minWidth: 0 }}
        data-testid={`nav-axis-${axis.name}`}
        active={active}
        onClick={() => openAxisTab(axis.name)}
        label={
          <Text size="xs" fw={600} truncate="end" title={axis.name}>
            {axis.name}
          </Text>
        }
        description={
          <Text size="10px" c="dimmed" truncate="end">
            {axisTypeLabel(axis.type)}
            {axis.node_address !== null ? ` · node ${axis.node_address}` : ""}
          </Text>
        }
        leftSection={<IconAxisX size={15} />}
        rightSection={<StateBadge name={axis.name} />}
        py={3}
        pl={8}
        pr={4}
        styles={{ section: { marginInlineEnd: 6 } }}
      />
      <Tooltip label={`Axis settings of ${axis.name}`} position="right" openDelay={300}>
        <ActionIcon
          size="sm"
          variant={settingsActive ? "light" : "subtle"}
          color={settingsActive ? "blue" : "gray"}
          aria-label={`Axis settings of ${axis.name}`}
          data-testid={`nav-axis-settings-${axis.name}`}
          onClick={() => openSettingsTab(axis.name)}
          mr={2}
        >
          <IconSettings size={14} />
        </ActionIcon>
      </Tooltip>
    </Box>
  );
}

/**
 * The project tree: controller, axes (each opens its test-run tab; the gear opens its settings), EtherCAT (network
 * view, a PDO map per slave), the device library and the 3D view.
 */
export function ProjectTree() {
  const project = useLive((s) => s.controller?.project ?? null);
  const period = useLive((s) => s.controller?.period_s ?? null);
  const active = useStore(tabsStore, (s) => s.active);
  const { status, axes, error } = useAxisList();

  return (
    <ScrollArea h="100%" type="auto" data-testid="project-tree">
      <Box p={4}>
        <NavLink
          label={
            <Text size="xs" fw={700}>
              {project ?? "Project"}
            </Text>
          }
          leftSection={<IconFolder size={15} />}
          defaultOpened
          childrenOffset={6}
          py={4}
        >
          <NavLink
            label={<Text size="xs" fw={600}>Controller</Text>}
            description={
              <Text size="10px" c="dimmed">
                {period !== null ? `Primary period ${Math.round(period * 1e6)} µs` : "—"}
              </Text>
            }
            leftSection={<IconCpu size={15} />}
            py={3}
            data-testid="nav-controller"
          />
          <NavLink
            label={
              <Text size="xs" fw={600}>
                Axes{status === "ready" ? ` (${axes.length})` : ""}
              </Text>
            }
            leftSection={<IconTable size={15} />}
            defaultOpened
            childrenOffset={8}
            py={3}
            data-testid="nav-axes"
          >
            {status === "loading" && (
              <Box px="sm" py={4}>
                <Loader size="xs" />
              </Box>
            )}
            {status === "error" && (
              <Text size="xs" c="red" px="sm" py={4}>
                Cannot load axes: {error}
              </Text>
            )}
            {status === "ready" && axes.length === 0 && (
              <Text size="xs" c="dimmed" px="sm" py={4} data-testid="nav-no-axes">
                This project has no axes. Add axes to the project document (project.json).
              </Text>
            )}
            {axes.map((a) => (
              <AxisEntry
                key={a.name}
                axis={a}
                active={active === axisTabKey(a.name)}
                settingsActive={active === settingsTabKey(a.name)}
              />
            ))}
          </NavLink>
          <GroupTreeNode />
          <EthercatTreeNode />
          <CamTreeNode />
          <NavLink
            label={<Text size="xs" fw={600}>Data trace</Text>}
            leftSection={<IconTimeline size={15} />}
            active={active === TAB_TRACE}
            onClick={openTraceTab}
            py={3}
            data-testid="nav-trace"
          />
          <NavLink
            label={<Text size="xs" fw={600}>3D view</Text>}
            leftSection={<IconBox size={15} />}
            active={active === TAB_3D}
            onClick={() => activateTab(TAB_3D)}
            py={3}
            data-testid="nav-3d"
          />
        </NavLink>
      </Box>
    </ScrollArea>
  );
}
