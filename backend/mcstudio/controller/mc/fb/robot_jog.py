"""MC_RobotJog — Cartesian jog of a Delta3 TCP for the test run (MC Studio extension, not an NJ instruction).

The NJ has no Cartesian jog; the robot manual's test run moves the axes one by one. `omron-robot-delta3.md` §12.8
[Emulator] suggests building one from the robot instructions, which is what this instruction does, in one place and
every period: a command point in the MCS moves along a direction at the jog speed (with a ramp), is checked against
the workspace and the axes' limits, mapped with the one-point inverse kinematics (`kinematics/point.py`) and
commanded to the three axes through the group the way MC_GroupSyncMoveAbsolute does (a `GROUP_SYNC` job whose
per-period target this instruction writes; `group_motion.py` `_step_sync`). The TCP therefore moves on a straight
line in the Cartesian frame. It uses only the group's public interface: `check_start`, `member_error`, `point`,
`submit`, `coord_systems` and `end_sync` (which ends its job after the stop, or on deletion).

* **Mode 0 (jog)**: while Enable is TRUE the point moves along `Direction` (X, Y, Z of the MCS or of a UCS,
  normalised) at `Velocity`, accelerating and decelerating at `Acceleration` (0 = step). Enable FALSE decelerates to
  a stop; then the group is Standby again. A new direction while moving: the point first stops, then turns.
* **Mode 2 (step, inching)**: at Enable↑ the point moves `Distance` along `Direction` (the target is fixed at the
  start) with the same ramps and stops there (`InPosition`); a step that would leave the workspace stops at the
  boundary (AtBoundary, WarningID 6700). The next step needs a new Enable↑ (decision D93).
* **Mode 1 (go to)**: while Enable is TRUE the point moves on a straight line to `TargetPosition` and stops there
  (trapezoidal speed, `InPosition` once the command is there and every axis within its in-position range); a new
  target is taken at once. The demo's pick-and-place sequence uses it.
* **Workspace** (docs/robot.md): the command point never leaves the workspace (0.1 mm margin) nor the reachable set
  or the axes' software limits. A step that would, is cut at the boundary (bisection, 1e-6 of the step) and the
  point stops there: `AtBoundary` TRUE and `WarningID` 6700 (the manual's code for a command position outside the
  workspace) — a warning, not an error; a jog in another direction continues. A go-to target outside gives WarningID
  571B and no motion. The current TCP must be inside at Enable↑ (else 6701, an error as at MC_MoveTimeAbsolute's
  start).
* The joint speed is kept within each axis's Maximum Velocity by slowing the step (not by the group's saturation,
  which would bend the line).
* Errors (group minor faults, like the group instructions): 5461 group, 5710 kinematics not set, 543F disabled,
  5441/5466 servo OFF / not homed, 5422 Velocity ≤ 0, 5423 Acceleration < 0, 5431 Mode, 5479 Distance ≤ 0 (Mode 2),
  542C CoordSystem,
  570B CSID not defined, 570F no forward kinematics, 6701 TCP outside the workspace at the start. MC_GroupStop, a
  group error or another group instruction aborts it (CommandAborted until Enable falls).

Readings: docs/decisions.md D90.
"""

from __future__ import annotations

import math
from typing import Any

from .. import errors as E
from ..group import E_ILLEGAL_GROUP, AxesGroup
from ..jobs import Job, JobKind
from ..kinematics import Delta3Params, Delta3Workspace, Status, contains_point, forward_point, inverse_point
from ..kinematics.codes import E_COMMAND_OUTSIDE, E_CSID, E_CURRENT_OUTSIDE, E_KIN_CALC, E_TARGET_OUTSIDE
from .admin import I_ENABLE
from .base import O_ABORTED, O_ACTIVE, O_BUSY, O_ERROR, O_ERRORID, FBDef, FunctionBlock, Var
from .group_fb import IO_GROUP, _GroupRef

E_KIN_NOT_SET = 0x5710
E_COORD_SYSTEM = 0x542C
MCS, UCS = 1, 3  # _eMC_RBT_COORD_SYSTEM: _mcRBT_MCS, _mcRBT_UCS (§8.1)
BISECT_STEPS = 24  # 2⁻²⁴ of one period's step (< 1e-6 mm at 16 mm per period)
Vec3 = tuple[float, float, float]


class _SyncTarget:
    """Owner of the group's synchronous job: the group reads `inp["Position"]` (A0–A2 in degrees) every period,
    exactly as it reads MC_GroupSyncMoveAbsolute's input; status changes wake the instruction."""

    def __init__(self, fb: MC_RobotJog, angles: Vec3) -> None:
        self.fb = fb
        self.inp: dict[str, list[float]] = {"Position": [*angles, 0.0]}

    @property
    def label(self) -> str:
        return self.fb.label

    def wake(self) -> None:
        self.fb.wake()

    def sync_job(self) -> None:
        self.fb.wake()


class MC_RobotJog(_GroupRef, FunctionBlock):
    DEF = FBDef(
        name="MC_RobotJog", title="Cartesian jog of a robot (MC Studio)",
        summary="MC Studio extension for the test run: while Enable is TRUE the Delta3 TCP moves in a straight line "
                "along Direction (Mode 0), to TargetPosition (Mode 1) or by Distance along Direction (Mode 2, a step) "
                "in the MCS or a UCS, never leaving the "
                "workspace; the axes follow through the group like MC_GroupSyncMoveAbsolute.",
        kind="enable", inouts=(IO_GROUP,),
        inputs=(I_ENABLE,
                Var("Mode", "UINT", 0, "0: jog along Direction; 1: go to TargetPosition; 2: step Distance along "
                    "Direction at Enable↑", None, "0, 1, 2"),
                Var("Direction", "ARRAY[0..2] OF LREAL", [1.0, 0.0, 0.0],
                    "Jog direction [X, Y, Z] in the coordinate system (normalised; [0, 0, 0] = stand still)", None,
                    "any"),
                Var("TargetPosition", "ARRAY[0..2] OF LREAL", [0.0, 0.0, 0.0],
                    "Go-to target [X, Y, Z] in the coordinate system (Mode 1)", "mm", "inside the workspace"),
                Var("Distance", "LREAL", 1.0, "Step length along Direction (Mode 2)", "mm", "positive"),
                Var("Velocity", "LREAL", 50.0, "TCP speed", "mm/s", "positive"),
                Var("Acceleration", "LREAL", 500.0, "TCP acceleration and deceleration (0 = step change)", "mm/s²",
                    "positive or 0"),
                Var("CoordSystem", "UINT", MCS, "1: MCS (_mcRBT_MCS), 3: UCS (_mcRBT_UCS)", None, "1, 3"),
                Var("CSID", "UINT", 0, "User coordinate system (CoordSystem 3)", None, "0–15")),
        outputs=(Var("Enabled", "BOOL", False, "TRUE while the instruction controls the group"), O_BUSY, O_ACTIVE,
                 Var("InPosition", "BOOL", False,
                     "Modes 1 and 2: the command is at the target and the axes in position"),
                 Var("AtBoundary", "BOOL", False, "TRUE while the point is stopped at the workspace boundary"),
                 Var("WarningID", "WORD", 0, "6700: stopped at the boundary; 571B: go-to target outside"),
                 Var("CommandPosition", "ARRAY[0..2] OF LREAL", [0.0, 0.0, 0.0],
                     "TCP command position [X, Y, Z] in the coordinate system", "mm"),
                 Var("CommandVelocity", "LREAL", 0.0, "TCP command speed", "mm/s"),
                 O_ABORTED, O_ERROR, O_ERRORID),
        spec="omron-robot-delta3.md §12.8 [Emulator] (Cartesian jog for the test run), §3.2 workspace, §11 codes",
        notes="MC Studio extension for the test run (not an NJ instruction; decision D90)",
    )

    def __init__(self, mc: Any, fb_id: int, inputs: dict[str, Any] | None = None) -> None:
        super().__init__(mc, fb_id, inputs)
        self._prev_enable = False
        self._group: AxesGroup | None = None
        self._job: Job | None = None
        self._target: _SyncTarget | None = None
        self._params: Delta3Params | None = None
        self._ws: Delta3Workspace | None = None
        self._check_ws = True
        self._p: Vec3 = (0.0, 0.0, 0.0)  # command point, MCS [mm]
        self._u: Vec3 | None = None  # direction of the current motion (MCS unit vector)
        self._s = 0.0  # speed along _u [mm/s]
        self._rot: tuple[Vec3, Vec3, Vec3] | None = None  # UCS rotation rows (None = MCS)
        self._origin: Vec3 = (0.0, 0.0, 0.0)
        self._goal: Vec3 | None = None  # Mode 2: the step's end point (MCS), fixed at Enable↑
        self._warned = 0

    # ------------------------------------------------------------------ coordinate systems
    def _to_mcs(self, v: list[float], *, point: bool) -> Vec3:
        r = self._rot
        if r is None:
            return (float(v[0]), float(v[1]), float(v[2]))
        x = tuple(r[k][0] * v[0] + r[k][1] * v[1] + r[k][2] * v[2] for k in range(3))
        if point:
            x = tuple(a + b for a, b in zip(x, self._origin, strict=True))
        return x  # type: ignore[return-value]

    def _from_mcs(self, p: Vec3) -> list[float]:
        r = self._rot
        if r is None:
            return list(p)
        d = [p[k] - self._origin[k] for k in range(3)]
        return [r[0][k] * d[0] + r[1][k] * d[1] + r[2][k] * d[2] for k in range(3)]  # Rᵀ·(p − T)

    # ------------------------------------------------------------------ the call
    def call(self) -> None:
        o = self.out
        en = bool(self.inp["Enable"])
        edge = en and not self._prev_enable
        self._prev_enable = en
        if o["Error"]:
            if not self._error_released():
                return
            o["Error"] = False
            o["ErrorID"] = 0
        job = self._job
        if job is not None and not job.running:  # aborted by MC_GroupStop, a group error or another instruction
            self._release(aborted=True)
            job = None
        if not en and o["CommandAborted"]:
            o["CommandAborted"] = False
        if job is None:
            if edge and not o["CommandAborted"]:
                self._start()
            if self._job is None:
                o["Busy"] = o["Enabled"] = o["Active"] = o["InPosition"] = False
                o["CommandVelocity"] = 0.0
                if not en and not o["Error"]:
                    self.sleep()  # woken by an input change
                return
            o["Busy"] = o["Enabled"] = True
            return  # the first target is the current point; motion from the next call on (Active then)
        o["Active"] = True
        self._period(en)

    def _start(self) -> None:
        group: AxesGroup | None = self.resolve_axis()
        if group is None:
            self.fail(E_ILLEGAL_GROUP, None)
            return
        i = self.inp
        kin = group.kinematics
        if kin is None or group.m.cycle < group.kin_from_cycle:
            self.fail(E_KIN_NOT_SET, group)
            return
        distance = i.get("Distance", 1.0)
        bad_distance = i["Mode"] == 2 and (isinstance(distance, bool) or not isinstance(distance, int | float)
                                           or not math.isfinite(distance) or not distance > 0)
        code = (E.E_MOVE_MODE if i["Mode"] not in (0, 1, 2) else E.E_TRAVEL_DISTANCE if bad_distance
                else E.E_VELOCITY if not i["Velocity"] > 0
                else E.E_ACCELERATION if i["Acceleration"] < 0 else E_COORD_SYSTEM if i["CoordSystem"] not in (MCS, UCS)
                else 0)
        if code:
            self.fail(code, group)
            return
        self._rot, self._origin = None, (0.0, 0.0, 0.0)
        if i["CoordSystem"] == UCS:
            ucs = group.coord_systems.get(int(i["CSID"]))  # MC_DefineCoordSystem (volatile, D83)
            if ucs is None:
                self.fail(E_CSID, group)
                return
            R = ucs.R
            self._rot = tuple(tuple(float(R[r][c]) for c in range(3)) for r in range(3))  # type: ignore[assignment]
            T = ucs.T
            self._origin = (float(T[0]), float(T[1]), float(T[2]))
        verdict, code = group.check_start("move")
        if verdict == "abort":
            self.out["CommandAborted"] = True
            return
        if verdict == "error":
            self.fail(code, group)
            return
        code = group.member_error()
        if code:
            self.fail(code, group)
            return
        params, ws = kin.params(), kin.workspace_obj()
        cmd = group.point()
        status, p = forward_point(params, cmd[0], cmd[1], cmd[2])
        if status != Status.OK:
            self.fail(E_KIN_CALC, group)
            return
        self._check_ws = bool(group.workspace_check)
        if not contains_point(ws, *p):
            self.fail(E_CURRENT_OUTSIDE, group)  # as at the start of MC_MoveTimeAbsolute (check 1, §3.2)
            return
        self._params, self._ws, self._group = params, ws, group
        self._p, self._u, self._s = p, None, 0.0
        self._goal = None
        if i["Mode"] == 2:
            dv = self._to_mcs(i["Direction"], point=False)
            n = math.sqrt(dv[0] * dv[0] + dv[1] * dv[1] + dv[2] * dv[2])
            d = float(distance) / n if n > 1e-12 else 0.0
            self._goal = (p[0] + dv[0] * d, p[1] + dv[1] * d, p[2] + dv[2] * d)
        self._target = _SyncTarget(self, (cmd[0], cmd[1], cmd[2]))
        job = Job(JobKind.GROUP_SYNC, self._target)
        code = group.submit(job)
        if code:
            self.fail(code, group)
            return
        self._job = job
        self._warned = 0
        self.out["CommandPosition"] = self._from_mcs(p)

    def _release(self, *, aborted: bool) -> None:
        self._job = None
        self._target = None
        self._s = 0.0
        self._u = None
        o = self.out
        o["Busy"] = o["Enabled"] = o["Active"] = o["InPosition"] = o["AtBoundary"] = False
        o["CommandVelocity"] = 0.0
        o["WarningID"] = 0
        if aborted:
            o["CommandAborted"] = True

    # ------------------------------------------------------------------ one period
    def _admissible(self, q: Vec3) -> Vec3 | None:
        """ACS angles of a command point if it is inside the workspace, reachable and within the software limits."""
        assert self._params is not None and self._ws is not None and self._group is not None
        if not contains_point(self._ws, *q):
            return None
        status, angles = inverse_point(self._params, *q)
        if status != Status.OK:
            return None
        for a, v in zip(self._group.axes, angles, strict=False):
            lim = a.params.Limit
            if lim.SwLimitMode != 0 and not (lim.NegaSwLimit <= v <= lim.PosiSwLimit):
                return None
        return angles

    def _period(self, en: bool) -> None:
        i, o = self.inp, self.out
        group, job, target = self._group, self._job, self._target
        assert group is not None and job is not None and target is not None
        T = self.mc.period_s
        v_max = min(float(i["Velocity"]), group.op.MaxInterpolationVel) if i["Velocity"] > 0 else 0.0
        acc = float(i["Acceleration"])
        p = self._p
        mode = int(i["Mode"])
        goto = mode == 1
        stepping = mode == 2 and self._goal is not None
        targeted = goto or stepping  # a fixed end point: approach it and stop there (InPosition)
        warning = 0
        dist = math.inf
        want_u: Vec3 | None = None
        goal = p
        if targeted:
            goal = self._goal if stepping and self._goal is not None else self._to_mcs(i["TargetPosition"], point=True)
            d = (goal[0] - p[0], goal[1] - p[1], goal[2] - p[2])
            dist = math.sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2])
            if goto and self._admissible(goal) is None:  # a step is cut at the boundary instead (like the jog)
                warning, dist = E_TARGET_OUTSIDE, 0.0
            elif dist > 1e-9:
                want_u = (d[0] / dist, d[1] / dist, d[2] / dist)
        else:
            dv = self._to_mcs(i["Direction"], point=False)
            n = math.sqrt(dv[0] * dv[0] + dv[1] * dv[1] + dv[2] * dv[2])
            if n > 1e-12:
                want_u = (dv[0] / n, dv[1] / n, dv[2] / n)
        # speed: towards the wanted one; a change of the jog direction first stops the point
        v_goal = v_max if (en and want_u is not None) else 0.0
        if self._u is not None and want_u is not None and self._s > 0 and not targeted and want_u != self._u:
            v_goal = 0.0
        if targeted and acc > 0 and dist < math.inf:
            v_goal = min(v_goal, math.sqrt(2.0 * acc * dist))
        s = self._s
        s = v_goal if acc <= 0 else max(s - acc * T, min(s + acc * T, v_goal))
        if s <= 1e-12:
            s = 0.0
        if s == 0.0 or (self._s == 0.0 and want_u is not None):
            self._u = want_u if en else self._u
        elif targeted:
            self._u = want_u  # a new target: the direction changes at once, the speed stays continuous
        u = self._u
        step = s * T
        if targeted:
            step = min(step, dist)
        at_boundary = False
        if u is not None and step > 0:
            q = (p[0] + u[0] * step, p[1] + u[1] * step, p[2] + u[2] * step)
            angles = self._admissible(q)
            if angles is not None:
                # keep every axis within its Maximum Velocity by a shorter step on the same line
                cur = target.inp["Position"]
                f = min((a.params.Operation.MaxVel * T / abs(v - cur[k]) for k, (a, v)
                         in enumerate(zip(group.axes, angles, strict=False)) if abs(v - cur[k]) > 0), default=1.0)
                if f < 1.0:
                    step *= f * 0.999
                    s = step / T
                    q = (p[0] + u[0] * step, p[1] + u[1] * step, p[2] + u[2] * step)
                    angles = self._admissible(q)
            if angles is None:
                # cut the step at the boundary: the last admissible point on the segment (bisection)
                lo, hi, best = 0.0, 1.0, None
                for _ in range(BISECT_STEPS):
                    mid = 0.5 * (lo + hi)
                    qm = (p[0] + u[0] * step * mid, p[1] + u[1] * step * mid, p[2] + u[2] * step * mid)
                    am = self._admissible(qm)
                    if am is None:
                        hi = mid
                    else:
                        lo, best = mid, (qm, am)
                if best is not None:
                    q, angles = best
                else:
                    q = p
                s, at_boundary, warning = 0.0, True, E_COMMAND_OUTSIDE
            if angles is not None:
                target.inp["Position"] = [*angles, 0.0]
                p = q
            if targeted and dist - step <= 1e-9 and not at_boundary:
                p, s = goal, 0.0
                angles2 = self._admissible(p)
                if angles2 is not None:
                    target.inp["Position"] = [*angles2, 0.0]
        self._p, self._s = p, s
        if warning and warning != self._warned:
            self.mc.events.add(cycle=self.mc.cycle, time_s=self.mc.cycle * T, source=f"{group.name} / {self.label}",
                               code=f"{warning:04X}0000", level="observation",
                               message="Cartesian jog stopped at the workspace boundary" if warning == E_COMMAND_OUTSIDE
                               else "Go-to target outside the workspace: not moving",
                               source_kind="group", source_name=group.name, instruction=self.label)
        self._warned = warning
        o["AtBoundary"] = at_boundary
        o["WarningID"] = warning
        o["CommandPosition"] = self._from_mcs(p)
        o["CommandVelocity"] = s
        at_goal = targeted and s == 0.0 and warning == 0 and (dist - step) <= 1e-9
        o["InPosition"] = at_goal and job.in_velocity
        if not en and s == 0.0:
            # stopped after Enable fell: end the synchronous job, the group is Standby again
            group.end_sync(job)
            self._release(aborted=False)

    def on_delete(self) -> None:
        job, group = self._job, self._group
        if job is not None and group is not None:
            group.end_sync(job, aborted=True)


ROBOT_JOG_CLASSES = (MC_RobotJog,)
