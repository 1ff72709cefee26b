import { ActionIcon, Anchor, Badge, Button, Divider, Group, Text, Tooltip } from "@mantine/core";
import { IconAlertTriangle, IconSettings, IconTableOptions, IconTrash } from "@tabler/icons-react";
import type { ReactNode } from "react";
import type { SlaveOut } from "../../api/types";
import { hexH } from "../../lib/hex";
import { useStore } from "../../store/createStore";
import { networkConfigStore } from "../../store/network";
import { slaveEditorStore, toggleSlaveEditor } from "../../store/networkEditor";
import { openAxisTab, openPdoTab } from "../../store/tabs";
import { Led } from "../common/Led";
import { EsmBadge, esmColor } from "./EsmBadge";
import { FaultActions } from "./FaultActions";
import { SlaveConfigPanel } from "./SlaveConfigPanel";

function Field({ label, children, testId }: { label: ReactNode; children: ReactNode; testId?: string }) {
  return (
    <div className="ecat-field" data-testid={testId}>
      <span className="ecat-field-label">{label}</span>
      {children}
    </div>
  );
}

function DriveFields({ slave }: { slave: SlaveOut }) {
  const node = slave.node_address;
  const code = slave.drive_error_code ?? 0;
  const fault = slave.drive_state === "Fault" || slave.drive_state === "FaultReactionActive";
  // Without process data the master only has the drive's last answer.
  const stale = !slave.pd_ok;
  return (
    <div className="ecat-drive-fields" data-stale={stale ? "true" : undefined}
      title={stale ? "Last values received: the slave exchanges no process data" : undefined}>
      <Field label="PDS state" testId={`ecat-drive-state-${node}`}>
        <Text size="xs" fw={600} c={fault ? "red.7" : slave.drive_state === "OperationEnabled" ? "teal.8" : "dark"}>
          {slave.drive_state ?? "—"}
        </Text>
      </Field>
      <Field label={<>Error code <span style={{ textTransform: "none" }}>(603Fh)</span></>} testId={`ecat-drive-error-${node}`}>
        <Text size="xs" className="num" fw={code ? 700 : 400} c={code ? "red.7" : "dimmed"}>
          {hexH(code)}
        </Text>
      </Field>
    </div>
  );
}

/** Configure (opens the slave's configuration under its identity) and Remove. */
function EditActions({ slave, onRemove }: { slave: SlaveOut; onRemove: (node: number) => void }) {
  const node = slave.node_address;
  const cfg = useStore(networkConfigStore, (s) => s.data?.config.slaves.find((x) => x.node_address === node));
  const position = useStore(networkConfigStore, (s) => s.data?.config.slaves.findIndex((x) => x.node_address === node) ?? -1);
  const open = useStore(slaveEditorStore, (s) => s[node]?.open ?? false);
  const dirty = useStore(slaveEditorStore, (s) => s[node]?.dirty ?? false);
  return (
    <Group gap={2} wrap="nowrap">
      <Tooltip label={open ? "Close the configuration" : "Configure: name, node address, start-up parameters, drill"}
        openDelay={300}>
        <ActionIcon variant={open ? "light" : "subtle"} color={dirty ? "orange" : "gray"} size="md"
          disabled={!cfg || position < 0} onClick={() => cfg && toggleSlaveEditor(cfg, position)}
          aria-label={`Configure ${slave.name}`} aria-expanded={open} data-testid={`ecat-edit-${node}`}
          data-dirty={dirty ? "true" : "false"}>
          <IconSettings size={16} />
        </ActionIcon>
      </Tooltip>
      <Tooltip label="Remove the slave from the network" openDelay={300}>
        <ActionIcon variant="subtle" color="red" size="md" onClick={() => onRemove(node)}
          aria-label={`Remove ${slave.name}`} data-testid={`ecat-remove-${node}`}>
          <IconTrash size={16} />
        </ActionIcon>
      </Tooltip>
    </Group>
  );
}

/** One slave of the network, in wiring order: identity, state, the axis it drives, its configuration and the
 * commissioning drills. */
export function SlaveCard({ slave, onRemove }: { slave: SlaveOut; onRemove: (node: number) => void }) {
  const node = slave.node_address;
  return (
    <div className="ecat-slave" data-testid={`ecat-slave-${node}`} data-state={slave.state}>
      <div className="ecat-port" style={{ borderColor: `var(--mantine-color-${esmColor(slave.state)}-6)` }}
        title={`Position ${slave.position} in the wiring order`}>
        {slave.position + 1}
      </div>
      <div className="ecat-slave-body">
        <div className="ecat-slave-head">
          <Group gap={8} wrap="nowrap" style={{ minWidth: 0, flex: "1 1 auto" }}>
            <Text size="sm" fw={700} data-testid={`ecat-name-${node}`} style={{ whiteSpace: "nowrap" }}>
              {slave.name}
            </Text>
            <Badge size="sm" variant="default" className="num" style={{ textTransform: "none", flex: "none" }}>
              Node {node}
            </Badge>
            <Text size="sm" truncate="end" title={slave.device_name} data-testid={`ecat-device-${node}`}>
              {slave.device_name}
            </Text>
          </Group>
          <Group gap={10} wrap="nowrap" style={{ flex: "none" }}>
            <Led label="Wired" on={slave.wired} testId={`ecat-wired-${node}`} title="The slave is on the wire" />
            <Led label="PD" on={slave.pd_ok} testId={`ecat-pd-${node}`}
              title="Process data communication established" />
            <EsmBadge state={slave.state} testId={`ecat-state-${node}`} />
            <Divider orientation="vertical" />
            <EditActions slave={slave} onRemove={onRemove} />
          </Group>
        </div>
        <div className="ecat-slave-info">
          <Field label="Vendor">
            <Text size="xs" truncate="end" title={`${slave.vendor_name} (${hexH(slave.vendor_id, 8)})`}>
              {slave.vendor_name || hexH(slave.vendor_id, 8)}
            </Text>
          </Field>
          <Field label="Product">
            <Text size="xs" className="num">{hexH(slave.product_code, 8)}</Text>
          </Field>
          <Field label="Revision">
            <Text size="xs" className="num">{hexH(slave.revision, 8)}</Text>
          </Field>
          <Field label="Process data">
            <Text size="xs" className="num" data-testid={`ecat-bytes-${node}`}>
              Rx {slave.rx_bytes} B · Tx {slave.tx_bytes} B
            </Text>
          </Field>
          <Field label="Axis" testId={`ecat-axis-${node}`}>
            {slave.axis ? (
              <Anchor size="xs" fw={600} onClick={() => slave.axis && openAxisTab(slave.axis)} title="Open the test run">
                {slave.axis}
              </Anchor>
            ) : (
              <Text size="xs" c="dimmed">—</Text>
            )}
          </Field>
          {slave.kind === "servo" && <DriveFields slave={slave} />}
          <Tooltip label="Edit the PDO assignment and mapping, see the process image" openDelay={300}>
            <Button size="compact-xs" variant="light" leftSection={<IconTableOptions size={13} />} ml="auto"
              onClick={() => openPdoTab(node)} data-testid={`ecat-open-pdo-${node}`}>
              PDO map
            </Button>
          </Tooltip>
        </div>
        {slave.error && slave.state !== "Op" && (
          <Group gap={6} wrap="nowrap" className="ecat-slave-error" data-testid={`ecat-error-${node}`}>
            <IconAlertTriangle size={14} style={{ flex: "none" }} />
            <Text size="xs">{slave.error}</Text>
          </Group>
        )}
        <SlaveConfigPanel slave={slave} />
        <FaultActions slave={slave} />
      </div>
    </div>
  );
}
