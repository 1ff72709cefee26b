/**
 * The `_sHOMING_REF` edited in the test run's "home with parameters" section, per axis (MC_HomeWithParameter's
 * HomingParameter). It is prefilled from the axis' homing settings, member by member.
 */
import type { AxisConfig } from "../api/types";
import { type FieldSpec, type FieldValue, toFieldValue } from "../lib/schema";
import { createStore } from "./createStore";

/** `_sHOMING_REF` member ← `_sAXIS_HOMING_SETTINGS` member (HomingSettings in the schema). */
export const HOMING_REF_MEMBERS: readonly (readonly [string, string])[] = [
  ["HomingMode", "Mode"],
  ["HomeInput", "HomeInputSignal"],
  ["StartDir", "StartDirection"],
  ["HomeDir", "HomeInputDetectionDirection"],
  ["PosiLmtMode", "PosiLimitInputMode"],
  ["NegaLmtMode", "NegaLimitInputMode"],
  ["Vel", "Vel"],
  ["ApproachVel", "ApproachVel"],
  ["Acc", "Acc"],
  ["Dec", "Dec"],
  ["Jerk", "Jerk"],
  ["Mask", "HomeInputMaskDistance"],
  ["Offset", "HomeOffset"],
  ["PushTime", "HoldingTime"],
  ["Compensation", "CompensationVal"],
  ["CompensationVel", "CompensationVel"],
];

export type HomingRef = Readonly<Record<string, FieldValue>>;

export const homingRefStore = createStore<Readonly<Record<string, HomingRef>>>({});

/** The homing settings of an axis as a `_sHOMING_REF` (specs: HomingSettings fields by member name). */
export function homingRefFromConfig(config: AxisConfig, specs: ReadonlyMap<string, FieldSpec>): HomingRef {
  const homing = (config.parameters?.Homing ?? {}) as Record<string, unknown>;
  const out: Record<string, FieldValue> = {};
  for (const [ref, setting] of HOMING_REF_MEMBERS) {
    const spec = specs.get(setting);
    out[ref] = spec ? toFieldValue(spec, homing[setting]) : ((homing[setting] as FieldValue | undefined) ?? null);
  }
  return out;
}

export function setHomingRef(axis: string, values: HomingRef): void {
  homingRefStore.set((s) => ({ ...s, [axis]: values }));
}

export function setHomingRefMember(axis: string, member: string, value: FieldValue): void {
  homingRefStore.set((s) => ({ ...s, [axis]: { ...(s[axis] ?? {}), [member]: value } }));
}
