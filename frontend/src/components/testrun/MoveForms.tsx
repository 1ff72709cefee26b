import { Box, Button, NativeSelect, Text } from "@mantine/core";
import { IconPlayerPlay } from "@tabler/icons-react";
import { type FormEvent, Fragment, useState } from "react";
import { useInputEnumerators } from "../../hooks/useSchema";
import type { AxisUnits } from "../../lib/format";
import { notifyError } from "../../lib/notify";
import { issue } from "../../store/commands";
import { type AxisForms, type NumValue, axisForms, num, setFormField, useAxisForms } from "../../store/forms";
import { NumField } from "../common/NumField";
import { Panel } from "../common/Panel";

type NumKey = { [K in keyof AxisForms]: AxisForms[K] extends NumValue ? K : never }[keyof AxisForms];

interface FieldDef {
  key: NumKey;
  /** Input variable of the instruction */
  input: string;
  testId: string;
  unit: keyof AxisUnits;
}

interface MoveDef {
  title: string;
  type: string;
  executeTestId: string;
  bufferKey: "absBufferMode" | "relBufferMode" | "velBufferMode";
  /** Five columns: Position/Distance (or the direction select), Velocity, Acceleration, Deceleration, Jerk. */
  fields: (FieldDef | "direction" | null)[];
  extra?: (forms: AxisForms) => Record<string, unknown>;
}

const MOVES: MoveDef[] = [
  {
    title: "Absolute",
    type: "MC_MoveAbsolute",
    executeTestId: "abs-execute",
    bufferKey: "absBufferMode",
    fields: [
      { key: "absPosition", input: "Position", testId: "abs-position", unit: "pos" },
      { key: "absVelocity", input: "Velocity", testId: "abs-velocity", unit: "vel" },
      { key: "absAcceleration", input: "Acceleration", testId: "abs-acceleration", unit: "acc" },
      { key: "absDeceleration", input: "Deceleration", testId: "abs-deceleration", unit: "acc" },
      { key: "absJerk", input: "Jerk", testId: "abs-jerk", unit: "jerk" },
    ],
  },
  {
    title: "Relative",
    type: "MC_MoveRelative",
    executeTestId: "rel-execute",
    bufferKey: "relBufferMode",
    fields: [
      { key: "relDistance", input: "Distance", testId: "rel-distance", unit: "pos" },
      { key: "relVelocity", input: "Velocity", testId: "rel-velocity", unit: "vel" },
      { key: "relAcceleration", input: "Acceleration", testId: "rel-acceleration", unit: "acc" },
      { key: "relDeceleration", input: "Deceleration", testId: "rel-deceleration", unit: "acc" },
      { key: "relJerk", input: "Jerk", testId: "rel-jerk", unit: "jerk" },
    ],
  },
  {
    title: "Velocity",
    type: "MC_MoveVelocity",
    executeTestId: "vel-execute",
    bufferKey: "velBufferMode",
    fields: [
      "direction",
      { key: "velVelocity", input: "Velocity", testId: "vel-velocity", unit: "vel" },
      { key: "velAcceleration", input: "Acceleration", testId: "vel-acceleration", unit: "acc" },
      { key: "velDeceleration", input: "Deceleration", testId: "vel-deceleration", unit: "acc" },
      null,
    ],
    extra: (forms) => ({ Direction: forms.velDirection }),
  },
];

const COLUMNS: { label: string; unit: keyof AxisUnits | null }[] = [
  { label: "Pos. / dist.", unit: "pos" },
  { label: "Velocity", unit: "vel" },
  { label: "Acc.", unit: "acc" },
  { label: "Dec.", unit: "acc" },
  { label: "Jerk", unit: "jerk" },
  { label: "BufferMode", unit: null },
];

/** `_mcBlendingPrevious` → `Blend previous` (the select is narrow; the option title has the enumerator). */
function bufferLabel(name: string): string {
  return name
    .replace(/^_mc/, "")
    .replace(/^Blending(\w)/, (_m, c: string) => `Blend ${c.toLowerCase()}`);
}

function BufferModeSelect({ axis, def }: { axis: string; def: MoveDef }) {
  const value = useAxisForms(axis)[def.bufferKey];
  const enums = useInputEnumerators(def.type, "BufferMode");
  const data = (enums.length ? enums : [{ name: "_mcAborting", value: 0 }]).map((e) => ({
    value: e.name,
    label: bufferLabel(e.name),
  }));
  return (
    <NativeSelect
      aria-label={`${def.title} move BufferMode`}
      title={value}
      data={data}
      value={value}
      onChange={(e) => setFormField(axis, def.bufferKey, e.currentTarget.value)}
      data-testid={`${def.executeTestId.split("-")[0]}-buffer-mode`}
      rightSectionWidth={20}
      styles={{ input: { paddingLeft: 8, paddingRight: 20 } }}
    />
  );
}

const DIRECTIONS = [
  { value: "_mcPositiveDirection", label: "Positive" },
  { value: "_mcNegativeDirection", label: "Negative" },
  { value: "_mcCurrentDirection", label: "Current" },
];

function MoveRow({ axis, units, def }: { axis: string; units: AxisUnits; def: MoveDef }) {
  const f = useAxisForms(axis);
  const [busy, setBusy] = useState(false);

  const submit = async (e: FormEvent) => {
    e.preventDefault();
    // Read the values at submit time (not from the render): a value typed just before clicking counts.
    const forms = axisForms(axis);
    const inputs: Record<string, unknown> = {};
    for (const fd of def.fields) {
      if (fd === null || fd === "direction") continue;
      const v = num(forms[fd.key]);
      if (v === null) {
        notifyError(def.type, new Error(`${fd.input}: enter a number`));
        return;
      }
      inputs[fd.input] = v;
    }
    Object.assign(inputs, def.extra?.(forms));
    inputs.BufferMode = forms[def.bufferKey];
    setBusy(true);
    await issue(axis, def.type, inputs);
    setBusy(false);
  };

  return (
    <form onSubmit={(e) => void submit(e)} noValidate style={{ display: "contents" }} data-testid={`${def.executeTestId.split("-")[0]}-form`}>
      <Text size="xs" fw={600} title={def.type} style={{ alignSelf: "center" }}>
        {def.title}
      </Text>
      {def.fields.map((fd, i) => {
        if (fd === null) return <Box key={i} />;
        if (fd === "direction") {
          return (
            <NativeSelect
              key={i}
              aria-label="Direction"
              data={DIRECTIONS}
              value={f.velDirection}
              onChange={(e) => setFormField(axis, "velDirection", e.currentTarget.value)}
              data-testid="vel-direction"
              rightSectionWidth={18}
              styles={{ input: { paddingLeft: 6, paddingRight: 18 } }}
            />
          );
        }
        return (
          <NumField
            key={fd.key}
            ariaLabel={`${def.title} move ${fd.input} [${units[fd.unit]}]`}
            unit=""
            value={f[fd.key]}
            testId={fd.testId}
            onChange={(v) => setFormField(axis, fd.key, v)}
          />
        );
      })}
      <BufferModeSelect axis={axis} def={def} />
      <Button type="submit" data-testid={def.executeTestId} leftSection={<IconPlayerPlay size={12} />} loading={busy}
        px={10}>
        Execute
      </Button>
    </form>
  );
}

const TORQUE_DIRECTIONS = DIRECTIONS.slice(0, 2);

/** MC_TorqueControl: the drive in cyclic synchronous torque mode with a ramp and a speed limit (Aborting). */
function TorqueRow({ axis, units }: { axis: string; units: AxisUnits }) {
  const f = useAxisForms(axis);
  const [busy, setBusy] = useState(false);
  const submit = async (e: FormEvent) => {
    e.preventDefault();
    const forms = axisForms(axis);
    const torque = num(forms.trqTorque);
    const ramp = num(forms.trqRamp);
    const velocity = num(forms.trqVelocity);
    if (torque === null || ramp === null || velocity === null) {
      notifyError("MC_TorqueControl", new Error("Torque, TorqueRamp and Velocity: enter numbers"));
      return;
    }
    setBusy(true);
    await issue(axis, "MC_TorqueControl", {
      Torque: torque,
      TorqueRamp: ramp,
      Velocity: velocity,
      Direction: forms.trqDirection,
    });
    setBusy(false);
  };
  return (
    <form onSubmit={(e) => void submit(e)} noValidate data-testid="trq-form">
      <Box
        mt={8}
        pt={8}
        style={{
          borderTop: "1px solid var(--mantine-color-gray-2)",
          display: "grid",
          gridTemplateColumns: "58px minmax(0, 1.4fr) repeat(3, minmax(0, 1fr)) auto",
          columnGap: 6,
          alignItems: "end",
        }}
      >
        <Text size="xs" fw={600} title="MC_TorqueControl" pb={8}>
          Torque
        </Text>
        <NativeSelect
          label="Direction"
          data={TORQUE_DIRECTIONS}
          value={f.trqDirection}
          onChange={(e) => setFormField(axis, "trqDirection", e.currentTarget.value)}
          data-testid="trq-direction"
          rightSectionWidth={18}
          styles={{ label: { fontSize: 11, color: "var(--mantine-color-gray-7)" }, input: { paddingLeft: 6 } }}
        />
        <NumField label="Torque" unit="%" value={f.trqTorque} testId="trq-torque"
          onChange={(v) => setFormField(axis, "trqTorque", v)} />
        <NumField label="Ramp" unit="%/s" value={f.trqRamp} testId="trq-ramp"
          onChange={(v) => setFormField(axis, "trqRamp", v)} />
        <NumField label="Speed limit" unit={units.vel} value={f.trqVelocity} testId="trq-velocity"
          onChange={(v) => setFormField(axis, "trqVelocity", v)} />
        <Button type="submit" data-testid="trq-execute" leftSection={<IconPlayerPlay size={12} />} loading={busy}
          px={10}>
          Execute
        </Button>
      </Box>
    </form>
  );
}

/**
 * Absolute, relative and velocity moves: each Execute creates a new instance with Execute TRUE, with the row's
 * BufferMode (Aborting, Buffered or a Blending mode; the options are those the instruction accepts per fb-types).
 */
export function MoveForms({ axis, units }: { axis: string; units: AxisUnits }) {
  return (
    <Panel title="Motion (MC_MoveAbsolute, MC_MoveRelative, MC_MoveVelocity, MC_TorqueControl)" testId="move-panel">
      <Box
        style={{
          display: "grid",
          gridTemplateColumns: "58px minmax(0, 1.4fr) repeat(4, minmax(0, 1fr)) 116px auto",
          columnGap: 6,
          rowGap: 6,
          alignItems: "center",
        }}
      >
        <Box />
        {COLUMNS.map((c) => (
          <Box key={c.label} style={{ minWidth: 0, lineHeight: 1.15 }}>
            <Text size="11px" c="gray.7" truncate="end" title={c.label}>
              {c.label}
            </Text>
            <Text size="10px" c="dimmed" truncate="end">
              {c.unit ? units[c.unit] : "on multi-execution"}
            </Text>
          </Box>
        ))}
        <Box />
        {MOVES.map((m) => (
          <Fragment key={m.type}>
            <MoveRow axis={axis} units={units} def={m} />
          </Fragment>
        ))}
      </Box>
      <TorqueRow axis={axis} units={units} />
    </Panel>
  );
}
