/**
 * Form fields from the project's JSON Schema (GET /api/v1/project/schema): the axis settings editor renders every
 * member of the `$defs` groups from its schema (type, enumerators, minimum/maximum, description, unit) instead of
 * hard-coding the ~60 parameters.
 */
import type { NumValue } from "../store/forms";
import { num } from "../store/forms";
import { unitLabel } from "./format";

/** The subset of JSON Schema that pydantic emits for the project document. */
export interface JsonSchema {
  type?: string | string[];
  anyOf?: JsonSchema[];
  enum?: (string | number)[];
  minimum?: number;
  maximum?: number;
  exclusiveMinimum?: number;
  exclusiveMaximum?: number;
  description?: string;
  title?: string;
  default?: unknown;
  properties?: Record<string, JsonSchema>;
  $ref?: string;
  $defs?: Record<string, JsonSchema>;
}

export type FieldKind = "number" | "integer" | "enum" | "boolean" | "string";

export interface EnumOption {
  /** Enumerator name, e.g. `_mcRevDecelerationStop` (what the form holds and sends). */
  name: string;
  /** Its integer value, when the schema lists one. */
  value: number | null;
}

export interface FieldSpec {
  /** `Operation.MaxVel`, `drive.EncoderType`, `sensors.PositiveLimit` (form keys, test ids, error mapping). */
  key: string;
  member: string;
  kind: FieldKind;
  /** null is allowed (sensors: not fitted). */
  nullable: boolean;
  options: EnumOption[];
  /** Enumeration type, e.g. `_eMC_HOMING_MODE`. */
  enumType: string | null;
  min: number | null;
  max: number | null;
  exclusiveMin: number | null;
  exclusiveMax: number | null;
  /** The description as in the schema. */
  description: string;
  /** The unit from the description's `[...]`, with `unit` standing for the axis display unit (`unit/s`, `ms`). */
  unit: string | null;
  /** The description without its unit bracket. */
  help: string;
  default: unknown;
}

export interface SectionSpec {
  /** `UnitConversion` … `Homing`, `drive`, `sensors` (first part of the field keys). */
  group: string;
  title: string;
  /** Where the group sits in an AxisConfig, e.g. `["parameters", "Operation"]`. */
  path: string[];
  /** Its `$defs` name, e.g. `OperationSettings`. */
  def: string;
  description: string;
  fields: FieldSpec[];
}

/** A field value in a form: numbers (or their text while typed), enumerator names, booleans, null (not fitted). */
export type FieldValue = NumValue | boolean | null;

// ------------------------------------------------------------------ labels and units

/** `MaxJogVel` → `Max jog vel`, `ZPhaseOffset` → `Z phase offset`, `Latch2Start` → `Latch 2 start`. */
export function splitCamel(name: string): string {
  const words = name
    .replace(/_/g, " ")
    .replace(/([a-z0-9])([A-Z])/g, "$1 $2")
    .replace(/([A-Z]+)([A-Z][a-z])/g, "$1 $2")
    .replace(/([a-zA-Z])(\d)/g, "$1 $2")
    .split(/\s+/)
    .filter(Boolean);
  return words
    .map((w, i) => (i === 0 || (w.length > 1 && w === w.toUpperCase()) ? w : w.toLowerCase()))
    .join(" ");
}

/** Unit and help text from a description such as `Maximum acceleration [unit/s²]; 0 = no limit`. */
export function parseDescription(description: string): { unit: string | null; help: string } {
  const m = /\s*\[([^\]]+)\]/.exec(description);
  if (!m) return { unit: null, help: description };
  const inner = m[1].trim();
  const unit = inner.split(/\s+of\s+/)[0].trim();
  // "[% of MaxVel]" keeps its reference in the help text; a plain unit bracket is dropped.
  const rest = inner === unit ? "" : ` (${inner})`;
  return { unit, help: (description.slice(0, m.index) + rest + description.slice(m.index + m[0].length)).trim() };
}

/** `unit/s` with the display unit `_mcMm` → `mm/s`; `ms`, `%`, `pulse/rev` stay as they are. */
export function displayUnit(unit: string | null, unitDisplay: string | null | undefined): string | null {
  if (unit === null) return null;
  return unit.replace(/\bunit\b/g, unitLabel(unitDisplay ?? "_mcPls"));
}

// ------------------------------------------------------------------ schema → fields

function resolve(root: JsonSchema, s: JsonSchema | undefined): JsonSchema | undefined {
  if (!s?.$ref) return s;
  const name = s.$ref.replace(/^#\/\$defs\//, "");
  return root.$defs?.[name];
}

function refName(s: JsonSchema | undefined): string {
  return s?.$ref ? s.$ref.replace(/^#\/\$defs\//, "") : "";
}

function hasType(s: JsonSchema, t: string): boolean {
  return s.type === t || (Array.isArray(s.type) && s.type.includes(t));
}

function finite(v: unknown): number | null {
  return typeof v === "number" && Number.isFinite(v) ? v : null;
}

export function fieldSpec(key: string, member: string, s: JsonSchema): FieldSpec {
  const { unit, help } = parseDescription(s.description ?? "");
  const spec: FieldSpec = {
    key,
    member,
    kind: "string",
    nullable: false,
    options: [],
    enumType: null,
    min: null,
    max: null,
    exclusiveMin: null,
    exclusiveMax: null,
    description: s.description ?? "",
    unit,
    help,
    default: s.default,
  };
  let body: JsonSchema = s;
  if (s.anyOf) {
    const named = s.anyOf.find((b) => b.enum && hasType(b, "string"));
    const coded = s.anyOf.find((b) => b.enum && hasType(b, "integer"));
    if (named?.enum) {
      // An IEC enumeration: names and (in the same order) their values.
      spec.kind = "enum";
      spec.enumType = s.title ?? null;
      spec.options = named.enum.map((n, i) => ({ name: String(n), value: finite(coded?.enum?.[i]) }));
      return spec;
    }
    spec.nullable = s.anyOf.some((b) => hasType(b, "null"));
    body = s.anyOf.find((b) => !hasType(b, "null")) ?? s;
  }
  if (body.enum) {
    spec.kind = "enum";
    spec.options = body.enum.map((n) => ({ name: String(n), value: null }));
    return spec;
  }
  if (hasType(body, "boolean")) spec.kind = "boolean";
  else if (hasType(body, "integer")) spec.kind = "integer";
  else if (hasType(body, "number")) spec.kind = "number";
  spec.min = finite(body.minimum);
  spec.max = finite(body.maximum);
  spec.exclusiveMin = finite(body.exclusiveMinimum);
  spec.exclusiveMax = finite(body.exclusiveMaximum);
  return spec;
}

const SECTION_TITLES: Record<string, string> = {
  UnitConversion: "Unit conversion",
  Operation: "Operation",
  OtherOperation: "Other operation",
  Limit: "Limits",
  PosCount: "Position count",
  Homing: "Homing",
  drive: "Servo drive",
  sensors: "Simulated sensors",
};

function section(root: JsonSchema, group: string, path: string[], ref: JsonSchema | undefined): SectionSpec | null {
  const def = resolve(root, ref);
  if (!def?.properties) return null;
  return {
    group,
    title: SECTION_TITLES[group] ?? splitCamel(group),
    path,
    def: refName(ref),
    description: def.description ?? "",
    fields: Object.entries(def.properties).map(([m, s]) => fieldSpec(`${group}.${m}`, m, resolve(root, s) ?? s)),
  };
}

/** The editable groups of an AxisConfig: the `_sAXIS_PARAM` groups, then the servo drive and the sensors. */
export function axisSections(root: JsonSchema): SectionSpec[] {
  const axis = root.$defs?.AxisConfig;
  const props = axis?.properties ?? {};
  const out: SectionSpec[] = [];
  const params = resolve(root, props.parameters);
  for (const [group, ref] of Object.entries(params?.properties ?? {})) {
    const s = section(root, group, ["parameters", group], ref);
    if (s) out.push(s);
  }
  for (const group of ["drive", "sensors"]) {
    const s = section(root, group, [group], props[group]);
    if (s) out.push(s);
  }
  return out;
}

/** The field specs of one `$defs` entry, keyed by member name (used for `_sHOMING_REF` from HomingSettings). */
export function defFields(root: JsonSchema, def: string): Map<string, FieldSpec> {
  const d = root.$defs?.[def];
  const out = new Map<string, FieldSpec>();
  for (const [m, s] of Object.entries(d?.properties ?? {})) out.set(m, fieldSpec(m, m, resolve(root, s) ?? s));
  return out;
}

// ------------------------------------------------------------------ values

/** A value of the document (enumerators may be given by their integer value) as a form value. */
export function toFieldValue(spec: FieldSpec, raw: unknown): FieldValue {
  if (raw === null || raw === undefined) return spec.nullable ? null : toFieldValue(spec, spec.default ?? null);
  switch (spec.kind) {
    case "enum": {
      if (typeof raw === "number") return spec.options.find((o) => o.value === raw)?.name ?? String(raw);
      return String(raw);
    }
    case "boolean":
      return raw === true;
    case "number":
    case "integer":
      return typeof raw === "number" ? raw : String(raw);
    default:
      return String(raw);
  }
}

/** A form value as sent to the API; numbers that are not (yet) numbers are sent as typed, for the API to reject. */
export function fromFieldValue(spec: FieldSpec, v: FieldValue): unknown {
  if (v === null) return null;
  if (spec.kind === "number" || spec.kind === "integer") {
    if (typeof v === "boolean") return v;
    return num(v) ?? v;
  }
  return v;
}

function fmt(n: number): string {
  return Math.abs(n) >= 1e12 ? n.toExponential().replace("e+", "e") : String(n);
}

/** Bounds worth showing (the float maximum that pydantic emits for "any positive number" is not). */
export function rangeText(spec: FieldSpec): string {
  const lo = spec.exclusiveMin !== null ? `> ${fmt(spec.exclusiveMin)}` : spec.min !== null ? fmt(spec.min) : null;
  const hi = spec.exclusiveMax !== null ? `< ${fmt(spec.exclusiveMax)}` : spec.max !== null && spec.max < 1e300 ? fmt(spec.max) : null;
  if (lo !== null && hi !== null) return spec.exclusiveMin !== null || spec.exclusiveMax !== null ? `${lo}, ${hi}` : `${lo} … ${hi}`;
  if (lo !== null) return spec.exclusiveMin !== null ? lo : `≥ ${lo}`;
  if (hi !== null) return spec.exclusiveMax !== null ? hi : `≤ ${hi}`;
  return "";
}

/** Client-side check of one value against the schema; null when it is valid. */
export function validateField(spec: FieldSpec, v: FieldValue): string | null {
  if (v === null) return spec.nullable ? null : "Required";
  switch (spec.kind) {
    case "boolean":
      return typeof v === "boolean" ? null : "Must be TRUE or FALSE";
    case "enum":
      return spec.options.some((o) => o.name === v) ? null : `Not an enumerator of ${spec.enumType ?? "the type"}`;
    case "string":
      return null;
    default:
      break;
  }
  if (typeof v === "boolean") return "Enter a number";
  const n = num(v);
  if (n === null) return "Enter a number";
  if (spec.kind === "integer" && !Number.isInteger(n)) return "Must be an integer";
  if (spec.exclusiveMin !== null && !(n > spec.exclusiveMin)) return `Must be greater than ${fmt(spec.exclusiveMin)}`;
  if (spec.min !== null && n < spec.min) return `Must be at least ${fmt(spec.min)}`;
  if (spec.exclusiveMax !== null && !(n < spec.exclusiveMax)) return `Must be less than ${fmt(spec.exclusiveMax)}`;
  if (spec.max !== null && n > spec.max) return `Must be at most ${fmt(spec.max)}`;
  return null;
}

/** Equal form values ("10" typed equals 10 loaded). */
export function sameValue(a: FieldValue, b: FieldValue): boolean {
  if (a === b) return true;
  if (typeof a === "boolean" || typeof b === "boolean" || a === null || b === null) return false;
  const x = num(a);
  return x !== null && x === num(b);
}
