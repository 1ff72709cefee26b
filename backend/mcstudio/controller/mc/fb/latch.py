"""Latching instructions: MC_TouchProbe, MC_AbortTrigger, MC_MoveFeed (`omron-axis-instructions.md`, seed 000
lines 11271, 11881, 5064).

Drive mode arms the drive's touch probe (60B8h) on the Z phase or the external input of the selected latch and takes
the position the drive latched (60BAh/60BCh, exact edge position). Controller mode samples the BOOL in-out
`TriggerVariable` once per period and records the actual position of that period.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from .. import errors as E
from ..enums import (
    AxisState,
    _eMC_DIRECTION,
    _eMC_MOVE_MODE,
    _eMC_TRIGGER_INPUT_DRIVE,
    _eMC_TRIGGER_LATCH_ID,
    _eMC_TRIGGER_MODE,
)
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
    OneShotFB,
    Var,
)
from .single_axis import (
    I_ACC,
    I_DEC,
    I_JERK,
    _check_acc_dec_jerk,
    _clamp_profile,
    start_limit_error,
)

if TYPE_CHECKING:
    from ..axis import Axis

IO_TRIGGER = Var("TriggerInput", "_sTRIGGER_REF", None,
                 "Trigger: Mode (_mcDrive/_mcController), LatchID (_mcLatch1/_mcLatch2), InputDrive "
                 "(_mcEncoderMark = Z phase / _mcEXT = external input)")
IO_TRIGGER_VAR = Var("TriggerVariable", "BOOL", False, "Trigger in controller mode (rising edge)")
I_WINDOW = Var("WindowOnly", "BOOL", False, "Accept triggers only inside [FirstPosition, LastPosition]")
I_FIRST = Var("FirstPosition", "LREAL", 0.0, "Window start", "unit")
I_LAST = Var("LastPosition", "LREAL", 0.0, "Window end", "unit")


# objects a drive-mode latch needs in the slave's PDO mapping (omron-mc-basics.md §2.11; else 3461)
LATCH_PDO = {1: (0x60B8, 0x60B9, 0x60BA), 2: (0x60B8, 0x60B9, 0x60BC)}


def latch_pdo_missing(axis: Axis, mode: int, slot: int) -> int:
    """3461 when a drive-mode trigger's latch objects are not mapped for the axis's slave, else 0."""
    if mode == _eMC_TRIGGER_MODE._mcDrive and slot in LATCH_PDO and axis.pdo_missing(LATCH_PDO[slot]):
        return E.E_PDO_MISSING
    return 0


def parse_trigger(ref: dict[str, Any] | None) -> tuple[int, int, int, int]:
    """_sTRIGGER_REF → (error, mode, latch slot 1/2, z_phase). Out-of-range members give 5450/544E/5451."""
    ref = ref or {}

    def member(name: str, cls: Any, default: int) -> int | None:
        v = ref.get(name, default)
        if isinstance(v, str):
            return int(cls[v]) if v in cls.__members__ else None
        if isinstance(v, int) and not isinstance(v, bool) and v in [int(x) for x in cls]:
            return v
        return None

    mode = member("Mode", _eMC_TRIGGER_MODE, 0)
    if mode is None:
        return 0x5450, 0, 0, 0
    latch = member("LatchID", _eMC_TRIGGER_LATCH_ID, 0)
    if latch is None:
        return 0x544E, 0, 0, 0
    drive = member("InputDrive", _eMC_TRIGGER_INPUT_DRIVE, 1)
    if drive is None:
        return 0x5451, 0, 0, 0
    return 0, mode, latch + 1, int(drive == _eMC_TRIGGER_INPUT_DRIVE._mcEncoderMark)


def window_error(axis: Axis, first: float, last: float) -> int:
    """Window checks (MC_TouchProbe / MC_MoveFeed WindowOnly rules): 5469/546A out of range, 546B order (linear)."""
    for v, code in ((first, 0x5469), (last, 0x546A)):
        if not fits_position(v, axis.ppu) or (axis.rotary and not axis.mod_min <= v <= axis.mod_max):
            return code
    if not axis.rotary and first > last:
        return 0x546B
    return 0


def in_window(axis: Axis, pos: float, first: float, last: float) -> bool:
    p = axis.wrap(pos)
    return first <= p <= last if first <= last else (p >= first or p <= last)


class _Latcher:
    """Shared latch handling: arm, watch each period, window filter, release."""

    axis: Axis | None
    mc: Any
    id: int
    inp: dict[str, Any]

    def _claim(self, axis: Axis, slot: int) -> int:
        owner = axis.latch_owner.get(slot)
        if owner is not None and owner is not self and owner.latch_active():
            if isinstance(owner, MC_TouchProbe) and isinstance(self, MC_TouchProbe):
                owner.abort_latch()  # a new MC_TouchProbe on the same LatchID aborts the earlier one
            else:
                return E.E_DUPLICATE_LATCH
        axis.latch_owner[slot] = self
        return 0

    def _arm(self) -> None:
        assert self.axis is not None
        self._armed_cycle = self.mc.cycle
        if self._mode == _eMC_TRIGGER_MODE._mcDrive:
            self.mc.arm_latch(self.axis.i, self._slot, z_phase=bool(self._z))
        self._prev_trigger = bool(self.inp.get("TriggerVariable"))
        self.mc.watchers[self.id] = self

    def _release(self) -> None:
        self.mc.watchers.pop(self.id, None)
        axis = self.axis
        if axis is not None and axis.latch_owner.get(self._slot) is self:
            del axis.latch_owner[self._slot]
            if self._mode == _eMC_TRIGGER_MODE._mcDrive:
                self.mc.disarm_latch(axis.i, self._slot)

    def _poll(self) -> float | None:
        """The triggered position of this period, if any (window-filtered; re-armed when outside)."""
        axis = self.axis
        assert axis is not None
        m, i = self.mc, axis.i
        pos: float | None = None
        if getattr(self, "_rearm", False):
            # re-arm one period after disarming: the drive takes a new event on the enable edge (60B8h)
            self._rearm = False
            m.arm_latch(i, self._slot, z_phase=bool(self._z))
            self._armed_cycle = m.cycle
            return None
        if self._mode == _eMC_TRIGGER_MODE._mcController:
            trig = bool(self.inp.get("TriggerVariable"))
            if trig and not self._prev_trigger:
                pos = float(m.act_pos[i])
            self._prev_trigger = trig
        elif m.cycle > self._armed_cycle and m.latch_stored(i, self._slot):
            pos = m.latch_position(i, self._slot)
            m.disarm_latch(i, self._slot)  # first event kept; re-armed below when outside the window
            self._armed_cycle = m.cycle
        if pos is None:
            return None
        if self.inp.get("WindowOnly") and not in_window(axis, pos, self.inp["FirstPosition"],
                                                         self.inp["LastPosition"]):
            if self._mode == _eMC_TRIGGER_MODE._mcDrive:
                self._rearm = True
            return None
        return pos


class MC_TouchProbe(_Latcher, ExecuteFB):
    DEF = FBDef(
        name="MC_TouchProbe",
        title="Enable external latch",
        summary="Records the axis position at the first trigger edge; optionally stops the axis there.",
        kind="execute",
        inouts=(IO_AXIS, IO_TRIGGER, IO_TRIGGER_VAR),
        inputs=(
            I_EXECUTE,
            I_WINDOW,
            I_FIRST,
            I_LAST,
            Var("ReferenceType", "_eMC_REFERENCE_TYPE", 1, "Reserved: _mcFeedback", None, "1", allowed=(1,)),
            Var("StopMode", "_eMC_STOP_MODE", 4, "1: immediate stop at the latched position, 4: no stop", None,
                "1, 4", allowed=(1, 4)),
        ),
        outputs=(O_DONE, O_BUSY, Var("RecordedPosition", "LREAL", 0.0, "Latched position", "unit"), O_ABORTED,
                 O_ERROR, O_ERRORID),
        spec="omron-axis-instructions.md MC_TouchProbe (seed 000 line 11271)",
    )
    HAS_ACTIVE = False

    def latch_active(self) -> bool:
        return bool(self.out["Busy"])

    def on_delete(self) -> None:
        if hasattr(self, "_slot"):
            self._release()

    def execute(self, axis: Axis) -> None:
        verdict, code = axis.check_start("latch")
        if verdict == "abort":
            self._finish("CommandAborted")
            return
        i = self.inp
        err, self._mode, self._slot, self._z = parse_trigger(i.get("TriggerInput"))
        code = code or err or latch_pdo_missing(axis, self._mode, self._slot)
        if not code and i["StopMode"] not in (1, 4):
            code = E.E_STOP_MODE
        if not code and i["ReferenceType"] != 1:
            code = 0x5430
        if not code and i["StopMode"] == 1 and (axis.encoder or axis.m.trq_active[axis.i]):
            code = 0x5492  # the immediate stop needs CSP: not on encoder axes, not in torque control (CST)
        if not code and i["WindowOnly"]:
            code = window_error(axis, i["FirstPosition"], i["LastPosition"])
        if not code:
            code = self._claim(axis, self._slot)
        if code:
            self.fail(code, axis)
            return
        self._arm()

    def watch(self) -> None:
        axis = self.axis
        if axis is None or not self.out["Busy"] or self.job is not None:
            return
        if self.inp["StopMode"] == 1 and axis.m.trq_active[axis.i]:
            # the axis was switched to torque control (CST) while waiting: CommandAborted (MC_TouchProbe rules)
            self.abort_latch()
            return
        pos = self._poll()
        if pos is None:
            return
        self.out["RecordedPosition"] = axis.wrap(pos)
        self.mc.watchers.pop(self.id, None)
        if self.inp["StopMode"] == 1 and axis.servo_on and axis.state not in (AxisState.ErrorStop,
                                                                                 AxisState.Disabled):
            # immediate stop at the latched position: the running instruction is aborted, the command returns to
            # the latch (Stopping until there), Done when stopped (MC_TouchProbe StopMode rules)
            job = Job(JobKind.RESET_FE, self, target=pos)
            axis.abort_all()
            axis.halt()
            axis._start(job)
            self.job = job
            return
        self._release()
        self._finish("Done")

    def on_job_end(self) -> None:
        self._release()

    def abort_latch(self) -> None:
        """Aborted by MC_AbortTrigger or by a newer MC_TouchProbe on the same latch."""
        self._release()
        if self.out["Busy"]:
            self._finish("CommandAborted")


class MC_AbortTrigger(OneShotFB):
    DEF = FBDef(
        name="MC_AbortTrigger",
        title="Disable external latch",
        summary="Aborts the latch of (Axis, LatchID); the MC_TouchProbe using it gets CommandAborted.",
        kind="execute",
        inouts=(IO_AXIS, IO_TRIGGER),
        inputs=(I_EXECUTE,),
        outputs=(O_DONE, O_BUSY, O_ABORTED, O_ERROR, O_ERRORID),
        spec="omron-axis-instructions.md MC_AbortTrigger (seed 000 line 11881)",
    )

    def execute(self, axis: Axis) -> None:
        _, code = axis.check_start("latch")
        err, _, slot, _ = parse_trigger(self.inp.get("TriggerInput"))
        code = code or err
        owner = axis.latch_owner.get(slot)
        if not code and owner is not None and not isinstance(owner, MC_TouchProbe):
            code = E.E_DUPLICATE_LATCH  # the latch belongs to MC_MoveFeed / homing
        if code:
            self.fail(code, axis)
            return
        if isinstance(owner, MC_TouchProbe):
            owner.abort_latch()
        self.done_next()  # Done one period after Execute


class MC_MoveFeed(_Latcher, ExecuteFB):
    DEF = FBDef(
        name="MC_MoveFeed",
        title="Interrupt feeding",
        summary="Moves (absolute, relative or velocity); on the interrupt input feeds FeedDistance from the "
        "latched actual position.",
        kind="execute",
        inouts=(IO_AXIS, IO_TRIGGER, IO_TRIGGER_VAR),
        inputs=(
            I_EXECUTE,
            I_WINDOW,
            I_FIRST,
            I_LAST,
            Var("ReferenceType", "_eMC_REFERENCE_TYPE", 1, "_mcFeedback", None, "1", allowed=(1,)),
            Var("Position", "LREAL", 0.0, "Absolute target / travel distance before the interrupt", "unit"),
            Var("Velocity", "LREAL", 0.0, "Target velocity before the interrupt", "unit/s", "positive"),
            I_ACC,
            I_DEC,
            I_JERK,
            Var("Direction", "_eMC_DIRECTION", 0, "Direction", None, "0–4"),
            Var("MoveMode", "_eMC_MOVE_MODE", 0, "0: absolute, 1: relative, 2: velocity", None, "0–2"),
            Var("FeedDistance", "LREAL", 0.0, "Distance after the interrupt (+ = same direction)", "unit"),
            Var("FeedVelocity", "LREAL", 0.0, "Velocity of the feed", "unit/s", "positive"),
            Var("BufferMode", "_eMC_BUFFER_MODE", 0, "0: _mcAborting, 1: _mcBuffered", None, "0, 1",
                allowed=(0, 1)),
            Var("ErrorDetect", "BOOL", False, "Report when no interrupt occurs before the target"),
        ),
        outputs=(O_DONE, Var("InFeed", "BOOL", False, "TRUE while feeding after the interrupt"), O_BUSY, O_ACTIVE,
                 O_ABORTED, O_ERROR, O_ERRORID),
        spec="omron-axis-instructions.md MC_MoveFeed (seed 000 line 5064)",
    )

    def latch_active(self) -> bool:
        return bool(self.out["Busy"])

    def on_delete(self) -> None:
        if hasattr(self, "_slot"):
            self._release()

    def _check(self, axis: Axis) -> int:
        i = self.inp
        mode = i["MoveMode"]
        if mode not in (0, 1, 2):
            return E.E_MOVE_MODE
        if not (i["Velocity"] > 0 or (mode == 2 and i["Velocity"] == 0)):
            return E.E_VELOCITY
        code = _check_acc_dec_jerk(i["Acceleration"], i["Deceleration"], i["Jerk"])
        if code:
            return code
        d = i["Direction"]
        if d not in range(5) or (mode == 2 and d in (_eMC_DIRECTION._mcShortestWay, _eMC_DIRECTION._mcNoDirection)):
            return E.E_DIRECTION
        if i["BufferMode"] not in (0, 1):
            return E.E_BUFFER_MODE
        if not i["FeedVelocity"] > 0:
            return 0x542A
        if not fits_distance(i["FeedDistance"], axis.ppu):
            return 0x548D
        if mode == 0 and not fits_position(i["Position"], axis.ppu):
            return E.E_TARGET_POSITION
        if mode == 0 and axis.rotary and d != _eMC_DIRECTION._mcNoDirection and \
                not axis.mod_min <= i["Position"] <= axis.mod_max:
            return E.E_TARGET_POSITION  # absolute target outside the ring counter, as MC_MoveAbsolute (A-1 #85)
        if mode == 1 and not fits_distance(i["Position"], axis.ppu):
            return E.E_TRAVEL_DISTANCE
        if i["WindowOnly"]:
            return window_error(axis, i["FirstPosition"], i["LastPosition"])
        return 0

    def execute(self, axis: Axis) -> None:
        verdict, code = axis.check_start("move")
        if verdict == "abort":
            self._finish("CommandAborted")
            return
        i = self.inp
        err, self._mode, self._slot, self._z = parse_trigger(i.get("TriggerInput"))
        code = self._check(axis) or err or code or latch_pdo_missing(axis, self._mode, self._slot)
        if code:
            self.fail(code, axis)
            return
        v, acc, dec = _clamp_profile(axis, i["Velocity"], i["Acceleration"], i["Deceleration"])
        mode = i["MoveMode"]
        if mode == _eMC_MOVE_MODE._mcVelocity:
            sign = -1.0 if i["Direction"] == _eMC_DIRECTION._mcNegativeDirection else 1.0
            if i["Direction"] == _eMC_DIRECTION._mcCurrentDirection:
                sign = float(axis.last_direction)
            job = Job(JobKind.VELOCITY, self, velocity=sign * v, acceleration=acc, deceleration=dec,
                      jerk=i["Jerk"], buffer_mode=i["BufferMode"], overridable=True)
            direction = int(sign)
        else:
            job = Job(JobKind.POSITION, self, velocity=v, acceleration=acc, deceleration=dec, jerk=i["Jerk"],
                      buffer_mode=i["BufferMode"], overridable=True)
            cur = float(axis.m.cmd_pos[axis.i])
            if mode == _eMC_MOVE_MODE._mcRelative:
                job.relative, job.distance = True, i["Position"]
                target = cur + i["Position"]
            else:
                job.absolute_target, job.direction = i["Position"], i["Direction"]
                _, target = axis.resolve_target(i["Position"], i["Direction"])
                job.target = target
            direction = 1 if target >= cur else -1
        job.info["feed"] = True
        # a positioning target beyond a software limit is refused at start (A-1 #142/#143), as for MC_MoveAbsolute
        limit_target = None if mode == _eMC_MOVE_MODE._mcVelocity else target
        code = start_limit_error(axis, direction, limit_target) or self._claim(axis, self._slot)
        if code:
            self.fail(code, axis)
            return
        err = axis.submit(job)
        if err:
            self.fail(err, axis)
            return
        self.job = job
        self._feeding = False
        self._arm()

    def watch(self) -> None:
        job, axis = self.job, self.axis
        if job is None or axis is None or not job.running:
            return
        if job.status != JobStatus.ACTIVE or self._feeding:
            return
        pos = self._poll()
        if pos is None:
            return
        # feed from the latched actual position; positive FeedDistance continues the direction of travel
        i = self.inp
        sign = 1.0 if float(axis.m.prof_vel[axis.i]) >= 0 else -1.0
        if job.kind == JobKind.VELOCITY:
            sign = 1.0 if job.velocity >= 0 else -1.0
        target = pos + sign * i["FeedDistance"]
        if not axis.rotary and not (axis.m.lin_min[axis.i] <= target <= axis.m.lin_max[axis.i]):
            # the feed would leave the 40-bit range: error at the interrupt input (MC_MoveFeed rules, ch3 L684)
            self._release()
            axis.raise_error(E.E_POSITION_OVERFLOW, source=self.label,
                             detail=f"feed target {target:.6g} beyond the 40-bit pulse range")
            job.status = JobStatus.ERROR
            job.error_id = E.E_POSITION_OVERFLOW
            return
        feed = Job(JobKind.POSITION, self, velocity=min(i["FeedVelocity"], axis.params.Operation.MaxVel),
                   acceleration=job.acceleration, deceleration=job.deceleration, jerk=job.jerk, overridable=True,
                   target=target)
        feed.info["feed"] = True
        feed.status = JobStatus.ACTIVE
        axis.current = feed
        axis._set_state(AxisState.Discrete)
        feed.replan = True
        axis.m.schedule(axis)
        self.job = feed
        self._feeding = True
        self.out["InFeed"] = True
        self._release()

    def sync_job(self) -> None:
        job = self.job
        if job is not None and job.status == JobStatus.DONE and not self._feeding and self.inp["ErrorDetect"]:
            job.status = JobStatus.ABORTED  # no interrupt before the target: CommandAborted (MC_MoveFeed rules)
        super().sync_job()

    def on_job_end(self) -> None:
        self.out["InFeed"] = False
        self._release()


LATCH_CLASSES = (MC_TouchProbe, MC_AbortTrigger, MC_MoveFeed)
