import { Badge, NavLink, Text } from "@mantine/core";
import { IconRobot, IconTopologyStar } from "@tabler/icons-react";
import { useStore } from "../../store/createStore";
import { useGroups } from "../../store/groupCommands";
import { tabsStore } from "../../store/tabs";
import { groupStateColor } from "./GroupControls";
import { groupTabKey, openGroupTab } from "./tabs";

/** "Axes groups" in the project tree: each group opens its test-run tab. */
export function GroupTreeNode() {
  const { groups, loaded } = useGroups();
  const active = useStore(tabsStore, (s) => s.active);
  return (
    <NavLink
      label={
        <Text size="xs" fw={600}>
          Axes groups{loaded ? ` (${groups.length})` : ""}
        </Text>
      }
      leftSection={<IconTopologyStar size={15} />}
      defaultOpened
      childrenOffset={8}
      py={3}
      data-testid="nav-groups"
    >
      {loaded && groups.length === 0 && (
        <Text size="xs" c="dimmed" px="sm" py={4} data-testid="nav-no-groups">
          No axes groups. Add one under "groups" in project.json (composition, axes A0…) and reopen the project.
        </Text>
      )}
      {groups.map((g) => (
        <NavLink
          key={g.name}
          data-testid={`nav-group-${g.name}`}
          active={active === groupTabKey(g.name)}
          onClick={() => openGroupTab(g.name)}
          label={
            <Text size="xs" fw={600} truncate="end">
              {g.name}
            </Text>
          }
          description={
            <Text size="10px" c="dimmed" truncate="end">
              {g.kinematics ? "Delta3" : g.composition.replace("_mc", "")} · {g.axes.join(", ")}
            </Text>
          }
          leftSection={g.kinematics ? <IconRobot size={14} /> : <IconTopologyStar size={14} />}
          rightSection={
            <Badge size="xs" variant="light" color={groupStateColor(g.state)} style={{ textTransform: "none" }}>
              {g.state}
            </Badge>
          }
          py={3}
          pl={8}
          pr={4}
        />
      ))}
    </NavLink>
  );
}
