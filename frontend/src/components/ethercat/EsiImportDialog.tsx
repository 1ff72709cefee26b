import { Alert, Badge, Button, FileInput, Group, List, Modal, Stack, Table, Text } from "@mantine/core";
import { IconAlertTriangle, IconFileImport, IconFileTypeXml, IconPlus } from "@tabler/icons-react";
import { type ComponentPropsWithoutRef, useState } from "react";
import { ApiError, api, unwrap } from "../../api/client";
import type { EsiFile } from "../../api/types";
import { hexH } from "../../lib/hex";
import { notifyOk } from "../../lib/notify";
import { loadDevices } from "../../store/ethercat";

/** POST /api/v1/esi as multipart form data (field "file"). */
async function uploadEsi(file: File): Promise<EsiFile> {
  return unwrap(
    api.POST("/api/v1/esi", {
      body: { file: file.name },
      bodySerializer: () => {
        const fd = new FormData();
        fd.append("file", file, file.name);
        return fd;
      },
    }),
  );
}

function errorText(err: unknown): string {
  if (err instanceof ApiError) {
    const issues = err.issues;
    if (issues.length) return issues.map((i) => i.msg).join("\n");
    return `${err.message} (HTTP ${err.status})`;
  }
  return err instanceof Error ? err.message : String(err);
}

function Imported({ esi, onAdd }: { esi: EsiFile; onAdd?: (device: string) => void }) {
  return (
    <Stack gap={6} data-testid="esi-result">
      <Text size="sm">
        <b>{esi.devices.length}</b> device{esi.devices.length === 1 ? "" : "s"} of <b>{esi.vendor.name || "vendor"}</b>{" "}
        <Text span c="dimmed" size="xs" className="num">({hexH(esi.vendor.id, 8)})</Text> added to the device library:
      </Text>
      <Table withTableBorder striped data-testid="esi-devices">
        <Table.Thead>
          <Table.Tr>
            <Table.Th>Device</Table.Th>
            <Table.Th className="num">Product code</Table.Th>
            <Table.Th className="num">Revision</Table.Th>
            <Table.Th>Profile</Table.Th>
            <Table.Th className="num">RxPDOs</Table.Th>
            <Table.Th className="num">TxPDOs</Table.Th>
            {onAdd && <Table.Th />}
          </Table.Tr>
        </Table.Thead>
        <Table.Tbody>
          {esi.devices.map((d) => (
            <Table.Tr key={d.id} data-testid="esi-device">
              <Table.Td>
                <Text size="xs" fw={600}>{d.name}</Text>
                <Text size="10px" c="dimmed" ff="monospace">{d.id}</Text>
              </Table.Td>
              <Table.Td className="num">{hexH(d.product_code, 8)}</Table.Td>
              <Table.Td className="num">{hexH(d.revision, 8)}</Table.Td>
              <Table.Td>{d.profile != null ? `CiA ${d.profile}` : "—"}</Table.Td>
              <Table.Td className="num">{d.rx_pdos?.length ?? 0}</Table.Td>
              <Table.Td className="num">{d.tx_pdos?.length ?? 0}</Table.Td>
              {onAdd && (
                <Table.Td>
                  <Button size="compact-xs" variant="light" leftSection={<IconPlus size={12} />} onClick={() => onAdd(d.id)}
                    data-testid={`esi-add-${d.id}`}>
                    Add to network…
                  </Button>
                </Table.Td>
              )}
            </Table.Tr>
          ))}
        </Table.Tbody>
      </Table>
      {(esi.warnings?.length ?? 0) > 0 && (
        <Alert color="yellow" variant="light" py={6} icon={<IconAlertTriangle size={16} />} data-testid="esi-warnings"
          title={`${esi.warnings?.length} warning${esi.warnings?.length === 1 ? "" : "s"}`}>
          <List size="xs" spacing={2}>
            {esi.warnings?.map((w, i) => <List.Item key={i}>{w}</List.Item>)}
          </List>
        </Alert>
      )}
    </Stack>
  );
}

/** Import an ESI file: every device it describes joins the library (and the file the project's esi/ folder).
 * With `onAdd`, each imported device has a button to add it to the network as a new slave. */
export function EsiImportDialog({ opened, onClose, onAdd }: {
  opened: boolean;
  onClose: () => void;
  onAdd?: (device: string) => void;
}) {
  const [file, setFile] = useState<File | null>(null);
  const [busy, setBusy] = useState(false);
  const [error, setError] = useState<string | null>(null);
  const [result, setResult] = useState<EsiFile | null>(null);

  const close = () => {
    setFile(null);
    setError(null);
    setResult(null);
    onClose();
  };
  const submit = async () => {
    if (!file) return;
    setBusy(true);
    setError(null);
    setResult(null);
    try {
      const esi = await uploadEsi(file);
      setResult(esi);
      void loadDevices();
      notifyOk("ESI file imported", `${file.name}: ${esi.devices.length} device${esi.devices.length === 1 ? "" : "s"}`);
    } catch (err) {
      setError(errorText(err));
    } finally {
      setBusy(false);
    }
  };

  return (
    <Modal opened={opened} onClose={close} size="xl" title={<Text fw={700}>Import ESI file</Text>}
      data-testid="esi-dialog">
      <Stack gap="sm">
        <Text size="xs" c="dimmed">
          An EtherCAT Slave Information file (ETG.2000 XML) from the device vendor. Every device it describes joins the
          device library; the file is kept in the project's <code>esi/</code> folder.
        </Text>
        <Group gap={8} align="flex-end" wrap="nowrap">
          <FileInput
            style={{ flex: 1 }}
            label="ESI file"
            placeholder="Choose an .xml file"
            accept=".xml,application/xml,text/xml"
            value={file}
            onChange={(f) => {
              setFile(f);
              setError(null);
              setResult(null);
            }}
            clearable
            leftSection={<IconFileTypeXml size={16} />}
            size="xs"
            error={error ? true : undefined}
            data-testid="esi-file"
            fileInputProps={{ "data-testid": "esi-file-input" } as ComponentPropsWithoutRef<"input">}
          />
          <Button leftSection={<IconFileImport size={14} />} disabled={!file} loading={busy} onClick={() => void submit()}
            data-testid="esi-submit">
            Import
          </Button>
        </Group>
        {error && (
          <Alert color="red" variant="light" py={6} icon={<IconAlertTriangle size={16} />} title="Not imported"
            data-testid="esi-error">
            <Text size="xs" style={{ whiteSpace: "pre-wrap" }}>{error}</Text>
          </Alert>
        )}
        {result && (
          <Imported esi={result} onAdd={onAdd && ((id) => {
            setFile(null);
            setError(null);
            setResult(null);
            onAdd(id);
          })} />
        )}
        <Group justify="flex-end">
          {result && <Badge color="green" variant="light" style={{ textTransform: "none" }}>Imported</Badge>}
          <Button variant="default" onClick={close} data-testid="esi-close">
            Close
          </Button>
        </Group>
      </Stack>
    </Modal>
  );
}
