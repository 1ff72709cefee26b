import {
  ActionIcon,
  Badge,
  Box,
  Button,
  Divider,
  Group,
  NumberInput,
  ScrollArea,
  SegmentedControl,
  Select,
  Stack,
  Switch,
  Text,
  TextInput,
  Tooltip,
} from "@mantine/core";
import { IconDeviceFloppy, IconDownload, IconPlayerPlay, IconPlayerStop, IconRefresh, IconX } from "@tabler/icons-react";
import { useEffect, useMemo } from "react";
import { notifyError, notifyOk } from "../../lib/notify";
import { useStore } from "../../store/createStore";
import {
  type TraceCatalog,
  type TraceSettings,
  type TraceTrigger,
  csvUrl,
  loadCatalog,
  loadSaved,
  parseVarKey,
  saveDraftToProject,
  setDraft,
  startTrace,
  stopTrace,
  traceStore,
  varKey,
} from "../../store/trace";
import { TraceChart } from "./TraceChart";

interface Option {
  value: string;
  label: string;
}

const KIND_GROUP: Record<string, string> = { axis: "Axis", group: "Group", fb: "Instance", pdo: "Slave" };

/** Select data grouped by target ("Axis MC_Axis000", "Instance #3 MC_Power (MC_Axis000)", "Slave Node 1 …"). */
function catalogOptions(cat: TraceCatalog | null): { group: string; items: Option[] }[] {
  if (!cat) return [];
  const targets = [...cat.axes, ...cat.groups, ...cat.instances, ...cat.slaves];
  return targets.map((t) => ({
    group: `${KIND_GROUP[t.kind]} ${t.label}`,
    items: t.variables.map((v) => ({
      value: varKey({ kind: t.kind, target: t.target, name: v.name }),
      label: `${t.kind === "pdo" ? `Node${t.target}` : t.kind === "fb" ? `#${t.target}` : t.target}.${v.name}${
        v.description ? ` ${v.description}` : ""}${v.unit ? ` [${v.unit}]` : ""}`,
    })),
  }));
}

const STATE_BADGE: Record<string, { color: string; label: string }> = {
  waiting: { color: "yellow", label: "Waiting for trigger" },
  triggered: { color: "blue", label: "Triggered" },
  done: { color: "green", label: "Done" },
  running: { color: "blue", label: "Recording (ring)" },
  stopped: { color: "gray", label: "Stopped" },
};

const CONDITIONS = [
  { value: "rising", label: "Rising ↑" },
  { value: "falling", label: "Falling ↓" },
  { value: "gt", label: "> level" },
  { value: "lt", label: "< level" },
  { value: "eq", label: "= level" },
  { value: "ne", label: "≠ level" },
];

function TriggerEditor({ trigger, options }: { trigger: TraceTrigger; options: { group: string; items: Option[] }[] }) {
  const set = (u: Partial<TraceTrigger>) => setDraft({ trigger: { ...trigger, ...u } });
  return (
    <Stack gap={6}>
      <Select
        label="Trigger variable"
        size="xs"
        searchable
        data={options}
        value={varKey(trigger.variable)}
        onChange={(v) => v && set({ variable: parseVarKey(v) })}
        maxDropdownHeight={320}
        data-testid="trace-trigger-variable"
        nothingFoundMessage="No such variable"
      />
      <Group gap={6} grow>
        <Select
          label="Condition"
          size="xs"
          data={CONDITIONS}
          value={trigger.condition ?? "rising"}
          onChange={(v) => v && set({ condition: v as TraceTrigger["condition"] })}
          allowDeselect={false}
          data-testid="trace-trigger-condition"
        />
        <NumberInput
          label="Level"
          size="xs"
          value={trigger.level ?? 0.5}
          onChange={(v) => set({ level: typeof v === "number" ? v : Number(v) || 0 })}
          decimalScale={6}
          data-testid="trace-trigger-level"
        />
        <NumberInput
          label="Pre-trigger %"
          size="xs"
          min={0}
          max={100}
          value={trigger.pre_trigger_percent ?? 10}
          onChange={(v) => set({ pre_trigger_percent: typeof v === "number" ? v : Number(v) || 0 })}
          data-testid="trace-trigger-pre"
        />
      </Group>
    </Stack>
  );
}

function Settings() {
  const draft = useStore(traceStore, (s) => s.draft);
  const catalog = useStore(traceStore, (s) => s.catalog);
  const catalogError = useStore(traceStore, (s) => s.catalogError);
  const saved = useStore(traceStore, (s) => s.saved);
  const options = useMemo(() => catalogOptions(catalog), [catalog]);
  const chosen = new Set(draft.variables.map(varKey));
  const addOptions = useMemo(
    () => options.map((g) => ({ ...g, items: g.items.filter((i) => !chosen.has(i.value)) })).filter((g) => g.items.length),
    // eslint-disable-next-line react-hooks/exhaustive-deps
    [options, draft.variables],
  );
  const trigger = draft.trigger ?? null;
  const mode = draft.mode ?? "single";

  const setMode = (m: string) => {
    const next = m as TraceSettings["mode"];
    if (next === "continuous") setDraft({ mode: next, trigger: null });
    else if (next === "repeat" && !trigger)
      setDraft({ mode: next, trigger: { variable: draft.variables[0], condition: "rising", level: 0.5, pre_trigger_percent: 10 } });
    else setDraft({ mode: next });
  };

  return (
    <Stack gap={8} p="sm" data-testid="trace-settings">
      {saved.length > 0 && (
        <Select
          size="xs"
          label="Saved in the project"
          placeholder="Load saved settings…"
          data={saved.map((t) => t.name ?? "Trace")}
          value={null}
          onChange={(v) => {
            const s = saved.find((t) => t.name === v);
            if (s) setDraft(s);
          }}
          data-testid="trace-saved"
        />
      )}
      <TextInput size="xs" label="Name" value={draft.name ?? ""} onChange={(e) => setDraft({ name: e.currentTarget.value })}
        data-testid="trace-name" />
      <Text size="xs" fw={600}>
        Variables ({draft.variables.length})
      </Text>
      <Stack gap={2} data-testid="trace-variables">
        {draft.variables.map((v) => (
          <Group key={varKey(v)} gap={4} wrap="nowrap" className="trace-var-row">
            <Text size="xs" style={{ flex: 1, minWidth: 0 }} truncate="end" title={varKey(v)}>
              {v.kind === "pdo" ? `Node${v.target}` : v.kind === "fb" ? `#${v.target}` : v.target}.{v.name}
            </Text>
            <ActionIcon size="xs" variant="subtle" color="gray" aria-label={`Remove ${v.target}.${v.name}`}
              onClick={() => setDraft({ variables: draft.variables.filter((x) => varKey(x) !== varKey(v)) })}>
              <IconX size={12} />
            </ActionIcon>
          </Group>
        ))}
      </Stack>
      <Select
        size="xs"
        placeholder={catalog ? "Add a variable… (type to search)" : "Loading variables…"}
        searchable
        data={addOptions}
        value={null}
        onChange={(v) => v && setDraft({ variables: [...draft.variables, parseVarKey(v)] })}
        maxDropdownHeight={360}
        nothingFoundMessage="No such variable"
        data-testid="trace-add-variable"
        rightSection={
          <Tooltip label="Reload the list (new instances)">
            <ActionIcon size="xs" variant="subtle" onClick={() => void loadCatalog()} aria-label="Reload variables">
              <IconRefresh size={12} />
            </ActionIcon>
          </Tooltip>
        }
      />
      {catalogError && <Text size="xs" c="red">{catalogError}</Text>}
      <Divider />
      <Group gap={6} grow>
        <NumberInput size="xs" label="Sample every N periods" min={1} max={10000} value={draft.sampling_periods ?? 1}
          onChange={(v) => setDraft({ sampling_periods: Math.max(1, Math.round(Number(v) || 1)) })}
          data-testid="trace-sampling" />
        <NumberInput size="xs" label="Samples" min={2} max={catalog?.max_samples ?? 1000000} step={1000}
          value={draft.samples ?? 10000} thousandSeparator=","
          onChange={(v) => setDraft({ samples: Math.max(2, Math.round(Number(v) || 2)) })} data-testid="trace-samples" />
      </Group>
      <SegmentedControl size="xs" value={mode} onChange={setMode} data-testid="trace-mode"
        data={[{ value: "single", label: "Single" }, { value: "continuous", label: "Continuous" }, { value: "repeat", label: "Repeat" }]} />
      <Switch
        size="xs"
        label="Trigger"
        checked={trigger !== null}
        disabled={mode === "continuous"}
        onChange={(e) =>
          setDraft({
            trigger: e.currentTarget.checked
              ? { variable: draft.variables[0] ?? { kind: "axis", target: "MC_Axis000", name: "Cmd.Vel" }, condition: "rising", level: 0.5, pre_trigger_percent: 10 }
              : null,
          })
        }
        data-testid="trace-trigger-enable"
      />
      {trigger && <TriggerEditor trigger={trigger} options={options} />}
    </Stack>
  );
}

function Toolbar() {
  const data = useStore(traceStore, (s) => s.data);
  const traceId = useStore(traceStore, (s) => s.traceId);
  const busy = useStore(traceStore, (s) => s.busy);
  const error = useStore(traceStore, (s) => s.error);
  const recording = data !== null && ["waiting", "triggered", "running"].includes(data.state);
  const badge = data
    ? data.state === "waiting" && !data.armed
      ? { color: "gray", label: "Pre-trigger…" }
      : STATE_BADGE[data.state]
    : null;
  return (
    <Group gap={8} px="sm" py={6} style={{ borderBottom: "1px solid #e9ecef" }} wrap="nowrap">
      <Button size="xs" style={{ flex: "none" }} leftSection={<IconPlayerPlay size={14} />} loading={busy} data-testid="trace-start"
        onClick={() => startTrace().catch((err) => notifyError("Start trace", err))}>
        Start
      </Button>
      <Button size="xs" style={{ flex: "none" }} variant="default" leftSection={<IconPlayerStop size={14} />} disabled={!recording}
        data-testid="trace-stop" onClick={() => stopTrace().catch((err) => notifyError("Stop trace", err))}>
        Stop
      </Button>
      <Button size="xs" style={{ flex: "none" }} variant="default" leftSection={<IconDownload size={14} />} disabled={traceId === null}
        component="a" href={csvUrl() ?? undefined} download data-testid="trace-csv">
        CSV
      </Button>
      <Button size="xs" style={{ flex: "none" }} variant="default" leftSection={<IconDeviceFloppy size={14} />} data-testid="trace-save"
        onClick={() =>
          saveDraftToProject()
            .then(() => notifyOk("Trace settings put into the project", "Save the project to write them to project.json"))
            .catch((err) => notifyError("Save trace settings", err))
        }>
        Save to project
      </Button>
      <Box style={{ flex: 1, minWidth: 0 }}>
        {error && (
          <Text size="xs" c="red" truncate="end" title={error} data-testid="trace-error">
            {error}
          </Text>
        )}
      </Box>
      {data && (
        <Text size="xs" c="dimmed" data-testid="trace-info" ta="right" style={{ flex: "0 1 auto", minWidth: 0 }}>
          {data.sample_count.toLocaleString()} samples
          {data.decimation > 1 ? ` (1 in ${data.decimation} drawn)` : ""}
          {data.trigger_cycle !== null ? ` · trigger at cycle ${data.trigger_cycle}` : ""}
          {data.records > 0 ? ` · ${data.records} records` : ""}
        </Text>
      )}
      {badge && (
        <Badge color={badge.color} variant="light" data-testid="trace-state" data-state={data?.state}
          style={{ flex: "none", overflow: "visible" }}>
          {badge.label}
        </Badge>
      )}
    </Group>
  );
}

/** The data trace tab: settings on the left, the record on the right (see docs/trace.md). */
export function TraceView() {
  const data = useStore(traceStore, (s) => s.data);
  useEffect(() => {
    if (!traceStore.get().catalog) void loadCatalog();
    void loadSaved();
  }, []);
  return (
    <Box style={{ display: "flex", height: "100%", minHeight: 0 }} data-testid="trace-view">
      <ScrollArea w={330} h="100%" type="auto" style={{ borderRight: "1px solid #e9ecef", flex: "none" }}>
        <Settings />
      </ScrollArea>
      <Box style={{ flex: 1, minWidth: 0, display: "flex", flexDirection: "column" }}>
        <Toolbar />
        {data ? (
          <TraceChart data={data} />
        ) : (
          <Box p="md">
            <Text size="sm" c="dimmed">
              Choose variables, sampling and an optional trigger, then Start. Drag across the chart to zoom,
              double-click to reset; click to place cursor A, shift-click for B.
            </Text>
          </Box>
        )}
      </Box>
    </Box>
  );
}
