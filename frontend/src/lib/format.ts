import type { AxisStatusVar, EventLevel } from "../api/types";

const UNIT_LABELS: Record<string, string> = {
  _mcPls: "pulse",
  _mcMm: "mm",
  _mcUm: "µm",
  _mcNm: "nm",
  _mcDeg: "°",
  _mcInch: "inch",
};

/** `_mcMm` → `mm` (the unit display setting of an axis). */
export function unitLabel(unitDisplay: string | undefined | null): string {
  if (!unitDisplay) return "unit";
  return UNIT_LABELS[unitDisplay] ?? unitDisplay.replace(/^_mc/, "");
}

/** Units of position, velocity, acceleration and jerk for a unit display setting. */
export interface AxisUnits {
  pos: string;
  vel: string;
  acc: string;
  jerk: string;
}

export function axisUnits(unitDisplay: string | undefined | null): AxisUnits {
  const u = unitLabel(unitDisplay);
  return { pos: u, vel: `${u}/s`, acc: `${u}/s²`, jerk: `${u}/s³` };
}

/** `_mcServo` → `Servo`, `_mcVirServo` → `Virtual servo`. */
export function axisTypeLabel(type: string): string {
  switch (type) {
    case "_mcServo":
      return "Servo";
    case "_mcEncdr":
      return "Encoder";
    case "_mcVirServo":
      return "Virtual servo";
    case "_mcVirEncdr":
      return "Virtual encoder";
    default:
      return type.replace(/^_mc/, "");
  }
}

export const STATUS_FLAGS = [
  "Disabled",
  "Standstill",
  "Discrete",
  "Continuous",
  "Synchronized",
  "Homing",
  "Stopping",
  "ErrorStop",
  "Coordinated",
] as const satisfies readonly (keyof AxisStatusVar)[];

export type AxisState = (typeof STATUS_FLAGS)[number];

/** The axis state: the one Status flag that is TRUE (besides Ready), as the backend's axis summary does. */
export function axisState(status: AxisStatusVar): AxisState | "Unknown" {
  for (const f of STATUS_FLAGS) if (status[f]) return f;
  return "Unknown";
}

/** Mantine colour of an axis state badge. */
export function stateColor(state: string): string {
  switch (state) {
    case "Disabled":
      return "gray";
    case "Standstill":
      return "teal";
    case "Discrete":
    case "Continuous":
    case "Synchronized":
    case "Coordinated":
      return "blue";
    case "Homing":
      return "violet";
    case "Stopping":
      return "orange";
    case "ErrorStop":
      return "red";
    default:
      return "gray";
  }
}

export function levelColor(level: EventLevel | string): string {
  switch (level) {
    case "major fault":
      return "red.9";
    case "partial fault":
      return "red";
    case "minor fault":
      return "orange";
    case "observation":
      return "yellow";
    case "information":
      return "blue";
    default:
      return "gray";
  }
}

/** Fixed decimals; `-0.000` is shown as `0.000`. */
export function fixed(v: number | null | undefined, decimals = 3): string {
  if (v === null || v === undefined || !Number.isFinite(v)) return "—";
  const s = v.toFixed(decimals);
  return /^-0\.?0*$/.test(s) ? s.slice(1) : s;
}

export function isFault(level: string): boolean {
  return level === "major fault" || level === "partial fault" || level === "minor fault";
}
