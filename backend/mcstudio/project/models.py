"""Project format v1: pydantic models of the project document (`project.json`).

The axis parameters are laid out exactly as `_sAXIS_PARAM` (`omron-group-and-cam.md` §5.5): groups
`UnitConversion`, `Operation`, `OtherOperation`, `Limit`, `PosCount`, `Homing` with the manual's member names, units
and ranges. Defaults are the typical Sysmac Studio values listed in §5.5 (the manual itself gives none).
Cross-field rules (error 573B consistency checks) live in `mcstudio.project.checks`.
"""

from __future__ import annotations

import re
from typing import Literal

from pydantic import ConfigDict, Field, field_validator, model_validator

from ..controller.mc.enums import (
    _eMC_ACCDECOVER,
    _eMC_AXIS_TYPE,
    _eMC_AXIS_USE,
    _eMC_COUNT_MODE,
    _eMC_DIRECTION,
    _eMC_GROUP_TYPE,
    _eMC_GROUP_USE,
    _eMC_HOME_INPUT,
    _eMC_HOMING_MODE,
    _eMC_LIMIT_REVERSE_MODE,
    _eMC_REVERSE_MODE,
    _eMC_STOP_MODE,
    _eMC_SWLMT_MODE,
    _eMC_UNITS,
)
from ..controller.mc.kinematics import Delta3Params, Delta3Workspace
from ..fieldbus.pdo import SlavePdoConfig
from ..modelbase import StrictModel
from ..plant.ideal import DEFAULT_INERTIA, DEFAULT_LOAD_TORQUE, DEFAULT_RATED_TORQUE, DEFAULT_VISCOUS_FRICTION
from .cam_models import MAX_CAMS, CamDefinition
from .enumtypes import ManualEnum
from .trace_models import MAX_TRACES, TraceSettings

SCHEMA_VERSION = 1
PROJECT_FILE = "project.json"

UDINT_MAX = 4_294_967_295
LREAL_MAX = 1.7976931348623157e308

# Primary periods an NJ/NX controller offers (µs). NX701 goes down to 125 µs, NJ to 500 µs.
PRIMARY_PERIODS_US = (125, 250, 500, 1000, 2000, 4000, 8000)


class _Strict(StrictModel):
    model_config = ConfigDict(extra="forbid", validate_assignment=True, allow_inf_nan=False)


class UnitConversionSettings(_Strict):
    """`_sAXIS_UNIT_CONVERSION_SETTINGS` — command unit ↔ pulse (electronic gear)."""

    UnitDisplay: ManualEnum(_eMC_UNITS) = Field(_eMC_UNITS._mcPls, description="Unit of display (command unit)")
    CmdPlsCountPerMotorRotation: int = Field(
        8192, ge=1, le=UDINT_MAX, description="Command pulse count per motor rotation [pulse/rev]"
    )
    WorkTravelDistancePerMotorRotation: float = Field(
        10000.0, ge=0.000000001, le=4294967295.0, description="Work travel distance per motor rotation [unit/rev]"
    )
    ReducerUse: bool = Field(False, description="Use the reducer (gear ratio) settings below")
    WorkTravelDistancePerWorkSideRotation: float = Field(
        10000.0, gt=0, le=LREAL_MAX, description="Work travel distance per work-side rotation [unit]"
    )
    WorkSideGearRatio: int = Field(1, ge=1, le=UDINT_MAX, description="Work-side gear ratio")
    MotorSideGearRatio: int = Field(1, ge=1, le=UDINT_MAX, description="Motor-side gear ratio")


class OperationSettings(_Strict):
    """`_sAXIS_OPERATION_SETTINGS` — velocity/acceleration limits, in-position check."""

    MaxVel: float = Field(400000000.0, gt=0, description="Maximum velocity [unit/s]")
    StartVel: float = Field(0.0, ge=0, description="Start velocity [unit/s]")
    MaxJogVel: float = Field(1000000.0, gt=0, description="Maximum jog velocity [unit/s]")
    MaxAcc: float = Field(0.0, ge=0, description="Maximum acceleration [unit/s²]; 0 = no limit")
    MaxDec: float = Field(0.0, ge=0, description="Maximum deceleration [unit/s²]; 0 = no limit")
    AccDecOver: ManualEnum(_eMC_ACCDECOVER) = Field(
        _eMC_ACCDECOVER._mcAccDecOverBuffer, description="Acceleration/deceleration over"
    )
    ReverseMode: ManualEnum(_eMC_REVERSE_MODE) = Field(
        _eMC_REVERSE_MODE._mcReverseModeDecelerationStop, description="Operation selection at reversing"
    )
    VelWarningVal: int = Field(0, ge=0, le=100, description="Velocity warning value [% of MaxVel]; 0 = none")
    AccWarningVal: int = Field(0, ge=0, le=100, description="Acceleration warning value [% of MaxAcc]; 0 = none")
    DecWarningVal: int = Field(0, ge=0, le=100, description="Deceleration warning value [% of MaxDec]; 0 = none")
    PosiTrqWarningVal: int = Field(0, ge=0, le=1000, description="Positive torque warning value [%]; 0 = none")
    NegaTrqWarningVal: int = Field(0, ge=0, le=1000, description="Negative torque warning value [%]; 0 = none")
    InPosRange: float = Field(10.0, ge=0, description="In-position range [unit]")
    InPosCheckTime: int = Field(
        0, ge=0, le=10000, description="In-position check time [ms]; 0 = no in-position check except homing"
    )
    ActVelFilterTimeConstant: int = Field(
        0, ge=0, le=100, description="Actual velocity filter time constant [ms]; 0 = none"
    )
    ZeroPosRange: float = Field(10.0, ge=0, description="Zero position range [unit]")


class OtherOperationSettings(_Strict):
    """`_sAXIS_OTHER_OPERATION_SETTINGS` — stop methods, torque limits, input logic."""

    ImmediateStopInputStopMode: ManualEnum(_eMC_STOP_MODE, (1, 2, 3)) = Field(
        _eMC_STOP_MODE._mcImmediateStop, description="Immediate stop input stop method"
    )
    LimitInputStopMode: ManualEnum(_eMC_STOP_MODE, (0, 1, 2, 3)) = Field(
        _eMC_STOP_MODE._mcImmediateStop, description="Limit input stop method"
    )
    DriveErrorResetMonitoringTime: int = Field(
        200, ge=1, le=1000, description="Drive error reset monitoring time [ms]"
    )
    MaxPosiTrqLimit: float = Field(300.0, ge=0.0, le=1000.0, description="Maximum positive torque limit [%]")
    MaxNegaTrqLimit: float = Field(300.0, ge=0.0, le=1000.0, description="Maximum negative torque limit [%]")
    ImmediateStopInputLogicInversion: bool = False
    PosiLimitInputLogicInversion: bool = False
    NegaLimitInputLogicInversion: bool = False
    HomeProximityInputLogicInversion: bool = False


class LimitSettings(_Strict):
    """`_sAXIS_LIMIT_SETTINGS` — software limits and following error."""

    SwLimitMode: ManualEnum(_eMC_SWLMT_MODE) = Field(
        _eMC_SWLMT_MODE._mcNonSwLmt, description="Software limit function"
    )
    PosiSwLimit: float = Field(2147483647.0, description="Positive software limit [unit]")
    NegaSwLimit: float = Field(-2147483648.0, description="Negative software limit [unit]")
    FollowingErrorOverVal: float = Field(0.0, ge=0, description="Following error over value [unit]; 0 = no check")
    FollowingErrorWarningVal: float = Field(0.0, ge=0, description="Following error warning value [unit]; 0 = none")


class PositionCountSettings(_Strict):
    """`_sAXIS_POSITION_COUNT_SETTINGS` — linear or rotary (ring counter) mode."""

    CountMode: ManualEnum(_eMC_COUNT_MODE) = Field(_eMC_COUNT_MODE._mcCountModeLinear, description="Count mode")
    ModuloMaxPosVal: float = Field(360.0, description="Modulo maximum position setting value [unit]")
    ModuloMinPosVal: float = Field(0.0, description="Modulo minimum position setting value [unit]")


class HomingSettings(_Strict):
    """`_sAXIS_HOMING_SETTINGS` — homing method and its parameters."""

    Mode: ManualEnum(_eMC_HOMING_MODE) = Field(_eMC_HOMING_MODE._mcHomeSwTurnHomeSwOff, description="Homing method")
    HomeInputSignal: ManualEnum(_eMC_HOME_INPUT) = Field(_eMC_HOME_INPUT._mcZPhase, description="Home input signal")
    StartDirection: ManualEnum(_eMC_DIRECTION, (0, 2)) = Field(
        _eMC_DIRECTION._mcPositiveDirection, description="Homing start direction"
    )
    HomeInputDetectionDirection: ManualEnum(_eMC_DIRECTION, (0, 2)) = Field(
        _eMC_DIRECTION._mcPositiveDirection, description="Home input detection direction"
    )
    PosiLimitInputMode: ManualEnum(_eMC_LIMIT_REVERSE_MODE) = Field(
        _eMC_LIMIT_REVERSE_MODE._mcRevImmediateStop, description="Operation selection at positive limit input"
    )
    NegaLimitInputMode: ManualEnum(_eMC_LIMIT_REVERSE_MODE) = Field(
        _eMC_LIMIT_REVERSE_MODE._mcRevImmediateStop, description="Operation selection at negative limit input"
    )
    Vel: float = Field(10000.0, gt=0, description="Homing velocity [unit/s]")
    ApproachVel: float = Field(1000.0, gt=0, description="Homing approach velocity [unit/s]")
    Acc: float = Field(0.0, ge=0, description="Homing acceleration [unit/s²]")
    Dec: float = Field(0.0, ge=0, description="Homing deceleration [unit/s²]")
    Jerk: float = Field(0.0, ge=0, description="Homing jerk [unit/s³]")
    HomeInputMaskDistance: float = Field(10000.0, ge=0, description="Home input mask distance [unit]")
    HomeOffset: float = Field(0.0, description="Home offset [unit]")
    HoldingTime: int = Field(100, ge=0, le=10000, description="Homing holding time [ms]")
    CompensationVal: float = Field(0.0, description="Homing compensation value [unit]")
    CompensationVel: float = Field(1000.0, gt=0, description="Homing compensation velocity [unit/s]")


class AxisParameters(_Strict):
    """`_sAXIS_PARAM` without its Reserved bytes."""

    UnitConversion: UnitConversionSettings = Field(default_factory=UnitConversionSettings)
    Operation: OperationSettings = Field(default_factory=OperationSettings)
    OtherOperation: OtherOperationSettings = Field(default_factory=OtherOperationSettings)
    Limit: LimitSettings = Field(default_factory=LimitSettings)
    PosCount: PositionCountSettings = Field(default_factory=PositionCountSettings)
    Homing: HomingSettings = Field(default_factory=HomingSettings)


class ServoDriveSettings(_Strict):
    """Sysmac Studio's axis settings outside `_sAXIS_PARAM` that the instructions need: the encoder type (position
    count settings), and the servo drive with the mechanism behind it (rated torque, inertia, friction and load,
    supported modes). Not readable or writable by MC_Read/WriteAxisParameter."""

    EncoderType: Literal["incremental", "absolute"] = Field(
        "incremental", description="Incremental: home undefined at power-on; absolute: home defined as soon as "
        "EtherCAT process data communication is established (and again at servo ON if it was undefined)"
    )
    AbsoluteEncoderHomeOffset: float = Field(
        0.0, description="Absolute encoder home offset [unit]: position = encoder position + this offset when an "
        "absolute-encoder axis becomes home-defined"
    )
    # The mechanism behind the drive in cyclic synchronous torque mode (MC_TorqueControl):
    # J·dω/dt = T − ViscousFriction·ω − LoadTorque at the motor shaft (architecture.md "Mechanism").
    RatedTorque: float = Field(
        DEFAULT_RATED_TORQUE, gt=0, le=100000.0,
        description="Motor rated torque [N·m] = 100 % of the torque objects (6071h, 6077h, 60E0h/60E1h, Cmd/Act.Trq)"
    )
    Inertia: float = Field(
        DEFAULT_INERTIA, gt=0, le=10000.0,
        description="Total moment of inertia at the motor shaft (rotor + load) [kg·m²]"
    )
    ViscousFriction: float = Field(
        DEFAULT_VISCOUS_FRICTION, ge=0, le=10000.0,
        description="Viscous friction coefficient at the motor shaft [N·m/(rad/s)]"
    )
    LoadTorque: float = Field(
        DEFAULT_LOAD_TORQUE, ge=-100000.0, le=100000.0,
        description="Constant external load torque at the motor shaft [N·m] (e.g. gravity); a positive value acts "
        "in the negative direction"
    )
    CyclicTorqueMode: bool = Field(
        True, description="The drive supports cyclic synchronous torque mode (CST); without it a change to CST is "
        "ignored by the drive and MC_TorqueControl ends with 7439 after 1 s"
    )
    # The drive's position control (architecture.md "Mechanism"): Ideal = the shaft is at the target position at the
    # end of each period (no following error); SecondOrder = a closed position loop with this bandwidth and damping,
    # limited by the drive's torque limits, so Act.Pos lags Cmd.Pos as on a real machine.
    PositionLoop: Literal["Ideal", "SecondOrder"] = Field(
        "Ideal", description="Position control model of the drive in CSP: Ideal (no following error) or SecondOrder"
    )
    PositionLoopBandwidth: float = Field(
        50.0, gt=0, le=2000.0, description="SecondOrder: natural frequency of the closed position loop [Hz]; at "
        "most a quarter of the sampling frequency of the primary period"
    )
    PositionLoopDamping: float = Field(0.7, ge=0.05, le=5.0, description="SecondOrder: damping ratio ζ")
    VelocityFeedForward: float = Field(
        0.0, ge=0.0, le=100.0, description="SecondOrder: velocity feed-forward [%]; 100 % removes the following "
        "error at constant speed"
    )


class SensorSettings(_Strict):
    """The simulated mechanism's sensors, in command units of the initial coordinate system (null = not fitted).

    They reach the MC module as drive inputs (60FDh bits, touch-probe latches), like wired sensors: the positive and
    negative limit switches are ON beyond their positions, the home proximity dog and the external latch inputs
    are ON inside their zones, and the encoder's Z phase pulses once per motor revolution."""

    PositiveLimit: float | None = Field(None, description="Positive limit input (P_OT) ON at positions ≥ this [unit]")
    NegativeLimit: float | None = Field(None, description="Negative limit input (N_OT) ON at positions ≤ this [unit]")
    HomeProximityStart: float | None = Field(None, description="Home proximity dog: ON from here … [unit]")
    HomeProximityEnd: float | None = Field(None, description="… to here [unit]")
    ExternalHomeStart: float | None = Field(None, description="External home / latch input 1: ON from here … [unit]")
    ExternalHomeEnd: float | None = Field(None, description="… to here [unit]")
    Latch2Start: float | None = Field(None, description="External latch input 2: ON from here … [unit]")
    Latch2End: float | None = Field(None, description="… to here [unit]")
    ZPhaseOffset: int = Field(0, ge=0, le=UDINT_MAX, description="Encoder Z phase: one pulse per motor revolution, "
                              "at this offset from motor position 0 [pulse]")

    @model_validator(mode="after")
    def _zones(self) -> SensorSettings:
        for a, b in (("HomeProximityStart", "HomeProximityEnd"), ("ExternalHomeStart", "ExternalHomeEnd"),
                     ("Latch2Start", "Latch2End")):
            va, vb = getattr(self, a), getattr(self, b)
            if (va is None) != (vb is None):
                raise ValueError(f"{a} and {b} are set together (both numbers or both null)")
            if va is not None and vb is not None and not va < vb:
                raise ValueError(f"{a} must be less than {b}")
        if self.PositiveLimit is not None and self.NegativeLimit is not None and \
                not self.NegativeLimit < self.PositiveLimit:
            raise ValueError("NegativeLimit must be less than PositiveLimit")
        return self


_IDENT = re.compile(r"^[A-Za-z_][A-Za-z0-9_]{0,62}$")


class AxisConfig(_Strict):
    """Axis basic settings plus `_sAXIS_PARAM`."""

    name: str = Field(description="Axis variable name (default MC_Axis000 …); an identifier")
    number: int = Field(ge=0, le=255, description="Logical axis number (index into _MC_AX[])")
    use: ManualEnum(_eMC_AXIS_USE, (1, 2)) = Field(_eMC_AXIS_USE._mcUsedAxis, description="Axis use")
    type: ManualEnum(_eMC_AXIS_TYPE) = Field(_eMC_AXIS_TYPE._mcServo, description="Axis type")
    node_address: int | None = Field(
        None, ge=1, le=65534, description="EtherCAT node address of the drive/encoder slave; null for virtual axes"
    )
    parameters: AxisParameters = Field(default_factory=AxisParameters)
    drive: ServoDriveSettings = Field(default_factory=ServoDriveSettings)
    sensors: SensorSettings = Field(default_factory=SensorSettings)

    @field_validator("name")
    @classmethod
    def _name_is_identifier(cls, v: str) -> str:
        if not _IDENT.match(v):
            raise ValueError("must be an identifier: a letter or _, then letters, digits or _ (max 63)")
        return v


GROUP_AXIS_COUNT: dict[_eMC_GROUP_TYPE, int] = {
    _eMC_GROUP_TYPE._mcXY: 2, _eMC_GROUP_TYPE._mcXYZ: 3, _eMC_GROUP_TYPE._mcXYZU: 4,
}


class GroupOperationSettings(_Strict):
    """Sysmac Studio's axes-group operation settings (轴组动作设定): the limits of the interpolation instructions
    (seed 000 lines 1916–1951, 15772; seed 003 line 2405). Units are the composition axes' command units."""

    MaxInterpolationVel: float = Field(
        800000000.0, gt=0, description="Maximum interpolation velocity [unit/s] (最高插补速度): upper limit of "
        "Velocity of the interpolation instructions and of the override result"
    )
    MaxInterpolationAcc: float = Field(
        0.0, ge=0, description="Maximum interpolation acceleration [unit/s²] (最大插补加速度); 0 = no limit"
    )
    MaxInterpolationDec: float = Field(
        0.0, ge=0, description="Maximum interpolation deceleration [unit/s²] (最大插补减速度); 0 = no limit"
    )
    InterpolationAccDecOver: ManualEnum(_eMC_ACCDECOVER) = Field(
        _eMC_ACCDECOVER._mcAccDecOverBuffer, description="Interpolation acceleration/deceleration over"
    )
    InterpolationVelWarningVal: int = Field(
        0, ge=0, le=100, description="Interpolation velocity warning value [% of MaxInterpolationVel]; 0 = none"
    )
    InterpolationAccWarningVal: int = Field(
        0, ge=0, le=100, description="Interpolation acceleration warning value [% of MaxInterpolationAcc]; 0 = none"
    )
    InterpolationDecWarningVal: int = Field(
        0, ge=0, le=100, description="Interpolation deceleration warning value [% of MaxInterpolationDec]; 0 = none"
    )
    GroupStopMethod: ManualEnum(_eMC_STOP_MODE, (0, 1)) = Field(
        _eMC_STOP_MODE._mcImmediateStop, description="Axes group stop method (轴组停止方法) on a group error: "
        "_mcImmediateStop, or _mcDecelerationStop = decelerate each axis to a stop; a robot group (kinematics set) "
        "always stops immediately"
    )
    CorrectionAllowanceRatio: float = Field(
        0.1, ge=0.0, le=100.0, description="Centre correction allowance ratio [%] (中心点修正容许率) of "
        "MC_MoveCircular2D in centre mode; 0 = no check (5449 beyond it)"
    )


class Delta3WorkspaceConfig(_Strict):
    """`_sMC_WORKSPACE_REF.WorkspaceParam[0..4]` of a Delta3 (`kinematics.Delta3Workspace`), in mm."""

    Zu: float = Field(description="z of the workspace's top face [mm], ≤ 0")
    Rcy: float = Field(description="Cylinder radius [mm]")
    Hcy: float = Field(description="Cylinder height [mm]")
    Rco: float = Field(description="Radius of the cone's lower face [mm]")
    Hco: float = Field(description="Cone height [mm]")


class Delta3KinematicsConfig(_Strict):
    """A Delta3 robot on the group's A0–A2 (`omron-robot-delta3.md` §3.1–§3.3): the studio applies it at start-up as
    an implicit MC_SetKinTransform. Rf, Lf, Rm, Lm in mm, θ in degrees (`kinematics.Delta3Params`)."""

    type: Literal["delta3"] = "delta3"
    Rf: float = Field(description="Fixed-frame centre → motor axis [mm] (KinParam[0])")
    Rm: float = Field(description="Moving-frame centre → forearm joint [mm] (KinParam[2])")
    Lf: float = Field(description="Upper arm length [mm] (KinParam[1])")
    Lm: float = Field(description="Forearm length [mm] (KinParam[3])")
    theta: float = Field(0.0, description="Rotation of the arm layout about the MCS Z axis [deg] (ExpansionParam[0])")
    workspace: Delta3WorkspaceConfig

    def params(self) -> Delta3Params:
        return Delta3Params(Rf=self.Rf, Lf=self.Lf, Rm=self.Rm, Lm=self.Lm, theta=self.theta)

    def workspace_obj(self) -> Delta3Workspace:
        w = self.workspace
        return Delta3Workspace(Zu=w.Zu, Rcy=w.Rcy, Hcy=w.Hcy, Rco=w.Rco, Hco=w.Hco)


class AxesGroupConfig(_Strict):
    """Axes-group basic settings (轴组基本设定, `_sGROUP_REF.Cfg` / `.Kinematics`) plus the operation settings."""

    name: str = Field(description="Axes group variable name (default MC_Group000 …); an identifier")
    number: int = Field(ge=0, le=63, description="Axes group number (Cfg.GrpNo, index into _MC_GRP[])")
    use: ManualEnum(_eMC_GROUP_USE, (1, 2)) = Field(_eMC_GROUP_USE._mcUsedGroup, description="Axes group use")
    composition: ManualEnum(_eMC_GROUP_TYPE) = Field(
        _eMC_GROUP_TYPE._mcXY, description="Axis composition (Kinematics.GrpType): _mcXY 2 axes, _mcXYZ 3, _mcXYZU 4"
    )
    axes: list[str] = Field(
        default_factory=list, max_length=4,
        description="Composition axes: axis names for the logical axes A0, A1 … (one per axis of the composition)"
    )
    operation: GroupOperationSettings = Field(default_factory=GroupOperationSettings)
    kinematics: Delta3KinematicsConfig | None = Field(
        None, description="Robot kinematics applied at start-up (implicit MC_SetKinTransform); null = none"
    )

    @field_validator("name")
    @classmethod
    def _name_is_identifier(cls, v: str) -> str:
        if not _IDENT.match(v):
            raise ValueError("must be an identifier: a letter or _, then letters, digits or _ (max 63)")
        return v

    @property
    def axis_count(self) -> int:
        return GROUP_AXIS_COUNT[self.composition]


class ControllerSettings(_Strict):
    primary_period_us: int = Field(1000, description="Primary period [µs]: 125, 250, 500, 1000, 2000, 4000 or 8000")

    @field_validator("primary_period_us")
    @classmethod
    def _period_allowed(cls, v: int) -> int:
        if v not in PRIMARY_PERIODS_US:
            raise ValueError(f"must be one of {', '.join(map(str, PRIMARY_PERIODS_US))} µs")
        return v

    @property
    def period_s(self) -> float:
        return self.primary_period_us * 1e-6


class StartupSdo(_Strict):
    """One line of a slave's start-up parameter list: an SDO write in the Pre-Op state (codesys-lc1200.md §5.4)."""

    index: int = Field(ge=0x1000, le=0xFFFF, description="Object index")
    subindex: int = Field(0, ge=0, le=255)
    value: int = Field(ge=-(2**63), le=2**64 - 1, description="Value written")
    bit_len: Literal[8, 16, 32, 64] = Field(32, description="Size of the write")
    abort_on_error: bool = Field(True, description="A failed write stops the slave's start-up (it stays in Pre-Op)")
    comment: str = Field("", max_length=200)


class SlaveEmulation(_Strict):
    """How the emulated wire differs from the configuration (commissioning drills); not part of a real project."""

    connected: bool = Field(True, description="The slave is on the wire when the network starts")
    wired_device: str | None = Field(
        None, description="A different device found at this position (topology mismatch), by library id")
    encoder_velocity: float = Field(
        0.0, ge=-1e9, le=1e9, description="Encoder input slaves: speed of the mechanism turning the encoder [pulse/s]")


class EtherCATSlaveConfig(_Strict):
    node_address: int = Field(ge=1, le=65534, description="Node address (station address) of the slave")
    name: str = Field("", max_length=63, description="Device name shown in the network view (default E001 …)")
    device: str = Field("builtin:cia402-servo", description="Library id of the device description: "
                        "'builtin:cia402-servo', 'builtin:encoder-input' or 'esi:<vendor>:<product>:<revision>'")
    pdo: SlavePdoConfig | None = Field(None, description="PDO assignment and mapping; null = the device's default")
    startup_sdos: list[StartupSdo] = Field(default_factory=list, max_length=256)
    emulation: SlaveEmulation = Field(default_factory=SlaveEmulation)


class EtherCATMasterConfig(_Strict):
    """Master settings; the cycle time is the primary period (`controller.primary_period_us`)."""

    dc_enabled: bool = Field(True, description="Distributed clocks: the slaves latch and apply data on SYNC0")
    sync_offset_pct: int = Field(20, ge=0, le=80, description="SYNC0 shift relative to the primary period [%]")
    auto_restart_slaves: bool = Field(
        True, description="A slave that comes back after a drop-out is brought back to Op automatically (else "
        "only POST /api/v1/ethercat/slaves/{address}/connect or a controller restart reconnects it)")


class EtherCATConfig(_Strict):
    master: EtherCATMasterConfig = Field(default_factory=EtherCATMasterConfig)
    slaves: list[EtherCATSlaveConfig] = Field(
        default_factory=list, max_length=512,
        description="Configured slaves in wiring order; empty = one built-in device per servo/encoder axis")


class Project(_Strict):
    """The project document: one JSON file in the project folder."""

    model_config = ConfigDict(extra="forbid", validate_assignment=True, allow_inf_nan=False, populate_by_name=True)

    schema_ref: str | None = Field(
        None, alias="$schema", max_length=2000,
        description="URL or path of this document's JSON Schema, for editors (e.g. "
        "http://127.0.0.1:8000/api/v1/project/schema or a file written by `mcstudio schema`); kept as written, "
        "not used by the studio (docs/project-format.md, D113)")
    format: Literal["mcstudio-project"] = "mcstudio-project"
    schema_version: Literal[1] = Field(SCHEMA_VERSION, description="Version of this document's schema")
    name: str = Field(min_length=1, max_length=100)
    description: str = Field("", max_length=2000)
    controller: ControllerSettings = Field(default_factory=ControllerSettings)
    axes: list[AxisConfig] = Field(default_factory=list, max_length=256)
    ethercat: EtherCATConfig = Field(default_factory=EtherCATConfig)
    groups: list[AxesGroupConfig] = Field(default_factory=list, max_length=64, description="Axes groups")
    cams: list[CamDefinition] = Field(
        default_factory=list, max_length=MAX_CAMS,
        description="Cam tables (cam data variables); their points are in cams/<name>.csv")
    traces: list[TraceSettings] = Field(
        default_factory=list, max_length=4 * MAX_TRACES, description="Saved data trace settings (docs/trace.md)")

    def axis(self, name: str) -> AxisConfig | None:
        return next((a for a in self.axes if a.name == name), None)

    def group(self, name: str) -> AxesGroupConfig | None:
        return next((g for g in self.groups if g.name == name), None)
