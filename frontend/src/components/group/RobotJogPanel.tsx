import {
  Button,
  Collapse,
  Group,
  NumberInput,
  SegmentedControl,
  Select,
  SimpleGrid,
  Stack,
  Text,
  Tooltip,
} from "@mantine/core";
import { IconAdjustments, IconPlayerPlay, IconPlayerStop, IconTarget } from "@tabler/icons-react";
import { useEffect, useMemo, useState } from "react";
import type { RobotOut } from "../../api/types";
import { useFb, useLive } from "../../hooks/useLive";
import { notifyError } from "../../lib/notify";
import type { NumValue } from "../../store/forms";
import { num } from "../../store/forms";
import {
  DEMO_DEFAULTS,
  type GroupInfo,
  moveToPose,
  robotJogPress,
  robotJogRelease,
  robotJogStep,
  runDemo,
  stopDemo,
  useGroupCommands,
} from "../../store/groupCommands";
import { useRobots } from "../viz/useRobots";
import { HoldButton } from "../testrun/HoldButton";
import { ErrorCode } from "./GroupControls";

const READY_POINT = [0, 0, -300];

type CoordSystems = RobotOut["coord_systems"];

// ------------------------------------------------------------------ settings kept in the browser (D93)

interface DemoSettings {
  conveyorVelocity: number;
  velocity: number;
  acceleration: number;
  pick: number[];
  place: number[];
  approach: number;
}

/** The robot test run's settings: jog speed, acceleration, hold or step, step length, frame; the demo's points. */
export interface RobotTestRunSettings {
  velocity: number;
  acceleration: number;
  mode: "hold" | "step";
  step: number;
  /** "mcs" or "ucs:<CSID>" */
  frame: string;
  demo: DemoSettings;
}

export const ROBOT_SETTINGS_DEFAULTS: RobotTestRunSettings = {
  velocity: 50,
  acceleration: 500,
  mode: "hold",
  step: 1,
  frame: "mcs",
  demo: {
    conveyorVelocity: DEMO_DEFAULTS.conveyorVelocity,
    velocity: DEMO_DEFAULTS.velocity,
    acceleration: DEMO_DEFAULTS.acceleration,
    pick: [...DEMO_DEFAULTS.pick],
    place: [...DEMO_DEFAULTS.place],
    approach: DEMO_DEFAULTS.approach,
  },
};

/**
 * localStorage key of a robot's settings: per project name and axes group, so another project (or robot) keeps its
 * own. Browser storage, not the project (D93): these are the engineer's test-run preferences on this workstation, and
 * a project change restarts the controller.
 */
export const robotSettingsKey = (project: string | null, group: string) =>
  `mcstudio.robotTestRun.v1:${project ?? "-"}:${group}`;

const isNum = (v: unknown, ok: (n: number) => boolean = () => true): v is number =>
  typeof v === "number" && Number.isFinite(v) && ok(v);
const isPoint = (v: unknown): v is number[] => Array.isArray(v) && v.length === 3 && v.every((x) => isNum(x));
const positive = (n: number) => n > 0;

/** The stored settings, every member checked (a bad or missing one takes its default). */
export function loadRobotSettings(key: string): RobotTestRunSettings {
  const d = ROBOT_SETTINGS_DEFAULTS;
  let raw: Record<string, unknown> = {};
  try {
    const text = window.localStorage.getItem(key);
    const parsed: unknown = text ? JSON.parse(text) : {};
    if (parsed && typeof parsed === "object") raw = parsed as Record<string, unknown>;
  } catch {
    /* unreadable: defaults */
  }
  const demo = (raw.demo && typeof raw.demo === "object" ? raw.demo : {}) as Record<string, unknown>;
  return {
    velocity: isNum(raw.velocity, positive) ? raw.velocity : d.velocity,
    acceleration: isNum(raw.acceleration, (n) => n >= 0) ? raw.acceleration : d.acceleration,
    mode: raw.mode === "step" ? "step" : "hold",
    step: isNum(raw.step, positive) ? raw.step : d.step,
    frame: typeof raw.frame === "string" && /^(mcs|ucs:(\d|1[0-5]))$/.test(raw.frame) ? raw.frame : d.frame,
    demo: {
      conveyorVelocity: isNum(demo.conveyorVelocity, (n) => n >= 0) ? demo.conveyorVelocity : d.demo.conveyorVelocity,
      velocity: isNum(demo.velocity, positive) ? demo.velocity : d.demo.velocity,
      acceleration: isNum(demo.acceleration, positive) ? demo.acceleration : d.demo.acceleration,
      pick: isPoint(demo.pick) ? demo.pick : [...d.demo.pick],
      place: isPoint(demo.place) ? demo.place : [...d.demo.place],
      approach: isNum(demo.approach, (n) => n >= 0) ? demo.approach : d.demo.approach,
    },
  };
}

function useRobotSettings(group: string): [RobotTestRunSettings, (patch: Partial<RobotTestRunSettings>) => void] {
  const project = useLive((s) => s.controller?.project ?? null);
  const key = robotSettingsKey(project, group);
  const [settings, setSettings] = useState<RobotTestRunSettings>(() => loadRobotSettings(key));
  useEffect(() => setSettings(loadRobotSettings(key)), [key]);
  const update = (patch: Partial<RobotTestRunSettings>) => {
    setSettings((s) => {
      const next = { ...s, ...patch };
      try {
        window.localStorage.setItem(key, JSON.stringify(next));
      } catch {
        /* storage full or disabled: the settings hold for this page */
      }
      return next;
    });
  };
  return [settings, update];
}

/** A number input that keeps what is typed and commits only valid numbers (the stored value stays valid). */
function SettingNumber(props: {
  label: string;
  unit?: string;
  value: number;
  valid: (n: number) => boolean;
  onCommit: (n: number) => void;
  testId: string;
  w?: number;
}) {
  const { label, unit, value, valid, onCommit, testId, w } = props;
  const [draft, setDraft] = useState<NumValue>(value);
  useEffect(() => setDraft((d) => (num(d) === value ? d : value)), [value]);
  const n = num(draft);
  return (
    <NumberInput size="xs" label={label} value={draft} w={w ?? 100} data-testid={testId}
      error={n === null || !valid(n) ? " " : undefined}
      rightSection={unit ? <Text size="10px" c="dimmed">{unit}</Text> : undefined}
      rightSectionWidth={unit ? 44 : undefined}
      onChange={(v) => {
        setDraft(v);
        const x = num(v);
        if (x !== null && valid(x)) onCommit(x);
      }} />
  );
}

// ------------------------------------------------------------------ read-out

function JogReadout({ id, frameLabel }: { id: number | null; frameLabel: string }) {
  const fb = useFb(id);
  if (!fb) return null;
  const o = fb.outputs;
  const p = Array.isArray(o.CommandPosition) ? (o.CommandPosition as number[]) : null;
  return (
    <Stack gap={2} data-testid="robot-jog-status">
      <Group gap={8} wrap="nowrap">
        <Text size="xs" c={o.Active === true ? "blue" : "dimmed"} fw={o.Active === true ? 600 : 400}>
          {o.Active === true ? `moving ${Number(o.CommandVelocity ?? 0).toFixed(1)} mm/s` : "idle"}
        </Text>
        {o.AtBoundary === true && (
          <Text size="xs" c="orange" fw={600} data-testid="robot-jog-boundary">
            at the workspace boundary
          </Text>
        )}
      </Group>
      {p && o.Busy === true && (
        <Text size="xs" ff="monospace" c="dimmed" data-testid="robot-jog-cmd">
          cmd ({frameLabel}) {p.map((v) => v.toFixed(2)).join(", ")} mm
        </Text>
      )}
      <ErrorCode code={typeof o.WarningID === "string" ? o.WarningID : "0000"} testId="robot-jog-warning" />
      <ErrorCode code={typeof o.ErrorID === "string" ? o.ErrorID : "0000"} testId="robot-jog-error" />
    </Stack>
  );
}

// ------------------------------------------------------------------ demo settings

function PointInputs({ label, value, onCommit, testId }: {
  label: string;
  value: number[];
  onCommit: (p: number[]) => void;
  testId: string;
}) {
  return (
    <Group gap={4} wrap="nowrap" align="flex-end">
      {["X", "Y", "Z"].map((n, k) => (
        <SettingNumber key={n} label={k === 0 ? `${label} ${n}` : n} value={value[k]} valid={() => true} w={84}
          testId={`${testId}-${k}`} onCommit={(x) => onCommit(value.map((v, j) => (j === k ? x : v)))} />
      ))}
    </Group>
  );
}

function DemoSettingsForm({ demo, onChange }: { demo: DemoSettings; onChange: (d: DemoSettings) => void }) {
  const set = (patch: Partial<DemoSettings>) => onChange({ ...demo, ...patch });
  return (
    <Stack gap={4} data-testid="robot-demo-settings">
      <Group gap={4} wrap="nowrap">
        <SettingNumber label="Robot speed" unit="mm/s" value={demo.velocity} valid={positive} w={100}
          testId="robot-demo-speed" onCommit={(velocity) => set({ velocity })} />
        <SettingNumber label="Acceleration" unit="mm/s²" value={demo.acceleration} valid={positive} w={110}
          testId="robot-demo-acc" onCommit={(acceleration) => set({ acceleration })} />
      </Group>
      <Group gap={4} wrap="nowrap">
        <SettingNumber label="Conveyor" unit="mm/s" value={demo.conveyorVelocity} valid={(n) => n >= 0} w={100}
          testId="robot-demo-conveyor" onCommit={(conveyorVelocity) => set({ conveyorVelocity })} />
        <SettingNumber label="Approach height" unit="mm" value={demo.approach} valid={(n) => n >= 0} w={110}
          testId="robot-demo-approach" onCommit={(approach) => set({ approach })} />
      </Group>
      <PointInputs label="Pick" value={demo.pick} testId="robot-demo-pick" onCommit={(pick) => set({ pick })} />
      <PointInputs label="Place" value={demo.place} testId="robot-demo-place" onCommit={(place) => set({ place })} />
      <Group gap={4}>
        <Button size="compact-xs" variant="subtle" data-testid="robot-demo-defaults"
          onClick={() => onChange({ ...ROBOT_SETTINGS_DEFAULTS.demo, pick: [...DEMO_DEFAULTS.pick],
            place: [...DEMO_DEFAULTS.place] })}>
          Defaults
        </Button>
        <Text size="xs" c="dimmed">
          MCS, mm · kept in this browser
        </Text>
      </Group>
    </Stack>
  );
}

// ------------------------------------------------------------------ the panel

/**
 * Cartesian jog of a Delta3 TCP (MC_RobotJog, an MC Studio extension): hold ±X/±Y/±Z, or step (inching) by a
 * distance, along the axes of the MCS or of a user coordinate system defined with MC_DefineCoordSystem; a dead-man
 * lease stops the robot when the browser goes away. Plus the way into the workspace (ready pose) and the
 * pick-and-place demo. The settings are kept in the browser per project and group (D93).
 */
export function RobotJogPanel({ group, coordSystems }: { group: GroupInfo; coordSystems?: CoordSystems }) {
  const cmds = useGroupCommands(group.name);
  const [settings, update] = useRobotSettings(group.name);
  const [readyBusy, setReadyBusy] = useState(false);
  const [demoOpen, setDemoOpen] = useState(false);
  // the 3D tab hands the UCS in (it polls /viz/robots anyway); the group tab polls them itself, once a second
  const polled = useRobots(coordSystems === undefined, 1000);
  const systems: CoordSystems = coordSystems
    ?? polled.data?.robots.find((r) => r.group === group.name)?.coord_systems ?? [];
  const demo = cmds.demo !== null;

  const defined = useMemo(() => new Set(systems.map((c) => c.csid)), [systems]);
  const wantedCsid = settings.frame.startsWith("ucs:") ? Number(settings.frame.slice(4)) : null;
  // a UCS not defined now (they are lost on a restart, D83) is not jogged in: that would be 570B; the MCS instead
  const csid = wantedCsid !== null && defined.has(wantedCsid) ? wantedCsid : null;
  const frameLabel = csid === null ? "MCS" : `UCS ${csid}`;
  const frameData = [
    { value: "mcs", label: "MCS" },
    ...systems.map((c) => ({ value: `ucs:${c.csid}`, label: `UCS ${c.csid}` })),
    ...(wantedCsid !== null && csid === null ? [{ value: settings.frame, label: `UCS ${wantedCsid} (not defined)` }] : []),
  ];
  const pose = csid === null ? null : systems.find((c) => c.csid === csid)?.pose ?? null;

  const jogSettings = () => ({
    velocity: settings.velocity,
    acceleration: settings.acceleration,
    coordSystem: csid === null ? 1 : 3,
    csid: csid ?? 0,
  });
  const press = (dir: string) => {
    if (settings.mode === "step") {
      void robotJogStep(group.name, dir, { ...jogSettings(), distance: settings.step });
    } else {
      robotJogPress(group.name, dir, jogSettings());
    }
  };
  const release = () => {
    if (settings.mode === "hold") robotJogRelease(group.name);
  };
  const btn = (dir: string) => {
    const testId = `robot-jog-${dir[0] === "+" ? "plus" : "minus"}-${dir[1].toLowerCase()}`;
    return settings.mode === "hold" ? (
      <HoldButton key={dir} testId={testId} label={`Jog ${dir} of the ${frameLabel} (hold)`} held={cmds.jogHeld === dir}
        disabled={demo} onPress={() => press(dir)} onRelease={release}>
        {dir}
      </HoldButton>
    ) : (
      <Button key={dir} className="jog-button" data-testid={testId} aria-label={`Step ${dir} of the ${frameLabel}`}
        variant={cmds.jogHeld === dir ? "filled" : "light"} data-held={cmds.jogHeld === dir ? "true" : "false"}
        disabled={demo || (cmds.jogHeld !== null && cmds.jogHeld !== dir)} miw={84} onClick={() => press(dir)}>
        {dir} {settings.step} mm
      </Button>
    );
  };

  return (
    <Stack gap={8} data-testid={`robot-jog-${group.name}`}>
      <Group gap={6} align="flex-end" wrap="nowrap">
        <Select size="xs" label="Frame" w={150} allowDeselect={false} value={settings.frame} data={frameData}
          onChange={(v) => v && update({ frame: v })} data-testid="robot-jog-frame" comboboxProps={{ withinPortal: true }} />
        <SegmentedControl size="xs" value={settings.mode} onChange={(v) => update({ mode: v === "step" ? "step" : "hold" })}
          data={[{ value: "hold", label: "Hold" }, { value: "step", label: "Step" }]} data-testid="robot-jog-mode" />
      </Group>
      <Group gap={6} align="flex-end" wrap="nowrap">
        <SettingNumber label="Speed" unit="mm/s" value={settings.velocity} valid={positive} w={96}
          testId="robot-jog-speed" onCommit={(velocity) => update({ velocity })} />
        <SettingNumber label="Acceleration" unit="mm/s²" value={settings.acceleration} valid={(n) => n >= 0} w={108}
          testId="robot-jog-acc" onCommit={(acceleration) => update({ acceleration })} />
        {settings.mode === "step" && (
          <SettingNumber label="Step" unit="mm" value={settings.step} valid={positive} w={84}
            testId="robot-jog-step" onCommit={(step) => update({ step })} />
        )}
      </Group>
      <Text size="xs" c={wantedCsid !== null && csid === null ? "orange" : "dimmed"} data-testid="robot-jog-frame-note">
        {wantedCsid !== null && csid === null
          ? `UCS ${wantedCsid} is not defined (MC_DefineCoordSystem, lost on a restart): jogging along the MCS`
          : pose
            ? `±X/±Y/±Z of UCS ${csid}: origin (${pose.slice(0, 3).map((v) => v.toFixed(1)).join(", ")}) mm, `
              + `Rx ${pose[3].toFixed(1)}° Ry ${pose[4].toFixed(1)}° Rz ${pose[5].toFixed(1)}°`
            : "±X/±Y/±Z of the MCS"}
      </Text>
      <SimpleGrid cols={3} spacing={4} verticalSpacing={4}>
        {btn("+X")}
        {btn("+Y")}
        {btn("+Z")}
        {btn("-X")}
        {btn("-Y")}
        {btn("-Z")}
      </SimpleGrid>
      <JogReadout id={cmds.jogId} frameLabel={frameLabel} />
      <Group gap={4} wrap="wrap">
        <Tooltip label="Group disabled, MC_MoveAbsolute of the arms to the inverse kinematics of (0, 0, −300) mm, group enabled again"
          openDelay={400} multiline w={240}>
          <Button size="compact-xs" variant="default" leftSection={<IconTarget size={13} />} loading={readyBusy}
            disabled={demo} data-testid={`robot-ready-${group.name}`}
            onClick={async () => {
              setReadyBusy(true);
              await moveToPose(group.name, READY_POINT);
              setReadyBusy(false);
            }}>
            Ready pose
          </Button>
        </Tooltip>
        {!demo ? (
          <Tooltip
            label={`Pick and place between (${settings.demo.pick.join(", ")}) and (${settings.demo.place.join(", ")}) mm with the conveyor running`}
            openDelay={400} multiline w={240}>
            <Button size="compact-xs" color="teal" leftSection={<IconPlayerPlay size={13} />}
              data-testid={`robot-demo-run-${group.name}`}
              onClick={() => {
                const d = settings.demo;
                if (d.pick.some((v) => !Number.isFinite(v)) || d.place.some((v) => !Number.isFinite(v))) {
                  notifyError("Pick-and-place demo", new Error("enter the pick and place points"));
                  return;
                }
                void runDemo(group.name, group.axes, { ...DEMO_DEFAULTS, ...d });
              }}>
              Run demo sequence
            </Button>
          </Tooltip>
        ) : (
          <Button size="compact-xs" color="red" leftSection={<IconPlayerStop size={13} />}
            data-testid={`robot-demo-stop-${group.name}`} onClick={() => stopDemo(group.name)}>
            Stop demo
          </Button>
        )}
        <Button size="compact-xs" variant="subtle" leftSection={<IconAdjustments size={13} />}
          data-testid="robot-demo-settings-toggle" onClick={() => setDemoOpen((o) => !o)}>
          Demo settings
        </Button>
      </Group>
      <Collapse in={demoOpen}>
        <DemoSettingsForm demo={settings.demo} onChange={(d) => update({ demo: d })} />
      </Collapse>
      {demo && (
        <Text size="xs" c="teal" data-testid={`robot-demo-status-${group.name}`}>
          Demo: {cmds.demo} · {cmds.demoCycles} cycles
        </Text>
      )}
    </Stack>
  );
}
