"""Axes-group motion instructions (`omron-group-and-cam.md` §4.3–§4.6, §4.12, seed 000 lines 14568–16383 and
17041–17218): MC_MoveLinear, MC_MoveLinearAbsolute, MC_MoveLinearRelative, MC_MoveCircular2D and
MC_GroupSyncMoveAbsolute — the input checks and the submission to the group (`group_planning.py`); the shared
in-out and input definitions and the other group instructions are in `group_fb.py`.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from .. import errors as E
from ..enums import _eMC_BUFFER_MODE, _eMC_DIRECTION
from ..group import E_COUNT_MODE, AxesGroup, transition_error
from ..group_path import LinePath, Path, border_arc, centre_arc, radius_arc
from ..jobs import Job, JobKind, JobStatus
from ..units import fits_distance, fits_position
from .base import I_EXECUTE, O_ABORTED, O_ACTIVE, O_BUSY, O_ERROR, O_ERRORID, ExecuteFB, FBDef, FunctionBlock, Var
from .group_fb import (
    GROUP_ADMIN_CLASSES,
    I_ACC,
    I_BUFFER,
    I_COORD,
    I_DEC,
    I_JERK,
    I_MOVEMODE,
    I_POSITION4,
    I_TRANSITION,
    I_VELOCITY,
    IO_GROUP,
    MOTION_OUTPUTS,
    SPEC,
    _GroupRef,
)

if TYPE_CHECKING:
    from ..axis import Axis


# --------------------------------------------------------------------------------------------------- motion
class _GroupMotionFB(_GroupRef, ExecuteFB):
    """Common input checks and submission of the interpolation instructions (§4.3–§4.6)."""

    ABSOLUTE: bool | None = True  # None: by MoveMode

    def absolute(self) -> bool:
        if self.ABSOLUTE is None:
            return int(self.inp["MoveMode"]) == 0
        return self.ABSOLUTE

    def common_error(self) -> int:
        i = self.inp
        if i["CoordSystem"] != 0:
            return 0x542C
        if i["BufferMode"] not in tuple(int(b) for b in _eMC_BUFFER_MODE):
            return E.E_BUFFER_MODE
        code = transition_error(int(i["BufferMode"]), int(i["TransitionMode"]))
        if code:
            return code
        if "MoveMode" in i and i["MoveMode"] not in (0, 1):
            return E.E_MOVE_MODE
        if not i["Velocity"] > 0:
            return E.E_VELOCITY
        if i["Acceleration"] < 0:
            return E.E_ACCELERATION
        if i["Deceleration"] < 0:
            return E.E_DECELERATION
        if i["Jerk"] < 0:
            return E.E_JERK
        return 0

    def specific_error(self, group: AxesGroup) -> int:
        return 0

    def builder(self, group: AxesGroup) -> Callable[[tuple[float, ...]], Path | int]:
        raise NotImplementedError

    def may_start(self, group: AxesGroup, input_error: int) -> bool:
        """The start checks in the manual's order: input errors, the group's state (CommandAborted or an error), the
        composition axes (servo, home, MC_Stop, limit inputs: for every group motion instruction, including
        MC_GroupSyncMoveAbsolute, D130), the instruction's own checks. False: the instance already shows why it did
        not start."""
        if input_error:
            self.fail(input_error, group)
            return False
        verdict, code = group.check_start("move")
        if verdict == "abort":
            self._finish("CommandAborted")
            return False
        code = code if verdict == "error" else group.member_error() or self.specific_error(group)
        if code:
            self.fail(code, group)
            return False
        return True

    def execute(self, axis: Any) -> None:
        group: AxesGroup = axis
        if not self.may_start(group, self.common_error() or (0 if group.kinematics is None else 0x5705)):
            return
        i = self.inp
        job = Job(JobKind.GROUP_MOVE, self, velocity=i["Velocity"], acceleration=i["Acceleration"],
                  deceleration=i["Deceleration"], jerk=i["Jerk"], buffer_mode=int(i["BufferMode"]),
                  overridable=True, blendable=True)
        job.info["build"] = self.builder(group)
        job.info["corner"] = int(i["TransitionMode"]) == 10
        code = group.submit(job)
        if code:
            self.fail(code, group)
            return
        self.job = job


def _sw_limit(axis: Axis, target: float) -> int:
    lim = axis.params.Limit
    if lim.SwLimitMode != 0 and not axis.rotary and axis.homed:
        if target > lim.PosiSwLimit:
            return E.E_POSI_SW_LIMIT
        if target < lim.NegaSwLimit:
            return E.E_NEGA_SW_LIMIT
    return 0


class _LinearFB(_GroupMotionFB):
    VALUES = "Position"

    def specific_error(self, group: AxesGroup) -> int:
        code = E.E_TARGET_POSITION if self.absolute() else E.E_TRAVEL_DISTANCE
        for a, v in zip(group.axes, self.inp[self.VALUES], strict=False):
            if not (fits_position(v, a.ppu) if self.absolute() else fits_distance(v, a.ppu)):
                return code
        return 0

    def builder(self, group: AxesGroup) -> Callable[[tuple[float, ...]], Path | int]:
        values = list(self.inp[self.VALUES])
        absolute = self.absolute()
        axes = list(group.axes)

        def build(start: tuple[float, ...]) -> Path | int:
            target = list(start)
            for k, a in enumerate(axes):
                if absolute:
                    # rotary axes: as single-axis absolute positioning with _mcNoDirection (§4.3 Position)
                    _, target[k] = a.resolve_target(values[k], _eMC_DIRECTION._mcNoDirection, base=start[k])
                else:
                    target[k] = start[k] + values[k]
                if not fits_position(target[k], a.ppu):
                    return E.E_TRAVEL_DISTANCE if not absolute else E.E_TARGET_POSITION
                code = _sw_limit(a, target[k])
                if code:
                    return code
            return LinePath.between(start, tuple(target))

        return build


_LINEAR_INPUTS = (I_EXECUTE, I_VELOCITY, I_ACC, I_DEC, I_JERK, I_COORD, I_BUFFER, I_TRANSITION)


class MC_MoveLinear(_LinearFB):
    ABSOLUTE = None
    DEF = FBDef(
        name="MC_MoveLinear", title="Linear interpolation",
        summary="Linear interpolation of the 2–4 composition axes to a position (absolute or relative by MoveMode).",
        kind="execute", inouts=(IO_GROUP,),
        inputs=(I_EXECUTE, I_POSITION4, *_LINEAR_INPUTS[1:], I_MOVEMODE), outputs=MOTION_OUTPUTS,
        spec=f"{SPEC} §4.3 (seed 000 line 14568)",
    )


class MC_MoveLinearAbsolute(_LinearFB):
    DEF = FBDef(
        name="MC_MoveLinearAbsolute", title="Absolute linear interpolation",
        summary="Linear interpolation of the composition axes to an absolute position.",
        kind="execute", inouts=(IO_GROUP,), inputs=(I_EXECUTE, I_POSITION4, *_LINEAR_INPUTS[1:]),
        outputs=MOTION_OUTPUTS, spec=f"{SPEC} §4.4 (seed 000 line 15433)",
    )


class MC_MoveLinearRelative(_LinearFB):
    ABSOLUTE = False
    VALUES = "Distance"
    DEF = FBDef(
        name="MC_MoveLinearRelative", title="Relative linear interpolation",
        summary="Linear interpolation of the composition axes by a distance from the start position.",
        kind="execute", inouts=(IO_GROUP,),
        inputs=(I_EXECUTE, Var("Distance", "ARRAY[0..3] OF LREAL", [0.0] * 4, "Travel distance of A0–A3", "unit",
                               "negative, positive or 0"), *_LINEAR_INPUTS[1:]),
        outputs=MOTION_OUTPUTS, spec=f"{SPEC} §4.5 (seed 000 line 15507)",
    )


class MC_MoveCircular2D(_GroupMotionFB):
    ABSOLUTE = None
    DEF = FBDef(
        name="MC_MoveCircular2D", title="Circular 2D interpolation",
        summary="Circular interpolation of two composition axes: border (via) point, centre or radius; full circles.",
        kind="execute", inouts=(IO_GROUP,),
        inputs=(I_EXECUTE,
                Var("CircAxes", "ARRAY[0..1] OF UINT", [0, 1], "Logical axes used as X and Y (0–3 = A0–A3)", None,
                    "0–3"),
                Var("CircMode", "_eMC_CIRC_MODE", 0, "Via (border) point, centre or radius", None, "0–2"),
                Var("AuxPoint", "ARRAY[0..1] OF LREAL", [0.0, 0.0], "Via point, centre, or radius in [0]", "unit"),
                Var("EndPoint", "ARRAY[0..1] OF LREAL", [0.0, 0.0], "End point", "unit"),
                Var("PathChoice", "_eMC_CIRC_PATHCHOICE", 0, "Direction (_mcCW/_mcCCW)", None, "0, 1"),
                *_LINEAR_INPUTS[1:], I_MOVEMODE),
        outputs=MOTION_OUTPUTS, spec=f"{SPEC} §4.6 (seed 000 line 15581)",
    )

    def common_error(self) -> int:
        i = self.inp
        if i["CircMode"] not in (0, 1, 2):
            return 0x542D
        if i["PathChoice"] not in (0, 1):
            return 0x542F
        return super().common_error()

    def specific_error(self, group: AxesGroup) -> int:
        i = self.inp
        ix, iy = i["CircAxes"]
        n = len(group.axes)
        if not (0 <= ix < n and 0 <= iy < n) or ix == iy:
            return 0x547E
        ax, ay = group.axes[ix], group.axes[iy]
        if ax.rotary or ay.rotary:
            return E_COUNT_MODE
        aux, end = i["AuxPoint"], i["EndPoint"]
        if i["CircMode"] == 2:
            if not fits_distance(abs(aux[0]), ax.ppu):
                return 0x5489
        elif not (fits_position(aux[0], ax.ppu) and fits_position(aux[1], ay.ppu)):
            return 0x5489
        if not (fits_position(end[0], ax.ppu) and fits_position(end[1], ay.ppu)):
            return 0x548A
        return 0

    def builder(self, group: AxesGroup) -> Callable[[tuple[float, ...]], Path | int]:
        i = self.inp
        ix, iy = int(i["CircAxes"][0]), int(i["CircAxes"][1])
        mode = int(i["CircMode"])
        aux, end = (float(i["AuxPoint"][0]), float(i["AuxPoint"][1])), (float(i["EndPoint"][0]),
                                                                         float(i["EndPoint"][1]))
        ccw = int(i["PathChoice"]) == 1
        absolute = self.absolute()
        ax, ay = group.axes[ix], group.axes[iy]
        allowance = group.op.CorrectionAllowanceRatio

        def build(start: tuple[float, ...]) -> Path | int:
            sx, sy = start[ix], start[iy]
            e = end if absolute else (sx + end[0], sy + end[1])
            a = aux if absolute or mode == 2 else (sx + aux[0], sy + aux[1])
            for axis, v in ((ax, e[0]), (ay, e[1])):
                code = _sw_limit(axis, v)
                if code:
                    return code
            if mode == 0:
                for axis, v in ((ax, a[0]), (ay, a[1])):
                    code = _sw_limit(axis, v)
                    if code:
                        return code
                path = border_arc(start, a, e, ix, iy, ccw, (1.0 / ax.ppu, 1.0 / ay.ppu))
            elif mode == 1:
                path = centre_arc(start, a, e, ix, iy, ccw, allowance)
            else:
                path = radius_arc(start, a[0], e, ix, iy, ccw)
            if not isinstance(path, int) and hasattr(path, "radius"):
                r = path.radius  # type: ignore[union-attr]
                if not (fits_distance(r, ax.ppu) and fits_distance(r, ay.ppu)):
                    return 0x547D
            return path

        return build


class MC_GroupSyncMoveAbsolute(_GroupMotionFB):
    DEF = FBDef(
        name="MC_GroupSyncMoveAbsolute", title="Axes group cyclic synchronous absolute positioning",
        summary="Outputs the program's absolute target of every composition axis each period (CSP), limited by each "
                "axis's Maximum Velocity; no Done, InPosition when all axes are in position.",
        kind="execute", inouts=(IO_GROUP,),
        inputs=(I_EXECUTE, I_POSITION4, I_COORD,
                Var("BufferMode", "_eMC_BUFFER_MODE", 0, "Only _mcAborting", None, "0", allowed=(0,))),
        outputs=(Var("InPosition", "BOOL", False, "TRUE while every axis is within its in-position range"), O_BUSY,
                 O_ACTIVE, O_ABORTED, O_ERROR, O_ERRORID),
        spec=f"{SPEC} §4.12 (seed 000 line 17041)",
    )

    def common_error(self) -> int:
        i = self.inp
        if i["CoordSystem"] != 0:
            return 0x542C
        if i["BufferMode"] != 0:
            return E.E_BUFFER_MODE
        return 0

    def specific_error(self, group: AxesGroup) -> int:
        for a, v in zip(group.axes, self.inp["Position"], strict=False):
            if a.rotary:
                return E_COUNT_MODE
            if not fits_position(v, a.ppu):
                return E.E_TARGET_POSITION
            code = _sw_limit(a, v)
            if code:
                return code
        return 0

    def execute(self, axis: Any) -> None:
        group: AxesGroup = axis
        if not self.may_start(group, self.common_error()):
            return
        job = Job(JobKind.GROUP_SYNC, self)
        code = group.submit(job)
        if code:
            self.fail(code, group)
            return
        self.job = job

    def sync_job(self) -> None:
        super().sync_job()
        job = self.job
        self.out["InPosition"] = job is not None and job.status == JobStatus.ACTIVE and job.in_velocity


GROUP_CLASSES: tuple[type[FunctionBlock], ...] = (
    *GROUP_ADMIN_CLASSES, MC_GroupSyncMoveAbsolute, MC_MoveLinear, MC_MoveLinearAbsolute, MC_MoveLinearRelative,
    MC_MoveCircular2D,
)
