import { Button, Divider, Group, Text, Tooltip } from "@mantine/core";
import { IconArrowLeft, IconArrowRight, IconChevronLeft, IconChevronRight } from "@tabler/icons-react";
import { useState } from "react";
import { useAxisCommands, useFb } from "../../hooks/useLive";
import type { AxisUnits } from "../../lib/format";
import { notifyError } from "../../lib/notify";
import { type JogDir, issue, jogPress, jogRelease } from "../../store/commands";
import { axisForms, num, setFormField, useAxisForms } from "../../store/forms";
import { Led } from "../common/Led";
import { NumField } from "../common/NumField";
import { Panel } from "../common/Panel";
import { HoldButton } from "./HoldButton";

function JogStatus({ id }: { id: number | null }) {
  const fb = useFb(id);
  if (!fb) return null;
  const o = fb.outputs;
  return (
    <Group gap={10} wrap="nowrap" data-testid="jog-status">
      <Led label="Busy" on={o.Busy === true} color="blue" />
      <Led label="Error" on={o.Error === true} color="red" />
      {o.Error === true && (
        <Text size="xs" c="red" className="num">
          {String(o.ErrorID)}
        </Text>
      )}
    </Group>
  );
}

/** Inching: one MC_MoveRelative of ± the step per click, at the jog velocity and acceleration. */
function Inching({ axis, unit }: { axis: string; unit: string }) {
  const f = useAxisForms(axis);
  const [busy, setBusy] = useState<JogDir | null>(null);

  const inch = async (dir: JogDir) => {
    const forms = axisForms(axis);
    const d = num(forms.inchDistance);
    const v = num(forms.jogVelocity);
    const a = num(forms.jogAcceleration);
    if (d === null || v === null || a === null) {
      notifyError("Inching", new Error("enter numbers for the step, the jog velocity and the acceleration"));
      return;
    }
    setBusy(dir);
    await issue(axis, "MC_MoveRelative", {
      Distance: dir === "plus" ? Math.abs(d) : -Math.abs(d),
      Velocity: v,
      Acceleration: a,
      Deceleration: a,
      Jerk: 0,
    });
    setBusy(null);
  };

  return (
    <Group gap={8} align="flex-end" wrap="nowrap">
      <NumField label="Inching step" unit={unit} value={f.inchDistance} testId="inch-distance"
        onChange={(v) => setFormField(axis, "inchDistance", v)} w={130} />
      <Text size="11px" c="dimmed" pb={6} style={{ flex: 1, minWidth: 0 }} lineClamp={2}>
        One MC_MoveRelative per click, at the jog velocity and acceleration.
      </Text>
      <Group gap={6} wrap="nowrap">
        <Tooltip label="MC_MoveRelative by −step">
          <Button variant="default" data-testid="inch-minus" leftSection={<IconChevronLeft size={14} />} miw={84}
            loading={busy === "minus"} onClick={() => void inch("minus")}>
            Inch −
          </Button>
        </Tooltip>
        <Tooltip label="MC_MoveRelative by +step">
          <Button variant="default" data-testid="inch-plus" rightSection={<IconChevronRight size={14} />} miw={84}
            loading={busy === "plus"} onClick={() => void inch("plus")}>
            Inch +
          </Button>
        </Tooltip>
      </Group>
    </Group>
  );
}

/** Start a hold-to-jog with the jog velocity and acceleration of the form (buttons and the ← / → keys). */
export function startJog(axis: string, dir: JogDir): void {
  const forms = axisForms(axis);
  const v = num(forms.jogVelocity);
  const a = num(forms.jogAcceleration);
  if (v === null || a === null) {
    notifyError("Jog", new Error("enter numbers for the jog velocity and acceleration"));
    return;
  }
  jogPress(axis, dir, v, a);
}

/** MC_MoveJog with a dead-man lease: hold − / + to jog; inching steps with MC_MoveRelative. */
export function JogPanel({ axis, units }: { axis: string; units: AxisUnits }) {
  const f = useAxisForms(axis);
  const cmds = useAxisCommands(axis);

  const press = (dir: JogDir) => startJog(axis, dir);
  const release = () => jogRelease(axis);

  return (
    <Panel
      title="Jog (MC_MoveJog, hold to move; ← / → keys) and inching"
      right={<JogStatus id={cmds.jogId} />}
      testId="jog-panel"
    >
      <Group gap={8} align="flex-end" wrap="nowrap">
        <NumField label="Velocity" unit={units.vel} value={f.jogVelocity} testId="jog-velocity"
          onChange={(v) => setFormField(axis, "jogVelocity", v)} w={130} />
        <NumField label="Acc./deceleration" unit={units.acc} value={f.jogAcceleration} testId="jog-acceleration"
          onChange={(v) => setFormField(axis, "jogAcceleration", v)} w={140} />
        <Group gap={6} wrap="nowrap" ml="auto">
          <HoldButton testId="jog-minus" label="Jog in negative direction (hold)" held={cmds.jogHeld === "minus"}
            onPress={() => press("minus")} onRelease={release} leftSection={<IconArrowLeft size={14} />}>
            Jog −
          </HoldButton>
          <HoldButton testId="jog-plus" label="Jog in positive direction (hold)" held={cmds.jogHeld === "plus"}
            onPress={() => press("plus")} onRelease={release} leftSection={<IconArrowRight size={14} />}>
            Jog +
          </HoldButton>
        </Group>
      </Group>
      <Divider my={6} color="gray.2" />
      <Inching axis={axis} unit={units.pos} />
    </Panel>
  );
}
