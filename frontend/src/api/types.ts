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
export type RobotsOut = S["RobotsOut"];
export type RobotOut = S["RobotOut"];
export type ProjectInfo = S["ProjectInfo"];
export type WsSnapshot = S["WsSnapshot"];
export type WsSubscribe = S["WsSubscribe"];
export type WsHeartbeat = S["WsHeartbeat"];
export type WsPing = S["WsPing"];
export type ControlState = S["ControlState"];
export type ControlHolder = S["ControlHolder"];
export type ControlOut = S["ControlOut"];
export type ValidationError = S["ValidationError"];
export type AxisConfig = S["AxisConfig-Output"];
export type AxisConfigInput = S["AxisConfig-Input"];
export type AxisDetail = S["AxisDetail"];
export type FBType = S["FBType"];
export type VarInfo = S["VarInfo"];

// EtherCAT: network view, PDO configuration, device library, ESI import, fault injection
export type EtherCATOut = S["EtherCATOut"];
export type EtherCATMaster = S["MasterOut"];
export type SlaveOut = S["SlaveOut"];
export type EsmState = SlaveOut["state"];
export type PdoOut = S["PdoOut"];
export type MappedEntryOut = S["MappedEntryOut"];
export type ImageOut = S["ImageOut"];
export type SlavePdoConfig = S["SlavePdoConfig"];
export type PdoMappingConfig = S["PdoMappingConfig"];
export type PdoEntryConfig = S["PdoEntryConfig"];
export type DeviceSummary = S["DeviceSummary"];
export type DeviceDescription = S["DeviceDescription"];
export type PdoDescription = S["PdoDescription"];
export type ObjectDescription = S["ObjectDescription"];
export type EsiFile = S["EsiFile"];
export type FaultIn = S["FaultIn"];
export type FaultKind = FaultIn["kind"];
export type FaultOut = S["FaultOut"];
// EtherCAT network configuration (PUT /api/v1/ethercat; the project's `ethercat` section)
export type Project = S["Project"];
export type EtherCATConfig = S["EtherCATConfig"];
export type EtherCATMasterConfig = S["EtherCATMasterConfig"];
export type EtherCATSlaveConfig = S["EtherCATSlaveConfig"];
export type StartupSdo = S["StartupSdo"];
export type SlaveEmulation = S["SlaveEmulation"];
