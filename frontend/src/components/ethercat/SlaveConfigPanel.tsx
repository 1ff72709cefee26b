import {
  Alert,
  Anchor,
  Badge,
  Button,
  Checkbox,
  Group,
  NumberInput,
  Select,
  Stack,
  Switch,
  Tabs,
  Text,
  TextInput,
  Tooltip,
} from "@mantine/core";
import { IconAlertTriangle, IconArrowBackUp, IconCheck, IconInfoCircle, IconTableOptions } from "@tabler/icons-react";
import { useEffect, useRef } from "react";
import type { SlaveOut } from "../../api/types";
import { hexH } from "../../lib/hex";
import { useStore } from "../../store/createStore";
import { devicesStore } from "../../store/ethercat";
import { axisOfNode, axisTypeText, networkConfigStore, refusalText, refusalTitle } from "../../store/network";
import {
  type FieldIssue,
  type SlaveEditor,
  type SlaveTab,
  applySlave,
  revertSlave,
  setSlaveField,
  setSlaveTab,
  slaveDraftProblems,
  slaveEditorStore,
  syncSlaveEditor,
  tabOfField,
} from "../../store/networkEditor";
import { openPdoTab } from "../../store/tabs";
import { StartupSdoTable } from "./StartupSdoTable";

const LABEL = { label: { fontSize: 11, color: "var(--mantine-color-gray-7)", marginBottom: 1 } };

/** The message to show on a field: the studio's own check first, else the controller's refusal. */
function fieldMsg(problems: readonly FieldIssue[], issues: readonly FieldIssue[], field: string): string | undefined {
  return problems.find((p) => p.field === field)?.msg ?? issues.find((i) => i.field === field)?.msg;
}

function errorProps(testId: string) {
  return { "data-testid": testId, role: "alert", "data-field-error": "true" } as Record<string, string>;
}

function TabLabel({ label, count, issues }: { label: string; count?: number; issues: number }) {
  return (
    <Group gap={5} wrap="nowrap">
      <span>{label}</span>
      {count !== undefined && (
        <Badge size="xs" variant="light" color="gray" className="num" style={{ textTransform: "none" }}>{count}</Badge>
      )}
      {issues > 0 && <span className="tab-issue-dot" title={`${issues} problem${issues === 1 ? "" : "s"}`} />}
    </Group>
  );
}

function General({ node, slave, ed, problems, count }: {
  node: number;
  slave: SlaveOut;
  ed: SlaveEditor;
  problems: FieldIssue[];
  count: number;
}) {
  const axes = useStore(networkConfigStore, (s) => s.data?.axes);
  const axis = axes ? axisOfNode(axes, node) : undefined;
  const d = ed.draft;
  const moved = typeof d.node_address === "number" && d.node_address !== node;
  const nodeMsg = fieldMsg(problems, ed.issues, "node_address");
  const positions = Array.from({ length: count }, (_, i) => ({ value: String(i), label: `${i + 1} of ${count}` }));
  return (
    <div className="slave-general">
      <TextInput size="xs" label="Name" w={150} value={d.name} onChange={(e) => setSlaveField(node, "name", e.currentTarget.value)}
        error={fieldMsg(problems, ed.issues, "name")} errorProps={errorProps(`slave-error-${node}-name`)}
        data-testid={`slave-name-${node}`} disabled={ed.applying} styles={LABEL} maxLength={80} />
      <Stack gap={2}>
        <NumberInput size="xs" label="Node address" w={130} value={d.node_address}
          onChange={(v) => setSlaveField(node, "node_address", v)} allowDecimal={false} allowNegative={false}
          error={nodeMsg} errorProps={errorProps(`slave-error-${node}-node_address`)} data-testid={`slave-node-${node}`}
          disabled={ed.applying} styles={{ ...LABEL, error: { whiteSpace: "normal", width: 300 } }} />
        {axis && moved && (
          <Checkbox size="xs" mt={2} checked={d.moveAxis} onChange={(e) => setSlaveField(node, "moveAxis", e.currentTarget.checked)}
            label={<Text size="11px">Move {axis.name} to node {d.node_address} too</Text>}
            data-testid={`slave-move-axis-${node}`} disabled={ed.applying} />
        )}
      </Stack>
      <Select size="xs" label="Position in the wiring order" w={150} data={positions} value={String(d.position)}
        onChange={(v) => v !== null && setSlaveField(node, "position", Number(v))} allowDeselect={false}
        data-testid={`slave-position-${node}`} disabled={ed.applying} styles={LABEL} comboboxProps={{ withinPortal: true }} />
      <div className="ecat-field" style={{ maxWidth: 260 }}>
        <span className="ecat-field-label">Used by</span>
        <Text size="xs" fw={axis ? 600 : 400} c={axis ? "dark" : "dimmed"} data-testid={`slave-axis-${node}`}>
          {axis ? `${axis.name} (${axisTypeText(axis.type)})` : "No axis"}
        </Text>
      </div>
      <div className="ecat-field" style={{ maxWidth: 300 }}>
        <span className="ecat-field-label">Device</span>
        <Text size="xs" truncate="end" title={slave.device_id}>
          {slave.device_name}{" "}
          <Text span size="10px" c="dimmed" ff="monospace">{slave.device_id}</Text>
        </Text>
        <Anchor size="xs" onClick={() => openPdoTab(node)} data-testid={`slave-open-pdo-${node}`}>
          <Group gap={3} wrap="nowrap" component="span">
            <IconTableOptions size={12} /> PDO map (applied on its own)
          </Group>
        </Anchor>
      </div>
    </div>
  );
}

function Drill({ node, slave, ed, problems }: { node: number; slave: SlaveOut; ed: SlaveEditor; problems: FieldIssue[] }) {
  const devices = useStore(devicesStore, (s) => s.data);
  const d = ed.draft;
  const options = [
    { value: "", label: `The configured device (${slave.device_name})` },
    ...devices.filter((x) => x.id !== slave.device_id).map((x) => ({
      value: x.id,
      label: `${x.name} · ${x.vendor_name || hexH(x.vendor_id, 8)} · product ${hexH(x.product_code, 8)}`,
    })),
  ];
  if (d.wired_device && !options.some((o) => o.value === d.wired_device)) {
    options.push({ value: d.wired_device, label: d.wired_device });
  }
  return (
    <Stack gap={8}>
      <Group gap={6} wrap="nowrap" className="settings-notice">
        <IconInfoCircle size={14} color="var(--mantine-color-blue-6)" style={{ flex: "none" }} />
        <Text size="xs" c="gray.7">
          Commissioning drills for the topology check (not part of a real machine): they describe the wire when the
          controller starts. The slave stays in Init with its reason; every other slave runs.
        </Text>
      </Group>
      <div className="slave-general">
        <Switch size="sm" checked={d.connected} onChange={(e) => setSlaveField(node, "connected", e.currentTarget.checked)}
          label={<Text size="xs" fw={600}>On the wire at start</Text>}
          description={d.connected ? "The slave is found at its position" : "Configured, not connected: it stays in Init"}
          error={fieldMsg(problems, ed.issues, "emulation.connected")} data-testid={`slave-connected-${node}`}
          disabled={ed.applying} />
        <Select size="xs" label="Device found at this position" w={420} data={options} value={d.wired_device ?? ""}
          onChange={(v) => setSlaveField(node, "wired_device", v ? v : null)} allowDeselect={false} searchable
          description="Another device: the identity check (vendor, product code) keeps the slave in Init"
          error={fieldMsg(problems, ed.issues, "emulation.wired_device")}
          errorProps={errorProps(`slave-error-${node}-emulation.wired_device`)}
          data-testid={`slave-wired-device-${node}`} disabled={ed.applying || !d.connected} styles={LABEL}
          comboboxProps={{ withinPortal: true }} />
        {slave.kind === "encoder" && (
          <NumberInput size="xs" label="Encoder speed at start" w={170} value={d.encoder_velocity}
            onChange={(v) => setSlaveField(node, "encoder_velocity", v)} rightSection={<Text size="xs" c="dimmed">pulse/s</Text>}
            rightSectionWidth={52} error={fieldMsg(problems, ed.issues, "emulation.encoder_velocity")}
            data-testid={`slave-encoder-velocity-${node}`} disabled={ed.applying} styles={LABEL} />
        )}
      </div>
    </Stack>
  );
}

function Problems({ node, ed, problems }: { node: number; ed: SlaveEditor; problems: FieldIssue[] }) {
  if (ed.refusal) {
    return (
      <Alert color="orange" variant="light" py={6} mx={10} my={6} icon={<IconAlertTriangle size={16} />}
        title={refusalTitle(ed.refusal.status)} data-testid={`slave-refusal-${node}`}>
        <Text size="xs">{refusalText(ed.refusal.status, ed.refusal.message)}</Text>
      </Alert>
    );
  }
  if (ed.issues.length) {
    const placed = ed.issues.filter((i) => i.field).length;
    const others = ed.issues.filter((i) => !i.field);
    return (
      <Alert color="red" variant="light" py={6} mx={10} my={6} icon={<IconAlertTriangle size={16} />}
        title={`The controller refused this change (${ed.issues.length} problem${ed.issues.length === 1 ? "" : "s"})`}
        data-testid={`slave-issues-${node}`}>
        <Stack gap={2}>
          {placed > 0 && (
            <Text size="xs">
              {placed === ed.issues.length ? "Shown" : `${placed} shown`} on the marked field{placed === 1 ? "" : "s"}.
            </Text>
          )}
          {others.map((i, k) => (
            <Text size="xs" key={k} data-testid="slave-issue">
              {i.msg}
            </Text>
          ))}
        </Stack>
      </Alert>
    );
  }
  if (problems.length && ed.dirty) {
    const names: Record<SlaveTab, string> = { general: "General", sdo: "Start-up parameters", drill: "Commissioning drill" };
    const where = [...new Set(problems.map((p) => names[tabOfField(p.field)]))].join(", ");
    return (
      <Text size="xs" c="orange.8" px={10} pt={4} data-testid={`slave-problems-${node}`}>
        Correct the marked field{problems.length === 1 ? "" : "s"} ({where}) before applying.
      </Text>
    );
  }
  return null;
}

/** The configuration of one slave in the network view: general settings, start-up SDOs, commissioning drill. */
export function SlaveConfigPanel({ slave }: { slave: SlaveOut }) {
  const node = slave.node_address;
  const cfg = useStore(networkConfigStore, (s) => s.data?.config.slaves.find((x) => x.node_address === node));
  const position = useStore(networkConfigStore, (s) => s.data?.config.slaves.findIndex((x) => x.node_address === node) ?? -1);
  const count = useStore(networkConfigStore, (s) => s.data?.config.slaves.length ?? 0);
  const ed = useStore(slaveEditorStore, (s) => s[node]);
  const issues = ed?.issues;
  const refusal = ed?.refusal;
  const root = useRef<HTMLDivElement>(null);

  useEffect(() => {
    if (cfg && position >= 0) syncSlaveEditor(cfg, position);
  }, [cfg, position]);

  // A refusal: bring the first field it concerns (else the message) into view.
  useEffect(() => {
    if (!issues?.length && !refusal) return;
    const el = root.current?.querySelector("[data-field-error]") ?? root.current?.querySelector(".mantine-Alert-root");
    el?.scrollIntoView({ block: "nearest" });
  }, [issues, refusal]);

  if (!ed || !ed.open) return null;
  const problems = slaveDraftProblems(ed.draft);
  const all = [...problems, ...ed.issues];
  const onTab = (t: SlaveTab) => all.filter((i) => i.field && tabOfField(i.field) === t).length;
  const apply = () => {
    const axes = networkConfigStore.get().data?.axes ?? [];
    void applySlave(node, axes);
  };

  return (
    <div className="ecat-config" ref={root} data-testid={`slave-config-${node}`} data-dirty={ed.dirty ? "true" : "false"}>
      <Tabs value={ed.tab} onChange={(t) => t && setSlaveTab(node, t as SlaveTab)} keepMounted={false}>
        <div className="ecat-config-bar">
          <Tabs.List style={{ flex: "1 1 auto" }}>
            <Tabs.Tab value="general" data-testid={`slave-tab-general-${node}`}>
              <TabLabel label="General" issues={onTab("general")} />
            </Tabs.Tab>
            <Tabs.Tab value="sdo" data-testid={`slave-tab-sdo-${node}`}>
              <TabLabel label="Start-up parameters" count={ed.draft.startup_sdos.length} issues={onTab("sdo")} />
            </Tabs.Tab>
            <Tabs.Tab value="drill" data-testid={`slave-tab-drill-${node}`}>
              <TabLabel label="Commissioning drill" issues={onTab("drill")} />
            </Tabs.Tab>
          </Tabs.List>
          <Group gap={6} wrap="nowrap" px={8}>
            {ed.dirty ? (
              <Badge color="orange" variant="light" style={{ textTransform: "none" }} data-testid={`slave-dirty-${node}`}>
                Not applied
              </Badge>
            ) : (
              <Badge color="gray" variant="light" style={{ textTransform: "none" }} data-testid={`slave-clean-${node}`}>
                No changes
              </Badge>
            )}
            <Button size="compact-sm" variant="default" leftSection={<IconArrowBackUp size={14} />}
              disabled={(!ed.dirty && !ed.issues.length && !ed.refusal) || ed.applying} onClick={() => revertSlave(node)}
              data-testid={`slave-revert-${node}`}>
              Revert
            </Button>
            <Tooltip label={problems.length ? `Cannot apply: ${problems.map((p) => `${p.field}: ${p.msg}`).join("; ")}`
              : ed.dirty ? "Restart the controller with this configuration (all axes must be stopped)" : "Nothing changed"}
              multiline maw={360} position="bottom-end" openDelay={300}>
              <Button size="compact-sm" leftSection={<IconCheck size={14} />} loading={ed.applying}
                disabled={!ed.dirty || problems.length > 0} onClick={apply} data-testid={`slave-apply-${node}`}>
                Apply
              </Button>
            </Tooltip>
          </Group>
        </div>
        <Problems node={node} ed={ed} problems={problems} />
        <div className="ecat-config-body">
          <Tabs.Panel value="general">
            <General node={node} slave={slave} ed={ed} problems={problems} count={count} />
          </Tabs.Panel>
          <Tabs.Panel value="sdo">
            <StartupSdoTable node={node} slave={slave} rows={ed.draft.startup_sdos} issues={all} disabled={ed.applying} />
          </Tabs.Panel>
          <Tabs.Panel value="drill">
            <Drill node={node} slave={slave} ed={ed} problems={problems} />
          </Tabs.Panel>
        </div>
      </Tabs>
    </div>
  );
}
