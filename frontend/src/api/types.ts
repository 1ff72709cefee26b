/** Short names for the generated OpenAPI schema types (src/api/schema.d.ts is generated: npm run gen:api). */
import type { components } from "./schema";

type S = components["schemas"];

export type ControllerStatus = S["ControllerStatus"];
export type ControllerMode = ControllerStatus["mode"];
export type AxisSummary = S["AxisSummary"];
export type AxisVariables = S["AxisVariables"];
export type AxisStatusVar = S["AxisStatusVar"];
export type AxisLive = S["AxisLive"];
export type FBOut = S["FBOut"];
export type FBCreate = S["FBCreate"];
export type EventOut = S["EventOut"];
export type EventLevel = EventOut["level"];
export type ErrorInfo = S["ErrorInfo"];
export type VizInfo = S["VizInfo"];
export type ProjectInfo = S["ProjectInfo"];
export type WsSnapshot = S["WsSnapshot"];
export type WsSubscribe = S["WsSubscribe"];
export type WsHeartbeat = S["WsHeartbeat"];
export type ValidationError = S["ValidationError"];
export type AxisConfig = S["AxisConfig-Output"];
export type AxisConfigInput = S["AxisConfig-Input"];
export type AxisDetail = S["AxisDetail"];
export type FBType = S["FBType"];
export type VarInfo = S["VarInfo"];
