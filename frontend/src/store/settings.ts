/**
 * The axis settings editor: one draft per axis with an open (or recently open) settings tab, kept outside React so
 * that it survives switching tabs and so that the tab title can show unsaved changes.
 *
 * Values are flat by field key (`Operation.MaxVel`, `drive.EncoderType`, `sensors.PositiveLimit`; see lib/schema.ts).
 * Apply sends the whole edited AxisConfig with PUT /api/v1/axes/{name}/config: the backend validates it like the
 * whole project (422 with `detail[].path` / `code`, e.g. `axes[1].parameters.Operation.MaxJogVel`, `573B/1102`) and
 * restarts the controller at cycle 0 — refused with 409 while an axis moves.
 */
import { ApiError, api, formatLoc, unwrap } from "../api/client";
import type { AxisConfig, AxisConfigInput } from "../api/types";
import { notifyOk } from "../lib/notify";
import { type FieldValue, type SectionSpec, fromFieldValue, sameValue, toFieldValue } from "../lib/schema";
import { putAxisConfig } from "./axisConfig";
import { createStore } from "./createStore";

export interface SettingsIssue {
  /** The field it concerns (`Operation.MaxJogVel`), when one does. */
  key: string | null;
  /** The section it concerns (`sensors` for a check across its fields), when known. */
  group: string | null;
  /** Where the API located it, e.g. `axes[1].parameters.Operation.MaxJogVel`. */
  path: string;
  msg: string;
  /** The controller's error code, e.g. `573B/1102` (error 573B with its ErrorParameterCode). */
  code: string | null;
}

export interface SettingsEditor {
  /** The settings the draft started from (as loaded or as applied); the PUT body is built from it. */
  config: AxisConfig;
  base: Readonly<Record<string, FieldValue>>;
  draft: Readonly<Record<string, FieldValue>>;
  dirty: boolean;
  /** Problems the API reported for the last Apply. */
  issues: SettingsIssue[];
  /** Apply was refused as a whole (409: an axis moves; network). */
  refusal: { status: number | null; message: string } | null;
  applying: boolean;
}

export const settingsStore = createStore<Readonly<Record<string, SettingsEditor>>>({});

function patch(axis: string, p: Partial<SettingsEditor> | ((ed: SettingsEditor) => Partial<SettingsEditor>)): void {
  settingsStore.set((s) => {
    const ed = s[axis];
    if (!ed) return s;
    return { ...s, [axis]: { ...ed, ...(typeof p === "function" ? p(ed) : p) } };
  });
}

function getPath(obj: unknown, path: readonly string[]): Record<string, unknown> | undefined {
  let cur: unknown = obj;
  for (const p of path) {
    if (typeof cur !== "object" || cur === null) return undefined;
    cur = (cur as Record<string, unknown>)[p];
  }
  return typeof cur === "object" && cur !== null ? (cur as Record<string, unknown>) : undefined;
}

/** The form values of a config. */
export function flatten(config: AxisConfig, sections: readonly SectionSpec[]): Record<string, FieldValue> {
  const out: Record<string, FieldValue> = {};
  for (const sec of sections) {
    const group = getPath(config, sec.path);
    for (const f of sec.fields) out[f.key] = toFieldValue(f, group?.[f.member]);
  }
  return out;
}

function isDirty(draft: Readonly<Record<string, FieldValue>>, base: Readonly<Record<string, FieldValue>>): boolean {
  return Object.keys(draft).some((k) => !sameValue(draft[k], base[k] ?? null));
}

/** The whole config with the draft's values. */
function buildBody(config: AxisConfig, draft: Readonly<Record<string, FieldValue>>, sections: readonly SectionSpec[]) {
  const body = structuredClone(config) as unknown as Record<string, unknown>;
  for (const sec of sections) {
    let obj: Record<string, unknown> = body;
    for (const p of sec.path) {
      const next = obj[p];
      if (typeof next !== "object" || next === null) obj[p] = {};
      obj = obj[p] as Record<string, unknown>;
    }
    for (const f of sec.fields) if (f.key in draft) obj[f.member] = fromFieldValue(f, draft[f.key]);
  }
  return body;
}

function fresh(config: AxisConfig, sections: readonly SectionSpec[]): SettingsEditor {
  const base = flatten(config, sections);
  return { config, base, draft: base, dirty: false, issues: [], refusal: null, applying: false };
}

/**
 * Start editing, or follow the settings the controller now has (after a restart): an unchanged draft is replaced,
 * a changed one is kept (and compared with the new settings).
 */
export function syncEditor(axis: string, config: AxisConfig, sections: readonly SectionSpec[]): void {
  settingsStore.set((s) => {
    const ed = s[axis];
    if (ed && ed.config === config) return s;
    if (!ed || !ed.dirty) return { ...s, [axis]: fresh(config, sections) };
    const base = flatten(config, sections);
    return { ...s, [axis]: { ...ed, config, base, dirty: isDirty(ed.draft, base) } };
  });
}

export function setSetting(axis: string, key: string, value: FieldValue): void {
  patch(axis, (ed) => {
    const draft = { ...ed.draft, [key]: value };
    return { draft, dirty: isDirty(draft, ed.base), issues: ed.issues.filter((i) => i.key !== key) };
  });
}

export function revertSettings(axis: string): void {
  patch(axis, (ed) => ({ draft: ed.base, dirty: false, issues: [], refusal: null }));
}

/** Forget the draft (its tab was closed). */
export function discardSettings(axis: string): void {
  settingsStore.set((s) => {
    if (!(axis in s)) return s;
    const next = { ...s };
    delete next[axis];
    return next;
  });
}

export function pruneSettings(existing: readonly string[]): void {
  settingsStore.set((s) => {
    const gone = Object.keys(s).filter((a) => !existing.includes(a));
    if (!gone.length) return s;
    const next = { ...s };
    for (const a of gone) delete next[a];
    return next;
  });
}

// ------------------------------------------------------------------ apply

interface DetailItem {
  loc?: (string | number)[];
  msg?: string;
  path?: string;
  code?: string;
}

/** `axes[1].parameters.Operation.MaxJogVel` or loc `body.sensors.PositiveLimit` → field key / section. */
export function mapIssue(d: DetailItem, sections: readonly SectionSpec[]): SettingsIssue {
  const path = typeof d.path === "string" ? d.path : formatLoc(d.loc ?? []);
  const rel = path.replace(/^axes\[\d+\]\.?/, "").replace(/^parameters\.?/, "");
  let key: string | null = null;
  let group: string | null = null;
  for (const sec of sections) {
    if (rel === sec.group || rel.startsWith(`${sec.group}.`)) group = sec.group;
    for (const f of sec.fields) {
      if (rel === f.key || rel.startsWith(`${f.key}.`) || rel.startsWith(`${f.key}[`)) key = f.key;
    }
  }
  const msg = (d.msg ?? "invalid").replace(/^Value error, /, "");
  return { key, group, path, msg, code: typeof d.code === "string" ? d.code : null };
}

/** PUT the edited settings. Returns true when they were applied (the controller restarted). */
export async function applySettings(axis: string, sections: readonly SectionSpec[]): Promise<boolean> {
  const ed = settingsStore.get()[axis];
  if (!ed || ed.applying) return false;
  patch(axis, { applying: true, refusal: null });
  const body = buildBody(ed.config, ed.draft, sections);
  try {
    const config = await unwrap(
      api.PUT("/api/v1/axes/{name}/config", {
        params: { path: { name: axis } },
        body: body as unknown as AxisConfigInput,
      }),
    );
    putAxisConfig(axis, config);
    settingsStore.set((s) => ({ ...s, [axis]: fresh(config, sections) }));
    notifyOk("Applied — the controller restarted at cycle 0; save the project to keep it", `Settings of ${axis}`);
    return true;
  } catch (err) {
    if (err instanceof ApiError && err.status === 422 && Array.isArray(err.detail)) {
      const issues = (err.detail as DetailItem[]).map((d) => mapIssue(d, sections));
      patch(axis, { applying: false, issues });
    } else {
      const status = err instanceof ApiError ? err.status : null;
      const message = err instanceof Error ? err.message : String(err);
      patch(axis, { applying: false, issues: [], refusal: { status, message } });
    }
    return false;
  }
}
