"""Homing sequences of MC_Home / MC_HomeWithParameter: the ten `_eMC_HOMING_MODE` modes.

Spec: `omron-axis-instructions.md` "MC_Home" (seed 000 lines 2713–3228). The sequence reads the drive's inputs each
period — limit and home-proximity bits of 60FDh, the touch-probe latch (60B9h/60BAh) armed on the Z phase or the
external home input — and plans its moves with the axis planner. Every mode that uses the home input ends with the
manual's common tail T: latch at the home-input edge and stop immediately (T1), return to the latched position by an
absolute move and always wait for in-position (T2), wait 500 ms and move by the compensation value if it is not 0
(T3), preset the position to the home offset, home defined, Done (T4).

Readings where the manual is ambiguous (docs/decisions.md D20): mode 5 started on the proximity dog behaves like
mode 4 (approach velocity in the detection direction); mode 8 leaves the limit opposite the detection direction
after reversing and arms the latch once it is OFF; mode 11 defines home at the sampled OFF edge of that limit; a
virtual axis has no sensors and is homed like mode 14 (preset).
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

from ...drives.cia402 import (
    DI_HOME_SWITCH,
    DI_NEGATIVE_LIMIT,
    DI_POSITIVE_LIMIT,
    TP1_ENABLE,
    TP1_POS_EDGE,
    TP1_SOURCE_Z,
    TS1_STORED,
)
from . import errors as E
from .enums import _eMC_DIRECTION, _eMC_HOMING_MODE, _eMC_LIMIT_REVERSE_MODE
from .jobs import Job, JobStatus
from .profile import Segments, hold

if TYPE_CHECKING:
    from .axis import Axis

M = _eMC_HOMING_MODE
RETREAT_MODES = (M._mcHomeSwTurnHomeSwOff, M._mcHomeSwTurnHomeSwOn, M._mcHomeSwTurnHomeMask,
                 M._mcHomeSwTurnHoldingTime)
PROX_MODES = (*RETREAT_MODES, M._mcHomeSwOff, M._mcHomeSwOn)
COMPENSATION_WAIT_S = 0.5


@dataclass(frozen=True)
class HomingParams:
    """The homing settings in `_sHOMING_REF` terms (from the axis parameters or MC_HomeWithParameter)."""

    mode: int
    home_input_z: bool
    start_dir: int  # +1 / −1
    detect_dir: int
    posi_limit_mode: int
    nega_limit_mode: int
    vel: float
    approach_vel: float
    acc: float
    dec: float
    jerk: float
    mask: float
    offset: float
    holding_ms: int
    compensation: float
    compensation_vel: float


def _dir(d: int) -> int:
    return -1 if int(d) == _eMC_DIRECTION._mcNegativeDirection else 1


def params_from_axis(axis: Axis) -> HomingParams:
    h = axis.params.Homing
    return HomingParams(int(h.Mode), int(h.HomeInputSignal) == 0, _dir(h.StartDirection),
                        _dir(h.HomeInputDetectionDirection), int(h.PosiLimitInputMode), int(h.NegaLimitInputMode),
                        h.Vel, h.ApproachVel, h.Acc, h.Dec, h.Jerk, h.HomeInputMaskDistance, h.HomeOffset,
                        h.HoldingTime, h.CompensationVal, h.CompensationVel)


class Phase(enum.Enum):
    SEARCH = "search"  # moving at the homing velocity, looking for the proximity dog (or the limit)
    RETREAT = "retreat"  # on the dog at start: leaving it against the detection direction
    REVERSING = "reversing"  # stopping at a limit before reversing
    APPROACH = "approach"  # at the approach velocity in the detection direction
    ARMED = "armed"  # waiting for the home input (latch armed)
    HOLDING = "holding"  # mode 12: the holding time runs
    RETURN = "return"  # T2: moving back to the latched position
    COMP_WAIT = "comp_wait"  # T3: 500 ms before the compensation move
    COMPENSATE = "compensate"  # T3: compensation move
    FINISH = "finish"


class Homing:
    """One homing execution on one axis; `step()` runs in the motion stage of every period."""

    def __init__(self, axis: Axis, job: Job, p: HomingParams) -> None:
        self.axis = axis
        self.job = job
        self.p = p
        self.m = axis.m
        self.i = axis.i
        self.phase = Phase.SEARCH
        self.dir = p.start_dir  # direction of the current run
        self.speed = 0.0
        self.started = False
        self.prev_din = 0
        self.timer_start = -1
        self.mask_from: float | None = None
        self.latched: float | None = None
        self.edge: float | None = None  # mode 11: home = the sampled OFF edge of the limit
        self.limits_reversed: set[int] = set()
        self.pending: Phase | None = None
        self.move_wait_inpos = False
        self.move_start = -1
        self.move_duration = 0.0

    # ------------------------------------------------------------------ plumbing
    @property
    def cycle(self) -> int:
        return self.m.cycle

    def plan(self, p0: float, v0: float, a0: float) -> Segments:
        """Initial profile when the job starts: hold; `step()` starts the motion in the same period."""
        self.m.homing_axes[self.i] = self.axis
        self.m.limit_check[self.i] = False
        return hold(p0)

    def close(self) -> None:
        m, i = self.m, self.i
        m.homing_axes.pop(i, None)
        m.tp_func[i] = 0
        m.limit_check[i] = True
        m.fe_check[i] = True

    def on_profile_end(self) -> bool:
        return False  # the sequence watches its moves itself

    def _load(self, seg: Segments) -> None:
        m, i = self.m, self.i
        m.profiles.load(i, seg, self.cycle)
        m.notify[i] = False
        m.stop_dec[i] = self.p.dec
        self.move_start = self.cycle
        self.move_duration = seg.duration

    def _state(self) -> tuple[float, float, float]:
        m, i = self.m, self.i
        return float(m.cmd_pos[i]), float(m.prof_vel[i]), float(m.prof_acc[i])

    def _run(self, direction: int, speed: float) -> None:
        p0, v0, a0 = self._state()
        self.dir, self.speed = direction, speed
        self._load(self.m.planner.velocity(p0=p0, v0=v0, a0=a0, target_velocity=direction * speed,
                                           acceleration=self.p.acc, deceleration=self.p.dec, jerk=self.p.jerk))

    def _stop(self, immediate: bool) -> None:
        p0, v0, a0 = self._state()
        if immediate:
            self.axis.halt()
            self._load(hold(p0))
        else:
            self._load(self.m.planner.stop(p0=p0, v0=v0, a0=a0, deceleration=self.p.dec, jerk=self.p.jerk))

    def _move_to(self, target: float, speed: float, *, wait_inpos: bool) -> None:
        p0, v0, a0 = self._state()
        self._load(self.m.planner.position(p0=p0, v0=v0, a0=a0, target=target, velocity=speed,
                                           acceleration=self.p.acc, deceleration=self.p.dec, jerk=self.p.jerk))
        self.move_wait_inpos = wait_inpos
        self.move_target = target

    def _move_done(self) -> bool:
        """The move reached its target and its last command value reached the drive (+ in-position if asked)."""
        elapsed = (self.cycle - self.move_start + 1) * self.m.period_s
        if elapsed < self.move_duration + self.m.period_s - 1e-12:
            return False
        if not self.move_wait_inpos:
            return True
        op = self.axis.params.Operation
        waiting = abs(float(self.m.act_pos[self.i]) - self.move_target) > op.InPosRange
        self.axis.in_pos_waiting = waiting
        return not waiting

    def _stopped(self) -> bool:
        return float(self.m.prof_vel[self.i]) == 0.0 and self._move_done()

    def _arm(self) -> None:
        fn = TP1_ENABLE | TP1_POS_EDGE | (TP1_SOURCE_Z if self.p.home_input_z else 0)
        self.m.tp_func[self.i] = fn
        self.arm_cycle = self.cycle

    def _latch(self) -> float | None:
        if self.m.tp_func[self.i] == 0 or self.cycle <= getattr(self, "arm_cycle", self.cycle):
            return None  # the armed function reaches the drive with this period's outputs
        if int(self.m.tp_status[self.i]) & TS1_STORED:
            return self.m.latch_position(self.i, 1)
        return None

    def fail(self, code: int, detail: str = "") -> None:
        job = self.job
        self.axis.raise_error(code, source=job.owner.label if job.owner is not None else None, detail=detail,
                              stop=self.axis.limit_input_stop_mode())
        job.status = JobStatus.ERROR  # the homing instruction shows the error (its own processing failed)
        job.error_id = code

    # ------------------------------------------------------------------ the sequence
    def step(self) -> None:
        m, i = self.m, self.i
        din = int(m.din[i])
        prox = bool(din & DI_HOME_SWITCH)
        rising = prox and not self.prev_din & DI_HOME_SWITCH
        falling = not prox and bool(self.prev_din & DI_HOME_SWITCH)
        if not self.started:
            self.started = True
            self.prev_din = din
            self._begin(din)
            return
        try:
            if self.phase in (Phase.SEARCH, Phase.RETREAT, Phase.APPROACH, Phase.ARMED, Phase.HOLDING) and \
                    self._limit_rule(din):
                return
            getattr(self, "_on_" + self.phase.value)(din, prox, rising, falling)
        finally:
            self.prev_din = din

    def _begin(self, din: int) -> None:
        p = self.p
        axis = self.axis
        if p.mode == M._mcHomePreset or axis.virtual:
            self._define()
            return
        prox = bool(din & DI_HOME_SWITCH)
        opposite_limit = DI_NEGATIVE_LIMIT if p.detect_dir > 0 else DI_POSITIVE_LIMIT
        if p.mode in PROX_MODES and prox:
            if p.mode in RETREAT_MODES:
                self.phase = Phase.RETREAT
                self._run(-p.detect_dir, p.vel)
            else:  # modes 4 and 5 (D20): start on the dog in the detection direction at the approach velocity
                self._approach(started_on_dog=True)
            return
        if p.mode == M._mcNoHomeSwHoldingHomeInput:
            self.phase = Phase.ARMED
            self.m.fe_check[self.i] = False  # pushing: following error not monitored
            self._arm()
            self._run(p.detect_dir, p.approach_vel)
            return
        if p.mode in (M._mcLimitInputOff, M._mcLimitInputOnly):
            if din & opposite_limit:
                self._leave_limit()
            else:
                self.phase = Phase.SEARCH
                self._run(-p.detect_dir, p.vel)
            return
        self.phase = Phase.SEARCH
        self._run(p.start_dir, p.vel)

    def _approach(self, *, started_on_dog: bool = False) -> None:
        p = self.p
        self.phase = Phase.APPROACH
        self.timer_start = self.cycle
        self.mask_from = float(self.m.cmd_pos[self.i])
        self._run(p.detect_dir, p.approach_vel)
        if p.mode == M._mcHomeSwTurnHoldingTime:
            self.phase = Phase.HOLDING
            self.m.fe_check[self.i] = False
        elif p.mode in (M._mcHomeSwTurnHomeSwOn, M._mcHomeSwOn) and started_on_dog:
            pass  # the latch is armed once the approach velocity is reached

    def _leave_limit(self) -> None:
        """Modes 8/11: in the limit opposite the detection direction; leave it in the detection direction."""
        self.phase = Phase.APPROACH
        self.timer_start = self.cycle
        self._run(self.p.detect_dir, self.p.approach_vel)

    def _limit_rule(self, din: int) -> bool:
        """A limit input in the direction of motion during homing (MC_Home general rules). True = handled."""
        p = self.p
        moving = self.dir
        hit = (moving > 0 and din & DI_POSITIVE_LIMIT) or (moving < 0 and din & DI_NEGATIVE_LIMIT)
        if not hit or self.phase == Phase.REVERSING:
            return False
        limit_bit = DI_POSITIVE_LIMIT if moving > 0 else DI_NEGATIVE_LIMIT
        if p.mode in (M._mcLimitInputOff, M._mcLimitInputOnly) and moving == -p.detect_dir \
                and self.phase == Phase.SEARCH:
            # the limit these modes look for: stop in it, then leave it in the detection direction
            self.phase = Phase.REVERSING
            self.pending = Phase.APPROACH
            self._stop(immediate=False)
            return True
        if moving == p.detect_dir and self.phase in (Phase.APPROACH, Phase.ARMED, Phase.HOLDING) \
                and p.mode != M._mcNoHomeSwHoldingHomeInput:
            self.fail(E.E_HOMING_LIMIT, "limit input in the home input detection direction at the approach velocity")
            return True
        op = p.posi_limit_mode if moving > 0 else p.nega_limit_mode
        if op == _eMC_LIMIT_REVERSE_MODE._mcErrorStop:
            self.fail(E.E_HOMING_LIMIT, "limit input during homing; operation selection = error stop")
            return True
        opposite_bit = DI_NEGATIVE_LIMIT if p.detect_dir > 0 else DI_POSITIVE_LIMIT
        if moving == p.detect_dir and opposite_bit in self.limits_reversed:
            self.fail(E.E_HOMING_NO_HOME_INPUT, "travelled from one limit to the other without the home input")
            return True
        self.limits_reversed.add(limit_bit)
        self.phase = Phase.REVERSING
        self.pending = Phase.SEARCH
        self._stop(immediate=op == _eMC_LIMIT_REVERSE_MODE._mcRevImmediateStop)
        return True

    # ------------------------------------------------------------------ phase handlers
    def _on_search(self, din: int, prox: bool, rising: bool, falling: bool) -> None:
        p = self.p
        if p.mode not in PROX_MODES:
            return
        if rising and self.dir == p.detect_dir:
            self._approach()
        elif falling and self.dir == -p.detect_dir and self.limits_reversed:
            # Reversed at a limit and passed the whole dog against the detection direction: that is the end of a
            # retreat — turn back and find the dog in the detection direction instead of travelling on to the
            # other limit (docs/decisions.md D20).
            self._end_retreat()

    def _on_retreat(self, din: int, prox: bool, rising: bool, falling: bool) -> None:
        if not prox:
            self._end_retreat()

    def _end_retreat(self) -> None:
        """Off the dog: back in the detection direction — modes 0/1 (and 4/5) at the homing velocity, 9/12 at the
        approach velocity (MC_Home mode descriptions)."""
        p = self.p
        self.phase = Phase.SEARCH
        slow = p.mode in (M._mcHomeSwTurnHomeMask, M._mcHomeSwTurnHoldingTime)
        self._run(p.detect_dir, p.approach_vel if slow else p.vel)

    def _on_reversing(self, din: int, prox: bool, rising: bool, falling: bool) -> None:
        if not self._stopped():
            return
        p = self.p
        if self.pending == Phase.APPROACH:
            self._leave_limit()
        else:
            self.phase = Phase.SEARCH
            self._run(-self.dir, p.vel)

    def _on_approach(self, din: int, prox: bool, rising: bool, falling: bool) -> None:
        p, m, i = self.p, self.m, self.i
        at_speed = abs(float(m.prof_vel[i])) <= p.approach_vel + 1e-9 and float(m.prof_acc[i]) == 0.0
        if p.mode in (M._mcHomeSwTurnHomeSwOff, M._mcHomeSwOff):
            if falling or (not prox and at_speed):
                self._arm()
                self.phase = Phase.ARMED
        elif p.mode in (M._mcHomeSwTurnHomeSwOn, M._mcHomeSwOn):
            if at_speed:
                self._arm()
                self.phase = Phase.ARMED
        elif p.mode == M._mcHomeSwTurnHomeMask:
            travelled = abs(float(m.cmd_pos[i]) - (self.mask_from or 0.0))
            if travelled >= p.mask:
                if not at_speed:
                    self.fail(E.E_MASK_DISTANCE, f"mask distance {p.mask:g} consumed before the approach velocity")
                    return
                self._arm()
                self.phase = Phase.ARMED
        elif p.mode == M._mcLimitInputOff:
            limit = DI_NEGATIVE_LIMIT if p.detect_dir > 0 else DI_POSITIVE_LIMIT
            if not din & limit:
                self._arm()
                self.phase = Phase.ARMED
        elif p.mode == M._mcLimitInputOnly:
            limit = DI_NEGATIVE_LIMIT if p.detect_dir > 0 else DI_POSITIVE_LIMIT
            if not din & limit:
                # home = the OFF edge as sampled by the MC module; stop immediately, no return (L + D)
                self.edge = float(m.act_pos[i])
                self._stop(immediate=True)
                self.latched = None
                self._after_home_stop()

    def _on_armed(self, din: int, prox: bool, rising: bool, falling: bool) -> None:
        latched = self._latch()
        if latched is None:
            return
        self.latched = latched
        self.m.tp_func[self.i] = 0
        self._stop(immediate=True)  # T1
        self.phase = Phase.RETURN
        self._move_to(latched, self.p.approach_vel, wait_inpos=True)  # T2: always waits for in-position

    def _on_holding(self, din: int, prox: bool, rising: bool, falling: bool) -> None:
        if (self.cycle - self.timer_start) * self.m.period_s * 1000.0 >= self.p.holding_ms:
            self.edge = float(self.m.cmd_pos[self.i])
            self._stop(immediate=True)
            self.m.fe_check[self.i] = True
            self._after_home_stop()

    def _on_return(self, din: int, prox: bool, rising: bool, falling: bool) -> None:
        if self._move_done():
            self.axis.in_pos_waiting = False
            self.edge = self.latched
            self._after_home_stop()

    def _after_home_stop(self) -> None:
        if self.p.compensation != 0.0:
            self.phase = Phase.COMP_WAIT
            self.timer_start = self.cycle
        else:
            self._define()

    def _on_comp_wait(self, din: int, prox: bool, rising: bool, falling: bool) -> None:
        if (self.cycle - self.timer_start) * self.m.period_s >= COMPENSATION_WAIT_S - 1e-12:
            self.phase = Phase.COMPENSATE
            op = self.axis.params.Operation
            self._move_to(float(self.m.cmd_pos[self.i]) + self.p.compensation, self.p.compensation_vel,
                          wait_inpos=op.InPosCheckTime > 0)
            self.comp_home = (self.edge if self.edge is not None else float(self.m.cmd_pos[self.i])) + \
                self.p.compensation

    def _on_compensate(self, din: int, prox: bool, rising: bool, falling: bool) -> None:
        if self._move_done():
            self.axis.in_pos_waiting = False
            self.edge = self.comp_home
            self._define()

    def _on_finish(self, din: int, prox: bool, rising: bool, falling: bool) -> None:
        pass

    def _define(self) -> None:
        """T4: the home position (edge / latch / compensated position, or here for mode 14) becomes Home Offset."""
        m, i = self.m, self.i
        home = self.edge if self.edge is not None else float(m.cmd_pos[i])
        if math.isfinite(home):
            m.shift_coordinates(i, self.p.offset - home)
        self.axis.homed = True
        self.phase = Phase.FINISH
        m.tp_func[i] = 0
        m.profiles.clear(i)
        m.prof_vel[i] = 0.0
        m.prof_acc[i] = 0.0
        self.axis._end_job(self.job, JobStatus.DONE)
        self.axis._set_state(self.axis._rest_state())
