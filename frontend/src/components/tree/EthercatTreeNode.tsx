import { ActionIcon, Badge, Box, Loader, NavLink, Text } from "@mantine/core";
import { IconBooks, IconChevronDown, IconChevronRight, IconCpu2, IconNetwork } from "@tabler/icons-react";
import { type MouseEvent, useState } from "react";
import type { SlaveOut } from "../../api/types";
import { useStore } from "../../store/createStore";
import { useEthercat, useEthercatPoll } from "../../store/ethercat";
import { TAB_DEVICES, TAB_ETHERCAT, openDevicesTab, openEthercatTab, openPdoTab, pdoTabKey, tabsStore } from "../../store/tabs";
import { esmColor } from "../ethercat/EsmBadge";

function SlaveEntry({ slave, active }: { slave: SlaveOut; active: boolean }) {
  const node = slave.node_address;
  return (
    <NavLink
      data-testid={`nav-slave-${node}`}
      active={active}
      onClick={() => openPdoTab(node)}
      title={`${slave.name}: PDO map`}
      label={
        <Text size="xs" fw={600} truncate="end">
          {slave.name} <Text span size="10px" c="dimmed" fw={400}>node {node}</Text>
        </Text>
      }
      description={
        <Text size="10px" c="dimmed" truncate="end" title={slave.device_name}>
          {slave.device_name}
        </Text>
      }
      leftSection={<IconCpu2 size={14} />}
      rightSection={
        <Badge size="xs" variant="light" color={esmColor(slave.state)} style={{ textTransform: "none" }}
          data-testid={`nav-slave-state-${node}`} data-state={slave.state}>
          {slave.state}
        </Badge>
      }
      py={3}
      pl={8}
      pr={4}
      styles={{ section: { marginInlineEnd: 6 } }}
    />
  );
}

/** The EtherCAT branch of the project tree: the network view, its slaves (each opens its PDO map) and the library. */
export function EthercatTreeNode() {
  useEthercatPoll(2000);
  const { status, data } = useEthercat();
  const active = useStore(tabsStore, (s) => s.active);
  const slaves = data?.slaves ?? [];
  const inOp = slaves.filter((s) => s.pd_ok).length;
  const [opened, setOpened] = useState(true);
  return (
    <>
      <NavLink
        label={<Text size="xs" fw={600}>EtherCAT</Text>}
        description={
          <Text size="10px" c={data && inOp < slaves.length ? "red.7" : "dimmed"}>
            {data ? `${inOp} / ${slaves.length} slaves in Op` : "—"}
          </Text>
        }
        leftSection={<IconNetwork size={15} />}
        active={active === TAB_ETHERCAT}
        onClick={openEthercatTab}
        opened={opened}
        rightSection={
          <ActionIcon size="sm" variant="subtle" color="gray" component="span" role="button"
            aria-label={opened ? "Hide the slaves" : "Show the slaves"} data-testid="nav-ethercat-toggle"
            onClick={(e: MouseEvent) => {
              e.stopPropagation();
              setOpened((o) => !o);
            }}>
            {opened ? <IconChevronDown size={14} /> : <IconChevronRight size={14} />}
          </ActionIcon>
        }
        disableRightSectionRotation
        childrenOffset={8}
        py={3}
        data-testid="nav-ethercat"
      >
        {status === "loading" && !data && (
          <Box px="sm" py={4}>
            <Loader size="xs" />
          </Box>
        )}
        {slaves.map((s) => (
          <SlaveEntry key={s.node_address} slave={s} active={active === pdoTabKey(s.node_address)} />
        ))}
      </NavLink>
      <NavLink
        label={<Text size="xs" fw={600}>Device library</Text>}
        leftSection={<IconBooks size={15} />}
        active={active === TAB_DEVICES}
        onClick={openDevicesTab}
        py={3}
        data-testid="nav-devices"
      />
    </>
  );
}
