import { Box, Button, Collapse, Divider, Group, Text, Tooltip, UnstyledButton } from "@mantine/core";
import {
  IconChevronDown,
  IconChevronRight,
  IconCrosshair,
  IconDownload,
  IconHome,
  IconHomeCog,
  IconTarget,
} from "@tabler/icons-react";
import { type ReactNode, useEffect, useState } from "react";
import { useAxisSummary, useLive } from "../../hooks/useLive";
import { useDefFields } from "../../hooks/useSchema";
import { type AxisUnits, fixed } from "../../lib/format";
import { notifyError } from "../../lib/notify";
import { type FieldSpec, displayUnit, fromFieldValue, validateField } from "../../lib/schema";
import { useAxisConfig } from "../../store/axisConfig";
import { issue } from "../../store/commands";
import { useStore } from "../../store/createStore";
import { axisForms, num, setFormField, useAxisForms } from "../../store/forms";
import {
  HOMING_REF_MEMBERS,
  homingRefFromConfig,
  homingRefStore,
  setHomingRef,
  setHomingRefMember,
} from "../../store/homingRef";
import { openSettingsTab } from "../../store/tabs";
import { FieldInput } from "../settings/FieldInput";
import { Led } from "../common/Led";
import { NumField } from "../common/NumField";
import { Panel } from "../common/Panel";

function Setting({ label, children, testId }: { label: string; children: ReactNode; testId?: string }) {
  return (
    <Text size="xs" component="div" style={{ whiteSpace: "nowrap" }} data-testid={testId}>
      <Text span size="xs" c="dimmed">
        {label}:
      </Text>{" "}
      {children}
    </Text>
  );
}

function Mono({ children }: { children: ReactNode }) {
  return (
    <Text span size="xs" ff="monospace" fw={600}>
      {children}
    </Text>
  );
}

/** What MC_Home will do: the homing settings of the axis. */
function ConfiguredHoming({ axis, units }: { axis: string; units: AxisUnits }) {
  const entry = useAxisConfig(axis);
  const h = entry?.data?.parameters?.Homing;
  if (!h) {
    return (
      <Text size="xs" c="dimmed">
        {entry?.status === "error" ? `Cannot load the homing settings: ${entry.error}` : "Loading the homing settings…"}
      </Text>
    );
  }
  const n = (v: unknown) => (typeof v === "number" ? fixed(v, v % 1 === 0 ? 0 : 3) : String(v));
  return (
    <Box className="homing-settings" data-testid="homing-settings">
      <Group gap="4px 18px" wrap="wrap">
        <Setting label="Mode" testId="homing-mode">
          <Mono>{String(h.Mode)}</Mono>
        </Setting>
        <Setting label="Home input">
          <Mono>{String(h.HomeInputSignal)}</Mono>
        </Setting>
        <Setting label="Start direction" testId="homing-start-direction">
          <Mono>{String(h.StartDirection)}</Mono>
        </Setting>
        <Setting label="Detection direction" testId="homing-detection-direction">
          <Mono>{String(h.HomeInputDetectionDirection)}</Mono>
        </Setting>
      </Group>
      <Group gap="4px 18px" wrap="wrap" mt={3}>
        <Setting label="Velocity">
          <span className="num">{n(h.Vel)}</span> <span className="unit">{units.vel}</span>
        </Setting>
        <Setting label="Approach">
          <span className="num">{n(h.ApproachVel)}</span> <span className="unit">{units.vel}</span>
        </Setting>
        <Setting label="Acc./dec.">
          <span className="num">
            {n(h.Acc)} / {n(h.Dec)}
          </span>{" "}
          <span className="unit">{units.acc}</span>
        </Setting>
        <Setting label="Offset">
          <span className="num">{n(h.HomeOffset)}</span> <span className="unit">{units.pos}</span>
        </Setting>
      </Group>
    </Box>
  );
}

/** One `_sHOMING_REF` member: its name, unit and input (checked against the matching homing setting's schema). */
function RefField({ axis, member, spec, unitDisplay }: {
  axis: string;
  member: string;
  spec: FieldSpec;
  unitDisplay: string | undefined;
}) {
  const value = useStore(homingRefStore, (s) => s[axis]?.[member] ?? null);
  const error = validateField(spec, value);
  const unit = displayUnit(spec.unit, unitDisplay);
  return (
    <Box style={{ minWidth: 0 }}>
      <Group gap={4} wrap="nowrap" justify="space-between">
        <Text size="11px" ff="monospace" fw={600} c="gray.8" truncate="end" title={spec.description}>
          {member}
        </Text>
        {unit && spec.kind !== "enum" && (
          <Text size="10px" c="dimmed" style={{ whiteSpace: "nowrap" }}>
            {unit}
          </Text>
        )}
      </Group>
      <FieldInput
        spec={spec}
        value={value}
        onChange={(v) => setHomingRefMember(axis, member, v)}
        unit={null}
        invalid={error !== null}
        testId={`homeparam-${member}`}
        ariaLabel={`HomingParameter.${member}`}
      />
      {error && (
        <Text size="10px" c="red.7" data-testid={`homeparam-error-${member}`}>
          {error}
        </Text>
      )}
    </Box>
  );
}

/** MC_HomeWithParameter with an edited `_sHOMING_REF`, prefilled from the axis homing settings. */
function HomeWithParameter({ axis }: { axis: string }) {
  const settingsSpecs = useDefFields("HomingSettings");
  const entry = useAxisConfig(axis);
  const config = entry?.data ?? null;
  const unitDisplay = useAxisSummary(axis)?.units;
  const loaded = useStore(homingRefStore, (s) => s[axis] !== undefined);
  const [busy, setBusy] = useState(false);

  useEffect(() => {
    if (!loaded && config && settingsSpecs.size) setHomingRef(axis, homingRefFromConfig(config, settingsSpecs));
  }, [axis, loaded, config, settingsSpecs]);

  const members = HOMING_REF_MEMBERS.map(([ref, setting]) => ({ ref, spec: settingsSpecs.get(setting) })).filter(
    (m): m is { ref: string; spec: FieldSpec } => m.spec !== undefined,
  );
  const enums = members.filter((m) => m.spec.kind === "enum");
  const numbers = members.filter((m) => m.spec.kind !== "enum");

  const run = async () => {
    const values = homingRefStore.get()[axis] ?? {};
    const bad = members.filter((m) => validateField(m.spec, values[m.ref] ?? null) !== null).map((m) => m.ref);
    if (bad.length) {
      notifyError("MC_HomeWithParameter", new Error(`correct HomingParameter ${bad.join(", ")}`));
      return;
    }
    const ref: Record<string, unknown> = {};
    for (const m of members) ref[m.ref] = fromFieldValue(m.spec, values[m.ref] ?? null);
    setBusy(true);
    await issue(axis, "MC_HomeWithParameter", { HomingParameter: ref });
    setBusy(false);
  };

  if (!members.length || !loaded) {
    return (
      <Text size="xs" c="dimmed">
        Loading…
      </Text>
    );
  }
  return (
    <Box data-testid="home-with-parameter">
      <div className="homeref-grid homeref-enums">
        {enums.map((m) => (
          <RefField key={m.ref} axis={axis} member={m.ref} spec={m.spec} unitDisplay={unitDisplay} />
        ))}
      </div>
      <div className="homeref-grid homeref-numbers">
        {numbers.map((m) => (
          <RefField key={m.ref} axis={axis} member={m.ref} spec={m.spec} unitDisplay={unitDisplay} />
        ))}
      </div>
      <Group justify="space-between" mt={8} wrap="nowrap" gap={8}>
        <Text size="11px" c="dimmed" style={{ minWidth: 0 }}>
          Mask is used by <code className="ticks">_mcHomeSwTurnHomeMask</code>, PushTime by{" "}
          <code className="ticks">_mcHomeSwTurnHoldingTime</code> only. Invalid members end with error 5700.
        </Text>
        <Group gap={6} wrap="nowrap">
          <Tooltip label="Copy the axis homing settings into HomingParameter">
            <Button variant="default" leftSection={<IconDownload size={14} />} disabled={!config}
              onClick={() => config && setHomingRef(axis, homingRefFromConfig(config, settingsSpecs))}
              data-testid="homeparam-load">
              From settings
            </Button>
          </Tooltip>
          <Button leftSection={<IconHomeCog size={14} />} loading={busy} onClick={() => void run()}
            data-testid="home-with-parameter-button">
            Home with parameters
          </Button>
        </Group>
      </Group>
    </Box>
  );
}

/** Homing: MC_Home, MC_HomeWithParameter, MC_MoveZeroPosition and MC_SetPosition. */
export function HomingPanel({ axis, units }: { axis: string; units: AxisUnits }) {
  const f = useAxisForms(axis);
  const inPosWaiting = useLive((s) => s.axes[axis]?.Details.InPosWaiting ?? false);
  const inHome = useLive((s) => s.axes[axis]?.Details.InHome ?? false);
  const [busy, setBusy] = useState<"home" | "zero" | "setpos" | null>(null);
  const [advanced, setAdvanced] = useState(false);

  const run = async (what: "home" | "zero" | "setpos") => {
    const forms = axisForms(axis);
    if (what === "home") {
      setBusy(what);
      await issue(axis, "MC_Home", {});
    } else if (what === "zero") {
      const v = num(forms.absVelocity);
      const a = num(forms.absAcceleration);
      const d = num(forms.absDeceleration);
      const j = num(forms.absJerk);
      if (v === null || a === null || d === null || j === null) {
        notifyError("MC_MoveZeroPosition", new Error("enter numbers in the absolute move form"));
        return;
      }
      setBusy(what);
      await issue(axis, "MC_MoveZeroPosition", { Velocity: v, Acceleration: a, Deceleration: d, Jerk: j });
    } else {
      const p = num(forms.setPosition);
      if (p === null) {
        notifyError("MC_SetPosition", new Error("enter a position"));
        return;
      }
      setBusy(what);
      await issue(axis, "MC_SetPosition", { Position: p });
    }
    setBusy(null);
  };

  return (
    <Panel
      title="Homing (MC_Home, MC_HomeWithParameter)"
      testId="homing-panel"
      right={
        <Group gap={10} wrap="nowrap">
          <Led label="InHome" on={inHome} color="teal" testId="homing-inhome" />
          <Led label="InPosWaiting" on={inPosWaiting} color="blue" testId="homing-inposwaiting" />
        </Group>
      }
    >
      <Group justify="space-between" align="flex-start" wrap="nowrap" gap={8}>
        <Box style={{ flex: 1, minWidth: 0 }}>
          <ConfiguredHoming axis={axis} units={units} />
        </Box>
        <Tooltip label="Edit the homing settings of the axis">
          <Button variant="subtle" size="compact-xs" onClick={() => openSettingsTab(axis)} data-testid="homing-edit-settings"
            style={{ flex: "none" }}>
            Settings…
          </Button>
        </Tooltip>
      </Group>
      <Group gap={8} mt={8} wrap="nowrap" align="flex-end">
        <Tooltip label="MC_Home with the axis homing settings">
          <Button leftSection={<IconHome size={14} />} loading={busy === "home"} onClick={() => void run("home")}
            data-testid="home-button">
            Home
          </Button>
        </Tooltip>
        <Tooltip label="MC_MoveZeroPosition: to absolute 0 with the absolute move's velocity, acc./dec. and jerk">
          <Button variant="default" leftSection={<IconTarget size={14} />} loading={busy === "zero"}
            onClick={() => void run("zero")} data-testid="zero-position-button">
            Zero position
          </Button>
        </Tooltip>
        <Divider orientation="vertical" mx={4} />
        <NumField label="New current position" unit={units.pos} value={f.setPosition} testId="set-position-value"
          onChange={(v) => setFormField(axis, "setPosition", v)} w={150} />
        <Tooltip label="MC_SetPosition: the current position becomes this value; home becomes undefined">
          <Button variant="default" leftSection={<IconCrosshair size={14} />} loading={busy === "setpos"}
            onClick={() => void run("setpos")} data-testid="set-position-button">
            Set position
          </Button>
        </Tooltip>
      </Group>
      <UnstyledButton className="collapse-toggle" onClick={() => setAdvanced((o) => !o)} mt={8}
        data-testid="home-advanced-toggle" aria-expanded={advanced}>
        {advanced ? <IconChevronDown size={14} /> : <IconChevronRight size={14} />}
        <Text size="xs" fw={600}>
          Advanced: home with parameters
        </Text>
        <Text size="xs" c="dimmed">
          MC_HomeWithParameter with a <code className="ticks">_sHOMING_REF</code>
        </Text>
      </UnstyledButton>
      <Collapse in={advanced}>
        <Box pt={6}>{advanced && <HomeWithParameter axis={axis} />}</Box>
      </Collapse>
    </Panel>
  );
}
