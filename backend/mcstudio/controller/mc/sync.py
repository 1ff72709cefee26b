"""Synchronized control: a slave axis whose command position follows master axes every period.

Laws (`omron-axis-instructions.md` MC_CamIn … MC_CombineAxes, decisions D38–D44):

* `CamLaw` — MC_CamIn: waits for the master to pass StartPosition (InCam) and the cam start position (InSync), then
  slave = reference + SlaveScaling · table((master − StartPosition − MasterOffset) / MasterScaling) + SlaveOffset,
  the table interpolated linearly; periodic tables repeat (a feeding cam advances the reference by the end distance
  each cycle), EndOfProfile pulses when the end point is output; Direction holds the slave while the master moves
  the other way.
* `GearLaw` — MC_GearIn: the slave velocity ramps (Acceleration/Deceleration) to master velocity × ratio
  (catching), then follows the master's position increments × ratio (InGear).
* `GearPosLaw` — MC_GearInPos: a catch-up move planned in the master's position domain so that the slave is at
  SlaveSyncPosition when the master is at MasterSyncPosition (InSync), then gearing.
* `LinkLaw` — MC_MoveLink: the slave moves SlaveDistance as a trapezoid of velocity *ratio* over MasterDistance of
  master travel, after the start condition (InSync); Done at the end.
* `CombineLaw` — MC_CombineAxes: slave = start + Δmaster ± Δauxiliary.

Master positions are sampled by ReferenceType: `_mcCommand` the command position of the previous period,
`_mcFeedback` the actual position of this period, `_mcLatestCommand` the command position computed in this period
(the stage runs slaves in ascending axis number, so a master with a lower number — itself a slave or not — is
already computed). Positions are the continuous (unwrapped) values, so a rotary master needs no wrap handling.

MC_Phasing shifts the master phase a slave sees (`Law.phase`, a relative profile evaluated over time);
MC_SyncOffsetPosition adds an offset to the slave output (`Law.offset`). The stage keeps `prof_vel`/`prof_acc` of
each slave current, so an instruction that takes over (MC_Stop, MC_CamOut, a positioning) starts from the slave's
real velocity.
"""

from __future__ import annotations

import math
from bisect import bisect_right
from typing import TYPE_CHECKING, Any

from .axis_planning import E_INPOS_TIME
from .profile import Segments

if TYPE_CHECKING:
    from .axis import Axis
    from .cam.table import CamTable
    from .jobs import Job
    from .module import MotionModule

REF_COMMAND, REF_FEEDBACK, REF_LATEST = 0, 1, 2
E_MASTER_VELOCITY_ZERO = 0x5476  # MC_GearInPos: master velocity 0 at start
E_GEARPOS_VALUE = 0x5475  # MC_GearInPos: synchronisation impossible with the given velocity/acc/dec


def master_sample(m: MotionModule, i: int, ref: int) -> float:
    """Master axis i's position as the slave sees it (ReferenceType)."""
    if ref == REF_FEEDBACK:
        return float(m.act_pos[i])
    if ref == REF_LATEST:
        return float(m.cmd_pos[i])
    return float(m.prev_cmd_pos[i])


def master_velocity(m: MotionModule, i: int, ref: int) -> float:
    if ref == REF_FEEDBACK:
        return float(m.act_vel[i])
    if ref == REF_LATEST:
        return float((m.cmd_pos[i] - m.prev_cmd_pos[i]) / m.period_s)
    return float(m.cmd_vel[i])


def start_velocity(m: MotionModule, i: int, ref: int) -> float:
    """Master velocity when an instruction starts (its motion stage, before this period's values are computed)."""
    return float(m.act_vel[i]) if ref == REF_FEEDBACK else float(m.cmd_vel[i])


class PhaseShift:
    """MC_Phasing: a relative profile of the master phase, evaluated over the periods since it started."""

    def __init__(self, seg: Segments, start_cycle: int, base: float) -> None:
        self.seg = seg
        self.start_cycle = start_cycle
        self.base = base  # shift already applied before this profile
        self.done = False

    def value(self, cycle: int, period_s: float) -> float:
        t = (cycle - self.start_cycle + 1) * period_s
        if t >= self.seg.duration:
            self.done = True
            return self.base + self.seg.end_position
        return self.base + self.seg.sample(t)[0]


class Law:
    """How one slave follows; `step` returns the slave's command position of this period."""

    kind = ""

    def __init__(self, m: MotionModule, job: Job, slave: Axis) -> None:
        self.m = m
        self.job = job
        self.slave = slave
        self.offset = 0.0  # MC_SyncOffsetPosition
        self.phasing: PhaseShift | None = None  # MC_Phasing
        self.phase_base = 0.0  # shift of finished phasings (kept until the law ends)
        self.in_sync = False
        self.flags_changed = False  # an output the instruction shows changed: its instance is refreshed
        self.finished = False  # the law ended by itself this period (Done / end of a non-periodic cam)

    @property
    def masters(self) -> tuple[int, ...]:
        return ()

    def begin(self) -> int:
        """First period (the job becomes Active). Returns an ErrorID to refuse (0 = running)."""
        return 0

    def can_blend_into(self, nxt: Law) -> bool:
        """Blending is allowed only from MC_CamIn to MC_CamIn on the same master and ReferenceType."""
        return False

    def shift(self) -> float:
        """Master phase compensation of this period (MC_Phasing)."""
        ph = self.phasing
        if ph is None:
            return self.phase_base
        v = ph.value(self.m.cycle, self.m.period_s)
        if ph.done:
            self.phase_base = v
        return v

    def step(self) -> float:
        raise NotImplementedError

    def _set(self, attr: str, value: Any) -> None:
        if getattr(self, attr) != value:
            setattr(self, attr, value)
            self.flags_changed = True
            if attr == "in_sync":
                self.m.sync_changed()  # a cam follower may join the batch (sync_batch.py)


# ------------------------------------------------------------------------------------------------------- gears
class GearLaw(Law):
    kind = "gear"

    def __init__(self, m: MotionModule, job: Job, slave: Axis, master: Axis, *, ratio: float, ref: int,
                 acceleration: float, deceleration: float) -> None:
        super().__init__(m, job, slave)
        self.master = master
        self.ref = ref
        self.ratio = ratio
        self.acc = acceleration
        self.dec = deceleration
        self.v = 0.0  # slave velocity in the catching phase
        self.in_gear = False
        self.anchor: tuple[float, float] = (0.0, 0.0)  # (master, slave) positions when InGear began

    @property
    def masters(self) -> tuple[int, ...]:
        return (self.master.i,)

    def begin(self) -> int:
        self.v = float(self.m.prof_vel[self.slave.i])
        return 0

    def set_ratio(self, ratio: float, acceleration: float, deceleration: float) -> None:
        """Re-execution: a new ratio in the InGear phase applies at once (acc/dec as 0); in the catching phase the
        new ramp applies (MC_GearIn re-execution rules, decision D40)."""
        self.acc, self.dec = acceleration, deceleration
        if self.in_gear and ratio != self.ratio:
            m_now = master_sample(self.m, self.master.i, self.ref) + self.shift()
            s_now = float(self.m.cmd_pos[self.slave.i]) - self.offset
            self.anchor = (m_now, s_now)
        self.ratio = ratio

    def step(self) -> float:
        m, i = self.m, self.slave.i
        mpos = master_sample(m, self.master.i, self.ref) + self.shift()
        if self.in_gear:
            m0, s0 = self.anchor
            return s0 + self.ratio * (mpos - m0) + self.offset
        T = m.period_s
        target = master_velocity(m, self.master.i, self.ref) * self.ratio
        v = self.v
        speeding_up = abs(target) > abs(v) and (target * v >= 0)
        limit = self.acc if speeding_up else self.dec
        dv = target - v
        if limit > 0 and abs(dv) > limit * T:
            v += math.copysign(limit * T, dv)
            reached = False
        else:
            v = target
            reached = True
        self.v = v
        pos = float(m.cmd_pos[i]) + v * T
        if reached:
            self._set("in_gear", True)
            self.anchor = (mpos, pos - self.offset)
        return pos


class GearPosLaw(Law):
    """MC_GearInPos: the catch-up is planned once, at start, in master-position units: with the master velocity vm
    at start, master travel x corresponds to the time x/vm; the slave profile (from its velocity to vm × ratio, at
    most Velocity, arriving at the sync position when the master does) is sampled at that time (decision D41)."""

    kind = "gearpos"

    def __init__(self, m: MotionModule, job: Job, slave: Axis, master: Axis, *, ratio: float, ref: int,
                 master_sync: float, slave_sync: float, velocity: float, acceleration: float,
                 deceleration: float) -> None:
        super().__init__(m, job, slave)
        self.master = master
        self.ref = ref
        self.ratio = ratio
        self.master_sync_in = master_sync
        self.slave_sync_in = slave_sync
        self.velocity = velocity
        self.acc = acceleration
        self.dec = deceleration
        self.start_sync = False
        self.in_gear = False
        self.vm = 0.0
        self.m0 = self.s0 = self.m_sync = self.s_sync = 0.0
        self.seg: Segments | None = None

    @property
    def masters(self) -> tuple[int, ...]:
        return (self.master.i,)

    def begin(self) -> int:
        m = self.m
        vm = start_velocity(m, self.master.i, self.ref)
        if vm == 0.0:
            return E_MASTER_VELOCITY_ZERO
        if not self.velocity > abs(vm * self.ratio):
            return 0x5447  # insufficient target velocity
        self.vm = vm
        self.m0 = master_sample(m, self.master.i, self.ref)
        self.s0 = float(m.cmd_pos[self.slave.i])
        self.m_sync = _ahead(self.master, self.master_sync_in, self.m0, 1 if vm > 0 else -1)
        _, self.s_sync = self.slave.resolve_target(self.slave_sync_in, 4)  # as MC_MoveAbsolute _mcNoDirection
        duration = (self.m_sync - self.m0) / vm
        v0 = float(m.prof_vel[self.slave.i])
        v_end = vm * self.ratio
        seg = m.planner.timed(p0=self.s0, v0=v0, target=self.s_sync, v_end=v_end, velocity=self.velocity,
                              acceleration=self.acc, deceleration=self.dec, duration=duration)
        if seg is None:
            return E_GEARPOS_VALUE
        self.seg = seg
        self.start_sync = True
        self.flags_changed = True
        return 0

    def step(self) -> float:
        m = self.m
        mpos = master_sample(m, self.master.i, self.ref) + self.shift()
        if self.in_gear:
            return self.s_sync + self.ratio * (mpos - self.m_sync) + self.offset
        assert self.seg is not None
        tau = (mpos - self.m0) / self.vm
        if tau >= self.seg.duration:
            self._set("in_gear", True)
            self._set("in_sync", True)
            return self.s_sync + self.ratio * (mpos - self.m_sync) + self.offset
        return self.seg.sample(max(tau, 0.0))[0] + self.offset


# ------------------------------------------------------------------------------------------------------- link
class LinkLaw(Law):
    """MC_MoveLink: the slave velocity ratio (slave speed / master speed) ramps 0 → k over MasterDistanceInACC, stays
    k, ramps k → 0 over MasterDistanceInDEC; k = S / (Ma/2 + Mc + Md/2). Master travel is counted in the direction
    the master moves when the link starts (decision D42)."""

    kind = "link"

    def __init__(self, m: MotionModule, job: Job, slave: Axis, master: Axis, *, ref: int, slave_distance: float,
                 master_distance: float, acc_distance: float, dec_distance: float, option: int,
                 master_start: float) -> None:
        super().__init__(m, job, slave)
        self.master = master
        self.ref = ref
        self.S = slave_distance
        self.M = master_distance
        self.Ma = acc_distance
        self.Md = dec_distance
        self.option = option
        self.master_start = master_start
        self.waiting = True
        self.done = False
        self.sign = 1.0
        self.m0 = self.s0 = 0.0
        self.last_master = 0.0
        self.trigger: Any = None  # set by the instruction for _mcTriggerDetection
        self.arrived_cycle = -1  # the master travel was complete (in-position check from here)

    @property
    def masters(self) -> tuple[int, ...]:
        return (self.master.i,)

    def begin(self) -> int:
        self.last_master = master_sample(self.m, self.master.i, self.ref)
        self.s0 = float(self.m.cmd_pos[self.slave.i])
        if self.option == 0:
            self._start(self.last_master, at_begin=True)
        return 0

    def _start(self, mpos: float, *, at_begin: bool = False) -> None:
        self.waiting = False
        self.m0 = mpos
        v = (start_velocity if at_begin else master_velocity)(self.m, self.master.i, self.ref)
        self.sign = -1.0 if v < 0 else 1.0
        self._set("in_sync", True)

    def _in_position(self, target: float) -> bool:
        """MC_MoveLink completes with the in-position check ([In-position Range] within [In-position Check Time],
        as positioning does; no check when the check time is 0)."""
        op = self.slave.params.Operation
        m, i = self.m, self.slave.i
        if op.InPosCheckTime <= 0 or abs(m.act_pos.item(i) - target) <= op.InPosRange:
            self.slave.in_pos_waiting = False
            return True
        if self.arrived_cycle < 0:
            self.arrived_cycle = m.cycle
        self.slave.in_pos_waiting = True
        if (m.cycle - self.arrived_cycle) * m.period_s * 1000.0 >= op.InPosCheckTime:
            self.slave.in_pos_waiting = False
            self.slave.raise_error(E_INPOS_TIME, source=None, detail="MC_MoveLink: in-position check time exceeded")
        return False

    def fraction(self, x: float) -> float:
        """Share of the slave distance done after master travel x (0 … M)."""
        Ma, Md, M = self.Ma, self.Md, self.M
        Mc = M - Ma - Md
        denom = Ma / 2 + Mc + Md / 2
        if denom <= 0:
            return 1.0
        x = min(max(x, 0.0), M)
        if x < Ma:
            area = x * x / (2 * Ma)
        elif x <= Ma + Mc:
            area = Ma / 2 + (x - Ma)
        else:
            r = M - x
            area = denom - r * r / (2 * Md) if Md > 0 else denom
        return area / denom

    def step(self) -> float:
        m = self.m
        mpos = master_sample(m, self.master.i, self.ref) + self.shift()
        if self.waiting:
            prev, self.last_master = self.last_master, mpos
            if (self.option == 2 and _passed(self.master, self.master_start, prev, mpos)) or (
                    self.option == 1 and self.trigger is not None and self.trigger()):
                self._start(mpos)
            return float(m.cmd_pos[self.slave.i])
        x = (mpos - self.m0) * self.sign
        if x >= self.M:
            self._set("done", True)
            target = self.s0 + self.S + self.offset
            self.finished = self._in_position(target)
            return target
        return self.s0 + self.S * self.fraction(x) + self.offset


class CombineLaw(Law):
    kind = "combine"

    def __init__(self, m: MotionModule, job: Job, slave: Axis, master: Axis, auxiliary: Axis, *, subtract: bool,
                 ref_master: int, ref_aux: int) -> None:
        super().__init__(m, job, slave)
        self.master, self.aux = master, auxiliary
        self.subtract = subtract
        self.ref_m, self.ref_a = ref_master, ref_aux
        self.m0 = self.a0 = self.s0 = 0.0

    @property
    def masters(self) -> tuple[int, ...]:
        return (self.master.i, self.aux.i)

    def begin(self) -> int:
        m = self.m
        self.m0 = master_sample(m, self.master.i, self.ref_m)
        self.a0 = master_sample(m, self.aux.i, self.ref_a)
        self.s0 = float(m.cmd_pos[self.slave.i])
        self.in_sync = True  # InCombination from the period output starts
        self.flags_changed = True
        return 0

    def step(self) -> float:
        m = self.m
        dm = master_sample(m, self.master.i, self.ref_m) - self.m0 + self.shift()
        da = master_sample(m, self.aux.i, self.ref_a) - self.a0
        return self.s0 + (dm - da if self.subtract else dm + da) + self.offset


# ------------------------------------------------------------------------------------------------------- cams
class CamLaw(Law):
    kind = "cam"

    def __init__(self, m: MotionModule, job: Job, slave: Axis, master: Axis, table: CamTable, *, ref: int,
                 periodic: bool, start_mode: int, start_position: float, master_start_distance: float,
                 master_scaling: float, slave_scaling: float, master_offset: float, slave_offset: float,
                 direction: int) -> None:
        super().__init__(m, job, slave)
        self.master = master
        self.ref = ref
        self.periodic = periodic
        self.start_mode = start_mode
        self.start_position = start_position
        self.msd = master_start_distance
        self.mscale = master_scaling
        self.sscale = slave_scaling
        self.moffset = master_offset
        self.soffset = slave_offset
        self.direction = direction
        self.in_cam = False
        self.eop_cycle = -1
        self.ended = False
        self.index = 0
        self.base = 0.0  # unwrapped master position of table phase 0 (StartPosition crossing + MasterOffset)
        self.sync_at = 0.0  # unwrapped master position where camming starts
        self.sref = 0.0  # slave position of the table start point
        self.last_master = 0.0
        self.last_out = 0.0
        self.blend_from: float | None = None  # blending: start at the previous cam's end position at once
        self.set_table(table)

    @property
    def masters(self) -> tuple[int, ...]:
        return (self.master.i,)

    def can_blend_into(self, nxt: Law) -> bool:
        return isinstance(nxt, CamLaw) and nxt.master is self.master and nxt.ref == self.ref

    def set_table(self, table: CamTable) -> None:
        if hasattr(self, "table"):
            self.m.sync_changed()  # re-execution switches the table: the batch is rebuilt with the new data
        self.table = table
        p, d = table.valid()
        # Python lists: one bisection and one interpolation per period are several times cheaper than numpy calls
        # on scalars (the kernel benchmark runs ¼ of its axes as cam followers)
        self.P: list[float] = p.astype(float).tolist()
        self.D: list[float] = d.astype(float).tolist()
        self.last = len(self.P) - 1
        self.end_phase = self.P[-1]
        self.end_distance = self.D[-1]

    def begin(self) -> int:
        m = self.m
        self.last_master = mpos = master_sample(m, self.master.i, self.ref) + self.shift()
        self.sref = float(m.cmd_pos[self.slave.i])
        self.last_out = self.sref
        if self.blend_from is not None:
            # blending between cams: the new table starts at once where the previous one ended (InSync at once)
            self.base = mpos - self.moffset
            self.sref = self.blend_from
            self._set("in_cam", True)
            self._set("in_sync", True)
            return 0
        if _at(self.master, self.start_position, mpos):
            self._enter_cam(mpos)
        return 0

    def _enter_cam(self, mpos: float) -> None:
        # the unwrapped master position of StartPosition at this crossing
        sp = _nearest(self.master, self.start_position, mpos)
        self.base = sp + self.moffset
        self._set("in_cam", True)
        start = self.msd if self.start_mode == 0 else self.start_position + self.msd
        # the first occurrence of the cam start position from the StartPosition crossing on, in the direction of
        # motion; reached already when the master passed both in this period
        sign = _dir(self.m, self.master.i, self.ref) or (1 if mpos >= sp else -1)
        self.sync_at = _ahead_or_at(self.master, start, sp, sign)
        if (self.sync_at - mpos) * sign <= 0:
            self._set("in_sync", True)

    def phase_of(self, mpos: float) -> float:
        return (mpos - self.base) / self.mscale

    def step(self) -> float:
        m = self.m
        ref = self.ref
        src = m.act_pos if ref == REF_FEEDBACK else m.cmd_pos if ref == REF_LATEST else m.prev_cmd_pos
        mpos = src.item(self.master.i)
        mpos += self.phase_base if self.phasing is None else self.shift()
        prev, self.last_master = self.last_master, mpos
        if self.in_sync and self.direction == 4:
            return self._cam(mpos)
        hold = m.cmd_pos.item(self.slave.i)
        if not self.in_cam:
            if _passed(self.master, self.start_position, prev, mpos):
                self._enter_cam(mpos)
            if not self.in_cam:
                return hold
        if not self.in_sync:
            start = self.sync_at
            if ((prev - start) * (mpos - start) <= 0 and prev != mpos) or mpos == start:
                self._set("in_sync", True)
            else:
                return hold
        moving = mpos - prev
        if (self.direction == 0 and moving < 0) or (self.direction == 2 and moving > 0):
            return hold  # master moving against Direction: the slave holds
        return self._cam(mpos)

    def _cam(self, mpos: float) -> float:
        """Camming: the slave position for master position `mpos` (phase wrapped for periodic tables)."""
        m = self.m
        phase = (mpos - self.base) / self.mscale
        end = self.end_phase
        eop = False
        if self.periodic and phase >= end and self.slave.buffered is not None:
            # a buffered successor takes over when this cycle's end point has been output
            phase = end
            eop = True
            self.finished = True
        elif self.periodic:
            while phase >= end:
                self.base += end * self.mscale
                self.sref += self.sscale * self.end_distance
                phase -= end
                eop = True
            while phase < 0:
                self.base -= end * self.mscale
                self.sref -= self.sscale * self.end_distance
                phase += end
        elif phase >= end:
            phase = end
            eop = True
            self.ended = self.finished = True
        elif phase < 0:
            phase = 0.0
        if eop:
            self.eop_cycle = m.cycle
            self.flags_changed = True
        P, last = self.P, self.last
        if last == 0:
            k, dist = 0, self.D[0]
        else:
            k = bisect_right(P, phase) - 1
            k = 0 if k < 0 else (last - 1 if k >= last else k)
            p0, p1 = P[k], P[k + 1]
            d0 = self.D[k]
            dist = d0 + (self.D[k + 1] - d0) * (phase - p0) / (p1 - p0) if p1 > p0 else d0
            if phase >= p1:
                dist = self.D[k + 1]
        if k != self.index:
            self.index = k
            self.flags_changed = True
        if eop and phase == 0.0 and self.periodic:
            dist = 0.0
        return self.sref + self.sscale * dist + self.soffset + self.offset


# ------------------------------------------------------------------------------------------------------- cyclic
class CyclicPositionLaw(Law):
    """MC_SyncMoveAbsolute: the target the program writes every period is output in the next period, the step
    limited to Maximum Velocity × period (the rest follows in the next periods, `Details.VelLimit`); Maximum
    Acceleration/Deceleration are not applied."""

    kind = "cyclic"

    def __init__(self, m: MotionModule, job: Job, slave: Axis, target: float) -> None:
        super().__init__(m, job, slave)
        self.target = target
        self.vel_limit = False
        self.vmax_step = slave.params.Operation.MaxVel * m.period_s

    def step(self) -> float:
        cur = self.m.cmd_pos.item(self.slave.i)
        d = self.target - cur
        limit = self.vmax_step
        saturated = abs(d) > limit > 0
        if saturated != self.vel_limit:
            self.vel_limit = saturated
            self.flags_changed = True
        if saturated:
            return cur + math.copysign(limit, d)
        return self.target


# ------------------------------------------------------------------------------------------------------- helpers
def _ring(axis: Axis) -> float:
    return axis.mod_max - axis.mod_min if axis.rotary else math.inf


def _nearest(axis: Axis, pos: float, around: float) -> float:
    """The unwrapped value of ring position `pos` nearest to `around` (linear axes: pos)."""
    L = _ring(axis)
    if not math.isfinite(L):
        return pos
    k = round((around - pos) / L)
    return pos + k * L


def _at(axis: Axis, pos: float, mpos: float) -> bool:
    return abs(_nearest(axis, pos, mpos) - mpos) <= 1e-9 * max(1.0, abs(mpos))


def _passed(axis: Axis, pos: float, prev: float, cur: float) -> bool:
    """The master went from prev to cur through (or onto) ring position `pos` (not counting leaving it)."""
    if cur == prev:
        return False
    lo, hi = (prev, cur) if cur > prev else (cur, prev)
    L = _ring(axis)
    if not math.isfinite(L):
        return (lo < pos <= hi) if cur > prev else (lo <= pos < hi)
    k = math.ceil((lo - pos) / L)
    x = pos + k * L
    if cur > prev:
        return lo < x <= hi or (x == lo and False) or (lo < x + L <= hi)
    return lo <= x < hi


def _ahead(axis: Axis, pos: float, mpos: float, sign: int) -> float:
    """The unwrapped value of `pos` strictly ahead of mpos in direction `sign` (linear: pos)."""
    L = _ring(axis)
    if not math.isfinite(L):
        return pos
    x = _nearest(axis, pos, mpos)
    if sign > 0:
        while x <= mpos:
            x += L
        while x - L > mpos:
            x -= L
    else:
        while x >= mpos:
            x -= L
        while x + L < mpos:
            x += L
    return x


def _ahead_or_at(axis: Axis, pos: float, mpos: float, sign: int) -> float:
    if _at(axis, pos, mpos):
        return mpos
    return _ahead(axis, pos, mpos, sign if sign else 1)


def _dir(m: MotionModule, i: int, ref: int) -> int:
    v = master_velocity(m, i, ref)
    return 1 if v > 0 else -1 if v < 0 else 0
