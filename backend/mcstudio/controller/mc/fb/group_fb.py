"""Axes-group instructions (`omron-group-and-cam.md` chapter 4, seed 000 lines 14384–17345): MC_GroupEnable,
MC_GroupDisable, MC_GroupReset, MC_GroupStop, MC_GroupImmediateStop, MC_GroupSetOverride, MC_GroupReadPosition,
MC_ChangeAxesInGroup, and the in-out / input definitions shared with the motion instructions (MC_GroupSyncMoveAbsolute,
MC_MoveLinear, MC_MoveLinearAbsolute, MC_MoveLinearRelative, MC_MoveCircular2D: `group_motion_fb.py`).

The instances use the Execute/Enable timing of the single-axis instructions (`base.py`); the in-out `AxesGroup` names a
group variable and takes the place of `Axis`: the group's `reset_generation` releases the Error outputs (MC_GroupReset)
and errors of these instructions are group minor faults (A-1 source "Group"), logged with the group's name.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from .. import errors as E
from ..group import (
    E_CHANGE_AXES,
    E_GROUP_DISABLED,
    E_ILLEGAL_GROUP,
    AxesGroup,
)
from ..jobs import Job, JobKind
from .admin import I_ENABLE, O_ENABLED, _EnableFB
from .base import (
    I_EXECUTE,
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

SPEC = "omron-group-and-cam.md"
IO_GROUP = Var("AxesGroup", "_sGROUP_REF", None, "Axes group (name of the group variable, e.g. MC_Group000)")
I_POSITION4 = Var("Position", "ARRAY[0..3] OF LREAL", [0.0] * 4, "Target position of A0–A3", "unit",
                  "negative, positive or 0")
I_VELOCITY = Var("Velocity", "LREAL", 0.0, "Target interpolation velocity (must be set)", "unit/s", "positive")
I_ACC = Var("Acceleration", "LREAL", 0.0, "Interpolation acceleration (0 = step change)", "unit/s²", "positive or 0")
I_DEC = Var("Deceleration", "LREAL", 0.0, "Interpolation deceleration (0 = step change)", "unit/s²", "positive or 0")
I_JERK = Var("Jerk", "LREAL", 0.0, "Interpolation jerk (0 = trapezoid)", "unit/s³", "positive or 0")
I_COORD = Var("CoordSystem", "_eMC_COORD_SYSTEM", 0, "Coordinate system (only _mcACS)", None, "0")
I_BUFFER = Var("BufferMode", "_eMC_BUFFER_MODE", 0, "Behaviour on multi-execution", None, "0–5")
I_TRANSITION = Var("TransitionMode", "_eMC_TRANSITION_MODE", 0, "Path at the junction (blending only)", None,
                   "0, 10")
I_MOVEMODE = Var("MoveMode", "_eMC_MOVE_MODE", 0, "Absolute or relative", None, "0, 1", allowed=(0, 1))
MOTION_OUTPUTS = (O_DONE, O_BUSY, O_ACTIVE, O_ABORTED, O_ERROR, O_ERRORID)
ONESHOT_OUTPUTS = (O_DONE, O_BUSY, O_ABORTED, O_ERROR, O_ERRORID)


class _GroupRef:
    """Resolves the AxesGroup in-out instead of an axis; 5461 for a group that does not exist or is unused."""

    mc: Any
    inp: dict[str, Any]

    def resolve_axis(self, name_input: str = "AxesGroup", *, allow_unused: bool = False) -> Any:
        return self.mc.groups_by_name.get(self.inp.get("AxesGroup") or "")

    def fail(self, code: int, axis: Any, *, fault_axis: bool = True) -> None:
        if axis is None and code == E.E_ILLEGAL_AXIS:
            code = E_ILLEGAL_GROUP
        FunctionBlock.fail(self, code, axis, fault_axis=fault_axis)  # type: ignore[arg-type]


class _GroupOneShot(_GroupRef, OneShotFB):
    pass


# --------------------------------------------------------------------------------------------------- enable/disable
class MC_GroupEnable(_GroupOneShot):
    DEF = FBDef(
        name="MC_GroupEnable", title="Enable axes group",
        summary="Enables the axes group: its composition axes become Coordinated; group motion can start.",
        kind="execute", inouts=(IO_GROUP,), inputs=(I_EXECUTE,), outputs=ONESHOT_OUTPUTS,
        spec=f"{SPEC} §4.1 (seed 000 line 14384), §0.4",
    )

    def execute(self, axis: Any) -> None:
        group: AxesGroup = axis
        result = group.enable()
        if isinstance(result, int):
            self.fail(result, group)
            return
        self.done_next("Done" if result == "done" else "CommandAborted")


class MC_GroupDisable(_GroupOneShot):
    DEF = FBDef(
        name="MC_GroupDisable", title="Disable axes group",
        summary="Disables the axes group; running and buffered group instructions are aborted, moving axes "
                "decelerate at their Maximum Deceleration.",
        kind="execute", inouts=(IO_GROUP,), inputs=(I_EXECUTE,), outputs=ONESHOT_OUTPUTS,
        spec=f"{SPEC} §4.2 (seed 000 line 14486), §0.4",
    )

    def execute(self, axis: Any) -> None:
        axis.disable()
        self.done_next()


class MC_GroupReset(_GroupOneShot):
    """§4.13: composition axes with a drive error get the CiA402 fault reset first, all at once, each until its drive
    clears or its Drive Error Reset Monitoring Time elapses (Failure if a drive still reports the fault); then the
    group and axis errors are cleared (MC_Reset's procedure for the members, decision D108)."""

    DEF = FBDef(
        name="MC_GroupReset", title="Reset axes group error",
        summary="Clears the errors of the group and of its composition axes (drive errors first, with the Drive Error "
                "Reset Monitoring Time); Failure while they still decelerate or a drive keeps its fault.",
        kind="execute", inouts=(IO_GROUP,), inputs=(I_EXECUTE,),
        outputs=(O_DONE, O_BUSY, Var("Failure", "BOOL", False, "TRUE when the reset could not be performed"),
                 O_ERROR, O_ERRORID),
        spec=f"{SPEC} §4.13 (seed 000 line 17219)",
    )

    _group: AxesGroup | None = None
    _deadlines: dict[int, int] | None = None  # axis index → last cycle of its drive error reset

    def execute(self, axis: Any) -> None:
        group: AxesGroup = axis
        if group.reset_failure_cause():
            self.done_next("Failure")
            return
        faulted = group.drive_faults()
        if faulted:
            m = group.m
            self._group = group
            self._deadlines = {}
            for a in faulted:
                ms = a.params.OtherOperation.DriveErrorResetMonitoringTime
                self._deadlines[a.i] = m.cycle + max(1, round(ms * 1e-3 / m.period_s))
                m.fault_reset_req[a.i] = True
            m._fault_resets = True
            return
        self.done_next("Done" if group.reset() else "Failure")

    def reexecute(self, axis: Any) -> None:
        """Re-execution is ignored (§4.13): a drive error reset in progress continues."""

    def sync_job(self) -> None:
        group, deadlines = self._group, self._deadlines
        if group is None or deadlines is None:
            super().sync_job()
            return
        m = group.m
        for i, last in list(deadlines.items()):
            if not m.drv_fault[i] or m.cycle >= last:
                m.fault_reset_req[i] = False
                del deadlines[i]
        if deadlines:
            return
        self._group = self._deadlines = None
        still = any(m.drv_fault[a.i] for a in group.axes)
        self._finish("Failure" if still else ("Done" if group.reset() else "Failure"))

    def on_delete(self) -> None:
        if self._group is not None and self._deadlines:
            for i in self._deadlines:
                self._group.m.fault_reset_req[i] = False
        super().on_delete()


class MC_GroupImmediateStop(_GroupOneShot):
    DEF = FBDef(
        name="MC_GroupImmediateStop", title="Axes group immediate stop",
        summary="Stops every composition axis immediately by its Immediate Stop Input Stop Method; the group goes to "
                "ErrorStop (5486).",
        kind="execute", inouts=(IO_GROUP,), inputs=(I_EXECUTE,), outputs=ONESHOT_OUTPUTS,
        spec=f"{SPEC} §4.8 (seed 000 line 16589)",
    )

    def execute(self, axis: Any) -> None:
        group: AxesGroup = axis
        verdict, code = group.check_start("immediate_stop")
        if verdict == "error":
            self.fail(code, group)
            return
        group.immediate_stop(self.label)
        self.done_next()


class MC_ChangeAxesInGroup(_GroupOneShot):
    DEF = FBDef(
        name="MC_ChangeAxesInGroup", title="Change composition axes",
        summary="Temporarily writes new axis numbers for A0–A3 (same composition); only while the group is disabled.",
        kind="execute",
        inouts=(IO_GROUP, Var("Axes", "ARRAY[0..3] OF UINT", [0] * 4, "New axis numbers of A0–A3", None, "0–255")),
        inputs=(I_EXECUTE,), outputs=ONESHOT_OUTPUTS,
        spec=f"{SPEC} §4.11 (seed 000 line 16923)",
    )

    def execute(self, axis: Any) -> None:
        group: AxesGroup = axis
        verdict, code = group.check_start("change_axes")
        if verdict == "error":
            self.fail(code, group)
            return
        by_number = {a.number: a for a in group.m.axes}
        new: list[Axis] = []
        for num in self.inp["Axes"][: len(group.axes)]:
            a = by_number.get(num)
            if a is None or a.encoder or not a.used or a in new:
                self.fail(E_CHANGE_AXES, group)
                return
            new.append(a)
        group.change_axes(new)
        self.done_next()


# --------------------------------------------------------------------------------------------------- stop
class MC_GroupStop(_GroupRef, ExecuteFB):
    DEF = FBDef(
        name="MC_GroupStop", title="Axes group stop",
        summary="Decelerates the group along its path to a stop; the group stays Stopping while Execute is TRUE.",
        kind="execute", inouts=(IO_GROUP,),
        inputs=(I_EXECUTE,
                Var("Deceleration", "LREAL", 0.0, "Deceleration (0 = immediate stop)", "unit/s²", "positive or 0"),
                Var("Jerk", "LREAL", 0.0, "Jerk", "unit/s³", "positive or 0"),
                Var("BufferMode", "_eMC_BUFFER_MODE", 0, "Only _mcAborting", None, "0", allowed=(0,))),
        outputs=MOTION_OUTPUTS,
        spec=f"{SPEC} §4.7 (seed 000 line 16384)",
    )

    def __init__(self, mc: Any, fb_id: int, inputs: dict[str, Any] | None = None) -> None:
        super().__init__(mc, fb_id, inputs)
        self._holding: AxesGroup | None = None

    def execute(self, axis: Any) -> None:
        group: AxesGroup = axis
        i = self.inp
        verdict, code = group.check_start("stop")
        if verdict == "abort":
            self._finish("CommandAborted")
            return
        if not code:
            code = (E.E_DECELERATION if i["Deceleration"] < 0 else E.E_JERK if i["Jerk"] < 0
                    else E.E_BUFFER_MODE if i["BufferMode"] != 0 else 0)
        if code:
            self.fail(code, group)
            return
        job = Job(JobKind.GROUP_STOP, self, deceleration=i["Deceleration"], jerk=i["Jerk"])
        group.stop(job)
        self.job = job
        self._holding = group
        group.hold_stop(self.id, True)

    def reexecute(self, axis: Any) -> None:
        job = self.job
        if job is None:
            return
        if self.inp["Deceleration"] < 0:
            self.fail(E.E_DECELERATION, axis)
            return
        job.deceleration = self.inp["Deceleration"]
        axis.restop(job)

    def _release(self) -> None:
        if self._holding is not None:
            self._holding.hold_stop(self.id, False)
            self._holding = None

    def after_call(self, exe: bool) -> None:
        if not exe:
            self._release()

    def on_delete(self) -> None:
        # D133: deleting an instance that holds the group in Stopping releases it as Execute falling would; nothing
        # else could (the group stayed in Stopping and refused every motion)
        self._release()
        super().on_delete()


# --------------------------------------------------------------------------------------------------- override, read
class MC_GroupSetOverride(_GroupRef, _EnableFB):
    DEF = FBDef(
        name="MC_GroupSetOverride", title="Set axes group override",
        summary="Scales the interpolation velocity of the running linear/circular interpolation (0.01–500 %, "
                "exactly 0 = pause in Moving).",
        kind="enable", inouts=(IO_GROUP,),
        inputs=(I_ENABLE, Var("VelFactor", "LREAL", 100.0, "Velocity override", "%", "0 to 500"),
                Var("AccFactor", "LREAL", 100.0, "Reserved", "%", "0 to 500"),
                Var("JerkFactor", "LREAL", 100.0, "Reserved", "%", "0 to 500")),
        outputs=(O_ENABLED, O_BUSY, O_ERROR, O_ERRORID),
        spec=f"{SPEC} §4.9 (seed 000 line 16694)",
    )

    def enabled(self, changed: bool) -> None:
        group = self.resolve_axis()
        if group is None:
            self.fail(E_ILLEGAL_GROUP, None)
            return
        i = self.inp
        for name, code in (("AccFactor", 0x5470), ("JerkFactor", 0x546F)):
            if not 0.0 <= i[name] <= 500.0:
                self.fail(code, group)
                return
        f = i["VelFactor"]
        f = 0.0 if f == 0.0 else min(500.0, max(0.01, f))
        group.set_override(self.id, f, changed)
        self.out["Enabled"] = True
        self._group = group

    def disable(self) -> None:
        group = getattr(self, "_group", None)
        if group is not None:
            group.set_override(self.id, None, True)


class MC_GroupReadPosition(_GroupRef, _EnableFB):
    DEF = FBDef(
        name="MC_GroupReadPosition", title="Read axes group position",
        summary="Command and actual positions of A0–A3 every period while Enable is TRUE (enabled or not, homed or "
                "not).",
        kind="enable", inouts=(IO_GROUP,), inputs=(I_ENABLE, I_COORD),
        outputs=(Var("Valid", "BOOL", False, "TRUE while the outputs are valid"), O_BUSY, O_ERROR, O_ERRORID,
                 Var("CommandPosition", "ARRAY[0..3] OF LREAL", [0.0] * 4, "Command current position of A0–A3",
                     "unit"),
                 Var("ActualPosition", "ARRAY[0..3] OF LREAL", [0.0] * 4, "Actual current position of A0–A3",
                     "unit")),
        spec=f"{SPEC} §4.10 (seed 000 line 16812)",
    )

    def enabled(self, changed: bool) -> None:
        group = self.resolve_axis()
        if group is None:
            self.fail(E_ILLEGAL_GROUP, None)
            return
        if self.inp["CoordSystem"] != 0:
            self.fail(0x542C, group)
            return
        m = group.m
        cmd = [a.wrap(float(m.cmd_pos[a.i])) for a in group.axes]
        act = [a.wrap(float(m.act_pos[a.i])) for a in group.axes]
        pad = [0.0] * (4 - len(cmd))
        o = self.out
        o["CommandPosition"] = cmd + pad
        o["ActualPosition"] = act + pad
        o["Valid"] = True

    def call(self) -> None:
        super().call()
        o = self.out
        if not o["Busy"] or o["Error"]:
            o["Valid"] = False


# the instructions of this module, in catalogue order (the motion instructions follow in `group_motion_fb.py`)
GROUP_ADMIN_CLASSES: tuple[type[FunctionBlock], ...] = (
    MC_GroupEnable, MC_GroupDisable, MC_GroupReset, MC_GroupStop, MC_GroupImmediateStop, MC_GroupSetOverride,
    MC_GroupReadPosition, MC_ChangeAxesInGroup,
)
_ = E_GROUP_DISABLED  # re-exported for tests
