import { Alert, Badge, Box, Button, Center, Group, Loader, ScrollArea, Stack, Text, Tooltip, UnstyledButton } from "@mantine/core";
import { IconAlertTriangle, IconArrowBackUp, IconCheck, IconInfoCircle, IconSettings, IconTool } from "@tabler/icons-react";
import { useCallback, useEffect, useRef, useState } from "react";
import type { AxisConfig } from "../../api/types";
import { useAxisSections } from "../../hooks/useSchema";
import { axisTypeLabel } from "../../lib/format";
import { type SectionSpec, sameValue, validateField } from "../../lib/schema";
import { useAxisConfig } from "../../store/axisConfig";
import { useStore } from "../../store/createStore";
import { type SettingsIssue, applySettings, revertSettings, settingsStore, syncEditor } from "../../store/settings";
import { openAxisTab } from "../../store/tabs";
import { Panel } from "../common/Panel";
import { ParamRow, Ticks, rowId } from "./ParamRow";

/** Groups whose change makes the axis home undefined (as on the controller). */
const REHOME_GROUPS = new Set(["UnitConversion", "PosCount"]);

const sectionId = (axis: string, group: string) => `settings-${axis}-section-${group}`;

interface SectionCounts {
  invalid: number;
  modified: number;
}

/** Per section: fields failing the client check or reported by the API, and changed fields. */
function useCounts(axis: string, sections: readonly SectionSpec[]): Map<string, SectionCounts> {
  const ed = useStore(settingsStore, (s) => s[axis]);
  const out = new Map<string, SectionCounts>();
  for (const sec of sections) {
    let invalid = 0;
    let modified = 0;
    for (const f of sec.fields) {
      const v = ed?.draft[f.key] ?? null;
      if (validateField(f, v) !== null || ed?.issues.some((i) => i.key === f.key)) invalid++;
      if (!sameValue(v, ed?.base[f.key] ?? null)) modified++;
    }
    if (ed?.issues.some((i) => i.key === null && i.group === sec.group)) invalid++;
    out.set(sec.group, { invalid, modified });
  }
  return out;
}

function Header({ axis, config, sections, counts }: {
  axis: string;
  config: AxisConfig;
  sections: readonly SectionSpec[];
  counts: Map<string, SectionCounts>;
}) {
  const dirty = useStore(settingsStore, (s) => s[axis]?.dirty ?? false);
  const applying = useStore(settingsStore, (s) => s[axis]?.applying ?? false);
  const hasIssues = useStore(settingsStore, (s) => (s[axis]?.issues.length ?? 0) > 0 || s[axis]?.refusal != null);
  let invalid = 0;
  let modified = 0;
  for (const c of counts.values()) {
    invalid += c.invalid;
    modified += c.modified;
  }
  const clientInvalid = useStore(settingsStore, (s) => {
    const ed = s[axis];
    if (!ed) return 0;
    let n = 0;
    for (const sec of sections) for (const f of sec.fields) if (validateField(f, ed.draft[f.key] ?? null) !== null) n++;
    return n;
  });

  return (
    <Group justify="space-between" wrap="wrap" gap="6px 12px" px="sm" py={6} className="settings-header">
      <Group gap={10} wrap="nowrap" style={{ minWidth: 0, flex: "1 1 260px" }}>
        <IconSettings size={20} color="var(--mantine-color-gray-6)" style={{ flex: "none" }} />
        <Stack gap={0} style={{ minWidth: 0 }}>
          <Text fw={700} size="md" truncate="end">
            {axis} <Text span fw={400} c="dimmed" size="sm">· axis settings</Text>
          </Text>
          <Text size="xs" c="dimmed" truncate="end">
            Axis {config.number} · {axisTypeLabel(config.type ?? "")} · {String(config.use ?? "")}
            {config.node_address != null ? ` · EtherCAT node ${config.node_address}` : " · no EtherCAT node"}
          </Text>
        </Stack>
      </Group>
      <Group gap={8} wrap="nowrap" ml="auto">
        {dirty ? (
          <Badge color="orange" variant="light" style={{ textTransform: "none" }} data-testid="settings-dirty">
            {modified} unsaved change{modified === 1 ? "" : "s"}
          </Badge>
        ) : (
          <Badge color="gray" variant="light" style={{ textTransform: "none" }} data-testid="settings-clean">
            No changes
          </Badge>
        )}
        {invalid > 0 && (
          <Badge color="red" variant="light" style={{ textTransform: "none" }} data-testid="settings-invalid-count">
            {invalid} problem{invalid === 1 ? "" : "s"}
          </Badge>
        )}
        <Tooltip label="Open the MC test run of this axis">
          <Button variant="subtle" leftSection={<IconTool size={14} />} onClick={() => openAxisTab(axis)}
            data-testid="settings-open-testrun">
            Test run
          </Button>
        </Tooltip>
        <Button variant="default" leftSection={<IconArrowBackUp size={14} />} disabled={(!dirty && !hasIssues) || applying}
          onClick={() => revertSettings(axis)} data-testid="settings-revert">
          Revert
        </Button>
        <Tooltip
          label={
            clientInvalid > 0
              ? "Correct the invalid values first"
              : dirty
                ? "Restart the controller with these settings"
                : "Nothing changed"
          }
        >
          <Button leftSection={<IconCheck size={14} />} disabled={!dirty || clientInvalid > 0} loading={applying}
            onClick={() => void applySettings(axis, sections).then((ok) => ok || revealFirstIssue(axis))}
            data-testid="settings-apply">
            Apply
          </Button>
        </Tooltip>
      </Group>
    </Group>
  );
}

/** Scroll to the first field the API complained about. */
function revealFirstIssue(axis: string): void {
  const first = settingsStore.get()[axis]?.issues.find((i) => i.key !== null || i.group !== null);
  if (!first) return;
  const el = document.getElementById(first.key ? rowId(axis, first.key) : sectionId(axis, first.group ?? ""));
  el?.scrollIntoView({ block: "center", behavior: "smooth" });
}

function IssueLine({ axis, issue }: { axis: string; issue: SettingsIssue }) {
  const target = issue.key ? rowId(axis, issue.key) : issue.group ? sectionId(axis, issue.group) : null;
  return (
    <Group gap={8} wrap="nowrap" align="baseline" data-testid="settings-issue">
      {issue.code && (
        <Badge size="sm" color="red" variant="filled" radius="xs" className="num" style={{ flex: "none" }}>
          {issue.code}
        </Badge>
      )}
      <Text size="xs">
        {target ? (
          <UnstyledButton
            className="issue-link"
            onClick={() => document.getElementById(target)?.scrollIntoView({ block: "center", behavior: "smooth" })}
          >
            {issue.key ?? issue.group}
          </UnstyledButton>
        ) : (
          <Text span ff="monospace" size="xs">
            {issue.path}
          </Text>
        )}
        : {issue.msg}
      </Text>
    </Group>
  );
}

function Problems({ axis }: { axis: string }) {
  const issues = useStore(settingsStore, (s) => s[axis]?.issues);
  const refusal = useStore(settingsStore, (s) => s[axis]?.refusal);
  if (refusal) {
    return (
      <Alert color="orange" variant="light" py={6} icon={<IconAlertTriangle size={16} />} data-testid="settings-refusal"
        title={refusal.status === 409 ? "Not applied: an axis is moving (409)" : `Not applied${refusal.status ? ` (${refusal.status})` : ""}`}>
        <Text size="xs">{refusal.message}</Text>
      </Alert>
    );
  }
  if (!issues?.length) return null;
  return (
    <Alert color="red" variant="light" py={6} icon={<IconAlertTriangle size={16} />} data-testid="settings-issues"
      title={`The controller rejected these settings (${issues.length} problem${issues.length === 1 ? "" : "s"})`}>
      <ScrollArea.Autosize mah={96} type="auto">
        <Stack gap={2}>
          {issues.map((i, k) => (
            <IssueLine key={k} axis={axis} issue={i} />
          ))}
        </Stack>
      </ScrollArea.Autosize>
    </Alert>
  );
}

function SectionNav({ sections, counts, active, onPick }: {
  sections: readonly SectionSpec[];
  counts: Map<string, SectionCounts>;
  active: string;
  onPick: (group: string) => void;
}) {
  return (
    <Stack gap={1} p={6} className="settings-nav" data-testid="settings-nav">
      {sections.map((s) => {
        const c = counts.get(s.group);
        return (
          <UnstyledButton key={s.group} className="settings-nav-item" data-active={active === s.group ? "true" : undefined}
            onClick={() => onPick(s.group)} data-testid={`settings-nav-${s.group}`}>
            <Text size="xs" fw={active === s.group ? 700 : 500} style={{ flex: 1 }} truncate="end">
              {s.title}
            </Text>
            {c && c.modified > 0 && (
              <Tooltip label={`${c.modified} changed`}>
                <span className="dot dot-modified" />
              </Tooltip>
            )}
            {c && c.invalid > 0 && (
              <Badge size="xs" color="red" variant="filled" circle>
                {c.invalid}
              </Badge>
            )}
          </UnstyledButton>
        );
      })}
    </Stack>
  );
}

function Section({ axis, section }: { axis: string; section: SectionSpec }) {
  const groupIssues = useStore(settingsStore, (s) => s[axis]?.issues);
  const mine = (groupIssues ?? []).filter((i) => i.key === null && i.group === section.group);
  return (
    <div id={sectionId(axis, section.group)} className="settings-section" data-group={section.group}>
      <Panel
        title={section.title}
        testId={`settings-section-${section.group}`}
        right={
          <Text size="11px" c="dimmed" tt="none" fw={400} truncate="end" maw="62%" lh={1.6} title={section.description}>
            <Ticks text={section.description.split("\n")[0]} />
          </Text>
        }
      >
        <Stack gap={6}>
          {REHOME_GROUPS.has(section.group) && (
            <Alert color="yellow" variant="light" py={4} px={8} icon={<IconAlertTriangle size={14} />}
              data-testid={`settings-rehome-${section.group}`} styles={{ icon: { marginRight: 6 } }}>
              <Text size="xs">
                Changing these settings requires defining home again (the axis becomes home undefined) — as on the
                controller.
              </Text>
            </Alert>
          )}
          {mine.map((i, k) => (
            <Text key={k} size="xs" c="red.7" data-testid={`settings-section-error-${section.group}`}>
              {i.msg}
              {i.code ? ` (${i.code})` : ""}
            </Text>
          ))}
          <div className="param-grid">
            {section.fields.map((f) => (
              <ParamRow key={f.key} axis={axis} spec={f} />
            ))}
          </div>
        </Stack>
      </Panel>
    </div>
  );
}

function SettingsBody({ axis, config, sections }: { axis: string; config: AxisConfig; sections: SectionSpec[] }) {
  const counts = useCounts(axis, sections);
  const scroller = useRef<HTMLDivElement>(null);
  const [active, setActive] = useState(sections[0]?.group ?? "");

  const onScroll = useCallback(() => {
    const box = scroller.current;
    if (!box) return;
    const top = box.getBoundingClientRect().top;
    let current = sections[0]?.group ?? "";
    for (const s of sections) {
      const el = document.getElementById(sectionId(axis, s.group));
      if (el && el.getBoundingClientRect().top - top <= box.clientHeight / 3) current = s.group;
    }
    if (box.scrollTop + box.clientHeight >= box.scrollHeight - 2) current = sections[sections.length - 1]?.group ?? current;
    setActive(current);
  }, [axis, sections]);

  const pick = (group: string) => {
    const box = scroller.current;
    const el = document.getElementById(sectionId(axis, group));
    if (!box || !el) return;
    // The scroller is positioned, so offsetTop is relative to it.
    box.scrollTo({ top: el.offsetTop - 6, behavior: "smooth" });
    setActive(group);
  };

  return (
    <Box style={{ height: "100%", display: "flex", flexDirection: "column", minHeight: 0 }} data-testid={`settings-${axis}`}>
      <Header axis={axis} config={config} sections={sections} counts={counts} />
      <Stack gap={6} px={8} pt={6} style={{ flex: "none" }}>
        <Group gap={6} wrap="nowrap" className="settings-notice" data-testid="settings-notice">
          <IconInfoCircle size={14} color="var(--mantine-color-blue-6)" style={{ flex: "none" }} />
          <Text size="xs" c="gray.7">
            Settings are applied to the controller by restarting it (cycle 0), only while all axes are stopped.
            Save the project to keep them.
          </Text>
        </Group>
        <Problems axis={axis} />
      </Stack>
      <Box style={{ flex: 1, minHeight: 0, display: "flex" }}>
        <SectionNav sections={sections} counts={counts} active={active} onPick={pick} />
        <div ref={scroller} className="settings-scroll" onScroll={onScroll} style={{ position: "relative" }}>
          <Stack gap={8}>
            {sections.map((s) => (
              <Section key={s.group} axis={axis} section={s} />
            ))}
          </Stack>
        </div>
      </Box>
    </Box>
  );
}

/** The axis settings editor: every `_sAXIS_PARAM` group, the servo drive and the simulated sensors, from the schema. */
export function AxisSettings({ axis }: { axis: string }) {
  const entry = useAxisConfig(axis);
  const { status, sections, error } = useAxisSections();
  const config = entry?.data ?? null;
  const ready = useStore(settingsStore, (s) => s[axis] !== undefined);

  useEffect(() => {
    if (config && sections.length) syncEditor(axis, config, sections);
  }, [axis, config, sections]);

  if (entry?.status === "error" && !config) {
    return (
      <Center h={160}>
        <Text size="sm" c="red">
          Cannot load the settings of {axis}: {entry.error}
        </Text>
      </Center>
    );
  }
  if (status === "error") {
    return (
      <Center h={160}>
        <Text size="sm" c="red">
          Cannot load the project schema: {error}
        </Text>
      </Center>
    );
  }
  if (!config || !ready) {
    return (
      <Center h={160}>
        <Loader size="sm" />
      </Center>
    );
  }
  return <SettingsBody axis={axis} config={config} sections={sections} />;
}
