import { Alert, Anchor, Badge, Button, Group, Modal, NumberInput, Select, Stack, Text, TextInput } from "@mantine/core";
import { IconAlertTriangle, IconFileImport, IconPlus } from "@tabler/icons-react";
import { useEffect, useMemo, useState } from "react";
import type { DeviceSummary } from "../../api/types";
import { hexH } from "../../lib/hex";
import { useStore } from "../../store/createStore";
import { devicesStore } from "../../store/ethercat";
import type { NumValue } from "../../store/forms";
import { defaultSlaveName, networkConfigStore, nextFreeNode, refusalText, refusalTitle } from "../../store/network";
import { type FieldIssue, type Refusal, addSlave } from "../../store/networkEditor";

function kindText(kind: string): string {
  return kind === "servo" ? "CiA402 servo drive" : kind === "encoder" ? "Encoder input" : "I/O (process image only)";
}

function DeviceOption({ d }: { d: DeviceSummary | undefined; }) {
  if (!d) return null;
  return (
    <Stack gap={0} style={{ minWidth: 0 }}>
      <Text size="xs" fw={600} truncate="end">{d.name}</Text>
      <Text size="10px" c="dimmed" truncate="end">
        {d.vendor_name || hexH(d.vendor_id, 8)} · product {hexH(d.product_code, 8)} · rev. {hexH(d.revision, 8)} ·{" "}
        {kindText(d.kind)}
      </Text>
    </Stack>
  );
}

/**
 * Add a slave from the device library (built-in devices and those of imported ESI files): device, node address (the
 * next free one), name (E001 style, following the node address until edited) and its place in the wiring order.
 */
export function AddSlaveDialog({ opened, initialDevice, onClose, onImport }: {
  opened: boolean;
  /** Preselect this device (e.g. one just imported). */
  initialDevice: string | null;
  onClose: () => void;
  onImport: () => void;
}) {
  const devices = useStore(devicesStore, (s) => s.data);
  const slaves = useStore(networkConfigStore, (s) => s.data?.config.slaves);
  const [device, setDevice] = useState<string | null>(null);
  const [node, setNode] = useState<NumValue>(1);
  const [name, setName] = useState("");
  const [nameEdited, setNameEdited] = useState(false);
  const [position, setPosition] = useState("0");
  const [busy, setBusy] = useState(false);
  const [issues, setIssues] = useState<FieldIssue[]>([]);
  const [refusal, setRefusal] = useState<Refusal | null>(null);

  // A fresh form each time the dialog opens.
  useEffect(() => {
    if (!opened) return;
    const list = networkConfigStore.get().data?.config.slaves ?? [];
    const n = nextFreeNode(list.map((s) => s.node_address));
    setDevice(initialDevice);
    setNode(n);
    setName(defaultSlaveName(n));
    setNameEdited(false);
    setPosition(String(list.length));
    setIssues([]);
    setRefusal(null);
    setBusy(false);
  }, [opened, initialDevice]);

  const groups = useMemo(() => {
    const bySource = new Map<string, { value: string; label: string }[]>();
    for (const d of devices) {
      const group = d.source === "builtin" ? "Built-in" : `Imported: ${d.source}`;
      if (!bySource.has(group)) bySource.set(group, []);
      bySource.get(group)?.push({ value: d.id, label: d.name });
    }
    return [...bySource.entries()].map(([group, items]) => ({ group, items }));
  }, [devices]);
  const byId = useMemo(() => new Map(devices.map((d) => [d.id, d])), [devices]);

  const list = slaves ?? [];
  const positions = [
    ...list.map((s, i) => ({ value: String(i), label: `${i + 1} · before ${s.name || `node ${s.node_address}`}` })),
    { value: String(list.length), label: `${list.length + 1} · at the end` },
  ];

  const nodeOk = typeof node === "number" && Number.isInteger(node) && node >= 1 && node <= 65534;
  const msg = (field: string) => issues.find((i) => i.field === field)?.msg;
  const general = issues.filter((i) => !["node_address", "name", "device"].includes(i.field));

  const changeNode = (v: NumValue) => {
    setNode(v);
    setIssues((xs) => xs.filter((i) => i.field !== "node_address"));
    if (!nameEdited && typeof v === "number" && Number.isInteger(v) && v >= 1) setName(defaultSlaveName(v));
  };

  const submit = async () => {
    if (!device || !nodeOk) return;
    setBusy(true);
    setIssues([]);
    setRefusal(null);
    const res = await addSlave({ device, node_address: node as number, name, position: Number(position) });
    setBusy(false);
    if (res.ok) {
      onClose();
      return;
    }
    setIssues(res.issues);
    setRefusal(res.refusal);
  };

  return (
    <Modal opened={opened} onClose={onClose} size="lg" title={<Text fw={700}>Add slave</Text>} data-testid="add-slave-dialog">
      <Stack gap="sm">
        <Text size="xs" c="dimmed">
          A device from the library joins the network with its default PDO map. Applying restarts the controller (all
          axes must be stopped); save the project to keep it.
        </Text>
        <Select
          label="Device"
          placeholder="Choose a device of the library"
          data={groups}
          value={device}
          onChange={(v) => {
            setDevice(v);
            setIssues((xs) => xs.filter((i) => i.field !== "device"));
          }}
          searchable
          nothingFoundMessage="No such device in the library"
          renderOption={({ option }) => <DeviceOption d={byId.get(option.value)} />}
          maxDropdownHeight={280}
          error={msg("device")}
          data-testid="add-slave-device"
          comboboxProps={{ withinPortal: true }}
          size="sm"
        />
        {device && byId.get(device) && (
          <Group gap={6} data-testid="add-slave-device-info">
            <Badge size="sm" variant="light" style={{ textTransform: "none" }}>{kindText(byId.get(device)?.kind ?? "")}</Badge>
            <Text size="xs" c="dimmed" ff="monospace">{device}</Text>
          </Group>
        )}
        <Group gap="sm" align="flex-start" grow>
          <NumberInput
            label="Node address"
            description="The next free one is proposed"
            value={node}
            onChange={changeNode}
            allowDecimal={false}
            allowNegative={false}
            error={msg("node_address") ?? (nodeOk ? undefined : "an integer from 1 to 65534")}
            errorProps={{ "data-testid": "add-slave-error-node_address", role: "alert" } as Record<string, string>}
            data-testid="add-slave-node"
            size="sm"
          />
          <TextInput
            label="Name"
            description="Shown in the network view"
            value={name}
            onChange={(e) => {
              setName(e.currentTarget.value);
              setNameEdited(true);
            }}
            maxLength={63}
            error={msg("name")}
            data-testid="add-slave-name"
            size="sm"
          />
          <Select
            label="Position"
            description="In the wiring order"
            data={positions}
            value={position}
            onChange={(v) => v !== null && setPosition(v)}
            allowDeselect={false}
            data-testid="add-slave-position"
            comboboxProps={{ withinPortal: true }}
            size="sm"
          />
        </Group>
        {(refusal || general.length > 0) && (
          <Alert color={refusal ? "orange" : "red"} variant="light" py={6} icon={<IconAlertTriangle size={16} />}
            title={refusal ? refusalTitle(refusal.status) : "The controller refused this slave"} data-testid="add-slave-refusal">
            <Stack gap={2}>
              {refusal && <Text size="xs">{refusalText(refusal.status, refusal.message)}</Text>}
              {general.map((i, k) => <Text size="xs" key={k}>{i.msg}</Text>)}
            </Stack>
          </Alert>
        )}
        <Group justify="space-between">
          <Anchor size="xs" onClick={onImport} data-testid="add-slave-import">
            <Group gap={4} component="span" wrap="nowrap">
              <IconFileImport size={14} /> Device not in the library? Import its ESI file…
            </Group>
          </Anchor>
          <Group gap={8}>
            <Button variant="default" onClick={onClose} data-testid="add-slave-cancel">Cancel</Button>
            <Button leftSection={<IconPlus size={14} />} disabled={!device || !nodeOk} loading={busy}
              onClick={() => void submit()} data-testid="add-slave-confirm">
              Add and apply
            </Button>
          </Group>
        </Group>
      </Stack>
    </Modal>
  );
}
