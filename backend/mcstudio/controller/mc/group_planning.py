"""Group motion planning (mixed into `AxesGroup`): start and buffer the interpolation instructions by BufferMode,
plan a path's 1-D profile s(t) with the axis planner, blending transit velocities, the interpolation velocity
clamp, and re-planning on an override change.

Group motion is a path (`group_path.py`) and a 1-D profile s(t) along it, planned once per move with the axis planner
(`profile.Planner`: trapezoid when Jerk = 0, S-curve otherwise) and re-planned only on events (blending successor,
override, MC_GroupStop). Spec: `omron-group-and-cam.md` §4.3 (BufferMode, TransitionMode), §4.6; decisions D50–D56.

* Deceleration = 0 with a blending successor (§4.3 velocity profile): no stop — the move keeps its velocity to its end
  and the successor starts at its own target velocity ("the velocity changes instantly", D105).
* Acceleration/Deceleration Over of the group (`InterpolationAccDecOver`, D106): a profile that would pass the end of
  its path (an Aborting multi-execution onto a moving group that cannot stop in time, a blended successor too short
  for its transit velocity) is 5444 / 5445 with "error stop", otherwise it uses the deceleration it takes ("rapid").
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from . import errors as E
from .enums import _eMC_ACCDECOVER, _eMC_BUFFER_MODE
from .group_path import Path
from .group_types import MAX_BUFFERED, G, Motion, _Pos, decel_start
from .jobs import Job, JobKind, JobStatus
from .profile import PlanningError, Segments, concat

if TYPE_CHECKING:
    from ...project.models import GroupOperationSettings
    from .axis import Axis
    from .module import MotionModule


class GroupPlanning:
    m: MotionModule
    name: str
    number: int
    op: GroupOperationSettings
    axes: list[Axis]
    current: Job | None
    queue: list[Job]
    motion: Motion | None
    overlap: Motion | None
    override: float
    override_owner: int | None
    sync_target: tuple[float, ...] | None

    # ------------------------------------------------------------------ override
    def set_override(self, fb_id: int, factor: float | None, changed: bool) -> None:
        """MC_GroupSetOverride: `factor` in % (None = Enable FALSE → 100 %); the later instance has priority."""
        if changed and factor is not None:
            self.override_owner = fb_id
        if self.override_owner != fb_id:
            return
        if factor is None:
            self.override_owner = -1
            factor = 100.0
        value = factor / 100.0
        if value == self.override:
            return
        self.override = value
        mv = self.motion
        if mv is not None and mv.job.kind == JobKind.GROUP_MOVE and not mv.stopping and self.overlap is None:
            self._replan(mv)

    def _target_velocity(self, mv: Motion) -> float:
        return min(mv.velocity * self.override, self.op.MaxInterpolationVel)

    # ------------------------------------------------------------------ group motion instructions
    def submit(self, job: Job) -> int:
        """Start or buffer a group motion instruction by its BufferMode. Returns an ErrorID (0 = accepted)."""
        cur = self.current
        if job.buffer_mode == _eMC_BUFFER_MODE._mcAborting or cur is None or cur.kind == JobKind.GROUP_STOP:
            start = self._abort_for(job)
            self.abort_all()
            return self._begin(job, start, t0=self.m.cycle * self.m.period_s)
        if cur.kind == JobKind.GROUP_SYNC or job.kind == JobKind.GROUP_SYNC:
            return E.E_MULTIEXEC_DISABLED  # MC_GroupSyncMoveAbsolute only aborts and is only aborted (§4.12)
        if len(self.queue) >= MAX_BUFFERED:
            return E.E_BUFFER_LIMIT
        job.status = JobStatus.WAITING
        self.queue.append(job)
        if job.buffer_mode >= _eMC_BUFFER_MODE._mcBlendingLow and len(self.queue) == 1:
            code = self._blend_current(job)
            if code:
                self.queue.remove(job)
                return code
        return 0

    def _abort_for(self, job: Job) -> _Pos:
        """Start point of an Aborting instruction: the command positions and the per-axis velocities now."""
        mv = self.motion
        if mv is None:
            return _Pos(self.point())
        v, _ = mv.path.velocity(mv.s, mv.sd, mv.sdd)
        return _Pos(self.point(), v)

    def _begin(self, job: Job, start: _Pos, *, t0: float, v0: float | None = None, pushed: bool = False,
               instant: bool = False) -> int:
        """Plan `job` from `start` and make it current. v0: the path velocity at the start (blending); None = the
        projection of the current per-axis velocity on the new direction (Aborting; a reversal starts from 0, D54).
        `instant`: the predecessor had Deceleration 0 — start at the target velocity (D105)."""
        m = self.m
        self.clear_member_flags()
        if job.kind == JobKind.GROUP_SYNC:
            self.halt()
            self.current = job
            job.status = JobStatus.STARTING
            self.sync_target = None
            self._set_state(G.Moving)
            m.moving_groups[self.number] = self
            return 0
        build = job.info["build"]
        path = build(start.point)
        if isinstance(path, int):
            return path
        if v0 is None:
            u = path.direction_in()
            v0 = max(0.0, sum(a * b for a, b in zip(start.velocity, u, strict=False))) if start.velocity else 0.0
        velocity = self._clamp_velocity(path, job.velocity)
        mv = Motion(job, path, Segments([0.0], [0.0], [0.0], [0.0], [0.0], 0.0, 0.0, 0.0), t0, velocity, s=0.0,
                    sd=v0)
        if instant:
            v0 = mv.sd = self._target_velocity(mv)
        nxt = self.queue[0] if self.queue else None
        if nxt is not None and nxt.buffer_mode >= _eMC_BUFFER_MODE._mcBlendingLow:
            self._set_transit(mv, nxt)
        prev = self.motion
        self.overlap = None if not pushed else self.overlap
        self.current = job
        self.motion = mv
        # a profile from a velocity > 0 that cannot stop on the path's end: 5444 for an Aborting multi-execution,
        # 5445 for a blended successor (with InterpolationAccDecOver = error stop, D106)
        over = 0 if v0 <= 0.0 else E.E_BLEND_DISTANCE if pushed else E.E_TRAVEL_SHORT
        code = self._plan(mv, s0=0.0, v0=v0, a0=0.0, t0=t0, over_code=over)
        if code:
            # the error stop (raise_error by the caller) decelerates along the path the group was following
            self.motion = prev if not pushed else None
            self.current = None
            return code
        job.status = JobStatus.ACTIVE if pushed else JobStatus.STARTING
        if pushed:
            m.job_changed(job)
        self._set_state(G.Moving)
        m.moving_groups[self.number] = self
        return 0

    def _clamp_velocity(self, path: Path, velocity: float) -> float:
        """The interpolation velocity: at most the maximum interpolation velocity and such that no axis exceeds its
        Maximum Velocity (§4.3 velocity decomposition, §4.6)."""
        v = min(velocity, self.op.MaxInterpolationVel)
        if hasattr(path, "u"):
            for a, k in zip(self.axes, path.u, strict=False):  # type: ignore[union-attr]
                if abs(k) > 0:
                    v = min(v, a.params.Operation.MaxVel / abs(k))
        else:
            for li in (path.ix, path.iy):  # type: ignore[union-attr]
                v = min(v, self.axes[li].params.Operation.MaxVel)
        return v

    def _acc_dec(self, job: Job) -> tuple[float, float, float]:
        acc, dec, jerk = job.acceleration, job.deceleration, job.jerk
        if self.op.MaxInterpolationAcc > 0 and acc > self.op.MaxInterpolationAcc:
            acc = self.op.MaxInterpolationAcc
        if self.op.MaxInterpolationDec > 0 and dec > self.op.MaxInterpolationDec:
            dec = self.op.MaxInterpolationDec
        if acc == 0 or dec == 0:
            jerk = 0.0  # §4.3: with Acceleration or Deceleration 0 the jerk is ignored
        return acc, dec, jerk

    def _set_transit(self, mv: Motion, nxt: Job) -> None:
        """The end velocity of `mv` for its blending successor `nxt`: the transit velocity of the BufferMode, or, when
        `mv` has Deceleration 0 (and no corner superimposition), its own velocity up to the end with the successor
        starting at its target velocity (§4.3: "the velocity changes instantly to the next instruction's target
        velocity", D105)."""
        if not nxt.info.get("corner") and self._acc_dec(mv.job)[1] == 0.0:
            mv.instant = True
            mv.v_end = self._target_velocity(mv)
        else:
            mv.instant = False
            mv.v_end = self._transit(mv.job, nxt)

    def _transit(self, job: Job, nxt: Job) -> float:
        """Transit velocity at the end of `job` for a blending successor (§4.3 BufferMode)."""
        v1, v2 = job.velocity, nxt.velocity
        if nxt.info.get("corner"):
            return 0.0  # corner superimposition: the previous move decelerates to its end, the next one overlaps
        mode = nxt.buffer_mode
        if mode == _eMC_BUFFER_MODE._mcBlendingLow:
            v = min(v1, v2)
        elif mode == _eMC_BUFFER_MODE._mcBlendingPrevious:
            v = v1
        elif mode == _eMC_BUFFER_MODE._mcBlendingNext:
            v = v2
        else:
            v = max(v1, v2)
        return min(v * self.override, self.op.MaxInterpolationVel)

    def _plan(self, mv: Motion, *, s0: float, v0: float, a0: float, t0: float, over_code: int = 0) -> int:
        """(Re)plan the profile of `mv` from (s0, v0, a0) at kernel time t0 to its end (or to velocity 0 when the
        override is 0). Returns an ErrorID (5445 when the transit velocity cannot be reached and the interpolation
        Acc/Dec Over is error stop; `over_code` when the profile cannot stop on the path's end and it is error stop,
        else the deceleration it takes is used, D106)."""
        acc, dec, jerk = self._acc_dec(mv.job)
        error_stop = self.op.InterpolationAccDecOver == _eMC_ACCDECOVER._mcAccDecOverErrorStop
        planner = self.m.planner
        velocity = self._target_velocity(mv)
        length = mv.path.length
        try:
            if velocity <= 0.0:
                seg = planner.velocity(p0=s0, v0=v0, a0=a0, target_velocity=0.0, acceleration=acc,
                                       deceleration=dec, jerk=jerk)
                mv.paused = True
            else:
                mv.paused = False
                if mv.instant:
                    mv.v_end = velocity  # Dec = 0 before a blending successor: no deceleration at the end (D105)
                v_end = self._reachable(mv.v_end, v0, length - s0, acc, dec)
                if v_end != mv.v_end and not mv.instant and error_stop:
                    return E.E_BLEND_DISTANCE
                mv.v_end = v_end
                if length - s0 <= 0.0:
                    seg = Segments([0.0], [length], [v_end], [0.0], [0.0], 0.0, length, v_end)
                else:
                    seg = None
                    if v0 > velocity * (1.0 + 1e-12):
                        # slower than now (override, Aborting): decelerate to the new velocity first, then on to the
                        # end (the planner alone would keep the present velocity as the limit)
                        slow = planner.velocity(p0=s0, v0=v0, a0=a0, target_velocity=velocity, acceleration=acc,
                                                deceleration=dec, jerk=jerk)
                        if slow.end_position < length:
                            rest = planner.position(p0=slow.end_position, v0=velocity, a0=0.0, target=length,
                                                    velocity=velocity, acceleration=acc, deceleration=dec,
                                                    jerk=jerk, v_end=v_end)
                            seg = concat(slow, rest)
                    if seg is None:
                        seg = planner.position(p0=s0, v0=v0, a0=a0, target=length, velocity=velocity,
                                               acceleration=acc, deceleration=dec, jerk=jerk, v_end=v_end)
                    if seg.overshoot:
                        if over_code and error_stop:
                            return over_code
                        # rapid: the deceleration (acceleration) it takes to arrive on the end at v_end
                        rest = length - s0
                        need = abs(v0 * v0 - v_end * v_end) / (2.0 * rest) * 1.000001
                        seg = planner.position(p0=s0, v0=v0, a0=0.0, target=length, velocity=max(velocity, v0),
                                               acceleration=max(acc, need), deceleration=max(dec, need), jerk=0.0,
                                               v_end=v_end)
        except PlanningError as err:
            self.m.log_error(0xFFFF, axis=None, source=self.name, detail=str(err), group=self.name)
            return 0xFFFF
        mv.seg = seg
        mv.t0 = t0
        mv.k = 0
        mv.end_cycle = -1
        mv.t_dec = decel_start(seg) if not mv.paused else math.inf
        return 0

    @staticmethod
    def _reachable(v_end: float, v0: float, rest: float, acc: float, dec: float) -> float:
        """The transit velocity the remaining distance allows with the acceleration/deceleration (trapezoid)."""
        if v_end <= 0.0 or rest <= 0.0:
            return max(0.0, v_end) if rest > 0.0 else v0
        if v_end > v0 and acc > 0:
            return min(v_end, math.sqrt(v0 * v0 + 2.0 * acc * rest))
        if v_end < v0 and dec > 0:
            return max(v_end, math.sqrt(max(v0 * v0 - 2.0 * dec * rest, 0.0)))
        return v_end

    def _replan(self, mv: Motion) -> None:
        """Override change: plan again from the last evaluated state, from this period on."""
        code = self._plan(mv, s0=mv.s, v0=mv.sd, a0=mv.sdd, t0=self.m.cycle * self.m.period_s)
        if code:
            self.raise_error(code, source=mv.job.owner.label if mv.job.owner is not None else None)

    def _blend_current(self, nxt: Job) -> int:
        """A blending successor was buffered behind the running move: re-plan it to reach its end at the transit
        velocity (or, for corner superimposition, mark where the successor starts)."""
        mv = self.motion
        cur = self.current
        if mv is None or cur is None or cur.kind != JobKind.GROUP_MOVE or mv.stopping:
            return 0
        if nxt.info.get("corner"):
            return 0
        self._set_transit(mv, nxt)
        if mv.paused:
            return 0
        return self._plan(mv, s0=mv.s, v0=mv.sd, a0=mv.sdd, t0=self.m.cycle * self.m.period_s)

    def _freeze_overlap(self) -> None:
        """Drop the decelerating previous move of a corner superimposition (its remaining travel is lost)."""
        ov = self.overlap
        self.overlap = None
        if ov is not None:
            self._end_job(ov.job, JobStatus.DONE)
