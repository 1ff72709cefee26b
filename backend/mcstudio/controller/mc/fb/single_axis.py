"""Single-axis instructions: MC_Power, MC_Reset, MC_Stop, MC_MoveAbsolute, MC_MoveRelative, MC_MoveVelocity,
MC_MoveJog — inputs, outputs and rules as in `omron-axis-instructions.md` (seed 000, chapter 3).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from ....drives.cia402 import DI_NEGATIVE_LIMIT, DI_POSITIVE_LIMIT
from .. import errors as E
from ..enums import _eMC_BUFFER_MODE, _eMC_DIRECTION
from ..jobs import Job, JobKind, JobStatus
from ..units import fits_distance, fits_position
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

_DIRS = tuple(int(d) for d in _eMC_DIRECTION)
_BUFS = tuple(int(b) for b in _eMC_BUFFER_MODE)

I_VELOCITY = Var("Velocity", "LREAL", 0.0, "Target velocity", "unit/s", "positive")
I_ACC = Var("Acceleration", "LREAL", 0.0, "Acceleration (0 = step change)", "unit/s²", "positive or 0")
I_DEC = Var("Deceleration", "LREAL", 0.0, "Deceleration (0 = step change)", "unit/s²", "positive or 0")
I_JERK = Var("Jerk", "LREAL", 0.0, "Jerk (0 = trapezoid)", "unit/s³", "positive or 0")
I_DIRECTION = Var("Direction", "_eMC_DIRECTION", 0, "Direction (Rotary Mode only)", None, "0–4")
I_BUFFER = Var("BufferMode", "_eMC_BUFFER_MODE", 0, "Behaviour on multi-execution", None, "0–5")


def _clamp_profile(axis: Axis, velocity: float, acc: float, dec: float) -> tuple[float, float, float]:
    """§2.6 clamping: velocity to [1 pulse/s, MaxVel], acc/dec to the axis maxima (0 = no limit)."""
    op = axis.params.Operation
    v = min(velocity, op.MaxVel)
    if 0 < v * axis.ppu < 1.0:
        v = 1.0 / axis.ppu
    if op.MaxAcc > 0 and acc > op.MaxAcc:
        acc = op.MaxAcc
    if op.MaxDec > 0 and dec > op.MaxDec:
        dec = op.MaxDec
    return v, acc, dec


def _check_acc_dec_jerk(acc: float, dec: float, jerk: float) -> int:
    if acc < 0:
        return E.E_ACCELERATION
    if dec < 0:
        return E.E_DECELERATION
    if jerk < 0:
        return E.E_JERK
    return 0


# --------------------------------------------------------------------------------------------------- MC_Power
class MC_Power(FunctionBlock):
    DEF = FBDef(
        name="MC_Power",
        title="Power servo",
        summary="Puts the drive into the operation-ready state (servo ON) while Enable is TRUE.",
        kind="enable",
        inouts=(IO_AXIS,),
        inputs=(Var("Enable", "BOOL", False, "TRUE: servo ON; FALSE: servo OFF", dead_man=True),),
        outputs=(
            Var("Status", "BOOL", False, "TRUE when the axis is operation-ready (servo ON)"),
            O_BUSY,
            O_ERROR,
            O_ERRORID,
        ),
        spec="omron-axis-instructions.md MC_Power (seed 000 line 2456)",
    )

    def __init__(self, mc: Any, fb_id: int, inputs: dict[str, Any] | None = None) -> None:
        super().__init__(mc, fb_id, inputs)
        self._prev_enable = False
        self._fast: tuple[Axis, str] | None = None

    def call(self) -> None:
        o = self.out
        enable = bool(self.inp["Enable"])
        d = self.__dict__
        fast = d["_fast"]
        if fast is not None and enable is d["_prev_enable"] and not o["Error"]:
            # steady state: same axis, same Enable, this instance owns the axis and the request is already made —
            # the full path below would only refresh Busy and Status
            axis, name = fast
            if (self.inp["Axis"] == name and axis.used and axis.power_owner == self.id
                    and enable == axis.servo_request):
                o["Busy"] = enable
                o["Status"] = bool(axis.m.servo_on[axis.i])
                # nothing changes until Enable, the axis's servo state, request, owner or use changes: sleep (the
                # axis wakes its sleepers on each of those)
                self.sleep()
                axis.power_sleepers.append(self)
                return
        d["_fast"] = None
        changed = enable != self._prev_enable
        d["_prev_enable"] = enable  # (hot path: bypasses FunctionBlock.__setattr__)
        if o["Error"] and self._error_released():
            o["Error"] = False
            o["ErrorID"] = 0
        axis = self.resolve_axis()
        if axis is None:
            o["Busy"] = o["Status"] = False
            if enable and changed and not o["Error"]:
                self.fail(E.E_ILLEGAL_AXIS, None)
            return
        if o["Error"]:
            o["Busy"] = o["Status"] = False
            if not enable:
                axis.power(self.id, False, changed)
            return
        if enable and changed:
            if axis.encoder:
                self.fail(E.E_AXIS_TYPE, axis)
                return
            if axis.m.cfg_fault[axis.i]:
                self.fail(int(axis.m.cfg_fault[axis.i]), axis, fault_axis=False)  # 3460 (D29)
                return
            if not axis.m.pd_ok[axis.i]:
                self.fail(E.E_CONNECTION, axis, fault_axis=False)  # the slave is not in Op (D29)
                return
            if not axis.virtual and not (int(axis.m.drv[axis.i]) & 0x4):
                self.fail(E.E_MAIN_POWER_OFF, axis, fault_axis=True)
                return
        axis.power(self.id, enable, changed)
        o["Busy"] = enable
        o["Status"] = axis.servo_on
        d["_fast"] = (axis, self.inp["Axis"])


# --------------------------------------------------------------------------------------------------- MC_Reset
class MC_Reset(OneShotFB):
    DEF = FBDef(
        name="MC_Reset",
        title="Reset axis error",
        summary="Clears the axis error (and drive error). Fails while the axis still decelerates from the error.",
        kind="execute",
        inouts=(IO_AXIS,),
        inputs=(I_EXECUTE,),
        outputs=(
            O_DONE,
            O_BUSY,
            Var("Failure", "BOOL", False, "TRUE when the reset could not be performed (axis still stopping)"),
            O_ERROR,
            O_ERRORID,
        ),
        spec="omron-axis-instructions.md MC_Reset (seed 000 line 12664)",
    )

    _waiting: Axis | None = None
    _deadline = 0

    def execute(self, axis: Axis) -> None:
        m, i = axis.m, axis.i
        if m.cfg_fault[i] or not m.pd_ok[i]:
            # the cause persists (configuration error, slave not in process-data communication): like the axis
            # errors caused by MC common errors, the reset is not performed (omron-axis-instructions.md MC_Reset)
            self.done_next("Failure")
            return
        if m.drv_fault[i]:
            # drive error first: CiA402 fault reset until the drive clears or the Drive Error Reset Monitoring
            # Time elapses, then the axis error (MC_Reset functional rules)
            ms = axis.params.OtherOperation.DriveErrorResetMonitoringTime
            self._waiting = axis
            self._deadline = m.cycle + max(1, round(ms * 1e-3 / m.period_s))
            m.fault_reset_req[i] = True
            m._fault_resets = True
            return
        self.done_next("Done" if axis.reset() else "Failure")

    def reexecute(self, axis: Axis) -> None:
        """A new Execute edge while the drive reset runs: ignored, the reset in progress continues."""

    def sync_job(self) -> None:
        axis = self._waiting
        if axis is not None:
            m, i = axis.m, axis.i
            if not m.drv_fault[i] or m.cycle >= self._deadline:
                m.fault_reset_req[i] = False
                self._waiting = None
                self._finish("Failure" if m.drv_fault[i] else ("Done" if axis.reset() else "Failure"))
            return
        super().sync_job()

    def on_delete(self) -> None:
        if self._waiting is not None:
            self._waiting.m.fault_reset_req[self._waiting.i] = False
        super().on_delete()


# --------------------------------------------------------------------------------------------------- MC_Stop
class MC_Stop(ExecuteFB):
    DEF = FBDef(
        name="MC_Stop",
        title="Stop",
        summary="Decelerates the axis to a stop; the axis stays in Stopping while Execute is TRUE.",
        kind="execute",
        inouts=(IO_AXIS,),
        inputs=(
            I_EXECUTE,
            Var("Deceleration", "LREAL", 0.0, "Deceleration (0 = immediate stop)", "unit/s²", "positive or 0"),
            I_JERK,
            Var("BufferMode", "_eMC_BUFFER_MODE", 0, "Reserved: only _mcAborting", None, "0", allowed=(0,)),
        ),
        outputs=(O_DONE, O_BUSY, O_ACTIVE, O_ABORTED, O_ERROR, O_ERRORID),
        spec="omron-axis-instructions.md MC_Stop (seed 000 line 5817)",
    )

    def __init__(self, mc: Any, fb_id: int, inputs: dict[str, Any] | None = None) -> None:
        super().__init__(mc, fb_id, inputs)
        self._holding: Axis | None = None

    def execute(self, axis: Axis) -> None:
        i = self.inp
        if axis.state.name != "ErrorStop":
            code = _check_acc_dec_jerk(0.0, i["Deceleration"], i["Jerk"])
            if not code and i["BufferMode"] != 0:
                code = E.E_BUFFER_MODE
            if not code and axis.encoder:
                code = E.E_AXIS_TYPE
            if not code and axis.state.name == "Coordinated":
                code = E.E_COORDINATED  # column I: the group → e, the axis stays Coordinated (D70)
            if code:
                self.fail(code, axis)
                return
        dec = i["Deceleration"]
        if axis.params.Operation.MaxDec > 0:
            dec = min(dec, axis.params.Operation.MaxDec)
        job = Job(JobKind.STOP, self, deceleration=dec, jerk=i["Jerk"])
        verdict = axis.stop(job)
        if verdict == "abort":
            self._finish("CommandAborted")
            return
        if verdict == "done":
            job.status = JobStatus.DONE
        self.job = job
        self._holding = axis
        axis.hold_stop(self.id, True)

    def reexecute(self, axis: Axis) -> None:
        # Only Deceleration can change (Jerk is kept) — MC_Stop functional rules.
        job = self.job
        if job is None:
            return
        dec = self.inp["Deceleration"]
        if dec < 0:
            self.fail(E.E_DECELERATION, axis)
            return
        job.deceleration = dec
        axis.replan(job)

    def _release(self) -> None:
        if self._holding is not None:
            self._holding.hold_stop(self.id, False)
            self._holding = None

    def after_call(self, exe: bool) -> None:
        if not exe:
            self._release()

    def on_delete(self) -> None:
        # D133: deleting an instance that holds the axis in Stopping releases it as Execute falling would; nothing
        # else could (the axis stayed in Stopping and refused every motion)
        self._release()
        super().on_delete()


# --------------------------------------------------------------------------------------------------- start checks
def start_limit_error(axis: Axis, direction: int, target: float | None = None) -> int:
    """Checks at the start of a motion in `direction` (+1/−1, 0 = no defined direction), A-1 #142–146: an active
    limit input in the direction of motion (6443/6444) and, in Linear Mode with home defined, software limits for
    the target or for a start position already beyond a limit (6440/6441)."""
    m, i = axis.m, axis.i
    din = int(m.din[i])
    if din & DI_POSITIVE_LIMIT and direction >= 0:
        return E.E_POSI_LIMIT_INPUT
    if din & DI_NEGATIVE_LIMIT and direction <= 0:
        return E.E_NEGA_LIMIT_INPUT
    lim = axis.params.Limit
    if lim.SwLimitMode != 0 and not axis.rotary and axis.homed:
        cur = float(m.cmd_pos[i])
        if (target is not None and target > lim.PosiSwLimit) or (cur >= lim.PosiSwLimit and direction > 0):
            return E.E_POSI_SW_LIMIT
        if (target is not None and target < lim.NegaSwLimit) or (cur <= lim.NegaSwLimit and direction < 0):
            return E.E_NEGA_SW_LIMIT
    return 0


# --------------------------------------------------------------------------------------------------- motion base
_REEXEC_LATCHED = (("Jerk", E.E_REEXEC_JERK), ("BufferMode", E.E_REEXEC_BUFFER_MODE),
                   ("Direction", E.E_REEXEC_DIRECTION), ("MoveMode", 0x545E), ("Continuous", 0x545D))


class _MotionFB(ExecuteFB):
    """A motion instruction with a job: state check, input check, submit; re-execution with latched inputs whose
    change is the manual's 5458/5454/5455/545E/545D error (A-2.3, A-1 #60)."""

    KIND: JobKind
    ACCEPT = "move"  # acceptance class (acceptance.py)
    OVERRIDABLE = True  # the seven instructions MC_SetOverride names
    BLENDABLE = False

    def _check(self, axis: Axis) -> int:
        raise NotImplementedError

    def _fill(self, job: Job, axis: Axis) -> None:
        raise NotImplementedError

    def _limits(self, job: Job, axis: Axis) -> int:
        return 0

    def execute(self, axis: Axis) -> None:
        verdict, code = axis.check_start(self.ACCEPT)
        if verdict == "abort":
            self._finish("CommandAborted")
            return
        if code != E.E_AXIS_TYPE:  # an encoder axis is refused before anything else
            code = self._check(axis) or code  # D2: input errors before state errors
        if code:
            self.fail(code, axis)
            return
        i = self.inp
        job = Job(self.KIND, self, buffer_mode=i.get("BufferMode", 0), direction=i.get("Direction", 0),
                  overridable=self.OVERRIDABLE, blendable=self.BLENDABLE)
        job.info["latched"] = {k: i[k] for k, _ in _REEXEC_LATCHED if k in i}
        self._fill(job, axis)
        code = self._limits(job, axis)
        if code:
            self.fail(code, axis)
            return
        self._submit(axis, job, "ok", 0)

    def reexecute(self, axis: Axis) -> None:
        job = self.job
        if job is None:
            return
        latched = job.info["latched"]
        for name, code in _REEXEC_LATCHED:
            if name in latched and self.inp[name] != latched[name]:
                self.fail(code, axis)
                return
        code = self._check(axis)
        if code:
            self.fail(code, axis)
            return
        self._fill(job, axis)
        if "InVelocity" in self.out:
            self.out["InVelocity"] = False
        axis.replan(job)


# --------------------------------------------------------------------------------------------------- positioning
class _PositionFB(_MotionFB):
    KIND = JobKind.POSITION
    BLENDABLE = True

    def _target_inputs(self, axis: Axis) -> tuple[int, float, bool]:
        """(error code, absolute target or distance, relative?)."""
        raise NotImplementedError

    def _check(self, axis: Axis) -> int:
        i = self.inp
        v = i["Velocity"]
        if not v > 0:
            return E.E_VELOCITY
        code = _check_acc_dec_jerk(i["Acceleration"], i["Deceleration"], i["Jerk"])
        if code:
            return code
        if "Direction" in i and i["Direction"] not in _DIRS:
            return E.E_DIRECTION
        if i["BufferMode"] not in self._buffer_modes():
            return E.E_BUFFER_MODE
        code, _, _ = self._target_inputs(axis)
        return code

    def _buffer_modes(self) -> tuple[int, ...]:
        return _BUFS

    def _fill(self, job: Job, axis: Axis) -> None:
        i = self.inp
        job.velocity, job.acceleration, job.deceleration = _clamp_profile(
            axis, i["Velocity"], i["Acceleration"], i["Deceleration"]
        )
        job.jerk = i["Jerk"]
        _, value, relative = self._target_inputs(axis)
        job.relative = relative
        if relative:
            job.distance = value
            if job.origin is not None:
                job.target = job.origin + value  # re-execution measures from the original start
        else:
            job.absolute_target = value
            job.direction = i.get("Direction", _eMC_DIRECTION._mcNoDirection)
            _, job.target = axis.resolve_target(value, job.direction)

    def _limits(self, job: Job, axis: Axis) -> int:
        cur = float(axis.m.cmd_pos[axis.i])
        target = cur + job.distance if job.relative else job.target
        direction = 1 if target > cur else -1 if target < cur else 1
        return start_limit_error(axis, direction, target)


def _absolute_target(axis: Axis, pos: float, direction: int) -> tuple[int, float, bool]:
    if not fits_position(pos, axis.ppu):
        return E.E_TARGET_POSITION, pos, False
    if axis.rotary and direction != _eMC_DIRECTION._mcNoDirection and not axis.mod_min <= pos <= axis.mod_max:
        return E.E_TARGET_POSITION, pos, False
    return 0, pos, False


def _relative_distance(axis: Axis, d: float) -> tuple[int, float, bool]:
    if not fits_distance(d, axis.ppu):
        return E.E_TRAVEL_DISTANCE, d, True
    if not axis.rotary and not fits_position(float(axis.m.cmd_pos[axis.i]) + d, axis.ppu):
        return E.E_TRAVEL_DISTANCE, d, True
    return 0, d, True


class MC_MoveAbsolute(_PositionFB):
    DEF = FBDef(
        name="MC_MoveAbsolute",
        title="Absolute positioning",
        summary="Positions to a target given in absolute coordinates.",
        kind="execute",
        inouts=(IO_AXIS,),
        inputs=(
            I_EXECUTE,
            Var("Position", "LREAL", 0.0, "Target position (absolute)", "unit", "negative, positive or 0"),
            I_VELOCITY,
            I_ACC,
            I_DEC,
            I_JERK,
            I_DIRECTION,
            I_BUFFER,
        ),
        outputs=(O_DONE, O_BUSY, O_ACTIVE, O_ABORTED, O_ERROR, O_ERRORID),
        spec="omron-axis-instructions.md MC_MoveAbsolute (seed 000 line 3491)",
    )

    def _target_inputs(self, axis: Axis) -> tuple[int, float, bool]:
        return _absolute_target(axis, self.inp["Position"], self.inp["Direction"])


class MC_MoveRelative(_PositionFB):
    DEF = FBDef(
        name="MC_MoveRelative",
        title="Relative positioning",
        summary="Positions by a travel distance from the command current position.",
        kind="execute",
        inouts=(IO_AXIS,),
        inputs=(
            I_EXECUTE,
            Var("Distance", "LREAL", 0.0, "Travel distance (sign = direction)", "unit", "negative, positive or 0"),
            I_VELOCITY,
            I_ACC,
            I_DEC,
            I_JERK,
            I_BUFFER,
        ),
        outputs=(O_DONE, O_BUSY, O_ACTIVE, O_ABORTED, O_ERROR, O_ERRORID),
        spec="omron-axis-instructions.md MC_MoveRelative (seed 000 line 4307)",
    )

    def _target_inputs(self, axis: Axis) -> tuple[int, float, bool]:
        return _relative_distance(axis, self.inp["Distance"])


class MC_Move(_PositionFB):
    DEF = FBDef(
        name="MC_Move",
        title="Positioning",
        summary="Absolute or relative positioning, selected by MoveMode.",
        kind="execute",
        inouts=(IO_AXIS,),
        inputs=(
            I_EXECUTE,
            Var("Position", "LREAL", 0.0, "Absolute: target position; relative: travel distance", "unit",
                "negative, positive or 0"),
            I_VELOCITY,
            I_ACC,
            I_DEC,
            I_JERK,
            I_DIRECTION,
            I_BUFFER,
            Var("MoveMode", "_eMC_MOVE_MODE", 0, "0: absolute, 1: relative", None, "0, 1", allowed=(0, 1)),
        ),
        outputs=(O_DONE, O_BUSY, O_ACTIVE, O_ABORTED, O_ERROR, O_ERRORID),
        spec="omron-axis-instructions.md MC_Move (seed 000 line 3364)",
    )

    def _check(self, axis: Axis) -> int:
        if self.inp["MoveMode"] not in (0, 1):
            return E.E_MOVE_MODE
        return super()._check(axis)

    def _target_inputs(self, axis: Axis) -> tuple[int, float, bool]:
        if self.inp["MoveMode"] == 1:
            return _relative_distance(axis, self.inp["Position"])
        return _absolute_target(axis, self.inp["Position"], self.inp["Direction"])


class MC_MoveZeroPosition(_PositionFB):
    DEF = FBDef(
        name="MC_MoveZeroPosition",
        title="High-speed home",
        summary="Positions to absolute 0 (the home); home must be defined.",
        kind="execute",
        inouts=(IO_AXIS,),
        inputs=(
            I_EXECUTE,
            I_VELOCITY,
            I_ACC,
            I_DEC,
            I_JERK,
            Var("BufferMode", "_eMC_BUFFER_MODE", 0, "Behaviour on multi-execution", None, "0, 1", allowed=(0, 1)),
        ),
        outputs=(O_DONE, O_BUSY, O_ACTIVE, O_ABORTED, O_ERROR, O_ERRORID),
        spec="omron-axis-instructions.md MC_MoveZeroPosition (seed 000 line 4899)",
    )
    BLENDABLE = False

    def _buffer_modes(self) -> tuple[int, ...]:
        return (0, 1)

    def _check(self, axis: Axis) -> int:
        code = super()._check(axis)
        if code:
            return code
        if not axis.homed:
            return E.E_HOME_UNDEFINED
        if axis.rotary and not axis.mod_min <= 0.0 <= axis.mod_max:
            return E.E_RING_NO_ZERO
        return 0

    def _target_inputs(self, axis: Axis) -> tuple[int, float, bool]:
        return 0, 0.0, False

    def _fill(self, job: Job, axis: Axis) -> None:
        super()._fill(job, axis)
        job.direction = _eMC_DIRECTION._mcShortestWay  # rotary: always the shortest way to 0
        _, job.target = axis.resolve_target(0.0, job.direction)
        job.info["zero_position"] = True


# --------------------------------------------------------------------------------------------------- MC_MoveVelocity
class MC_MoveVelocity(_MotionFB):
    DEF = FBDef(
        name="MC_MoveVelocity",
        title="Velocity control",
        summary="Velocity control in position control mode: runs at the target velocity until aborted.",
        kind="execute",
        inouts=(IO_AXIS,),
        inputs=(
            I_EXECUTE,
            Var("Velocity", "LREAL", 0.0, "Target velocity", "unit/s", "positive or 0"),
            I_ACC,
            I_DEC,
            I_JERK,
            Var("Direction", "_eMC_DIRECTION", 0, "Direction", None, "0, 2, 3", allowed=(0, 2, 3)),
            Var("Continuous", "BOOL", False, "Reserved"),
            Var("BufferMode", "_eMC_BUFFER_MODE", 0, "Behaviour on multi-execution", None, "0, 1", allowed=(0, 1)),
        ),
        outputs=(
            Var("InVelocity", "BOOL", False, "TRUE when the target velocity is reached"),
            O_BUSY,
            O_ACTIVE,
            O_ABORTED,
            O_ERROR,
            O_ERRORID,
        ),
        spec="omron-axis-instructions.md MC_MoveVelocity (seed 000 line 4486)",
    )
    KIND = JobKind.VELOCITY

    def _check(self, axis: Axis) -> int:
        i = self.inp
        if not i["Velocity"] >= 0:
            return E.E_VELOCITY
        code = _check_acc_dec_jerk(i["Acceleration"], i["Deceleration"], i["Jerk"])
        if code:
            return code
        if i["Direction"] not in (0, 2, 3):
            return E.E_DIRECTION
        if i["Continuous"]:
            return 0x5433
        if i["BufferMode"] not in (0, 1):
            return E.E_BUFFER_MODE
        return 0

    def _signed_velocity(self, axis: Axis) -> float:
        i = self.inp
        d = i["Direction"]
        if d == _eMC_DIRECTION._mcPositiveDirection:
            sign = 1.0
        elif d == _eMC_DIRECTION._mcNegativeDirection:
            sign = -1.0
        else:  # current direction: of the motion in progress, else of the last motion
            v = float(axis.m.prof_vel[axis.i])
            sign = 1.0 if v > 0 else -1.0 if v < 0 else float(axis.last_direction)
        v, _, _ = _clamp_profile(axis, i["Velocity"], 0.0, 0.0)
        return sign * v

    def _fill(self, job: Job, axis: Axis) -> None:
        i = self.inp
        _, job.acceleration, job.deceleration = _clamp_profile(axis, 0.0, i["Acceleration"], i["Deceleration"])
        job.jerk = i["Jerk"]
        job.velocity = self._signed_velocity(axis)

    def _limits(self, job: Job, axis: Axis) -> int:
        return start_limit_error(axis, 1 if job.velocity > 0 else -1 if job.velocity < 0 else 0)


# --------------------------------------------------------------------------------------------------- MC_MoveJog
class MC_MoveJog(FunctionBlock):
    DEF = FBDef(
        name="MC_MoveJog",
        title="Jog",
        summary="Jogs at the target velocity while PositiveEnable or NegativeEnable is TRUE.",
        kind="enable",
        inouts=(IO_AXIS,),
        inputs=(
            Var("PositiveEnable", "BOOL", False, "TRUE: jog in + direction", dead_man=True),
            Var("NegativeEnable", "BOOL", False, "TRUE: jog in − direction", dead_man=True),
            Var("Velocity", "LREAL", 0.0, "Target velocity (clamped to Maximum Jog Velocity)", "unit/s",
                "positive or 0"),
            I_ACC,
            I_DEC,
        ),
        outputs=(O_BUSY, O_ABORTED, O_ERROR, O_ERRORID),
        spec="omron-axis-instructions.md MC_MoveJog (seed 000 line 2573)",
    )

    def __init__(self, mc: Any, fb_id: int, inputs: dict[str, Any] | None = None) -> None:
        super().__init__(mc, fb_id, inputs)
        self._prev = (False, False)
        self._dir = 0  # +1 / −1 of the enable that owns the running jog
        self._aborted_cycle = -1
        self.job: Job | None = None
        self.axis: Axis | None = None

    def _check_inputs(self) -> int:
        i = self.inp
        if not i["Velocity"] >= 0:
            return E.E_VELOCITY
        return _check_acc_dec_jerk(i["Acceleration"], i["Deceleration"], 0.0)

    def _velocity(self, axis: Axis, direction: int) -> float:
        op = axis.params.Operation
        return direction * min(self.inp["Velocity"], op.MaxJogVel, op.MaxVel)

    def call(self) -> None:
        o = self.out
        pe, ne = bool(self.inp["PositiveEnable"]), bool(self.inp["NegativeEnable"])
        pe_edge, ne_edge = pe and not self._prev[0], ne and not self._prev[1]
        self._prev = (pe, ne)
        if o["Error"] and self._error_released():
            o["Error"] = False
            o["ErrorID"] = 0
        # CommandAborted: cleared with the enable going FALSE, or one period later if both were already FALSE
        if o["CommandAborted"] and not (pe or ne) and self._aborted_cycle < self.mc.cycle:
            o["CommandAborted"] = False
        self.sync_job()
        if o["Error"]:
            return
        want = 1 if pe_edge else -1 if ne_edge else 0
        if want:
            self._start(want)
        elif self.job is not None and self.axis is not None:
            held = pe if self._dir > 0 else ne
            if not held:
                self.axis.release_jog(self.job)

    def sync_job(self) -> None:
        job = self.job
        if job is None or job.running:
            return
        o = self.out
        self.job = None
        o["Busy"] = False
        if job.status == JobStatus.ABORTED:
            o["CommandAborted"] = True
            self._aborted_cycle = self.mc.cycle
        elif job.status == JobStatus.ERROR:
            self._set_error(job.error_id, self.axis)

    def on_delete(self) -> None:
        """Deleting a jogging instance releases the jog like its enable falling: the axis decelerates with the
        instance's Deceleration and stops (D58) — nothing would be left to stop it otherwise."""
        if self.job is not None and self.job.running and self.axis is not None:
            self.axis.release_jog(self.job)

    def _start(self, direction: int) -> None:
        o = self.out
        job = self.job
        if job is not None and self.axis is not None:
            # same instance, still busy: re-accelerate or reverse with the inputs latched now
            code = self._check_inputs()
            if code:
                self._fail_running(code)
                return
            i = self.inp
            job.velocity = self._velocity(self.axis, direction)
            _, job.acceleration, job.deceleration = _clamp_profile(
                self.axis, 0.0, i["Acceleration"], i["Deceleration"]
            )
            job.stopping = False
            self._dir = direction
            job.replan = True
            self.axis.replan(job)
            return
        axis = self.resolve_axis()
        self.axis = axis
        if axis is None:
            self.fail(E.E_ILLEGAL_AXIS, None)
            return
        o["CommandAborted"] = False
        verdict, code = axis.check_start("standstill_only")
        if verdict == "abort":
            o["CommandAborted"] = True
            self._aborted_cycle = self.mc.cycle
            return
        code = self._check_inputs() or code or start_limit_error(axis, direction)
        if code:
            self.fail(code, axis)
            return
        i = self.inp
        _, acc, dec = _clamp_profile(axis, 0.0, i["Acceleration"], i["Deceleration"])
        job = Job(JobKind.JOG, self, velocity=self._velocity(axis, direction), acceleration=acc, deceleration=dec,
                  overridable=True)
        err = axis.submit(job)
        if err:
            self.fail(err, axis)
            return
        self.job = job
        self._dir = direction
        o["Busy"] = True

    def _fail_running(self, code: int) -> None:
        axis = self.axis
        self.job = None
        self.fail(code, axis)


FB_CLASSES: tuple[type[FunctionBlock], ...] = (
    MC_Power,
    MC_Reset,
    MC_Stop,
    MC_Move,
    MC_MoveAbsolute,
    MC_MoveRelative,
    MC_MoveZeroPosition,
    MC_MoveVelocity,
    MC_MoveJog,
)
