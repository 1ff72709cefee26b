"""Axis administration instructions: MC_ImmediateStop, MC_SetPosition, MC_SetOverride, MC_ResetFollowingError,
MC_ZoneSwitch, MC_AxesObserve, MC_ChangeAxisUse (`omron-axis-instructions.md`, seed 000 chapter 3)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from .. import errors as E
from ..enums import AxisState
from ..jobs import Job, JobKind, JobStatus
from ..units import fits_position
from .base import (
    I_EXECUTE,
    IO_AXIS,
    O_ABORTED,
    O_ACTIVE,
    O_BUSY,
    O_DONE,
    O_ERROR,
    O_ERRORID,
    ExecuteFB,
    FBDef,
    FunctionBlock,
    OneShotFB,
    Var,
)

if TYPE_CHECKING:
    from ..axis import Axis

O_ENABLED = Var("Enabled", "BOOL", False, "TRUE while the instruction is in control")
I_ENABLE = Var("Enable", "BOOL", False, "TRUE: the instruction executes", dead_man=True)


class _EnableFB(FunctionBlock):
    """Enable-type instruction: Busy with Enable; Error sticky until the axis error is reset (or, for errors of the
    MC common source, until the instance is enabled again after a correction)."""

    def __init__(self, mc: Any, fb_id: int, inputs: dict[str, Any] | None = None) -> None:
        super().__init__(mc, fb_id, inputs)
        self._prev_enable = False
        self._common_error = False

    def call(self) -> None:
        o = self.out
        en = bool(self.inp["Enable"])
        changed = en != self._prev_enable
        self.__dict__["_prev_enable"] = en  # (hot path: bypasses FunctionBlock.__setattr__)
        if o["Error"] and (self._error_released() or (self._common_error and changed)):
            o["Error"] = False
            o["ErrorID"] = 0
            self._common_error = False
        if o["Error"]:
            return
        if not en:
            if changed:
                self.disable()
            o["Busy"] = False
            if "Enabled" in o:
                o["Enabled"] = False
            return
        o["Busy"] = True
        self.enabled(changed)

    def fail_common(self, code: int) -> None:
        """An error with source MC common (no effect on the axis): logged, the instance shows it."""
        self._set_error(code, None)
        self._common_error = True
        self.mc.log_error(code, axis=None, source=self.label)

    def enabled(self, changed: bool) -> None:
        raise NotImplementedError

    def disable(self) -> None:
        """Enable went FALSE."""


# --------------------------------------------------------------------------------------------------- ImmediateStop
class MC_ImmediateStop(OneShotFB):
    DEF = FBDef(
        name="MC_ImmediateStop",
        title="Immediate stop",
        summary="Stops the axis immediately by StopMode in any state; the axis goes to ErrorStop (5485).",
        kind="execute",
        inouts=(IO_AXIS,),
        inputs=(
            I_EXECUTE,
            Var("StopMode", "_eMC_STOP_MODE", 1, "1: immediate stop, 2: + following error reset, 3: servo OFF",
                None, "1, 2, 3", allowed=(1, 2, 3)),
        ),
        outputs=(O_DONE, O_BUSY, O_ABORTED, O_ERROR, O_ERRORID),
        spec="omron-axis-instructions.md MC_ImmediateStop (seed 000 line 6019)",
    )

    def execute(self, axis: Axis) -> None:
        mode = self.inp["StopMode"]
        if mode not in (1, 2, 3):
            self.fail(E.E_STOP_MODE, axis)
            return
        if axis.encoder:
            self.fail(E.E_AXIS_TYPE, axis)
            return
        if axis.state == AxisState.Coordinated:
            self.fail(E.E_COORDINATED, axis)  # column I: the group → e, the axis stays Coordinated (D70)
            return
        axis.immediate_stop(mode, self.label)
        self.done_next()


# --------------------------------------------------------------------------------------------------- SetPosition
class MC_SetPosition(OneShotFB):
    DEF = FBDef(
        name="MC_SetPosition",
        title="Set position",
        summary="Changes the command (and actual) current position to Position; the axis becomes home undefined.",
        kind="execute",
        inouts=(IO_AXIS,),
        inputs=(
            I_EXECUTE,
            Var("Position", "LREAL", 0.0, "New current position", "unit", "negative, positive or 0"),
            Var("ReferenceType", "_eMC_REFERENCE_TYPE", 0, "0: command position (servo axes), 1: feedback (encoder)",
                None, "0, 1", allowed=(0, 1)),
            Var("Relative", "BOOL", False, "Reserved"),
            Var("ExecutionMode", "_eMC_EXECUTION_MODE", 0, "Reserved", None, "0", allowed=(0,)),
        ),
        outputs=(O_DONE, O_BUSY, O_ABORTED, O_ERROR, O_ERRORID),
        spec="omron-axis-instructions.md MC_SetPosition (seed 000 line 6146)",
    )
    _BLOCKING = (JobKind.JOG, JobKind.HOMING, JobKind.TORQUE)  # + MC_TorqueControl: footnote *5

    def execute(self, axis: Axis) -> None:
        verdict, code = axis.check_start("set_position")
        if verdict == "abort":
            self._finish("CommandAborted")
            return
        i = self.inp
        ref = i["ReferenceType"]
        if ref not in (0, 1) or (ref == 0) == axis.encoder:
            code = code or E.E_POSITION_TYPE
        if i["Relative"]:
            code = code or 0x548F
        if i["ExecutionMode"] != 0:
            code = code or 0x5487
        pos = i["Position"]
        if not code and (not fits_position(pos, axis.ppu) or
                         (axis.rotary and not axis.mod_min <= pos <= axis.mod_max)):
            code = E.E_TARGET_POSITION
        cur = axis.current
        if not code and cur is not None and cur.running and (
            cur.kind in self._BLOCKING or cur.info.get("zero_position")
        ):
            code = E.E_MULTIEXEC_DISABLED  # not while jogging, homing or MC_MoveZeroPosition runs
        if code:
            self.fail(code, axis)
            return
        axis.set_position(axis.wrap(pos) if axis.rotary else pos)
        self.done_next()


# --------------------------------------------------------------------------------------------------- SetOverride
class MC_SetOverride(_EnableFB):
    DEF = FBDef(
        name="MC_SetOverride",
        title="Set override factors",
        summary="Scales the target velocity of the running motion (0.01–500 %, exactly 0 = pause).",
        kind="enable",
        inouts=(IO_AXIS,),
        inputs=(
            I_ENABLE,
            Var("VelFactor", "LREAL", 100.0, "Velocity override", "%", "0 to 500"),
            Var("AccFactor", "LREAL", 100.0, "Reserved", "%", "0 to 500"),
            Var("JerkFactor", "LREAL", 100.0, "Reserved", "%", "0 to 500"),
        ),
        outputs=(O_ENABLED, O_BUSY, O_ERROR, O_ERRORID),
        spec="omron-axis-instructions.md MC_SetOverride (seed 000 line 6331), omron-mc-basics.md §2.6 (VelFactor)",
    )

    def _axis(self) -> Axis | None:
        return self.resolve_axis()

    @staticmethod
    def effective(factor: float) -> float:
        """§2.6: exactly 0 → 0; below 0.01 (incl. negative) → 0.01; above 500 → 500."""
        if factor == 0.0:
            return 0.0
        return min(500.0, max(0.01, factor))

    def enabled(self, changed: bool) -> None:
        axis = self._axis()
        if axis is None:
            self.fail(E.E_ILLEGAL_AXIS, None)
            return
        if axis.encoder:
            self.fail(E.E_AXIS_TYPE, axis)  # MC_SetOverride on an encoder axis → H
            return
        i = self.inp
        for name, code in (("AccFactor", 0x5470), ("JerkFactor", 0x546F)):
            if not 0.0 <= i[name] <= 500.0:
                self.fail(code, axis)
                return
        axis.set_override(self.id, self.effective(i["VelFactor"]), changed)
        self.out["Enabled"] = True
        self._axis_ref = axis

    def disable(self) -> None:
        axis = getattr(self, "_axis_ref", None)
        if axis is not None:
            axis.set_override(self.id, None, True)


# ----------------------------------------------------------------------------------------------- ResetFollowingError
class MC_ResetFollowingError(ExecuteFB):
    DEF = FBDef(
        name="MC_ResetFollowingError",
        title="Reset following error counter",
        summary="Makes the actual position the command target: the following error becomes 0 (axis Stopping).",
        kind="execute",
        inouts=(IO_AXIS,),
        inputs=(I_EXECUTE,
                Var("BufferMode", "_eMC_BUFFER_MODE", 0, "Only _mcAborting", None, "0", allowed=(0,))),
        outputs=(O_DONE, O_BUSY, O_ACTIVE, O_ABORTED, O_ERROR, O_ERRORID),
        spec="omron-axis-instructions.md MC_ResetFollowingError (seed 000 line 6466)",
    )

    def execute(self, axis: Axis) -> None:
        verdict, code = axis.check_start("reset_fe")
        if verdict == "abort":
            self._finish("CommandAborted")
            return
        if not code and self.inp["BufferMode"] != 0:
            code = E.E_BUFFER_MODE
        if code:
            self.fail(code, axis)
            return
        cur = axis.current
        if cur is not None and cur.kind == JobKind.STOP:
            axis._end_job(cur, JobStatus.DONE)  # MC_Stop running + MC_ResetFollowingError → MC_Stop Done
        job = Job(JobKind.RESET_FE, self, target=float(axis.m.act_pos[axis.i]))
        axis.abort_all()
        axis._start(job)
        self.job = job


# --------------------------------------------------------------------------------------------------- ZoneSwitch
class MC_ZoneSwitch(_EnableFB):
    DEF = FBDef(
        name="MC_ZoneSwitch",
        title="Zone monitor",
        summary="InZone while the command or actual position lies between FirstPosition and LastPosition.",
        kind="enable",
        inouts=(IO_AXIS,),
        inputs=(
            I_ENABLE,
            Var("FirstPosition", "LREAL", 0.0, "Zone start", "unit", "negative, positive or 0"),
            Var("LastPosition", "LREAL", 0.0, "Zone end", "unit", "negative, positive or 0"),
            Var("ReferenceType", "_eMC_REFERENCE_TYPE", 0, "0: command position, 1: actual position", None,
                "0, 1", allowed=(0, 1)),
        ),
        outputs=(O_ENABLED, Var("InZone", "BOOL", False, "TRUE while the position is inside the zone"), O_BUSY,
                 O_ERROR, O_ERRORID),
        spec="omron-axis-instructions.md MC_ZoneSwitch (seed 000 line 11118)",
    )

    def enabled(self, changed: bool) -> None:
        axis = self.resolve_axis()
        if axis is None:
            self.fail(E.E_ILLEGAL_AXIS, None)
            return
        i = self.inp
        first, last, ref = i["FirstPosition"], i["LastPosition"], i["ReferenceType"]
        code = 0
        if ref not in (0, 1) or (axis.encoder and ref != 1):
            code = E.E_POSITION_TYPE
        elif not fits_position(first, axis.ppu) or (axis.rotary and not axis.mod_min <= first <= axis.mod_max):
            code = 0x5469
        elif not fits_position(last, axis.ppu) or (axis.rotary and not axis.mod_min <= last <= axis.mod_max):
            code = 0x546A
        elif not axis.rotary and last < first:
            code = 0x546B
        if code:
            self.fail(code, axis)
            return
        pos = axis.act_pos if ref == 1 else axis.cmd_pos
        # first > last: a rotary zone across the ring limits
        inside = first <= pos <= last if first <= last else (pos >= first or pos <= last)
        self.out["Enabled"] = True
        self.out["InZone"] = inside

    def disable(self) -> None:
        self.out["InZone"] = False


# --------------------------------------------------------------------------------------------------- AxesObserve
class MC_AxesObserve(_EnableFB):
    DEF = FBDef(
        name="MC_AxesObserve",
        title="Monitor axis following error",
        summary="Invalid while |master − slave| exceeds PermittedDeviation (does not affect motion).",
        kind="enable",
        inouts=(Var("Master", "_sAXIS_REF", None, "Master axis"), Var("Slave", "_sAXIS_REF", None, "Slave axis")),
        inputs=(
            I_ENABLE,
            Var("ReferenceType", "_eMC_REFERENCE_TYPE", 0, "0: command position, 1: actual position", None,
                "0, 1", allowed=(0, 1)),
            Var("PermittedDeviation", "LREAL", 0.0, "Maximum permitted difference", "unit", "positive or 0"),
        ),
        outputs=(O_ENABLED, Var("Invalid", "BOOL", False, "TRUE while the deviation exceeds the permitted value"),
                 O_BUSY, Var("DeviatedValue", "LREAL", 0.0, "Master − slave position", "unit"), O_ERROR, O_ERRORID),
        spec="omron-axis-instructions.md MC_AxesObserve (seed 000 line 11972)",
    )

    def enabled(self, changed: bool) -> None:
        master, slave = self.resolve_axis("Master"), self.resolve_axis("Slave")
        if master is None or slave is None:
            self.fail_common(E.E_ILLEGAL_AXIS if slave is None else 0x5462)
            return
        i = self.inp
        ref = i["ReferenceType"]
        if ref not in (0, 1) or ((master.encoder or slave.encoder) and ref != 1):
            self.fail_common(E.E_POSITION_TYPE)
            return
        if not i["PermittedDeviation"] >= 0:
            self.fail_common(0x5488)
            return
        pm = master.act_pos if ref == 1 else master.cmd_pos
        ps = slave.act_pos if ref == 1 else slave.cmd_pos
        dev = pm - ps
        if master.rotary and slave.rotary and master.mod_min == slave.mod_min and master.mod_max == slave.mod_max:
            span = master.mod_max - master.mod_min
            dev = (dev + span / 2) % span - span / 2  # the shorter way round the ring, signed
        self.out["DeviatedValue"] = dev
        self.out["Invalid"] = abs(dev) > i["PermittedDeviation"]
        self.out["Enabled"] = True

    def disable(self) -> None:
        self.out["Invalid"] = False  # DeviatedValue keeps its last value


# --------------------------------------------------------------------------------------------------- ChangeAxisUse
class MC_ChangeAxisUse(OneShotFB):
    DEF = FBDef(
        name="MC_ChangeAxisUse",
        title="Change axis use",
        summary="Temporarily switches an axis between used and unused (not saved).",
        kind="execute",
        inouts=(IO_AXIS,),
        inputs=(I_EXECUTE,
                Var("AxisUse", "_eMC_AXIS_USE", 1, "1: unused axis, 2: used axis", None, "1, 2", allowed=(1, 2))),
        outputs=(O_DONE, O_BUSY, O_ABORTED, O_ERROR, O_ERRORID),
        spec="omron-axis-instructions.md MC_ChangeAxisUse (seed 000 line 12758)",
    )

    def resolve_axis(self, name_input: str = "Axis", *, allow_unused: bool = True) -> Axis | None:
        # works on unused axes too
        return super().resolve_axis(name_input, allow_unused=True)

    def execute(self, axis: Axis) -> None:
        use = self.inp["AxisUse"]
        if use not in (1, 2):
            # source "MC common/Axis" (A-1 #121): an axis error on a used axis, an MC common error on an unused one
            # (MC_ChangeAxisUse rules, omron-axis-instructions.md line 1858)
            self.fail(0x549E, axis if axis.used else None)
            return
        if use == 1 and axis.used:
            if axis.state not in (AxisState.Disabled, AxisState.Standstill):
                # 5702 is an axis minor fault: the axis goes to ErrorStop (A-3.4 row MC_ChangeAxisUse, C–H → H)
                self.fail(0x5702, axis)
                return
            axis.used = False
            axis.wake_power()
            axis.homed = False  # switching to unused makes home undefined
        elif use == 2 and not axis.used:
            axis.used = True
            axis.wake_power()
            axis.error_code = 0
        self.mc.log_info(axis, f"{axis.name} is now a {'used' if axis.used else 'unused'} axis")
        self.done_next()


ADMIN_CLASSES: tuple[type[FunctionBlock], ...] = (
    MC_ImmediateStop,
    MC_SetPosition,
    MC_SetOverride,
    MC_ResetFollowingError,
    MC_ZoneSwitch,
    MC_AxesObserve,
    MC_ChangeAxisUse,
)
