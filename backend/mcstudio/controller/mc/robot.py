"""Robot motion of the NJ501-4□□□ robot instructions (`omron-robot-delta3.md` §9.4–§9.6, §10, §3.2).

A robot instruction is a group job (`JobKind.GROUP_ROBOT`) whose `info["robot"]` is one of the motions below; the
group's motion stage (`AxesGroup.step`) calls its `step` every period. Each period the motion computes one Cartesian
TCP command position in the MCS, checks it against the workspace (check 3, 6700, when the workspace check is on),
maps it to the joint angles with the one-point inverse kinematics (570F without a solution), checks every axis's
command velocity against its Maximum Velocity (6705) and writes the angles as the composition axes' command
positions. Any error stops the robot **immediately** (§10.3, §11 effect B): the command stays at the last value that
passed, the group goes to ErrorStop. The group variable's Cmd.Vel/AccDec stay 0 while robot instructions drive the
axes (§7.4). Readings: docs/decisions.md D80–D84.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from .jobs import Job, JobKind, JobStatus
from .kinematics import Delta3Params, Delta3Workspace, Status, UserCoordSystem, contains_point, inverse_point
from .kinematics.codes import E_COMMAND_OUTSIDE, E_KIN_CALC

if TYPE_CHECKING:
    from .group import AxesGroup

Vec3 = tuple[float, float, float]

E_MAX_VELOCITY = 0x6705  # command velocity of an axis above its Maximum Velocity (§11)
E_VELOCITY_ERROR = 0x6703  # command velocity above TrajData.MaxVelocity
E_ACCELERATION_ERROR = 0x6704  # command acceleration above TrajData.MaxAcceleration
E_SYNC_DEVIATION = 0x6702  # workpiece synchronization deviation (MC_SyncLinearConveyor)
E_CONVEYOR_READ = 0x7700  # conveyor axis position cannot be read
# relative tolerance of the 6705 comparison: a command exactly at Maximum Velocity is allowed
VEL_TOL = 1e-9


def kinematics_of(group: AxesGroup) -> tuple[Delta3Params, Delta3Workspace] | None:
    """The group's Delta3 parameters and workspace in force (cached per kinematics object)."""
    kin = group.kinematics
    if kin is None:
        return None
    cache: tuple[Any, Delta3Params, Delta3Workspace] | None = group.robot_kin_cache
    if cache is None or cache[0] is not kin:
        cache = (kin, kin.params(), kin.workspace_obj())
        group.robot_kin_cache = cache
    return cache[1], cache[2]


def to_mcs(ucs: UserCoordSystem | None, p: Vec3) -> Vec3:
    """A position of the chosen coordinate system in the MCS (§4: T + R·p)."""
    if ucs is None:
        return p
    R = ucs.R
    return (ucs.Tx + R[0, 0] * p[0] + R[0, 1] * p[1] + R[0, 2] * p[2],
            ucs.Ty + R[1, 0] * p[0] + R[1, 1] * p[1] + R[1, 2] * p[2],
            ucs.Tz + R[2, 0] * p[0] + R[2, 1] * p[1] + R[2, 2] * p[2])


def from_mcs(ucs: UserCoordSystem | None, p: Vec3) -> Vec3:
    """An MCS position in the chosen coordinate system (§4: Rᵀ·(p − T))."""
    if ucs is None:
        return p
    R = ucs.R
    d = (p[0] - ucs.Tx, p[1] - ucs.Ty, p[2] - ucs.Tz)
    return tuple(R[0, k] * d[0] + R[1, k] * d[1] + R[2, k] * d[2] for k in range(3))  # type: ignore[return-value]


def vector_from_mcs(ucs: UserCoordSystem | None, v: Vec3) -> Vec3:
    """An MCS velocity in the chosen coordinate system (Rᵀ·v)."""
    if ucs is None:
        return v
    R = ucs.R
    return tuple(R[0, k] * v[0] + R[1, k] * v[1] + R[2, k] * v[2] for k in range(3))  # type: ignore[return-value]


def cubic(tau: float) -> float:
    """`_mcPolynomial3`: s(τ) = 3τ² − 2τ³ on [0, 1] (zero velocity at both ends, §9.4)."""
    if tau <= 0.0:
        return 0.0
    if tau >= 1.0:
        return 1.0
    return tau * tau * (3.0 - 2.0 * tau)


def start(group: AxesGroup, job: Job, motion: RobotMotion) -> None:
    """Make `job` the group's running instruction: the running one is CommandAborted and the new command starts from
    velocity 0 (multi-execution OK1, §10.1)."""
    group.abort_all()
    group.halt()
    job.info["robot"] = motion
    job.status = JobStatus.STARTING
    group.begin_own_job(job)


def fail_running(group: AxesGroup, job: Job, code: int, detail: str = "") -> None:
    """An error during execution: the instance shows `code` and the robot stops immediately (group ErrorStop)."""
    group.end_own_job(job, error_id=code)
    owner = job.owner
    group.raise_error(code, source=owner.label if owner is not None else None, detail=detail, immediate=True)


def finish(group: AxesGroup, job: Job) -> None:
    group.end_own_job(job)


def drive(group: AxesGroup, job: Job, p: Vec3, params: Delta3Params, ws: Delta3Workspace | None) -> bool:
    """Output one TCP command position `p` (MCS): workspace check 3 (6700), inverse kinematics (570F), Maximum
    Velocity of each axis (6705), then the joint command positions. False when it stopped the robot."""
    if ws is not None and not contains_point(ws, p[0], p[1], p[2]):
        fail_running(group, job, E_COMMAND_OUTSIDE, f"command position {_fmt(p)} mm outside the workspace")
        return False
    st, q = inverse_point(params, p[0], p[1], p[2])
    if st != Status.OK:
        fail_running(group, job, E_KIN_CALC, f"no inverse kinematics for the command position {_fmt(p)} mm")
        return False
    m = group.m
    T = m.period_s
    cmd = m.cmd_pos
    for k, a in enumerate(group.axes):
        dq = q[k] - float(cmd[a.i])
        vmax = a.params.Operation.MaxVel
        if abs(dq) > vmax * T * (1.0 + VEL_TOL):
            fail_running(group, job, E_MAX_VELOCITY,
                         f"A{k} {a.name}: command velocity {abs(dq) / T:.6g} > Maximum Velocity {vmax:g} "
                         f"(attached information: logical axis {k})")
            return False
    pv, pa = m.prof_vel, m.prof_acc
    for k, i in enumerate(group.idx):
        pv[i] = (q[k] - float(cmd[i])) / T
        pa[i] = 0.0
        cmd[i] = q[k]
    return True


def _fmt(p: Vec3) -> str:
    return "(" + ", ".join(f"{v:.6g}" for v in p) + ")"


class RobotMotion:
    """One robot motion; `step` runs in the group's motion stage every period while its job is current."""

    def step(self, group: AxesGroup, job: Job, cycle: int) -> None:  # pragma: no cover - abstract
        raise NotImplementedError


@dataclass(slots=True)
class TimeMove(RobotMotion):
    """MC_MoveTimeAbsolute (§9.4): P(t) = P0 + (P1 − P0)·(3τ² − 2τ³), τ = t / TrajTime — every axis of the MCS
    follows the same time law, so the TCP moves on the straight line P0–P1. The first command value is output in
    the period the instruction is accepted (t = one period); the last (τ = 1, exactly P1) when t ≥ TrajTime; Done
    shows in the period after it (when the final command value reached the drives)."""

    p0: Vec3
    p1: Vec3
    duration: float  # s
    start_cycle: int
    params: Delta3Params
    workspace: Delta3Workspace | None  # None: workspace check off
    end_cycle: int = -1
    last: Vec3 = field(default=(0.0, 0.0, 0.0))

    def point(self, t: float) -> Vec3:
        s = cubic(t / self.duration)
        p0, p1 = self.p0, self.p1
        return (p0[0] + (p1[0] - p0[0]) * s, p0[1] + (p1[1] - p0[1]) * s, p0[2] + (p1[2] - p0[2]) * s)

    def step(self, group: AxesGroup, job: Job, cycle: int) -> None:
        if self.end_cycle >= 0:
            if cycle > self.end_cycle:
                finish(group, job)
            return
        if job.status == JobStatus.STARTING:
            job.status = JobStatus.ACTIVE
        t = (cycle - self.start_cycle + 1) * group.m.period_s
        ended = t >= self.duration * (1.0 - 1e-12)
        p = self.p1 if ended else self.point(t)
        if not drive(group, job, p, self.params, self.workspace):
            return
        self.last = p
        if ended:
            self.end_cycle = cycle


def new_job(owner: Any) -> Job:
    return Job(JobKind.GROUP_ROBOT, owner)


def velocity_limits(distance: float, duration: float) -> tuple[float, float]:
    """Peak TCP velocity and acceleration of the cubic over `distance` mm in `duration` s: 1.5·D/T and 6·D/T²."""
    return 1.5 * distance / duration, 6.0 * distance / (duration * duration)


def distance(a: Vec3, b: Vec3) -> float:
    return math.sqrt((b[0] - a[0]) ** 2 + (b[1] - a[1]) ** 2 + (b[2] - a[2]) ** 2)


@dataclass(slots=True)
class Rates:
    """6703/6704 while running: the command TCP velocity and acceleration from differences of the command positions
    (vector magnitudes, D81), checked against TrajData.MaxVelocity / MaxAcceleration (relative tolerance VEL_TOL)."""

    vmax: float
    amax: float
    prev: Vec3
    vel: Vec3 = (0.0, 0.0, 0.0)

    def check(self, p: Vec3, T: float, enabled: bool) -> int:
        v = ((p[0] - self.prev[0]) / T, (p[1] - self.prev[1]) / T, (p[2] - self.prev[2]) / T)
        a = math.dist(v, self.vel) / T
        self.prev, self.vel = p, v
        if not enabled:
            return 0
        if math.hypot(*v) > self.vmax * (1.0 + VEL_TOL):
            return E_VELOCITY_ERROR
        if a > self.amax * (1.0 + VEL_TOL):
            return E_ACCELERATION_ERROR
        return 0


@dataclass(slots=True)
class ConveyorSync(RobotMotion):
    """MC_SyncLinearConveyor (§9.5, the [Emulator] flat trajectory): rise by H1 in T1, catch up with the workpiece
    from Ttrans1·T1 to te = T1 + T2 + T3·(1 − Ttrans2) on the conveyor-speed prediction, descend in T3 from T1 + T2;
    at te the command must be within 0.1 mm per 1 ms period of the workpiece in X and Y (InSync, else 6702); from
    then on X/Y follow the workpiece by the conveyor's feedback. Times are seconds; k = cycle − start, t = (k+1)·T
    (the command of period k), the workpiece W = W0 + (c − c0)·u, its prediction W0 + v0·k·T·u (same time base)."""

    p0: Vec3
    w0: Vec3
    u: Vec3  # conveyor direction in the MCS (X of the chosen CS, horizontal)
    conveyor: int  # row of the conveyor axis
    c0: float
    v0: float
    T1: float
    T2: float
    T3: float
    tr1: float  # Ttrans1 / 100
    tr2: float
    H1: float
    start_cycle: int
    params: Delta3Params
    workspace: Delta3Workspace | None
    rates: Rates
    tolerance: float  # mm: 0.1 mm per 1 ms period
    period: float
    in_sync: bool = False
    phase: int = 1
    remain_ms: int = 0
    bounds: tuple[float, float, float, float, float] = (0.0, 0.0, 0.0, 0.0, 0.0)

    def __post_init__(self) -> None:
        T1, T2, T3, T = self.T1, self.T2, self.T3, self.period
        b1 = self.tr1 * T1 if self.tr1 < 1.0 else T1
        b2 = T1 if self.tr1 < 1.0 else T1 + T  # phases 2 and 4 last at least one period (§9.5 table)
        b4 = T1 + T2 + T3 * (1.0 - self.tr2) if self.tr2 < 1.0 else T1 + T2 + T
        self.bounds = (b1, b2, T1 + T2, b4, T1 + T2 + T3)

    def phase_at(self, t: float) -> int:
        for n, b in enumerate(self.bounds, start=1):
            if t <= b + 1e-12:
                return n
        return 6

    def workpiece(self, group: AxesGroup) -> Vec3:
        d = float(group.m.act_pos[self.conveyor]) - self.c0
        w, u = self.w0, self.u
        return (w[0] + d * u[0], w[1] + d * u[1], w[2])

    def step(self, group: AxesGroup, job: Job, cycle: int) -> None:
        m = group.m
        if not m.pd_ok[self.conveyor]:
            fail_running(group, job, E_CONVEYOR_READ, "conveyor axis without process-data communication")
            return
        if job.status == JobStatus.STARTING:
            job.status = JobStatus.ACTIVE
        T = self.period
        k = cycle - self.start_cycle
        t = (k + 1) * T
        b1, _, td, te, tend = self.bounds
        p0, w0 = self.p0, self.w0
        h1 = self.H1 if self.T1 > 0 else 0.0
        z = p0[2] + (h1 * cubic(t / self.T1) if self.T1 > 0 else 0.0) + (w0[2] - p0[2] - h1) * cubic((t - td) / self.T3)
        phase = self.phase_at(t)
        if phase <= 4:
            d = self.v0 * k * T
            wx, wy = w0[0] + d * self.u[0], w0[1] + d * self.u[1]
            s = cubic((t - b1) / (te - b1)) if te > b1 else 1.0
            p = (p0[0] + s * (wx - p0[0]), p0[1] + s * (wy - p0[1]), z)
        else:
            w = self.workpiece(group)
            if not self.in_sync:
                d = self.v0 * k * T
                plan = (w0[0] + d * self.u[0], w0[1] + d * self.u[1])
                dev = max(abs(plan[0] - w[0]), abs(plan[1] - w[1]))
                if dev > self.tolerance + 1e-9:
                    fail_running(group, job, E_SYNC_DEVIATION,
                                 f"X/Y deviation {dev:.6g} mm from the workpiece > {self.tolerance:g} mm")
                    return
                self.in_sync = True
                job.in_velocity = True  # InSync
            p = (w[0], w[1], z)
        # 6703/6704 only where the manual checks them: phases 1, 5, 6, or 2–4 with the conveyor stopped (§9.5)
        code = self.rates.check(p, T, phase in (1, 5, 6) or self.v0 == 0.0)
        if code:
            fail_running(group, job, code, f"phase {phase}")
            return
        if not drive(group, job, p, self.params, self.workspace):
            return
        self.phase = phase
        self.remain_ms = max(0, round((tend - t) * 1000.0))
        if k > 0:
            # InSync and TrajStatus are pushed to the instance in the period they change, like InVelocity (in the
            # Execute period the instance still shows Busy only: Active comes at its next call)
            m.job_changed(job)


@dataclass(slots=True)
class SyncOutMove(RobotMotion):
    """MC_SyncOut (§9.6 [Emulator]): from the present command, X/Y leave at the conveyor velocity v_c·u and stop in
    T4 with v(τ) = v_c·(1 − 3τ² + 2τ³) (travel v_c·T4/2), Z rises by H4·(3τ² − 2τ³); Done in the period after T4.
    T4 = 0 or _mcRBT_ImmediateStop: no further command (the TCP stops at once), Done in the next period."""

    p0: Vec3
    vel: Vec3  # conveyor velocity vector in the MCS at the start
    T4: float
    H4: float
    start_cycle: int
    params: Delta3Params
    workspace: Delta3Workspace | None
    rates: Rates | None
    end_cycle: int = -1

    def step(self, group: AxesGroup, job: Job, cycle: int) -> None:
        if job.status == JobStatus.STARTING:
            job.status = JobStatus.ACTIVE
        if self.end_cycle >= 0 or self.T4 <= 0.0:
            if self.end_cycle < 0:
                self.end_cycle = cycle  # immediate stop: nothing more is output
            elif cycle > self.end_cycle:
                finish(group, job)
            return
        T = group.m.period_s
        t = (cycle - self.start_cycle + 1) * T
        ended = t >= self.T4 * (1.0 - 1e-12)
        tau = 1.0 if ended else t / self.T4
        f = self.T4 * (tau - tau**3 + 0.5 * tau**4)
        p0, v = self.p0, self.vel
        p = (p0[0] + v[0] * f, p0[1] + v[1] * f, p0[2] + v[2] * f + self.H4 * cubic(tau))
        if self.rates is not None:
            code = self.rates.check(p, T, True)
            if code:
                fail_running(group, job, code)
                return
        if not drive(group, job, p, self.params, self.workspace):
            return
        if ended:
            self.end_cycle = cycle
