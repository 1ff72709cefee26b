"""Axes groups: `_sGROUP_REF`, the group state machine, and the group motion of the interpolation instructions.

States and transitions: `omron-group-and-cam.md` §0.4 (appendix A-3, seed 000 lines 21676–21700). A group is
Disabled, Standby, Moving, Stopping or ErrorStop; while it is enabled its composition axes are Coordinated (axis
state I), so single-axis motion on them is refused with 543E (`acceptance.py`). A group runs one motion instruction
and buffers up to seven more (5443 for the eighth).

Group motion is a path (`group_path.py`) and a 1-D profile s(t) along it, planned once per move with the axis planner
(`profile.Planner`: trapezoid when Jerk = 0, S-curve otherwise) and re-planned only on events (blending successor,
override, MC_GroupStop). Every period `step` evaluates s(t) — a few float operations — and writes the composition
axes' command positions, so the generic command-value stage of the MC module derives Cmd.Vel/AccDec from them.
Decisions on unclear points: docs/decisions.md D50–D56.
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from ...drives.cia402 import DI_NEGATIVE_LIMIT, DI_POSITIVE_LIMIT
from . import errors as E
from .enums import AxisState, _eMC_ACCDECOVER, _eMC_BUFFER_MODE, _eMC_STOP_MODE, _eMC_TRANSITION_MODE
from .group_path import Path
from .jobs import Job, JobKind, JobStatus
from .profile import PlanningError, Segments, concat

if TYPE_CHECKING:
    from ...project.models import AxesGroupConfig
    from .axis import Axis
    from .module import MotionModule

E_GROUP_CANNOT_ENABLE = 0x5440
E_GROUP_DISABLED = 0x543F
E_ILLEGAL_GROUP = 0x5461
E_MEMBER_STOPPING = 0x5442
E_COUNT_MODE = 0x544A
E_GROUP_IMMEDIATE_STOP = 0x5486
E_MEMBER_ERROR = 0x7430
E_CHANGE_AXES = 0x549D
MAX_BUFFERED = 7  # A-3 note: a group buffers up to 7 instructions (executing + buffered ≤ 8)


class GroupState(enum.IntEnum):
    """The five exclusive flags of `_sGROUP_REF.Status` (A-3 letters a–e)."""

    Disabled = 0
    Standby = 1
    Moving = 2
    Stopping = 3
    ErrorStop = 4


G = GroupState
# acceptance of group instructions per group state (§0.4, A-3-2 with the cell colours reconstructed, D50):
# "ok", "abort" (CommandAborted) or an ErrorID
_VERDICT: dict[str, tuple[str | int, ...]] = {
    #               Disabled          Standby  Moving   Stopping ErrorStop
    "move": (E_GROUP_DISABLED, "ok", "ok", "abort", "abort"),
    "stop": (E_GROUP_DISABLED, "ok", "ok", "ok", "abort"),
    "immediate_stop": (E_GROUP_DISABLED, "ok", "ok", "ok", "ok"),
    "change_axes": ("ok", 0x543C, 0x543C, 0x543C, 0x543C),
}


@dataclass(slots=True)
class Motion:
    """A path being followed: its 1-D profile `seg` starts at kernel time `t0` (s); `s`, `sd`, `sdd` are the last
    evaluated path position, velocity and acceleration."""

    job: Job
    path: Path
    seg: Segments
    t0: float
    velocity: float  # planned path velocity (clamped, before override)
    v_end: float = 0.0  # path velocity at the end (blending transit velocity)
    k: int = 0  # segment index of the last evaluation
    s: float = 0.0
    sd: float = 0.0
    sdd: float = 0.0
    end_cycle: int = -1  # period in which the final command value was output
    stopping: bool = False  # an MC_GroupStop / error deceleration along the path
    paused: bool = False  # override 0: decelerated to velocity 0 and waiting
    t_dec: float = math.inf  # profile time where the final deceleration begins (corner superimposition)


@dataclass(slots=True)
class _Pos:
    """Start data of a move: the path start and the per-axis velocity there (for the start velocity of Aborting)."""

    point: tuple[float, ...]
    velocity: tuple[float, ...] = field(default_factory=tuple)


def sample(seg: Segments, t: float, k: int) -> tuple[float, float, float, int]:
    """s, ṡ, s̈ of a profile at time t (seconds from its start), from segment k on (times only increase)."""
    ts = seg.t
    n = len(ts)
    while k + 1 < n and t >= ts[k + 1]:
        k += 1
    tau = t - ts[k]
    j, a, v = seg.j[k], seg.a[k], seg.v[k]
    return (seg.p[k] + tau * (v + tau * (a / 2 + tau * j / 6)), v + tau * (a + tau * j / 2), a + tau * j, k)


def decel_start(seg: Segments) -> float:
    """Time at which the final deceleration of a profile begins (its velocity no longer increases)."""
    k = len(seg.t) - 2  # the last segment is the tail
    while k >= 0:
        if seg.a[k] > 1e-9 or (seg.j[k] > 0 and seg.a[k] >= -1e-9):
            return seg.t[k + 1]
        if seg.a[k] >= -1e-9 and seg.j[k] == 0 and (k == 0 or seg.a[k - 1] >= -1e-9):
            return seg.t[k + 1]  # a cruise phase
        k -= 1
    return 0.0


class AxesGroup:
    def __init__(self, module: MotionModule, config: AxesGroupConfig) -> None:
        self.m = module
        self.config = config
        self.name = config.name
        self.number = config.number
        self.op = config.operation
        self.kinematics = config.kinematics
        # MC_SetKinTransform (fb/robot_fb.py): kinematics usable by the robot instructions from this cycle on (the
        # period after Done, §9.1), and EnableWorkspace; the project's kinematics apply from cycle 0
        self.kin_from_cycle = 0
        self.workspace_check = True
        # MC_DefineCoordSystem: user coordinate systems by CSID (volatile, robot.py)
        self.coord_systems: dict[int, Any] = {}
        self.axes: list[Axis] = [module.by_name[n] for n in config.axes if n in module.by_name]
        self.idx: list[int] = [a.i for a in self.axes]
        self.enabled = False
        self.state = G.Disabled
        self.error_code = 0
        self.reset_generation = 0
        self.stop_holders: set[int] = set()
        self.current: Job | None = None  # the running group instruction (move, stop, synchronous positioning)
        self.queue: list[Job] = []  # buffered group motion instructions
        self.motion: Motion | None = None
        self.overlap: Motion | None = None  # corner superimposition: the previous move finishing its deceleration
        self.override = 1.0
        self.override_owner: int | None = None
        self.sync_target: tuple[float, ...] | None = None  # MC_GroupSyncMoveAbsolute: target of the last period
        self.cmd_vel = 0.0
        self.cmd_accdec = 0.0
        self._last_point: tuple[float, ...] | None = None

    # ------------------------------------------------------------------ helpers
    @property
    def label(self) -> str:
        return self.name

    def _set_state(self, state: GroupState) -> None:
        self.state = state

    def _rest_state(self) -> GroupState:
        if self.error_code:
            return G.ErrorStop
        if not self.enabled:
            return G.Disabled
        return G.Stopping if self.stop_holders else G.Standby

    def point(self) -> tuple[float, ...]:
        cmd = self.m.cmd_pos
        return tuple(float(cmd[i]) for i in self.idx)

    def check_start(self, kind: str) -> tuple[str, int]:
        v = _VERDICT[kind][int(self.state)]
        if isinstance(v, int):
            return "error", v
        return v, 0

    def member_error(self, *, motion: bool = True) -> int:
        """Start conditions of a group motion on the composition axes (A-1: 5441, 5466, 5442, 6443/6444)."""
        m = self.m
        for a in self.axes:
            if not m.servo_on[a.i]:
                return E.E_SERVO_OFF
        for a in self.axes:
            if not a.homed:
                return E.E_HOME_UNDEFINED
        for a in self.axes:
            if a.stop_holders:
                return E_MEMBER_STOPPING
        if motion:
            for a in self.axes:
                din = int(m.din[a.i])
                if din & DI_POSITIVE_LIMIT:
                    return E.E_POSI_LIMIT_INPUT
                if din & DI_NEGATIVE_LIMIT:
                    return E.E_NEGA_LIMIT_INPUT
        return 0

    def _end_job(self, job: Job | None, status: JobStatus, error_id: int = 0) -> None:
        if job is None or not job.running:
            return
        job.status = status
        job.error_id = error_id
        job.finished_cycle = self.m.cycle
        self.m.job_changed(job)
        if job is self.current:
            self.current = None
        if job in self.queue:
            self.queue.remove(job)

    def abort_all(self) -> None:
        for job in list(self.queue):
            self._end_job(job, JobStatus.ABORTED)
        self.queue.clear()
        self._end_job(self.current, JobStatus.ABORTED)

    def halt(self) -> None:
        """Immediate stop: the command positions hold where they are."""
        m = self.m
        self.motion = None
        self.overlap = None
        for i in self.idx:
            m.prof_vel[i] = 0.0
            m.prof_acc[i] = 0.0
        m.moving_groups.pop(self.number, None)
        self.sync_target = None
        self.cmd_vel = self.cmd_accdec = 0.0

    # ------------------------------------------------------------------ errors
    def raise_error(self, code: int, *, source: str | None = None, detail: str = "", immediate: bool = False) -> None:
        """Group minor fault (A-1 source Group): MFaultLvl, ErrorStop, every group instruction aborted, the group
        stopped — by the [Axes group stop method] (immediate, or decelerating along the path at the maximum
        interpolation deceleration), immediately for robots and when `immediate` (D53). Member axes keep no error
        (§4.1: a group error does not put the composition axes into error)."""
        if self.error_code == 0:
            self.error_code = code
        self.m.log_error(code, axis=None, source=f"{self.name} / {source}" if source else self.name, detail=detail)
        self.abort_all()
        self._set_state(G.ErrorStop)
        mv = self.motion
        dec = self.op.MaxInterpolationDec
        decelerate = (not immediate and self.kinematics is None and mv is not None and not mv.paused
                      and self.op.GroupStopMethod == _eMC_STOP_MODE._mcDecelerationStop and dec > 0
                      and (mv.sd != 0 or mv.sdd != 0))
        if not decelerate:
            self.halt()
            return
        job = Job(JobKind.GROUP_STOP, None, deceleration=dec)
        self.current = job
        self._decelerate(job, dec, 0.0)

    def on_axis_error(self, axis: Axis, code: int) -> None:
        """A composition axis had an error: on a moving group 7430, the axes stop immediately (robot functions
        manual A-1 #7430; group stop method D53)."""
        if self.motion is not None or self.state == G.Moving:
            self.raise_error(E_MEMBER_ERROR, source=axis.name, immediate=True,
                             detail=f"{axis.name}: error {code:04X} during group motion")

    def on_member_servo_off(self, axis: Axis) -> None:
        if self.motion is not None or self.state == G.Moving:
            self.raise_error(E_MEMBER_ERROR, source=axis.name, immediate=True,
                             detail=f"{axis.name}: servo OFF during group motion")

    # ------------------------------------------------------------------ MC_GroupEnable / MC_GroupDisable
    def enable(self) -> str | int:
        """Returns "done", "abort" or an ErrorID."""
        if self.state == G.ErrorStop:
            return "abort"  # D50: §0.4 e (*1)
        if self.enabled:
            return "done"
        for a in self.axes:
            if a.encoder:
                return E.E_AXIS_TYPE
        for a in self.axes:
            if not a.used:
                return E_ILLEGAL_GROUP
            if a.state not in (AxisState.Disabled, AxisState.Standstill) or a.group is not None or a.latch_owner:
                return E_GROUP_CANNOT_ENABLE
        m = self.m
        for a in self.axes:
            m.profiles.clear(a.i)
            m.prof_vel[a.i] = 0.0
            m.prof_acc[a.i] = 0.0
            a.group = self
            a._set_state(AxisState.Coordinated)
        self.enabled = True
        self._set_state(self._rest_state())
        return "done"

    def disable(self) -> None:
        """MC_GroupDisable: buffered and running group instructions CommandAborted; moving axes decelerate at their
        Maximum Deceleration; the axes leave Coordinated (A-3 *2). In ErrorStop the group stays ErrorStop (D50)."""
        self.abort_all()
        m = self.m
        moving = [a for a in self.axes if m.prof_vel[a.i] != 0.0]
        self.halt()
        if not self.enabled:
            return
        self.enabled = False
        for a in self.axes:
            a.group = None
        for a in self.axes:
            if a.state == AxisState.ErrorStop:
                continue
            if a in moving and m.servo_on[a.i] and a.params.Operation.MaxDec > 0:
                # the path velocity of the last period, per axis: the single-axis planner decelerates from it
                m.prof_vel[a.i] = float(m.cmd_vel[a.i])
                a._start(Job(JobKind.STOP, None, deceleration=a.params.Operation.MaxDec))
            else:
                a._set_state(a._rest_state())
        if self.state != G.ErrorStop:
            self._set_state(G.Disabled)

    # ------------------------------------------------------------------ MC_GroupReset
    def reset(self) -> bool:
        """Clears the group error and (while the group is enabled) the errors of its axes. False (Failure) while the
        group or an axis still decelerates because of an error."""
        cur = self.current
        if cur is not None and cur.kind == JobKind.GROUP_STOP and cur.owner is None and cur.running:
            return False
        for a in self.axes:
            c = a.current
            if a.state == AxisState.ErrorStop and c is not None and c.kind == JobKind.ERROR_STOP and c.running:
                return False
        if self.enabled:
            for a in self.axes:
                if a.error_code or a.state == AxisState.ErrorStop or a.observations:
                    a.reset()
        if self.error_code or self.state == G.ErrorStop:
            self.error_code = 0
            self.reset_generation += 1
            self._set_state(self._rest_state())
            self.m.log_info(None, f"axes group error reset on {self.name}")
        return True

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
        t0 = self.m.cycle * self.m.period_s
        seg = self.m.planner.stop(p0=mv.s, v0=mv.sd, a0=mv.sdd, deceleration=dec, jerk=jerk)
        self.motion = Motion(job, mv.path, seg, t0, velocity=0.0, s=mv.s, sd=mv.sd, sdd=mv.sdd, stopping=True)
        job.status = JobStatus.STARTING
        self.m.moving_groups[self.number] = self

    def immediate_stop(self, source: str) -> None:
        """MC_GroupImmediateStop: every axis stops by its [Immediate stop input stop method]; ErrorStop with 5486."""
        m = self.m
        running_stop = self.current if self.current is not None and self.current.kind == JobKind.GROUP_STOP else None
        self._end_job(running_stop, JobStatus.ABORTED)
        self.halt()
        self.raise_error(E_GROUP_IMMEDIATE_STOP, source=source, immediate=True)
        for a in self.axes:
            mode = int(a.params.OtherOperation.ImmediateStopInputStopMode)
            if mode == _eMC_STOP_MODE._mcImmediateStopFEReset:
                m.reset_following_error(a.i)
            elif mode == _eMC_STOP_MODE._mcFreeRunStop and m.servo_on[a.i]:
                a._release_servo()
                a.forced_off = True

    def hold_stop(self, fb_id: int, held: bool) -> None:
        if held:
            self.stop_holders.add(fb_id)
            return
        if fb_id in self.stop_holders:
            self.stop_holders.discard(fb_id)
            if not self.stop_holders and self.state == G.Stopping and self.current is None:
                self._set_state(self._rest_state())

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

    def _begin(self, job: Job, start: _Pos, *, t0: float, v0: float | None = None, pushed: bool = False) -> int:
        """Plan `job` from `start` and make it current. v0: the path velocity at the start (blending); None = the
        projection of the current per-axis velocity on the new direction (Aborting; a reversal starts from 0, D54)."""
        m = self.m
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
        nxt = self.queue[0] if self.queue else None
        if nxt is not None and nxt.buffer_mode >= _eMC_BUFFER_MODE._mcBlendingLow:
            mv.v_end = self._transit(job, nxt)
        self.overlap = None if not pushed else self.overlap
        self.current = job
        self.motion = mv
        code = self._plan(mv, s0=0.0, v0=v0, a0=0.0, t0=t0)
        if code:
            self.motion = None
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

    def _plan(self, mv: Motion, *, s0: float, v0: float, a0: float, t0: float) -> int:
        """(Re)plan the profile of `mv` from (s0, v0, a0) at kernel time t0 to its end (or to velocity 0 when the
        override is 0). Returns an ErrorID (5445 when the transit velocity cannot be reached and the interpolation
        Acc/Dec Over is error stop)."""
        acc, dec, jerk = self._acc_dec(mv.job)
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
                v_end = self._reachable(mv.v_end, v0, length - s0, acc, dec)
                if v_end != mv.v_end and self.op.InterpolationAccDecOver == _eMC_ACCDECOVER._mcAccDecOverErrorStop:
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
        except PlanningError as err:
            self.m.log_error(0xFFFF, axis=None, source=self.name, detail=str(err))
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
        v_t = self._transit(cur, nxt)
        if nxt.info.get("corner"):
            return 0
        mv.v_end = v_t
        if mv.paused:
            return 0
        return self._plan(mv, s0=mv.s, v0=mv.sd, a0=mv.sdd, t0=self.m.cycle * self.m.period_s)

    def _freeze_overlap(self) -> None:
        """Drop the decelerating previous move of a corner superimposition (its remaining travel is lost)."""
        ov = self.overlap
        self.overlap = None
        if ov is not None:
            self._end_job(ov.job, JobStatus.DONE)

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
            code = self._begin(nxt, _Pos(mv.path.end), t0=mv.t0 + seg.duration, v0=mv.v_end, pushed=True)
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
        complete); a buffered successor takes over (its profile starts in the next period)."""
        job = mv.job
        self.motion = None
        for i in self.idx:
            self.m.prof_vel[i] = 0.0
            self.m.prof_acc[i] = 0.0
        self.cmd_vel = self.cmd_accdec = 0.0
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
            new = target[k] if abs(d) <= step else cur + math.copysign(step, d)
            m.cmd_pos[i] = new
            m.prof_vel[i] = (new - cur) / T
            m.prof_acc[i] = 0.0
            if abs(target[k] - float(m.act_pos[i])) > a.params.Operation.InPosRange:
                inpos = False
        if inpos != job.in_velocity:
            job.in_velocity = inpos
            m.job_changed(job)

    # ------------------------------------------------------------------ MC_ChangeAxesInGroup
    def change_axes(self, axes: list[Axis]) -> None:
        self.axes = axes
        self.idx = [a.i for a in axes]

    # ------------------------------------------------------------------ _sGROUP_REF
    def capture(self) -> dict[str, Any]:
        st = self.state
        m = self.m
        ready = (st == G.Standby and all(bool(m.servo_on[i]) for i in self.idx) and all(a.homed for a in self.axes)
                 and not any(a.stop_holders for a in self.axes))
        busy = self.current is not None and self.current.running
        return {
            "name": self.name,
            "Status": {"Ready": ready, **{s.name: st == s for s in G}},
            "Details": {"Idle": not busy, "InPosWaiting": False},
            "Cmd": {"Vel": self.cmd_vel, "AccDec": self.cmd_accdec},
            "MFaultLvl": {"Active": self.error_code != 0, "Code": f"{self.error_code:04X}"},
            "Obsr": {"Active": False, "Code": "0000"},
            "Cfg": {"GrpNo": self.number, "GrpEnable": "_mcUsedGroup", "ExecID": 1},
            "Kinematics": {"GrpType": self.config.composition.name,
                           "Axis": [a.number for a in self.axes] + [0] * (4 - len(self.axes))},
            "CmdPos": list(self.point()),
        }


def transition_error(buffer_mode: int, transition_mode: int) -> int:
    """5432: TransitionMode out of range, or corner superimposition without a Blending BufferMode (§4.3)."""
    if transition_mode not in (0, 10):
        return 0x5432
    if transition_mode == _eMC_TRANSITION_MODE._mcTMCornerSuperimposed and buffer_mode < 2:
        return 0x5432
    return 0
