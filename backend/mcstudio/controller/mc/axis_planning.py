"""Profile planning and profile ends of an axis (mixed into `Axis`).

* Positioning: target velocity × override (clamped to Maximum Velocity), Start Velocity, Operation Selection at
  Reversing; with a blending successor the move is planned to reach its target at the transit velocity
  (`_mcBlendingLow/Previous/Next/High`, `omron-mc-basics.md` §1.5) and the successor's profile is appended, so the
  hand-over happens without a gap inside one segment table.
* Acceleration/Deceleration Over (`_eMC_ACCDECOVER`): when a positioning started on a moving axis (multi-execution,
  re-execution, blending) cannot reach its target (or its transit velocity) with its acceleration/deceleration, the
  axis either uses the acceleration/deceleration needed to make it ("rapid", values 0 and 1; CPU ≥ 1.10 semantics:
  blending is not converted to buffered) or error-stops with 5444 / 5445 (value 2).
* Profile ends are reported one period after the profile reached them (decision D1).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from . import errors as E
from .enums import AxisState, _eMC_ACCDECOVER, _eMC_BUFFER_MODE, _eMC_REVERSE_MODE
from .jobs import Job, JobKind, JobStatus
from .profile import Segments, concat

if TYPE_CHECKING:
    from .module import MotionModule

S = AxisState
E_INPOS_TIME = 0x6455  # MC Studio assignment (errors_table.py)


class AxisPlanning:
    m: MotionModule
    i: int
    current: Job | None
    buffered: Job | None
    in_pos_waiting: bool
    homing: object

    # ------------------------------------------------------------------ planning
    def plan_job(self, job: Job, p0: float, v0: float, a0: float) -> Segments | int:
        """Profile of `job` from the current command state, or an ErrorID."""
        planner = self.m.planner
        op = self.params.Operation  # type: ignore[attr-defined]
        ovr = float(self.m.override[self.i]) if job.overridable else 1.0
        kind = job.kind
        if kind == JobKind.POSITION:
            if job.relative and job.origin is None:
                job.origin = p0
                job.target = p0 + job.distance
            elif job.absolute_target is not None and job.status == JobStatus.STARTING:
                # a rotary target is resolved (direction, shortest way) from where the instruction starts
                _, job.target = self.resolve_target(job.absolute_target, job.direction, p0)  # type: ignore[attr-defined]
            if job.overridable and ovr == 0.0:
                job.paused = True  # override 0: decelerate to 0 and wait, still Discrete (MC_SetOverride rules)
                return planner.stop(p0=p0, v0=v0, a0=a0, deceleration=job.deceleration, jerk=job.jerk)
            job.paused = False
            nxt = self.buffered
            blend = nxt is not None and nxt.buffer_mode >= _eMC_BUFFER_MODE._mcBlendingLow
            v_end = self._transit_velocity(job, nxt, p0, ovr) if blend else 0.0  # type: ignore[arg-type]
            seg = self._position(job, p0, v0, a0, ovr, v_end, blending=blend)
            if isinstance(seg, int) or not blend:
                job.info.pop("split_time", None)
                return seg
            assert nxt is not None
            if nxt.relative:
                nxt.origin = job.target
                nxt.target = job.target + nxt.distance
            elif nxt.absolute_target is not None:
                _, nxt.target = self.resolve_target(nxt.absolute_target, nxt.direction, job.target)  # type: ignore[attr-defined]
            nxt_ovr = float(self.m.override[self.i]) if nxt.overridable else 1.0
            seg2 = self._position(nxt, job.target, v_end, 0.0, nxt_ovr, 0.0, blending=True)
            if isinstance(seg2, int):
                return seg2
            job.info["split_time"] = seg.duration
            combined = concat(seg, seg2)
            nxt.info["end_time"] = combined.duration
            return combined
        if kind in (JobKind.VELOCITY, JobKind.JOG):
            v = 0.0 if job.stopping else job.velocity * ovr
            v = max(-op.MaxVel, min(op.MaxVel, v))
            return planner.velocity(p0=p0, v0=v0, a0=a0, target_velocity=v, acceleration=job.acceleration,
                                    deceleration=job.deceleration, jerk=job.jerk)
        if kind in (JobKind.STOP, JobKind.SYNC_OUT):
            return planner.stop(p0=p0, v0=v0, a0=a0, deceleration=job.deceleration, jerk=job.jerk)
        if kind == JobKind.ERROR_STOP:
            stop_at = job.info.get("stop_at")
            if stop_at is None:
                return planner.stop(p0=p0, v0=v0, a0=a0, deceleration=job.deceleration, jerk=0.0)
            d = abs(stop_at - p0)
            need = v0 * v0 / (2 * d) if d > 0 else 0.0
            return planner.position(p0=p0, v0=v0, a0=0.0, target=stop_at, velocity=max(abs(v0), 1e-9),
                                    acceleration=need * 1.000001, deceleration=need * 1.000001, jerk=0.0)
        if kind == JobKind.RESET_FE:
            # the correction runs at Maximum Velocity without acc/dec limits (MC_ResetFollowingError rules)
            return planner.position(p0=p0, v0=0.0, a0=0.0, target=job.target, velocity=op.MaxVel,
                                    acceleration=0.0, deceleration=0.0, jerk=0.0)
        if kind == JobKind.HOMING and self.homing is not None:
            return self.homing.plan(p0, v0, a0)  # type: ignore[attr-defined,no-any-return]
        return planner.stop(p0=p0, v0=v0, a0=a0, deceleration=0.0, jerk=0.0)

    def _position(self, job: Job, p0: float, v0: float, a0: float, ovr: float, v_end: float, *,
                  blending: bool) -> Segments | int:
        op = self.params.Operation  # type: ignore[attr-defined]
        planner = self.m.planner
        vmax = min(abs(job.velocity) * ovr, op.MaxVel)
        kwargs = {
            "v_start": op.StartVel,
            "reverse_immediate": op.ReverseMode == _eMC_REVERSE_MODE._mcReverseModeImmediateStop,
        }
        seg = planner.position(p0=p0, v0=v0, a0=a0, target=job.target, velocity=vmax,
                               acceleration=job.acceleration, deceleration=job.deceleration, jerk=job.jerk,
                               v_end=v_end, **kwargs)
        job.rapid = False
        if not seg.overshoot:
            return seg
        if op.AccDecOver == _eMC_ACCDECOVER._mcAccDecOverErrorStop:
            return E.E_BLEND_DISTANCE if blending else E.E_TRAVEL_SHORT
        # Rapid acc/dec: the acceleration or deceleration it takes to arrive on target (at the transit velocity).
        d = abs(job.target - p0)
        need = abs(v0 * v0 - v_end * v_end) / (2 * d) if d > 0 else 0.0
        acc = max(job.acceleration, need * 1.000001)
        dec = max(job.deceleration, need * 1.000001)
        job.rapid = True
        return planner.position(p0=p0, v0=v0, a0=0.0, target=job.target, velocity=max(vmax, abs(v0)),
                                acceleration=acc, deceleration=dec, jerk=0.0, v_end=v_end, **kwargs)

    def _transit_velocity(self, cur: Job, nxt: Job, p0: float, ovr: float) -> float:
        """Velocity at the junction of two blended positionings: 0 when the direction reverses."""
        op = self.params.Operation  # type: ignore[attr-defined]
        if nxt.relative:
            nxt_target = cur.target + nxt.distance
        elif nxt.absolute_target is not None:
            _, nxt_target = self.resolve_target(nxt.absolute_target, nxt.direction, cur.target)  # type: ignore[attr-defined]
        else:
            nxt_target = nxt.target
        d1 = cur.target - p0
        d2 = nxt_target - cur.target
        if d1 == 0 or d2 == 0 or (d1 > 0) != (d2 > 0):
            return 0.0
        nxt_ovr = float(self.m.override[self.i]) if nxt.overridable else 1.0
        vc = abs(cur.velocity) * ovr
        vn = abs(nxt.velocity) * nxt_ovr
        mode = nxt.buffer_mode
        if mode == _eMC_BUFFER_MODE._mcBlendingLow:
            v = min(vc, vn)
        elif mode == _eMC_BUFFER_MODE._mcBlendingPrevious:
            v = vc
        elif mode == _eMC_BUFFER_MODE._mcBlendingNext:
            v = vn
        else:
            v = max(vc, vn)
        v = min(v, op.MaxVel)
        return v if d1 > 0 else -v

    # ------------------------------------------------------------------ profile ends
    def on_profile_finished(self, job: Job) -> bool:
        """The profile of the current job reached its end (target, target velocity, standstill, transit point).

        Returns True while the end is still pending and must be reported again next period. Ends are reported one
        period after the profile reached them, when the command values the axis reports agree: Cmd.Vel (a difference
        of positions) equals the target velocity (InVelocity) or 0, and the final command value has reached the
        drive (positioning complete, stop complete). A positioning with an in-position check time also waits until
        the actual position is inside the in-position range.
        """
        m, i = self.m, self.i
        cycle = m.cycle
        if job.kind == JobKind.HOMING:
            return bool(self.homing.on_profile_end()) if self.homing is not None else False  # type: ignore[attr-defined]
        if job.kind == JobKind.POSITION and job.paused:
            return False
        split = job.info.get("split_time")
        if job.kind == JobKind.POSITION and split is not None and self.buffered is not None:
            # blended hand-over: the successor is already in the segment table and continues without a gap
            nxt = self.buffered
            self.buffered = None
            job.info.pop("split_time", None)
            self._end_job(job, JobStatus.DONE)  # type: ignore[attr-defined]
            nxt.status = JobStatus.ACTIVE
            m.job_changed(nxt)  # Active of the successor shows with the Done of this one
            self.current = nxt
            m.profiles.duration[i] = nxt.info.pop("end_time")
            return True
        if job.cmd_done_cycle < 0:
            job.cmd_done_cycle = cycle
        if cycle <= job.cmd_done_cycle:
            return True  # the final command value is sent in this period's outputs
        if job.kind in (JobKind.VELOCITY, JobKind.JOG) and not job.stopping:
            # InVelocity: Cmd.Vel (difference of positions) has reached the target velocity
            if not job.in_velocity:
                job.in_velocity = True
                m.job_changed(job)
                if self.buffered is not None:
                    self._promote_buffered()  # type: ignore[attr-defined]
            return False
        if job.kind == JobKind.POSITION:
            op = self.params.Operation  # type: ignore[attr-defined]
            if op.InPosCheckTime > 0 and abs(float(m.act_pos[i]) - job.target) > op.InPosRange:
                waited = (cycle - job.cmd_done_cycle) * m.period_s
                if waited * 1000.0 >= op.InPosCheckTime:
                    self.raise_error(E_INPOS_TIME, source=None,  # type: ignore[attr-defined]
                                     detail=f"|Act.Pos − target| = {abs(float(m.act_pos[i]) - job.target):g} after "
                                     f"{op.InPosCheckTime} ms")
                    return False
                self.in_pos_waiting = True
                return True
            self.in_pos_waiting = False
        m.profiles.clear(i)
        self._end_job(job, JobStatus.DONE)  # type: ignore[attr-defined]
        if job.kind == JobKind.ERROR_STOP:
            return False
        if job.kind in (JobKind.POSITION, JobKind.SYNC_OUT) and self.buffered is not None:
            self._promote_buffered()  # type: ignore[attr-defined]
        else:
            self._set_state(self._rest_state())  # type: ignore[attr-defined]
        return False
