/**
 * Typed REST client (openapi-fetch over the generated schema) and uniform error handling.
 *
 * All URLs are relative: the backend serves the studio and the API from the same origin
 * (in development Vite proxies /api to the backend).
 */
import createClient from "openapi-fetch";
import type { paths } from "./schema";
import type { ValidationError } from "./types";

export const api = createClient<paths>({ baseUrl: "" });

/** Header naming this page as a client of the controller: who holds test-run control (backend api/control.py). */
export const CLIENT_HEADER = "X-MCStudio-Client";

function newClientId(): string {
  const bytes = new Uint8Array(12);
  crypto.getRandomValues(bytes); // (crypto.randomUUID needs a secure context; the studio may be served over http)
  return "b-" + Array.from(bytes, (b) => b.toString(16).padStart(2, "0")).join("");
}

/** This page's client id: one per page load (a reloaded or second tab is another client). */
export const CLIENT_ID = newClientId();

type StatusListener = (status: number) => void;
const statusListeners = new Set<StatusListener>();

/** Called with the status of every API response that is 401 (token needed) or 423 (another client holds control). */
export function onApiStatus(listener: StatusListener): () => void {
  statusListeners.add(listener);
  return () => statusListeners.delete(listener);
}

api.use({
  onRequest({ request }) {
    request.headers.set(CLIENT_HEADER, CLIENT_ID);
    return request;
  },
  onResponse({ response }) {
    if (response.status === 401 || response.status === 423) for (const l of [...statusListeners]) l(response.status);
    return response;
  },
});

/** An HTTP error response of the API: `{"detail": string | ValidationError[]}`. */
export class ApiError extends Error {
  readonly status: number;
  readonly detail: unknown;

  constructor(status: number, detail: unknown) {
    super(describeDetail(detail) || `HTTP ${status}`);
    this.name = "ApiError";
    this.status = status;
    this.detail = detail;
  }

  /** Field-level problems (422 and some 409 responses list them with the offending field in `loc`). */
  get issues(): { field: string; msg: string }[] {
    return issuesOf(this.detail);
  }
}

function isValidationError(x: unknown): x is ValidationError {
  return typeof x === "object" && x !== null && "msg" in x && "loc" in x && Array.isArray((x as ValidationError).loc);
}

/** `["body", "inputs", "Position"]` → `inputs.Position`; `["body", "axes", 1, "name"]` → `axes[1].name`. */
export function formatLoc(loc: readonly (string | number)[]): string {
  const parts = loc[0] === "body" || loc[0] === "query" || loc[0] === "path" ? loc.slice(1) : loc;
  let out = "";
  for (const p of parts) out += typeof p === "number" ? `[${p}]` : out ? `.${p}` : p;
  return out;
}

function issuesOf(detail: unknown): { field: string; msg: string }[] {
  if (!Array.isArray(detail)) return [];
  return detail.filter(isValidationError).map((d) => ({ field: formatLoc(d.loc), msg: d.msg }));
}

function describeDetail(detail: unknown): string {
  if (typeof detail === "string") return detail;
  const issues = issuesOf(detail);
  if (issues.length) return issues.map((i) => (i.field ? `${i.field}: ${i.msg}` : i.msg)).join("\n");
  if (detail === undefined || detail === null) return "";
  return JSON.stringify(detail);
}

/** The `{data, error, response}` triple of an openapi-fetch call. */
interface FetchResult<T> {
  data?: T;
  error?: unknown;
  response: Response;
}

/**
 * Unwraps an openapi-fetch result: returns the data or throws an ApiError (HTTP error) / Error (network).
 * Usage: `const st = await unwrap(api.GET("/api/v1/controller"));`
 */
export async function unwrap<T>(call: Promise<FetchResult<T>>): Promise<T> {
  let res: FetchResult<T>;
  try {
    res = await call;
  } catch (err) {
    throw new Error(`cannot reach the controller (${err instanceof Error ? err.message : String(err)})`);
  }
  if (!res.response.ok) {
    const body = res.error;
    const detail = typeof body === "object" && body !== null && "detail" in body ? (body as { detail: unknown }).detail : body;
    throw new ApiError(res.response.status, detail);
  }
  return res.data as T;
}
