import { Button, Group, SegmentedControl, Stack, Text } from "@mantine/core";
import { IconPlayerPlay } from "@tabler/icons-react";
import { useState } from "react";
import { notifyError } from "../../lib/notify";
import type { NumValue } from "../../store/forms";
import { num } from "../../store/forms";
import { type GroupInfo, issueGroup } from "../../store/groupCommands";
import { NumField } from "../common/NumField";

const LOGICAL = ["A0", "A1", "A2", "A3"];
type Kind = "linear" | "circular";

/**
 * MC_MoveLinear (absolute or relative by MoveMode) and, for groups of two or more axes, MC_MoveCircular2D on A0/A1
 * (border point, centre or radius); one new instance per click, like the axis test run's move forms.
 */
export function GroupMoveForm({ group, unit = "mm" }: { group: GroupInfo; unit?: string }) {
  const n = group.axes.length;
  const [kind, setKind] = useState<Kind>("linear");
  const [mode, setMode] = useState<"0" | "1">("0");
  const [pos, setPos] = useState<NumValue[]>(() => [100, 100, 0, 0].slice(0, n));
  const [circMode, setCircMode] = useState<"0" | "1" | "2">("1");
  const [aux, setAux] = useState<NumValue[]>([100, 50]);
  const [end, setEnd] = useState<NumValue[]>([100, 100]);
  const [ccw, setCcw] = useState<"0" | "1">("1");
  const [vel, setVel] = useState<NumValue>(200);
  const [acc, setAcc] = useState<NumValue>(2000);
  const [busy, setBusy] = useState(false);

  const numbers = (vs: NumValue[]) => vs.map(num);
  const run = async () => {
    const v = num(vel);
    const a = num(acc);
    const p = numbers(pos);
    if (v === null || a === null || p.some((x) => x === null)) {
      notifyError("Move", new Error("enter numbers for every field"));
      return;
    }
    setBusy(true);
    const common = { Velocity: v, Acceleration: a, Deceleration: a, Jerk: 0, MoveMode: Number(mode) };
    if (kind === "linear") {
      await issueGroup(group.name, "MC_MoveLinear", { ...common, Position: p });
    } else {
      const ax = numbers(aux);
      const e = numbers(end);
      if (ax.some((x) => x === null) || e.some((x) => x === null)) {
        setBusy(false);
        notifyError("Move", new Error("enter numbers for every field"));
        return;
      }
      await issueGroup(group.name, "MC_MoveCircular2D", {
        ...common, CircAxes: [0, 1], CircMode: Number(circMode), AuxPoint: ax, EndPoint: e, PathChoice: Number(ccw),
      });
    }
    setBusy(false);
  };

  const setAt = (arr: NumValue[], set: (v: NumValue[]) => void, k: number) => (v: NumValue) => {
    const next = [...arr];
    next[k] = v;
    set(next);
  };
  const auxLabel = circMode === "0" ? "Border point" : circMode === "1" ? "Centre" : "Radius";

  return (
    <Stack gap={8} data-testid={`group-move-${group.name}`}>
      <Group gap={8} wrap="wrap">
        <SegmentedControl size="xs" value={kind} onChange={(v) => setKind(v as Kind)} data-testid="group-move-kind"
          data={[{ value: "linear", label: "MC_MoveLinear" },
            ...(n >= 2 ? [{ value: "circular", label: "MC_MoveCircular2D" }] : [])]} />
        <SegmentedControl size="xs" value={mode} onChange={(v) => setMode(v as "0" | "1")}
          data={[{ value: "0", label: "Absolute" }, { value: "1", label: "Relative" }]} />
      </Group>
      {kind === "linear" ? (
        <Group gap={6} wrap="wrap">
          {pos.map((v, k) => (
            <NumField key={k} label={`${LOGICAL[k]} ${group.axes[k]}`} unit={unit} value={v} w={120}
              testId={`group-move-pos-${k}`} onChange={setAt(pos, setPos, k)} />
          ))}
        </Group>
      ) : (
        <Stack gap={6}>
          <Group gap={8} wrap="wrap">
            <SegmentedControl size="xs" value={circMode} onChange={(v) => setCircMode(v as "0" | "1" | "2")}
              data={[{ value: "0", label: "Border point" }, { value: "1", label: "Centre" }, { value: "2", label: "Radius" }]} />
            <SegmentedControl size="xs" value={ccw} onChange={(v) => setCcw(v as "0" | "1")}
              data={[{ value: "0", label: "CW" }, { value: "1", label: "CCW" }]} />
          </Group>
          <Group gap={6} wrap="wrap">
            <NumField label={`${auxLabel} ${circMode === "2" ? "" : "X"}`} unit={unit} value={aux[0]} w={120}
              testId="group-move-aux-0" onChange={setAt(aux, setAux, 0)} />
            {circMode !== "2" && (
              <NumField label={`${auxLabel} Y`} unit={unit} value={aux[1]} w={120} testId="group-move-aux-1"
                onChange={setAt(aux, setAux, 1)} />
            )}
            <NumField label="End X" unit={unit} value={end[0]} w={120} testId="group-move-end-0"
              onChange={setAt(end, setEnd, 0)} />
            <NumField label="End Y" unit={unit} value={end[1]} w={120} testId="group-move-end-1"
              onChange={setAt(end, setEnd, 1)} />
          </Group>
        </Stack>
      )}
      <Group gap={6} align="flex-end" wrap="wrap">
        <NumField label="Velocity" unit={`${unit}/s`} value={vel} w={120} testId="group-move-velocity" onChange={setVel} />
        <NumField label="Acc./deceleration" unit={`${unit}/s²`} value={acc} w={140} testId="group-move-acceleration"
          onChange={setAcc} />
        <Button size="xs" leftSection={<IconPlayerPlay size={13} />} loading={busy} onClick={() => void run()}
          data-testid={`group-move-run-${group.name}`}>
          Execute
        </Button>
      </Group>
      <Text size="10px" c="dimmed">
        Jerk 0 (trapezoid), BufferMode _mcAborting, CoordSystem _mcACS.
      </Text>
    </Stack>
  );
}
