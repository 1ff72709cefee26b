import { Alert, Badge, Button, Group, NumberInput, Stack, Switch, Text, Tooltip } from "@mantine/core";
import { IconAlertTriangle, IconCheck, IconPencil, IconServer2, IconX } from "@tabler/icons-react";
import type { ReactNode } from "react";
import type { EtherCATMaster } from "../../api/types";
import { useStore } from "../../store/createStore";
import { refusalText, refusalTitle } from "../../store/network";
import {
  applyMaster,
  closeMasterEditor,
  masterDraftProblems,
  masterEditorStore,
  openMasterEditor,
  setMasterField,
} from "../../store/networkEditor";
import { Led } from "../common/Led";

function Item({ label, children }: { label: string; children: ReactNode }) {
  return (
    <div className="ecat-master-item">
      <Text size="10px" c="dimmed" tt="uppercase" fw={600} style={{ letterSpacing: "0.03em" }}>
        {label}
      </Text>
      <div>{children}</div>
    </div>
  );
}

/** The master settings as a form: DC on/off, SYNC0 shift, auto-restart; Apply restarts the controller. */
function MasterForm({ settings }: { settings: EtherCATMaster["settings"] }) {
  const m = useStore(masterEditorStore, (s) => s);
  const problems = masterDraftProblems(m.draft);
  const changed =
    m.draft.dc_enabled !== (settings.dc_enabled ?? true) ||
    m.draft.sync_offset_pct !== (settings.sync_offset_pct ?? 20) ||
    m.draft.auto_restart_slaves !== (settings.auto_restart_slaves ?? true);
  const msg = (field: string) => problems.find((p) => p.field === field)?.msg ?? m.issues.find((i) => i.field === field)?.msg;
  const general = m.issues.filter((i) => !i.field);
  return (
    <>
      <Item label="Distributed clocks">
        <Switch size="sm" checked={m.draft.dc_enabled} onChange={(e) => setMasterField("dc_enabled", e.currentTarget.checked)}
          label={<Text size="xs">{m.draft.dc_enabled ? "On" : "Off"}</Text>} disabled={m.applying}
          error={msg("dc_enabled")} data-testid="master-dc" />
      </Item>
      <Item label="SYNC0 shift">
        <NumberInput size="xs" w={86} value={m.draft.sync_offset_pct} onChange={(v) => setMasterField("sync_offset_pct", v)}
          allowDecimal={false} allowNegative={false} disabled={m.applying || !m.draft.dc_enabled}
          rightSection={<Text size="xs" c="dimmed">%</Text>} rightSectionWidth={22}
          aria-label="SYNC0 shift relative to the cycle (%)" error={msg("sync_offset_pct")}
          errorProps={{ "data-testid": "master-error-sync_offset_pct", role: "alert" } as Record<string, string>}
          data-testid="master-sync-offset" styles={{ input: { textAlign: "right" }, error: { whiteSpace: "nowrap" } }} />
      </Item>
      <Item label="Auto-restart slaves">
        <Switch size="sm" checked={m.draft.auto_restart_slaves}
          onChange={(e) => setMasterField("auto_restart_slaves", e.currentTarget.checked)}
          label={<Text size="xs">{m.draft.auto_restart_slaves ? "On" : "Off"}</Text>} disabled={m.applying}
          error={msg("auto_restart_slaves")} data-testid="master-auto-restart" />
      </Item>
      <Group gap={6} wrap="nowrap" ml="auto">
        <Button size="compact-sm" variant="default" leftSection={<IconX size={14} />} onClick={closeMasterEditor}
          disabled={m.applying} data-testid="master-cancel">
          Cancel
        </Button>
        <Tooltip label={changed ? "Restart the controller with these master settings (all axes must be stopped)"
          : "Nothing changed"} openDelay={300}>
          <Button size="compact-sm" leftSection={<IconCheck size={14} />} loading={m.applying}
            disabled={problems.length > 0 || !changed} onClick={() => void applyMaster()} data-testid="master-apply">
            Apply
          </Button>
        </Tooltip>
      </Group>
      {(m.refusal || general.length > 0) && (
        <Alert color={m.refusal ? "orange" : "red"} variant="light" py={6} icon={<IconAlertTriangle size={16} />}
          style={{ flexBasis: "100%" }} data-testid="master-refusal"
          title={m.refusal ? refusalTitle(m.refusal.status) : "The controller refused these settings"}>
          <Stack gap={2}>
            {m.refusal && <Text size="xs">{refusalText(m.refusal.status, m.refusal.message)}</Text>}
            {general.map((i, k) => (
              <Text size="xs" key={k}>{i.path ? `${i.path}: ` : ""}{i.msg}</Text>
            ))}
          </Stack>
        </Alert>
      )}
    </>
  );
}

/** The EtherCAT master: cycle time, distributed clocks, automatic slave restart and how many slaves are in Op. */
export function MasterBox({ master }: { master: EtherCATMaster }) {
  const all = master.slaves_in_op === master.slaves_configured;
  const editing = useStore(masterEditorStore, (s) => s.open);
  return (
    <div className="ecat-master" data-testid="ecat-master" data-editing={editing ? "true" : "false"}>
      <Group gap={8} wrap="nowrap" className="ecat-master-title">
        <IconServer2 size={18} color="var(--mantine-color-blue-7)" />
        <div>
          <Text size="sm" fw={700} lh={1.2}>
            EtherCAT master
          </Text>
          <Text size="11px" c="dimmed" lh={1.2}>
            {master.explicit ? "Slaves configured in the project" : "One built-in slave per axis (implicit)"}
          </Text>
        </div>
      </Group>
      <Item label="Cycle time">
        <Tooltip label="The controller's primary period (controller settings): one frame per period" openDelay={300}>
          <Text size="sm" className="num" data-testid="ecat-cycle-time">
            {master.cycle_time_us} <span className="unit">µs</span>
          </Text>
        </Tooltip>
      </Item>
      <Item label="Slaves in Op">
        <Badge size="md" color={all ? "green" : "red"} variant="light" className="num" data-testid="ecat-slaves-in-op"
          style={{ textTransform: "none" }}>
          {master.slaves_in_op} / {master.slaves_configured}
        </Badge>
      </Item>
      {editing ? (
        <MasterForm settings={master.settings} />
      ) : (
        <>
          <Item label="Distributed clocks">
            <Led
              label={master.settings.dc_enabled ? `On · SYNC0 shift ${master.settings.sync_offset_pct} %` : "Off"}
              on={master.settings.dc_enabled ?? true}
              testId="ecat-dc"
            />
          </Item>
          <Item label="Auto-restart slaves">
            <Tooltip label="A slave that comes back after a drop-out returns to Op by itself (else: Connect)" openDelay={300}>
              <div>
                <Led label={master.settings.auto_restart_slaves ? "On" : "Off"} on={master.settings.auto_restart_slaves ?? true}
                  testId="ecat-auto-restart" />
              </div>
            </Tooltip>
          </Item>
          <Tooltip label="Edit the master settings (DC, SYNC0 shift, auto-restart)" openDelay={300}>
            <Button size="compact-sm" variant="default" leftSection={<IconPencil size={14} />} ml="auto"
              onClick={() => openMasterEditor(master.settings)} data-testid="ecat-master-edit">
              Edit
            </Button>
          </Tooltip>
        </>
      )}
    </div>
  );
}
