"""Request and response models of the REST API (api.md). Names of MC variables are the manual's."""

from __future__ import annotations

from typing import Annotated, Any, Literal

from pydantic import AfterValidator, Field, StrictBool, StrictFloat, StrictInt, StrictStr

from ..modelbase import StrictModel
from ..project.models import AxisConfig
from .control import ControlState

Mode = Literal["realtime", "fast", "paused"]


_Model = StrictModel


class Health(_Model):
    status: Literal["ok"] = "ok"
    version: str


class ControllerStatus(_Model):
    mode: Mode
    period_s: float
    cycle: int
    time_s: float
    rtf: float = Field(description="Real-time factor: simulated seconds per wall-clock second (0 while paused)")
    overruns: int = Field(description="Realtime mode: periods whose computation finished after their deadline")
    project: str
    project_dirty: bool = Field(False, description="The project in the controller differs from the saved file")
    epoch: int = Field(0, description="Increments each time the controller is replaced (configuration applied, "
                       "project opened, reset): cycle, instance ids and event numbers restart")
    cycle_time_us: float = Field(0.0, description="Task monitor: mean computation time of a control period over the "
                                 "last half second [µs] (0 while paused)")
    cycle_time_max_us: float = Field(0.0, description="Task monitor: longest computation of a control period over the "
                                     "last half second [µs] (fast mode: the longest mean of a 4 ms slice)")


class ModeIn(_Model):
    mode: Mode


class UntilIn(_Model):
    fb: int = Field(description="Instance id")
    output: str = Field(description="Output variable name, e.g. Done")
    equals: StrictBool | StrictInt | StrictFloat | StrictStr = Field(
        description="Value to wait for; WORD outputs may be given as hex strings ('5422')"
    )


MAX_STEP_CYCLES = 2_000_000


class StepIn(_Model):
    cycles: int = Field(1, ge=1, le=MAX_STEP_CYCLES, description="Number of periods to run")
    until: UntilIn | None = Field(None, description="Stop early after the first cycle in which this holds")


class StepOut(ControllerStatus):
    stepped: int = Field(description="Cycles actually run")
    until_met: bool | None = None


class FBCreate(_Model):
    type: str = Field(description="Instruction name, e.g. MC_MoveAbsolute")
    inputs: dict[str, Any] = Field(default_factory=dict, description="Inputs and in-outs by name")
    lease_s: float | None = Field(
        None, gt=0, le=3600, description="Dead-man lease: Execute/Enable inputs drop to FALSE unless renewed"
    )


class FBPatch(_Model):
    inputs: dict[str, Any] = Field(description="Inputs to change; applied at the next cycle boundary")


class FBOut(_Model):
    id: int
    type: str
    inputs: dict[str, Any]
    outputs: dict[str, Any]
    lease_s: float | None = None
    cycle: int = Field(description="Controller cycle of this view")


class VarInfo(_Model):
    name: str
    type: str
    default: Any = None
    description: str = ""
    unit: str | None = None
    valid: str | None = None
    enumerators: list[dict[str, Any]] | None = None


class FBType(_Model):
    name: str
    title: str
    summary: str
    kind: Literal["execute", "enable"]
    inputs: list[VarInfo]
    outputs: list[VarInfo]
    inouts: list[VarInfo]
    spec: str
    status: Literal["complete", "partial"]
    notes: str = ""


class ErrorInfo(_Model):
    code: str = Field(description="ErrorID, four hex digits")
    event_code: str
    name: str
    cause: str
    correction: str
    level: str
    source: str
    ref: str


class EventOut(_Model):
    seq: int
    cycle: int
    time_s: float
    source: str
    code: str = Field(description="Event code, eight hex digits")
    level: Literal["major fault", "partial fault", "minor fault", "observation", "information"]
    message: str = Field(description="The manual's event name (or a note for information events)")
    cause: str = Field("", description="The manual's cause of the error (appendix A-1)")
    correction: str = Field("", description="The correction the manual suggests")
    detail: str = Field("", description="Attached information: the input, the value, the 603Fh code …")
    source_kind: Literal["axis", "group", "slave", "instruction", "controller"] = Field(
        "controller", description="What the event is about (decision D125)")
    source_name: str = Field("", description="The axis, axes group or slave name, or the instance label")
    instruction: str = Field("", description="The instance involved (\"fb 3 MC_MoveAbsolute\"), if any")


# ----------------------------------------------------------------------------------------------- _sAXIS_REF
class AxisStatusVar(_Model):
    Ready: bool
    Disabled: bool
    Standstill: bool
    Discrete: bool
    Continuous: bool
    Synchronized: bool
    Homing: bool
    Stopping: bool
    ErrorStop: bool
    Coordinated: bool


class AxisDetailsVar(_Model):
    Idle: bool
    InPosWaiting: bool
    Homed: bool
    InHome: bool
    VelLimit: bool


class AxisDirVar(_Model):
    Posi: bool
    Nega: bool


class AxisDrvStatusVar(_Model):
    ServoOn: bool
    Ready: bool
    MainPower: bool
    P_OT: bool
    N_OT: bool
    HomeSw: bool
    Home: bool
    ImdStop: bool
    Latch1: bool
    Latch2: bool
    DrvAlarm: bool
    DrvWarning: bool
    ILA: bool
    CSP: bool
    CSV: bool
    CST: bool


class AxisCmdVar(_Model):
    Pos: float
    Vel: float
    AccDec: float
    Jerk: float
    Trq: float


class AxisActVar(_Model):
    Pos: float
    Vel: float
    Trq: float
    TimeStamp: int


class RefEvent(_Model):
    Active: bool
    Code: str = Field(description="Upper four hex digits of the event code")


class AxisCfgVar(_Model):
    AxNo: int
    AxEnable: str
    AxType: str
    NodeAddress: int
    ExecID: int


class AxisScaleVar(_Model):
    Num: int
    Den: float
    Units: str
    CountMode: str
    MaxPos: float
    MinPos: float


class AxisVariables(_Model):
    """`_sAXIS_REF` (omron-mc-basics.md §2.3)."""

    Status: AxisStatusVar
    Details: AxisDetailsVar
    Dir: AxisDirVar
    DrvStatus: AxisDrvStatusVar
    Cmd: AxisCmdVar
    Act: AxisActVar
    MFaultLvl: RefEvent
    Obsr: RefEvent
    Cfg: AxisCfgVar
    Scale: AxisScaleVar


class AxisSummary(_Model):
    name: str
    number: int
    type: str
    use: str
    node_address: int | None
    units: str
    state: str
    cmd_pos: float
    act_pos: float
    cmd_vel: float
    act_vel: float
    servo_on: bool
    error_code: str


class AxisDetail(_Model):
    config: AxisConfig
    variables: AxisVariables
    cycle: int


class ProjectInfo(_Model):
    name: str = Field(description="Folder name under the projects root")
    title: str = Field(description="Project name from the document")
    path: str
    valid: bool
    error: str | None = None
    current: bool = False


def _project_name(name: str) -> str:
    from ..project.folders import check_project_name

    return check_project_name(name)


ProjectName = Annotated[str, AfterValidator(_project_name), Field(
    min_length=1, max_length=64,
    description="Folder name under the projects root: one folder name (no '/', '\\' or '..'), not hidden, at most "
    "64 characters (decision D110)")]


class OpenProjectIn(_Model):
    name: ProjectName


class SaveOut(_Model):
    path: str
    saved: bool = True


class SaveAsIn(_Model):
    name: ProjectName
    overwrite: bool = Field(False, description="Replace an existing project of that name (its project.json is kept "
                            "as the new folder's project.json.bak)")


class NewProjectIn(_Model):
    name: ProjectName
    template: str = Field("empty", min_length=1, max_length=64,
                          description="Template name (GET /api/v1/project-templates): empty, single-axis, demo")


class ProjectTemplateOut(_Model):
    name: str = Field(description="Template name for POST /api/v1/projects/new")
    title: str = Field(description="The template document's name")
    description: str
    axes: int = Field(description="Number of axes")
    groups: int = Field(description="Number of axes groups")
    cams: int = Field(description="Number of cam tables")


class VizInfo(_Model):
    enabled: bool
    port: int | None = None
    host: str | None = None


# ----------------------------------------------------------------------------------------------- WebSocket
class WsSubscribe(_Model):
    """Client → server: choose what to receive and how often."""

    type: Literal["subscribe"]
    rate_hz: float = Field(30.0, ge=1, le=120)
    axes: list[str] | None = Field(None, description="Axis names (null = all)")
    fbs: list[int] | None = Field(None, description="Instance ids whose outputs to include (null = all)")
    events: bool = True


class WsHeartbeat(_Model):
    """Client → server: renew the dead-man leases of these instances."""

    type: Literal["heartbeat"]
    fbs: list[int]


class WsPing(_Model):
    """Client → server: "still here" (a client that gave a client id must send something at least every 10 s or it
    loses test-run control, decision D117)."""

    type: Literal["ping"]


class AxisLive(_Model):
    name: str
    variables: AxisVariables


class WsSnapshot(_Model):
    """Server → client, at the subscribed rate."""

    type: Literal["snapshot"] = "snapshot"
    controller: ControllerStatus
    axes: list[AxisLive]
    fbs: dict[str, FBOut]
    events: list[EventOut]
    control: ControlState | None = Field(None, description="Who holds test-run control (api/control.py)")
