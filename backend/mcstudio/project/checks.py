"""Semantic validation of a project: cross-field rules that a schema cannot express.

Axis parameters follow the manual's error 573B consistency checks (`omron-group-and-cam.md` §5.5.9, A-2.4) and report
the `ErrorParameterCode`; project-level rules (unique names, numbers and node addresses) are ours. Every issue names
the JSON path of the offending field, e.g. `axes[1].parameters.Operation.MaxJogVel`.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..controller.mc.enums import (
    _eMC_AXIS_TYPE,
    _eMC_AXIS_USE,
    _eMC_COUNT_MODE,
    _eMC_GROUP_TYPE,
    _eMC_GROUP_USE,
    _eMC_UNITS,
)
from ..controller.mc.kinematics import check_kin_transform
from ..controller.mc.units import POS_MAX_PULSES, fits_distance, fits_position, pulses_per_unit
from ..fieldbus.config import check_network
from ..fieldbus.library import DeviceLibrary
from .cam_models import check_cams
from .models import AxesGroupConfig, AxisParameters, Project

# ErrorParameterCode of the 573B range checks, by member path. Used by MC_WriteAxisParameter.
RANGE_CODES: dict[str, int] = {
    "UnitConversion.UnitDisplay": 0x0000,
    "UnitConversion.CmdPlsCountPerMotorRotation": 0x0001,
    "UnitConversion.WorkTravelDistancePerMotorRotation": 0x0002,
    "UnitConversion.WorkTravelDistancePerWorkSideRotation": 0x0003,
    "UnitConversion.WorkSideGearRatio": 0x0004,
    "UnitConversion.MotorSideGearRatio": 0x0005,
    "Operation.MaxVel": 0x0100,
    "Operation.StartVel": 0x0101,
    "Operation.MaxJogVel": 0x0102,
    "Operation.MaxAcc": 0x0103,
    "Operation.MaxDec": 0x0104,
    "Operation.AccDecOver": 0x0105,
    "Operation.ReverseMode": 0x0106,
    "Operation.VelWarningVal": 0x0107,
    "Operation.AccWarningVal": 0x0108,
    "Operation.DecWarningVal": 0x0109,
    "Operation.PosiTrqWarningVal": 0x010A,
    "Operation.NegaTrqWarningVal": 0x010B,
    "Operation.InPosRange": 0x010C,
    "Operation.InPosCheckTime": 0x010D,
    "Operation.ActVelFilterTimeConstant": 0x010E,
    "Operation.ZeroPosRange": 0x010F,
    "OtherOperation.ImmediateStopInputStopMode": 0x0200,
    "OtherOperation.LimitInputStopMode": 0x0201,
    "OtherOperation.DriveErrorResetMonitoringTime": 0x0202,
    "OtherOperation.MaxPosiTrqLimit": 0x0203,
    "OtherOperation.MaxNegaTrqLimit": 0x0204,
    "Limit.SwLimitMode": 0x0300,
    "Limit.PosiSwLimit": 0x0301,
    "Limit.NegaSwLimit": 0x0302,
    "Limit.FollowingErrorOverVal": 0x0303,
    "Limit.FollowingErrorWarningVal": 0x0304,
    "PosCount.CountMode": 0x0400,
    "PosCount.ModuloMaxPosVal": 0x0401,
    "PosCount.ModuloMinPosVal": 0x0402,
    "Homing.Mode": 0x0500,
    "Homing.HomeInputSignal": 0x0501,
    "Homing.StartDirection": 0x0502,
    "Homing.HomeInputDetectionDirection": 0x0503,
    "Homing.PosiLimitInputMode": 0x0504,
    "Homing.NegaLimitInputMode": 0x0505,
    "Homing.Vel": 0x0506,
    "Homing.ApproachVel": 0x0507,
    "Homing.Acc": 0x0508,
    "Homing.Dec": 0x0509,
    "Homing.Jerk": 0x050A,
    "Homing.HomeInputMaskDistance": 0x050B,
    "Homing.HomeOffset": 0x050C,
    "Homing.HoldingTime": 0x050D,
    "Homing.CompensationVal": 0x050E,
    "Homing.CompensationVel": 0x050F,
}

MAX_VELOCITY_PULSES = 2_147_483_647  # CPU unit v1.11 (`omron-mc-basics.md` §2.6 footnote)
# Axes-group operation settings (seed 000 lines 1945–1951): the maximum interpolation velocity is at most twice the
# upper limit of an axis's maximum velocity, the maximum interpolation acceleration/deceleration 6.4e12 pulse/s².
MAX_INTERPOLATION_VELOCITY_PULSES = 2 * MAX_VELOCITY_PULSES
MAX_INTERPOLATION_ACC_PULSES = 6_400_000_000_000.0
_KIN_PARAM_FIELDS = {"KinParam[0]": "Rf", "KinParam[1]": "Lf", "KinParam[2]": "Rm", "KinParam[3]": "Lm",
                     "ExpansionParam[0]": "theta", "WorkspaceParam[0]": "workspace.Zu",
                     "WorkspaceParam[1]": "workspace.Rcy", "WorkspaceParam[2]": "workspace.Hcy",
                     "WorkspaceParam[3]": "workspace.Rco", "WorkspaceParam[4]": "workspace.Hco"}


@dataclass(frozen=True)
class Issue:
    path: str
    message: str
    code: str | None = None  # e.g. "573B/1102" for axis parameter consistency checks

    def as_dict(self) -> dict[str, str | None]:
        return {"path": self.path, "message": self.message, "code": self.code}


def check_axis_parameters(p: AxisParameters) -> list[tuple[int, str, str]]:
    """Return the 573B consistency violations as (ErrorParameterCode, member path, message), in code order."""
    out: list[tuple[int, str, str]] = []
    uc, op, lim, pc, hm = p.UnitConversion, p.Operation, p.Limit, p.PosCount, p.Homing
    rotary = pc.CountMode == _eMC_COUNT_MODE._mcCountModeRotary

    def add(code: int, path: str, msg: str) -> None:
        out.append((code, path, msg))

    if uc.ReducerUse:
        travel = (
            abs(pc.ModuloMaxPosVal - pc.ModuloMinPosVal) if rotary else uc.WorkTravelDistancePerWorkSideRotation
        )
        ratio = travel * uc.WorkSideGearRatio / uc.MotorSideGearRatio
        if not (0.00000001 <= ratio <= 2**31):
            add(0x1000, "UnitConversion.WorkTravelDistancePerWorkSideRotation",
                "work travel per work-side rotation × work gear ratio / motor gear ratio must be within 1e-8 … 2^31")
        if uc.CmdPlsCountPerMotorRotation * uc.MotorSideGearRatio > POS_MAX_PULSES:
            add(0x1001, "UnitConversion.MotorSideGearRatio",
                "command pulses per motor rotation × motor gear ratio must fit in 40 bits")
    if rotary and pc.ModuloMaxPosVal <= pc.ModuloMinPosVal:
        # The ring length feeds the conversion; report it before anything that depends on it.
        add(0x1402, "PosCount.ModuloMaxPosVal", "ModuloMaxPosVal must be greater than ModuloMinPosVal")
        return out
    ppu = pulses_per_unit(p)

    if op.MaxVel * ppu > MAX_VELOCITY_PULSES:
        add(0x1100, "Operation.MaxVel",
            f"MaxVel is {op.MaxVel * ppu:.0f} pulse/s; the limit is {MAX_VELOCITY_PULSES} pulse/s")
    if op.StartVel > op.MaxVel:
        add(0x1101, "Operation.StartVel", "StartVel must not exceed MaxVel")
    if op.MaxJogVel > op.MaxVel:
        add(0x1102, "Operation.MaxJogVel", "MaxJogVel must not exceed MaxVel")
    if not fits_distance(op.InPosRange, ppu):
        add(0x1103, "Operation.InPosRange", "InPosRange exceeds 40 bits in pulses")
    if not fits_distance(op.ZeroPosRange, ppu):
        add(0x1104, "Operation.ZeroPosRange", "ZeroPosRange exceeds 40 bits in pulses")
    if not fits_position(lim.PosiSwLimit, ppu):
        add(0x1300, "Limit.PosiSwLimit", "PosiSwLimit exceeds 40 bits in pulses")
    if not fits_position(lim.NegaSwLimit, ppu):
        add(0x1301, "Limit.NegaSwLimit", "NegaSwLimit exceeds 40 bits in pulses")
    if not lim.PosiSwLimit > lim.NegaSwLimit:
        add(0x1302, "Limit.PosiSwLimit", "PosiSwLimit must be greater than NegaSwLimit")
    if not fits_distance(lim.FollowingErrorOverVal, ppu):
        add(0x1303, "Limit.FollowingErrorOverVal", "FollowingErrorOverVal exceeds 40 bits in pulses")
    if lim.FollowingErrorOverVal < lim.FollowingErrorWarningVal:
        add(0x1304, "Limit.FollowingErrorWarningVal",
            "FollowingErrorWarningVal must not exceed FollowingErrorOverVal")
    ring = pc.ModuloMaxPosVal - pc.ModuloMinPosVal
    if rotary:
        if not fits_position(pc.ModuloMaxPosVal, ppu):
            add(0x1400, "PosCount.ModuloMaxPosVal", "ModuloMaxPosVal exceeds 40 bits in pulses")
        if not fits_position(pc.ModuloMinPosVal, ppu):
            add(0x1401, "PosCount.ModuloMinPosVal", "ModuloMinPosVal exceeds 40 bits in pulses")
        if ring * ppu < 2:
            add(0x1403, "PosCount.ModuloMaxPosVal", "the ring (ModuloMaxPosVal − ModuloMinPosVal) must be ≥ 2 pulses")
    if hm.Vel > op.MaxVel:
        add(0x1500, "Homing.Vel", "homing velocity must not exceed MaxVel")
    if not hm.ApproachVel <= hm.Vel:
        add(0x1501, "Homing.ApproachVel", "homing approach velocity must not exceed homing velocity")
    if op.MaxAcc > 0 and hm.Acc > op.MaxAcc:
        add(0x1502, "Homing.Acc", "homing acceleration must not exceed MaxAcc")
    if op.MaxDec > 0 and hm.Dec > op.MaxDec:
        add(0x1503, "Homing.Dec", "homing deceleration must not exceed MaxDec")
    if not fits_distance(hm.HomeInputMaskDistance, ppu):
        add(0x1504, "Homing.HomeInputMaskDistance", "home input mask distance exceeds 40 bits in pulses")
    if rotary and hm.HomeInputMaskDistance > ring:
        add(0x1505, "Homing.HomeInputMaskDistance", "home input mask distance exceeds the ring length")
    if not fits_position(hm.HomeOffset, ppu):
        add(0x1506, "Homing.HomeOffset", "home offset exceeds 40 bits in pulses")
    if rotary and not (pc.ModuloMinPosVal <= hm.HomeOffset <= pc.ModuloMaxPosVal):
        add(0x1507, "Homing.HomeOffset", "home offset must lie inside the ring counter range")
    if not fits_distance(hm.CompensationVal, ppu):
        add(0x1508, "Homing.CompensationVal", "|homing compensation value| exceeds 40 bits in pulses")
    if rotary and abs(hm.CompensationVal) > ring:
        add(0x1509, "Homing.CompensationVal", "|homing compensation value| exceeds the ring length")
    if hm.CompensationVel > op.MaxVel:
        add(0x150A, "Homing.CompensationVel", "homing compensation velocity must not exceed MaxVel")
    return out


def check_project(project: Project, library: DeviceLibrary | None = None) -> list[Issue]:
    issues: list[Issue] = []
    names: dict[str, int] = {}
    numbers: dict[int, int] = {}
    nodes: dict[int, int] = {}
    for i, ax in enumerate(project.axes):
        base = f"axes[{i}]"
        if ax.name in names:
            issues.append(Issue(f"{base}.name", f"duplicate axis name {ax.name!r} (also axes[{names[ax.name]}])"))
        names.setdefault(ax.name, i)
        if ax.number in numbers:
            other = numbers[ax.number]
            issues.append(Issue(f"{base}.number", f"duplicate axis number {ax.number} (also axes[{other}])"))
        numbers.setdefault(ax.number, i)
        virtual = ax.type in (_eMC_AXIS_TYPE._mcVirServo, _eMC_AXIS_TYPE._mcVirEncdr)
        if virtual and ax.node_address is not None:
            issues.append(Issue(f"{base}.node_address", "a virtual axis has no node address; set it to null"))
        if not virtual and ax.node_address is None:
            issues.append(Issue(f"{base}.node_address", "a servo or encoder axis needs the node address of its slave"))
        if ax.node_address is not None:
            if ax.node_address in nodes:
                other = nodes[ax.node_address]
                issues.append(Issue(f"{base}.node_address",
                                    f"node address {ax.node_address} is already used by axes[{other}]"))
            nodes.setdefault(ax.node_address, i)
        for code, path, msg in check_axis_parameters(ax.parameters):
            issues.append(Issue(f"{base}.parameters.{path}", msg, f"573B/{code:04X}"))
        d = ax.drive
        if d.PositionLoop == "SecondOrder" and d.PositionLoopBandwidth > 0.25e6 / project.controller.primary_period_us:
            issues.append(Issue(f"{base}.drive.PositionLoopBandwidth",
                                f"{d.PositionLoopBandwidth:g} Hz is more than a quarter of the sampling frequency "
                                f"({1e6 / project.controller.primary_period_us:g} Hz) of the primary period"))
    issues.extend(check_groups(project))
    issues.extend(Issue(path, msg) for path, msg in check_network(project, library))
    issues.extend(Issue(path, msg, code) for path, msg, code in check_cams(project.cams))
    return issues


def check_groups(project: Project) -> list[Issue]:
    """Axes groups: unique names (also against axis names) and numbers; the composition axes exist, are used servo or
    virtual servo axes (543D otherwise at MC_GroupEnable), match the composition and belong to one group only; the
    operation settings' pulse limits per member axis; the Delta3 kinematics (MC_SetKinTransform's checks: 5708,
    570A, 571F; 5706 for the composition: three axes, linear count mode, unit degree)."""
    issues: list[Issue] = []
    names: dict[str, int] = {}
    numbers: dict[int, int] = {}
    owner: dict[str, int] = {}
    axis_names = {a.name for a in project.axes}
    for i, g in enumerate(project.groups):
        base = f"groups[{i}]"
        if g.name in names:
            issues.append(Issue(f"{base}.name", f"duplicate axes group name {g.name!r} (also groups[{names[g.name]}])"))
        elif g.name in axis_names:
            issues.append(Issue(f"{base}.name", f"{g.name!r} is already the name of an axis"))
        names.setdefault(g.name, i)
        if g.number in numbers:
            issues.append(Issue(f"{base}.number",
                                f"duplicate axes group number {g.number} (also groups[{numbers[g.number]}])"))
        numbers.setdefault(g.number, i)
        if len(g.axes) != g.axis_count:
            issues.append(Issue(f"{base}.axes", f"composition {g.composition.name} needs {g.axis_count} axes "
                                f"(A0…A{g.axis_count - 1}), {len(g.axes)} given"))
        seen: set[str] = set()
        for k, name in enumerate(g.axes):
            path = f"{base}.axes[{k}]"
            ax = project.axis(name)
            if name in seen:
                issues.append(Issue(path, f"axis {name!r} is assigned twice in this group"))
                continue
            seen.add(name)
            if ax is None:
                issues.append(Issue(path, f"no axis named {name!r}"))
                continue
            if ax.type not in (_eMC_AXIS_TYPE._mcServo, _eMC_AXIS_TYPE._mcVirServo):
                issues.append(Issue(path, f"{name} is {ax.type.name}; only servo and virtual servo axes can be "
                                    "composition axes", "543D"))
            if ax.use != _eMC_AXIS_USE._mcUsedAxis and g.use == _eMC_GROUP_USE._mcUsedGroup:
                issues.append(Issue(path, f"{name} is an unused axis"))
            if name in owner and owner[name] != i:
                issues.append(Issue(path, f"{name} is already a composition axis of groups[{owner[name]}]"))
            owner.setdefault(name, i)
        issues.extend(_group_operation_issues(project, g, base))
        if g.kinematics is not None:
            issues.extend(_kinematics_issues(project, g, base))
    return issues


def _group_operation_issues(project: Project, g: AxesGroupConfig, base: str) -> list[Issue]:
    out: list[Issue] = []
    op = g.operation
    for name in g.axes:
        ax = project.axis(name)
        if ax is None:
            continue
        rotary = ax.parameters.PosCount.CountMode == _eMC_COUNT_MODE._mcCountModeRotary
        if rotary and ax.parameters.PosCount.ModuloMaxPosVal <= ax.parameters.PosCount.ModuloMinPosVal:
            continue  # reported on the axis
        ppu = pulses_per_unit(ax.parameters)
        reported = {i.path for i in out}
        path = f"{base}.operation.MaxInterpolationVel"
        if op.MaxInterpolationVel * ppu > MAX_INTERPOLATION_VELOCITY_PULSES and path not in reported:
            out.append(Issue(path, f"{op.MaxInterpolationVel * ppu:.0f} pulse/s on {name}; the limit is "
                             f"{MAX_INTERPOLATION_VELOCITY_PULSES} pulse/s (2 × the MaxVel limit)"))
        for field in ("MaxInterpolationAcc", "MaxInterpolationDec"):
            v = getattr(op, field)
            path = f"{base}.operation.{field}"
            if v * ppu > MAX_INTERPOLATION_ACC_PULSES and path not in reported:
                out.append(Issue(path, f"{v * ppu:.0f} pulse/s² on {name}; the limit is 6.4e12 pulse/s²"))
    return out


def _kinematics_issues(project: Project, g: AxesGroupConfig, base: str) -> list[Issue]:
    out: list[Issue] = []
    kin = g.kinematics
    assert kin is not None
    path = f"{base}.kinematics"
    if g.composition != _eMC_GROUP_TYPE._mcXYZ:
        out.append(Issue(f"{base}.composition", "a Delta3 robot group has the composition _mcXYZ (3 axes)", "5706"))
    for k, name in enumerate(g.axes):
        ax = project.axis(name)
        if ax is None:
            continue
        if ax.parameters.PosCount.CountMode != _eMC_COUNT_MODE._mcCountModeLinear:
            out.append(Issue(f"{base}.axes[{k}]", f"{name}: a robot axis must be in linear count mode", "5706"))
        if ax.parameters.UnitConversion.UnitDisplay != _eMC_UNITS._mcDeg:
            out.append(Issue(f"{base}.axes[{k}]", f"{name}: the unit of a Delta3 axis must be degree", "5706"))
    # MC_SetKinTransform's ranges (5708/570A), then Delta3Params.check's geometric restrictions (571F).
    params = kin.params()
    res = check_kin_transform(KinParam=params.kin_param(), ExpansionParam=params.expansion_param(),
                              WorkspaceParam=kin.workspace_obj().workspace_param())
    if not res.ok:
        field = _KIN_PARAM_FIELDS.get(res.parameter, "")
        out.append(Issue(f"{path}.{field}" if field else path, res.message, f"{res.error_id:04X}"))
    return out
