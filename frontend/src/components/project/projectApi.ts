/**
 * Project operations of the studio (docs/project-format.md): save, save as, revert, open, new from a template, and
 * how their refusals are split into "this field is wrong" and "the project on disk has these problems".
 */
import { ApiError, api, formatLoc, unwrap } from "../../api/client";
import type { components } from "../../api/schema";

export type ProjectInfo = components["schemas"]["ProjectInfo"];
export type ProjectTemplate = components["schemas"]["ProjectTemplateOut"];

/** A problem of a project on disk (`path` in the file, e.g. `axes[1].parameters.Operation.MaxVel`). */
export interface FileProblem {
  path: string | null;
  msg: string;
  code: string | null;
}

/** A refused operation, sorted for display: problems of request fields (`name`, `template`) and of the files. */
export interface Refusal {
  status: number | null;
  /** Field of the request → message (shown on that field). */
  fields: Record<string, string>;
  /** Summary line (e.g. "…/project.json is not valid JSON: … line 1, column 54"). */
  message: string;
  /** One entry per problem in the files, with its JSON path. */
  problems: FileProblem[];
}

interface DetailItem {
  loc?: (string | number)[];
  msg?: string;
  type?: string;
  path?: string | null;
  code?: string | null;
}

export function refusalOf(err: unknown): Refusal {
  if (!(err instanceof ApiError)) {
    return { status: null, fields: {}, message: err instanceof Error ? err.message : String(err), problems: [] };
  }
  const out: Refusal = { status: err.status, fields: {}, message: "", problems: [] };
  if (!Array.isArray(err.detail)) {
    out.message = err.message;
    return out;
  }
  for (const d of err.detail as DetailItem[]) {
    const msg = d.msg ?? "invalid";
    if (d.type === "project_file_error") {
      if (d.path === undefined) out.message = out.message ? `${out.message}\n${msg}` : msg;
      else out.problems.push({ path: d.path ?? null, msg: msg.replace(`${d.path}: `, ""), code: d.code ?? null });
    } else {
      const field = formatLoc(d.loc ?? []);
      out.fields[field || "request"] = msg.replace(/^Value error, /, "");
    }
  }
  if (!out.message && Object.keys(out.fields).length === 0) out.message = err.message;
  return out;
}

export async function saveProject(): Promise<string> {
  const out = await unwrap(api.POST("/api/v1/project/save"));
  return out.path;
}

export async function saveProjectAs(name: string, overwrite: boolean): Promise<string> {
  const out = await unwrap(api.POST("/api/v1/project/save-as", { body: { name, overwrite } }));
  return out.path;
}

export async function revertProject(): Promise<string> {
  const p = await unwrap(api.POST("/api/v1/project/revert"));
  return p.name;
}

export async function openProject(name: string): Promise<string> {
  const p = await unwrap(api.POST("/api/v1/projects/open", { body: { name } }));
  return p.name;
}

export async function newProject(name: string, template: string): Promise<string> {
  const p = await unwrap(api.POST("/api/v1/projects/new", { body: { name, template } }));
  return p.name;
}

export function listProjects(): Promise<ProjectInfo[]> {
  return unwrap(api.GET("/api/v1/projects"));
}

export function listTemplates(): Promise<ProjectTemplate[]> {
  return unwrap(api.GET("/api/v1/project-templates"));
}

/** Where the studio serves the JSON Schema of project.json (for `$schema` in an editor). */
export function schemaUrl(): string {
  return `${window.location.origin}/api/v1/project/schema`;
}
