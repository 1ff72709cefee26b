import { Box, Button, Center, Group, Loader, Stack, Text, Tooltip } from "@mantine/core";
import { IconBooks, IconFileImport, IconNetwork, IconPlus, IconRefresh } from "@tabler/icons-react";
import { useEffect, useState } from "react";
import { loadEthercat, useDevices, useEthercat, useEthercatPoll } from "../../store/ethercat";
import { useNetworkConfig } from "../../store/network";
import { pruneSlaveEditors } from "../../store/networkEditor";
import { openDevicesTab } from "../../store/tabs";
import { AddSlaveDialog } from "./AddSlaveDialog";
import { EsiImportDialog } from "./EsiImportDialog";
import { MasterBox } from "./MasterBox";
import { RemoveSlaveDialog } from "./RemoveSlaveDialog";
import { SlaveCard } from "./SlaveCard";

/**
 * The EtherCAT network view and editor: the master and its slaves in wiring order (polled twice a second while
 * visible); master settings, adding, configuring and removing slaves, each edit applied with PUT /api/v1/ethercat.
 */
export function NetworkView() {
  useEthercatPoll(500);
  useDevices();
  const config = useNetworkConfig();
  const { status, data, error } = useEthercat();
  const [importing, setImporting] = useState(false);
  const [adding, setAdding] = useState<{ device: string | null } | null>(null);
  const [removing, setRemoving] = useState<number | null>(null);

  const nodes = config.data?.config.slaves.map((s) => s.node_address).join(",");
  useEffect(() => {
    if (nodes !== undefined) pruneSlaveEditors(nodes ? nodes.split(",").map(Number) : []);
  }, [nodes]);

  return (
    <Box style={{ height: "100%", display: "flex", flexDirection: "column", minHeight: 0 }} data-testid="ecat-network">
      <Group justify="space-between" wrap="nowrap" gap="sm" px="sm" py={6} className="settings-header">
        <Group gap={10} wrap="nowrap" style={{ minWidth: 0 }}>
          <IconNetwork size={20} color="var(--mantine-color-gray-6)" style={{ flex: "none" }} />
          <Stack gap={0} style={{ minWidth: 0 }}>
            <Text fw={700} size="md" truncate="end">
              EtherCAT <Text span fw={400} c="dimmed" size="sm">· network</Text>
            </Text>
            <Text size="xs" c="dimmed" truncate="end">
              {data
                ? `Master and ${data.slaves.length} slave${data.slaves.length === 1 ? "" : "s"} in wiring order`
                : "Master and slaves in wiring order"}
            </Text>
          </Stack>
        </Group>
        <Group gap={8} wrap="nowrap">
          <Tooltip label="Add a slave from the device library (built-in or imported ESI devices)" openDelay={300}>
            <Button leftSection={<IconPlus size={14} />} onClick={() => setAdding({ device: null })}
              disabled={config.status !== "ready"} data-testid="ecat-add-slave">
              Add slave…
            </Button>
          </Tooltip>
          <Button variant="default" leftSection={<IconFileImport size={14} />} onClick={() => setImporting(true)}
            data-testid="ecat-import-esi">
            Import ESI…
          </Button>
          <Button variant="default" leftSection={<IconBooks size={14} />} onClick={openDevicesTab}
            data-testid="ecat-open-library">
            Device library
          </Button>
          <Tooltip label="Refresh now (the view refreshes twice a second)">
            <Button variant="subtle" leftSection={<IconRefresh size={14} />} onClick={() => void loadEthercat()}
              data-testid="ecat-refresh">
              Refresh
            </Button>
          </Tooltip>
        </Group>
      </Group>
      <div className="ecat-scroll">
        {status === "loading" && !data && (
          <Center h={160}>
            <Loader size="sm" />
          </Center>
        )}
        {status === "error" && !data && (
          <Center h={160}>
            <Text size="sm" c="red">Cannot load the EtherCAT network: {error}</Text>
          </Center>
        )}
        {data && (
          <div className="ecat-topology">
            <MasterBox master={data.master} />
            {data.slaves.length === 0 && (
              <Text size="sm" c="dimmed" p="md" data-testid="ecat-no-slaves">
                No slaves: the project has no servo or encoder axes on EtherCAT and lists no slaves.
              </Text>
            )}
            {data.slaves.map((s) => (
              <SlaveCard key={s.node_address} slave={s} onRemove={setRemoving} />
            ))}
          </div>
        )}
      </div>
      <EsiImportDialog opened={importing} onClose={() => setImporting(false)}
        onAdd={(device) => {
          setImporting(false);
          setAdding({ device });
        }} />
      <AddSlaveDialog opened={adding !== null && !importing} initialDevice={adding?.device ?? null}
        onClose={() => setAdding(null)} onImport={() => setImporting(true)} />
      <RemoveSlaveDialog node={removing} onClose={() => setRemoving(null)} />
    </Box>
  );
}
