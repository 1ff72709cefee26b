"""The period of a group (mixed into `AxesGroup`): evaluate s(t) of the running path and write the composition
axes' command positions, blended hand-over (with the Dec = 0 rule, D105) and corner superimposition, the end of a
move (with the in-position check of `group_monitor.py`, D103), MC_GroupStop's deceleration along the path, and
MC_GroupSyncMoveAbsolute (with `Details.VelLimit`, D107).

Every period `step` evaluates s(t) — a few float operations — and writes the composition axes' command positions, so
the generic command-value stage of the MC module derives Cmd.Vel/AccDec from them. Spec: `omron-group-and-cam.md`
§4.3, §4.12; decisions D50–D56.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from .enums import _eMC_BUFFER_MODE
from .group_types import G, Motion, _Pos, sample
from .jobs import Job, JobKind, JobStatus

if TYPE_CHECKING:
    from .axis import Axis
    from .module import MotionModule


class GroupMotion:
    m: MotionModule
    name: str
    number: int
    axes: list[Axis]
    idx: list[int]
    kinematics: object
    current: Job | None
    queue: list[Job]
    motion: Motion | None
    overlap: Motion | None
    sync_target: tuple[float, ...] | None
    cmd_vel: float
    cmd_accdec: float
    warn_on: bool

    # ------------------------------------------------------------------ MC_GroupStop / MC_GroupImmediateStop
    def stop(self, job: Job) -> None:
        """Decelerate along the path with the instruction's Deceleration (0 = immediate); the running and buffered
        motion instructions are CommandAborted; MC_GroupSyncMoveAbsolute stops immediately."""
        cur = self.current
        if cur is not None and cur.kind == JobKind.GROUP_STOP and cur.owner is not None:
            self._end_job(cur, JobStatus.DONE)  # multi-execution of MC_GroupStop: the earlier one is Done (D52)
        sync = cur is not None and cur.kind == JobKind.GROUP_SYNC
        self.abort_all()
        self.current = job
        self._set_state(G.Stopping)
        mv = self.motion
        if mv is None or sync or job.deceleration <= 0 or mv.paused:
            self.halt()
            job.status = JobStatus.STARTING  # Done in the next period
            job.info["done_next"] = self.m.cycle
            self.m.moving_groups[self.number] = self
            return
        self._decelerate(job, job.deceleration, job.jerk)

    def restop(self, job: Job) -> None:
        """Re-execution of MC_GroupStop: a new Deceleration (the jerk is kept)."""
        if job is self.current and self.motion is not None and job.running:
            if job.deceleration <= 0:
                self.halt()
                job.info["done_next"] = self.m.cycle
                self.m.moving_groups[self.number] = self
                return
            self._decelerate(job, job.deceleration, job.jerk)

    def _decelerate(self, job: Job, dec: float, jerk: float) -> None:
        mv = self.motion
        assert mv is not None
        if self.overlap is not None:
            self._freeze_overlap()
        self.clear_member_flags()  # a stop while waiting for in-position: no in-position check on stop (§4.7)
        t0 = self.m.cycle * self.m.period_s
        seg = self.m.planner.stop(p0=mv.s, v0=mv.sd, a0=mv.sdd, deceleration=dec, jerk=jerk)
        self.motion = Motion(job, mv.path, seg, t0, velocity=0.0, s=mv.s, sd=mv.sd, sdd=mv.sdd, stopping=True)
        job.status = JobStatus.STARTING
        self.m.moving_groups[self.number] = self

    # ------------------------------------------------------------------ the period
    def step(self, cycle: int) -> None:
        """Motion stage: evaluate the group motion of this period and write the composition axes' commands."""
        m = self.m
        T = m.period_s
        job = self.current
        if job is None:
            m.moving_groups.pop(self.number, None)
            return
        if job.kind == JobKind.GROUP_SYNC:
            self._step_sync(job, T)
            return
        if job.kind == JobKind.GROUP_ROBOT:
            job.info["robot"].step(self, job, cycle)  # robot.py: MC_MoveTimeAbsolute, conveyor tracking
            return
        done_next = job.info.get("done_next")
        if done_next is not None:
            if cycle > done_next:
                self._end_job(job, JobStatus.DONE)
                self.halt()
                self._set_state(self._rest_state())
            return
        mv = self.motion
        if mv is None:
            m.moving_groups.pop(self.number, None)
            return
        if mv.end_cycle >= 0:
            if cycle > mv.end_cycle:
                self._finish(mv, cycle)
            return
        if job.status == JobStatus.STARTING:
            job.status = JobStatus.ACTIVE
        t = (cycle + 1) * T - mv.t0
        seg = mv.seg
        ended = t >= seg.duration and not mv.paused
        nxt = self.queue[0] if self.queue else None
        if ended and not mv.stopping and nxt is not None and nxt.buffer_mode >= _eMC_BUFFER_MODE._mcBlendingLow \
                and not nxt.info.get("corner") and mv.v_end > 0:
            # blended hand-over without a stop: the successor continues from the transit velocity at the time the
            # previous profile ended (path velocity continuous; the axes' velocities may jump at the corner)
            self._end_job(job, JobStatus.DONE)
            self.queue.pop(0)
            code = self._begin(nxt, _Pos(mv.path.end), t0=mv.t0 + seg.duration, v0=mv.v_end, pushed=True,
                               instant=mv.instant)
            if code:
                self.raise_error(code, source=nxt.owner.label if nxt.owner is not None else None)
                return
            self.step(cycle)
            return
        if (not mv.stopping and nxt is not None and nxt.info.get("corner") and self.overlap is None
                and t >= mv.t_dec and nxt.buffer_mode >= _eMC_BUFFER_MODE._mcBlendingLow):
            self._start_corner(mv, nxt, cycle)
            self.step(cycle)
            return
        if ended:
            s, sd, sdd = (mv.path.length if not mv.stopping else seg.end_position), seg.end_velocity, 0.0
        else:
            s, sd, sdd, mv.k = sample(seg, t, mv.k)
            if s > mv.path.length:
                s = mv.path.length
        mv.s, mv.sd, mv.sdd = s, sd, sdd
        point = mv.path.point(s)
        vel, acc = mv.path.velocity(s, sd, sdd)
        ov = self.overlap
        if ov is not None:
            # corner superimposition: the previous move's deceleration plus this move's acceleration (§4.3)
            t1 = (cycle + 1) * T - ov.t0
            if t1 >= ov.seg.duration:
                self._end_job(ov.job, JobStatus.DONE)
                self.overlap = None
            else:
                s1, sd1, sdd1, ov.k = sample(ov.seg, t1, ov.k)
                s1 = min(s1, ov.path.length)
                ov.s, ov.sd, ov.sdd = s1, sd1, sdd1
                p1 = ov.path.point(s1)
                v1, a1 = ov.path.velocity(s1, sd1, sdd1)
                end = ov.path.end
                point = tuple(p + q - e for p, q, e in zip(point, p1, end, strict=True))
                vel = tuple(p + q for p, q in zip(vel, v1, strict=True))
                acc = tuple(p + q for p, q in zip(acc, a1, strict=True))
        cmd, pv, pa = m.cmd_pos, m.prof_vel, m.prof_acc
        for k, i in enumerate(self.idx):
            cmd[i] = point[k]
            pv[i] = vel[k]
            pa[i] = acc[k]
        self.cmd_vel = sd if ov is None else math.sqrt(sum(v * v for v in vel))
        self.cmd_accdec = sdd
        if self.warn_on:
            self.check_warnings()
        if ended and self.overlap is None:
            mv.end_cycle = cycle  # the final command value is output in this period; the end shows in the next

    def _start_corner(self, mv: Motion, nxt: Job, cycle: int) -> None:
        """Corner superimposition: the successor starts when the previous move begins its final deceleration, with
        an acceleration time equal to that deceleration time (jerk ignored, §4.3 TransitionMode)."""
        seg = mv.seg
        t_d = max(seg.duration - mv.t_dec, self.m.period_s)
        start = mv.t0 + mv.t_dec
        self.queue.pop(0)
        job = mv.job
        self.overlap = mv
        velocity_in = nxt.velocity
        nxt.acceleration = min(velocity_in, self.op.MaxInterpolationVel) / t_d
        nxt.jerk = 0.0
        self.motion = None
        self.current = None
        code = self._begin(nxt, _Pos(mv.path.end), t0=start, v0=0.0, pushed=True)
        if code:
            self.overlap = None
            self.motion = mv
            self.current = job
            self.raise_error(code, source=nxt.owner.label if nxt.owner is not None else None)
            return
        # the previous instruction still decelerates (its Done comes when its profile ends)
        self.overlap = mv

    def _finish(self, mv: Motion, cycle: int) -> None:
        """The period after the final command value: the instruction is Done (positioning complete / stop
        complete) — a move once its composition axes are in position (D103); a buffered successor takes over (its
        profile starts in the next period)."""
        job = mv.job
        for i in self.idx:
            self.m.prof_vel[i] = 0.0
            self.m.prof_acc[i] = 0.0
        self.cmd_vel = self.cmd_accdec = 0.0
        if self.observations:
            self.check_warnings()
        if job.kind == JobKind.GROUP_MOVE and self._in_position_pending(mv, cycle):
            return  # Done waits for the in-position check of the composition axes (D103)
        self.motion = None
        self._end_job(job, JobStatus.DONE)
        if job.kind == JobKind.GROUP_STOP:
            if job.owner is None:
                self.m.moving_groups.pop(self.number, None)
                return  # an error deceleration ended: the group stays in ErrorStop
            self._set_state(self._rest_state())
            self.m.moving_groups.pop(self.number, None)
            return
        if self.queue:
            nxt = self.queue.pop(0)
            code = self._begin(nxt, _Pos(mv.path.end), t0=(cycle + 1) * self.m.period_s, v0=0.0, pushed=True)
            if code:
                self.raise_error(code, source=nxt.owner.label if nxt.owner is not None else None)
            return
        self._set_state(self._rest_state())
        self.m.moving_groups.pop(self.number, None)

    # --- jobs whose commands their instruction computes (the robot instructions, robot.py) -------------------
    def begin_own_job(self, job: Job) -> None:
        """Make `job` the running instruction of a group whose commands the instruction itself computes each period
        (MC_MoveTimeAbsolute, MC_SyncLinearConveyor, MC_SyncOut): the group is Moving and in the module's moving set.
        The caller has aborted / halted what ran before."""
        self.current = job
        self._set_state(G.Moving)
        self.m.moving_groups[self.number] = self

    def end_own_job(self, job: Job, *, error_id: int = 0) -> None:
        """End such a job: Done (or Error with `error_id`, the caller raises the group error); when Done the profile
        velocity and acceleration are zero, the group leaves the moving set and returns to its rest state."""
        if error_id:
            self._end_job(job, JobStatus.ERROR, error_id)
            return
        m = self.m
        for i in self.idx:
            m.prof_vel[i] = 0.0
            m.prof_acc[i] = 0.0
        self._end_job(job, JobStatus.DONE)
        self._set_state(self._rest_state())
        m.moving_groups.pop(self.number, None)

    def end_sync(self, job: Job, *, aborted: bool = False) -> None:
        """End a synchronous job (`JobKind.GROUP_SYNC`) on behalf of its owner — MC_RobotJog once it has stopped
        after Enable↓, or when its instance is deleted (decision D90): the job is Done (CommandAborted with
        `aborted`), the command holds where it is and the group goes back to its rest state (Standby, or Stopping /
        Disabled / ErrorStop as it stands). A job that already ended (aborted by another instruction, a stop or an
        error) is left alone."""
        if not job.running:
            return
        self._end_job(job, JobStatus.ABORTED if aborted else JobStatus.DONE)
        self.halt()
        self._set_state(self._rest_state())

    def _step_sync(self, job: Job, T: float) -> None:
        """MC_GroupSyncMoveAbsolute: the program's target every period, each axis limited to its Maximum Velocity
        (the command saturates, §4.12); InPosition when the target is unchanged and every axis is within its
        In-position Range."""
        m = self.m
        if job.status == JobStatus.STARTING:
            job.status = JobStatus.ACTIVE
        owner = job.owner
        target = tuple(float(owner.inp["Position"][k]) for k in range(len(self.idx))) if owner is not None \
            else self.point()
        unchanged = target == self.sync_target
        self.sync_target = target
        inpos = unchanged
        if self.kinematics is not None:
            # a robot: an axis commanded faster than its Maximum Velocity is 6705 with an immediate stop instead of a
            # saturated command (omron-robot-delta3.md §9.8 [Emulator], §6.3; decision D49)
            for k, a in enumerate(self.axes):
                vmax = a.params.Operation.MaxVel
                if abs(target[k] - float(m.cmd_pos[a.i])) > vmax * T * (1.0 + 1e-9):
                    from .robot import E_MAX_VELOCITY, fail_running

                    fail_running(self, job, E_MAX_VELOCITY, f"A{k} {a.name}: target step above Maximum Velocity "
                                 f"{vmax:g} (attached information: logical axis {k})")
                    return
        for k, a in enumerate(self.axes):
            i = a.i
            cur = float(m.cmd_pos[i])
            step = a.params.Operation.MaxVel * T
            d = target[k] - cur
            saturated = abs(d) > step
            new = cur + math.copysign(step, d) if saturated else target[k]
            a.vel_limit = saturated  # Details.VelLimit while the step is cut to Maximum Velocity (§4.12, D107)
            m.cmd_pos[i] = new
            m.prof_vel[i] = (new - cur) / T
            m.prof_acc[i] = 0.0
            if abs(target[k] - float(m.act_pos[i])) > a.params.Operation.InPosRange:
                inpos = False
        if inpos != job.in_velocity:
            job.in_velocity = inpos
            m.job_changed(job)
