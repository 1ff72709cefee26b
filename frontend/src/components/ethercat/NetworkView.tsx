import { Box, Button, Center, Group, Loader, Stack, Text, Tooltip } from "@mantine/core";
import { IconBooks, IconFileImport, IconNetwork, IconRefresh } from "@tabler/icons-react";
import { useState } from "react";
import { loadEthercat, useEthercat, useEthercatPoll } from "../../store/ethercat";
import { openDevicesTab } from "../../store/tabs";
import { EsiImportDialog } from "./EsiImportDialog";
import { MasterBox } from "./MasterBox";
import { SlaveCard } from "./SlaveCard";

/** The EtherCAT network view: the master and its slaves in wiring order, polled twice a second while visible. */
export function NetworkView() {
  useEthercatPoll(500);
  const { status, data, error } = useEthercat();
  const [importing, setImporting] = useState(false);

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
              <SlaveCard key={s.node_address} slave={s} />
            ))}
          </div>
        )}
      </div>
      <EsiImportDialog opened={importing} onClose={() => setImporting(false)} />
    </Box>
  );
}
