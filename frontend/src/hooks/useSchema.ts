/** Form specs derived from the project's JSON Schema and the instruction catalogue (computed once per load). */
import { useMemo } from "react";
import type { VarInfo } from "../api/types";
import { type FieldSpec, type SectionSpec, axisSections, defFields } from "../lib/schema";
import { fbTypesStore, projectSchemaStore } from "../store/catalog";
import { useStore } from "../store/createStore";

export function useAxisSections(): { status: "loading" | "ready" | "error"; sections: SectionSpec[]; error?: string } {
  const st = useStore(projectSchemaStore, (s) => s);
  const sections = useMemo(() => (st.data ? axisSections(st.data) : []), [st.data]);
  return { status: st.status, sections, error: st.error };
}

/** Field specs of one `$defs` entry by member name (empty while the schema loads). */
export function useDefFields(def: string): Map<string, FieldSpec> {
  const schema = useStore(projectSchemaStore, (s) => s.data);
  return useMemo(() => (schema ? defFields(schema, def) : new Map<string, FieldSpec>()), [schema, def]);
}

/** Which integer values an input's `valid` text allows: "0–5", "0, 1", "1, 2, 3"; null = no restriction. */
function allowedValues(valid: string | null | undefined): Set<number> | null {
  if (!valid) return null;
  const range = /^\s*(\d+)\s*[–-]\s*(\d+)\s*$/.exec(valid);
  if (range) {
    const out = new Set<number>();
    for (let i = Number(range[1]); i <= Number(range[2]); i++) out.add(i);
    return out;
  }
  if (/^\s*\d+(\s*,\s*\d+)*\s*$/.test(valid)) return new Set(valid.split(",").map((x) => Number(x.trim())));
  return null;
}

export interface Enumerator {
  name: string;
  value: number;
}

/** The enumerators an instruction input accepts (fb-types: `enumerators` restricted by `valid`). */
export function useInputEnumerators(type: string, input: string): Enumerator[] {
  const types = useStore(fbTypesStore, (s) => s.data);
  return useMemo(() => {
    const v: VarInfo | undefined = types.get(type)?.inputs.find((i) => i.name === input);
    if (!v?.enumerators) return [];
    const allowed = allowedValues(v.valid);
    return v.enumerators
      .map((e) => ({ name: String(e.name), value: Number(e.value) }))
      .filter((e) => allowed === null || allowed.has(e.value));
  }, [types, type, input]);
}
