import { Badge, Box, Button, Center, Group, Loader, Stack, Table, Text } from "@mantine/core";
import { IconBooks, IconFileImport } from "@tabler/icons-react";
import { useState } from "react";
import type { DeviceSummary } from "../../api/types";
import { hexH } from "../../lib/hex";
import { useDevices } from "../../store/ethercat";
import { EsiImportDialog } from "./EsiImportDialog";

function KindBadge({ kind }: { kind: string }) {
  const color = kind === "servo" ? "blue" : kind === "encoder" ? "violet" : "gray";
  const label = kind === "servo" ? "CiA402 servo" : kind === "encoder" ? "Encoder input" : "I/O (image only)";
  return (
    <Badge size="xs" variant="light" color={color} style={{ textTransform: "none" }}>
      {label}
    </Badge>
  );
}

function DeviceRow({ d }: { d: DeviceSummary }) {
  return (
    <Table.Tr data-testid={`device-${d.id}`}>
      <Table.Td>
        <Text size="xs" fw={600}>{d.name}</Text>
        <Text size="10px" c="dimmed" ff="monospace">{d.id}</Text>
      </Table.Td>
      <Table.Td>
        <Text size="xs">{d.vendor_name || "—"}</Text>
        <Text size="10px" c="dimmed" className="num">{hexH(d.vendor_id, 8)}</Text>
      </Table.Td>
      <Table.Td className="num">{hexH(d.product_code, 8)}</Table.Td>
      <Table.Td className="num">{hexH(d.revision, 8)}</Table.Td>
      <Table.Td>{d.profile != null ? `CiA ${d.profile}` : "—"}</Table.Td>
      <Table.Td><KindBadge kind={d.kind} /></Table.Td>
      <Table.Td className="num">{d.rx_pdos}</Table.Td>
      <Table.Td className="num">{d.tx_pdos}</Table.Td>
      <Table.Td>
        <Text size="xs" c={d.source === "builtin" ? "dimmed" : "dark"} truncate="end" maw={200} title={d.source}>
          {d.source === "builtin" ? "built-in" : d.source}
        </Text>
      </Table.Td>
    </Table.Tr>
  );
}

/** The device library: built-in devices and those imported from ESI files. */
export function DeviceLibrary() {
  const { status, data, error } = useDevices();
  const [importing, setImporting] = useState(false);
  return (
    <Box style={{ height: "100%", display: "flex", flexDirection: "column", minHeight: 0 }} data-testid="device-library">
      <Group justify="space-between" wrap="nowrap" px="sm" py={6} className="settings-header">
        <Group gap={10} wrap="nowrap">
          <IconBooks size={20} color="var(--mantine-color-gray-6)" />
          <Stack gap={0}>
            <Text fw={700} size="md">Device library</Text>
            <Text size="xs" c="dimmed">
              {status === "ready" ? `${data.length} device description${data.length === 1 ? "" : "s"} · ` : ""}
              built-in and imported from ESI files
            </Text>
          </Stack>
        </Group>
        <Button variant="default" leftSection={<IconFileImport size={14} />} onClick={() => setImporting(true)}
          data-testid="library-import-esi">
          Import ESI…
        </Button>
      </Group>
      <Box style={{ flex: 1, minHeight: 0, overflow: "auto" }}>
        {status === "loading" && (
          <Center h={120}><Loader size="sm" /></Center>
        )}
        {status === "error" && (
          <Center h={120}><Text size="sm" c="red">Cannot load the device library: {error}</Text></Center>
        )}
        {status === "ready" && (
          <Table striped highlightOnHover stickyHeader data-testid="device-table" miw={900}>
            <Table.Thead>
              <Table.Tr>
                <Table.Th>Device</Table.Th>
                <Table.Th>Vendor</Table.Th>
                <Table.Th className="num">Product code</Table.Th>
                <Table.Th className="num">Revision</Table.Th>
                <Table.Th>Profile</Table.Th>
                <Table.Th>Emulated as</Table.Th>
                <Table.Th className="num">RxPDOs</Table.Th>
                <Table.Th className="num">TxPDOs</Table.Th>
                <Table.Th>Source</Table.Th>
              </Table.Tr>
            </Table.Thead>
            <Table.Tbody>
              {data.map((d) => <DeviceRow key={d.id} d={d} />)}
            </Table.Tbody>
          </Table>
        )}
      </Box>
      <EsiImportDialog opened={importing} onClose={() => setImporting(false)} />
    </Box>
  );
}
