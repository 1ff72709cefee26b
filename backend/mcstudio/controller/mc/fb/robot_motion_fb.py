"""Robot motion instructions of the NJ501-4□□□ (`omron-robot-delta3.md` §9.4–§9.6, §10): MC_MoveTimeAbsolute.

The instance checks its inputs and the start conditions and hands a motion of `controller/mc/robot.py` to the group;
the group's motion stage outputs one command position per period. Check order (decision D80): inputs (542B, 5432,
542C, 5715, 5714, 5712, 5713) → kinematics set (5710) → group state (543F disabled; CommandAborted in Stopping or
ErrorStop) → composition axes (5441 servo OFF, 5466 home undefined, 5442, limit inputs 6443/6444) → CSID (570B) →
start position (570F, workspace check 1: 6701) → feedback of a robot at rest (workspace check 4: 570F, 6701; D92) →
target (workspace check 2: 571B, 570F) → 6703/6704. Every error is a group minor fault and stops the robot
immediately; re-execution is 543B (§10.2).
"""

from __future__ import annotations

import math
from typing import Any

from .. import errors as E
from ..enums import _eMC_UNITS
from ..group import AxesGroup, GroupState
from ..jobs import JobKind, JobStatus
from ..kinematics import Status, UserCoordSystem, contains_point, forward_point, inverse_point
from ..kinematics.codes import E_CSID, E_CURRENT_OUTSIDE, E_INIT_WORKPIECE_OUTSIDE, E_KIN_CALC, E_TARGET_OUTSIDE
from ..robot import (
    E_ACCELERATION_ERROR,
    E_CONVEYOR_READ,
    E_VELOCITY_ERROR,
    VEL_TOL,
    ConveyorSync,
    Rates,
    SyncOutMove,
    TimeMove,
    Vec3,
    distance,
    kinematics_of,
    new_job,
    start,
    to_mcs,
    velocity_limits,
)
from .base import I_EXECUTE, ExecuteFB, FBDef, Var
from .group_fb import IO_GROUP, MOTION_OUTPUTS, _GroupRef

SPEC = "omron-robot-delta3.md"
E_KIN_NOT_SET = 0x5710
E_MAX_VEL_VALUE = 0x5712
E_MAX_ACC_VALUE = 0x5713
E_TRAJ_TIME = 0x5714
E_TRAJ_TYPE = 0x5715
E_COORD_SYSTEM = 0x542C
E_TRANSITION = 0x5432
MCS, UCS = 1, 3

I_POSITION6 = Var("Position", "ARRAY[0..5] OF LREAL", [0.0] * 6, "Target [X, Y, Z, 0, 0, 0] in the chosen CS", "mm",
                  "any")
I_RBT_COORD = Var("CoordSystem", "_eMC_RBT_COORD_SYSTEM", 1, "Coordinate system: _mcRBT_MCS or _mcRBT_UCS", None,
                  "1, 3")
I_CSID = Var("CSID", "UINT", 0, "User coordinate system ID (CoordSystem = _mcRBT_UCS)", None, "0–15")
I_RBT_BUFFER = Var("BufferMode", "_eMC_BUFFER_MODE", 0, "Only _mcAborting", None, "0", allowed=(0,))
I_RBT_TRANSITION = Var("TransitionMode", "_eMC_TRANSITION_MODE", 0, "Only _mcTMNone", None, "0", allowed=(0,))
I_TRANSITION_PARAM = Var("TransitionParameter", "ARRAY[0..7] OF LREAL", [0.0] * 8, "Reserved (not used)")


def number(value: Any) -> float | None:
    """A structure member that must be a finite number (None otherwise: the member's range error)."""
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(float(value)):
        return None
    return float(value)


def max_velocity(traj: dict[str, Any]) -> float | None:
    """TrajData.MaxVelocity; the manual's spelling MaxVelociy is accepted as well (§8.2 [Emulator])."""
    return number(traj.get("MaxVelocity", traj.get("MaxVelociy", 0.0)))


class _RobotMotionFB(_GroupRef, ExecuteFB):
    """Common start checks of MC_MoveTimeAbsolute, MC_SyncLinearConveyor and MC_SyncOut."""

    def input_error(self) -> int:
        i = self.inp
        if i["BufferMode"] != 0:
            return E.E_BUFFER_MODE
        if i.get("TransitionMode", 0) != 0:
            return E_TRANSITION
        if "CoordSystem" in i and i["CoordSystem"] not in (MCS, UCS):
            return E_COORD_SYSTEM
        return 0

    def condition_error(self, group: AxesGroup) -> int | str:
        """5710, the group state (543F, "abort"), the composition axes; 0 when the instruction may start."""
        if group.kinematics is None or group.m.cycle < group.kin_from_cycle:
            return E_KIN_NOT_SET
        verdict, code = group.check_start("move")
        if verdict == "abort":
            return "abort"
        if verdict == "error":
            return code
        return group.member_error()

    def ucs(self, group: AxesGroup) -> tuple[int, UserCoordSystem | None]:
        i = self.inp
        if i.get("CoordSystem", MCS) != UCS:
            return 0, None
        ucs = group.coord_systems.get(int(i["CSID"]))
        return (E_CSID, None) if ucs is None else (0, ucs)

    def reexecute(self, axis: Any) -> None:
        """§10.2: a new Execute edge while Busy is 543B and the robot stops immediately."""
        self.job = None
        self.fail(E.E_REEXEC_DISABLED, axis)

    def current_tcp(self, group: AxesGroup) -> tuple[int, Vec3]:
        """The TCP of the composition axes' command positions (forward kinematics; 570F without a solution)."""
        kin = kinematics_of(group)
        assert kin is not None
        q = [float(group.m.cmd_pos[i]) for i in group.idx]
        st, p = forward_point(kin[0], q[0], q[1], q[2])
        return (0, p) if st == Status.OK else (E_KIN_CALC, p)

    def feedback_error(self, group: AxesGroup, check: Any) -> int:
        """Workspace check 4 (§3.2, seed 003 L1982 and L2028; decision D92): a robot **at rest** — the group Standby,
        no robot instruction running — starts only if its TCP **feedback** position (forward kinematics of the
        axes' Act.Pos) lies inside the workspace (0.1 mm margin): else 6701, the manual's "current position outside
        the workspace … when starting the next instruction" (L7072–7095), a group error with the robot held
        (ErrorStop). Feedback angles without a forward solution → 570F ("an axis stopped where the forward
        kinematics cannot be computed", §11). Not checked on a moving robot (multi-execution: the feedback lags the
        command, check 1 covers the command) nor with EnableWorkspace FALSE (`check` None)."""
        if check is None or group.state != GroupState.Standby:
            return 0
        kin = kinematics_of(group)
        assert kin is not None
        act = group.m.act_pos
        q = [float(act[i]) for i in group.idx]
        st, p = forward_point(kin[0], q[0], q[1], q[2])
        if st != Status.OK:
            return E_KIN_CALC
        return 0 if contains_point(check, *p) else E_CURRENT_OUTSIDE


class MC_MoveTimeAbsolute(_RobotMotionFB):
    DEF = FBDef(
        name="MC_MoveTimeAbsolute", title="Time-specified absolute position command",
        summary="Moves the robot's TCP on a straight line from the current position to Position (MCS or a UCS) in "
                "exactly TrajData.TrajTime ms with a cubic time law; no in-position check.",
        kind="execute", inouts=(IO_GROUP,),
        inputs=(I_EXECUTE, I_POSITION6,
                Var("TrajData", "_sMC_MOVE_TRAJ_REF",
                    {"MoveTrajType": 0, "TrajTime": 0, "MaxVelocity": 0.0, "MaxAcceleration": 0.0},
                    "MoveTrajType (0 _mcPolynomial3), TrajTime (ms, > 0), MaxVelocity (mm/s, > 0), MaxAcceleration "
                    "(mm/s², > 0)", None, "§8.2"),
                I_RBT_COORD, I_CSID, I_RBT_BUFFER, I_RBT_TRANSITION, I_TRANSITION_PARAM),
        outputs=MOTION_OUTPUTS,
        spec=f"{SPEC} §9.4 (seed 003 L3338–3636), §10, §11",
    )

    def input_error(self) -> int:
        code = super().input_error()
        if code:
            return code
        traj = self.inp["TrajData"]
        if traj.get("MoveTrajType", 0) != 0:
            return E_TRAJ_TYPE
        t = traj.get("TrajTime", 0)
        if isinstance(t, bool) or not isinstance(t, int) or not 0 < t <= 65535:
            return E_TRAJ_TIME  # UINT, > 0
        v = max_velocity(traj)
        if v is None or not v > 0:
            return E_MAX_VEL_VALUE
        a = number(traj.get("MaxAcceleration", 0.0))
        if a is None or not a > 0:
            return E_MAX_ACC_VALUE
        return 0

    def execute(self, axis: Any) -> None:
        group: AxesGroup = axis
        code: int | str = self.input_error() or self.condition_error(group)
        if code == "abort":
            self._finish("CommandAborted")
            return
        if code:
            self.fail(int(code), group)
            return
        kin = kinematics_of(group)
        assert kin is not None
        params, ws = kin
        check = ws if group.workspace_check else None
        code, ucs = self.ucs(group)
        if not code:
            code, p0 = self.current_tcp(group)
        if code:
            self.fail(code, group)
            return
        pos = self.inp["Position"]
        p1 = to_mcs(ucs, (float(pos[0]), float(pos[1]), float(pos[2])))
        if check is not None and not contains_point(check, *p0):
            self.fail(E_CURRENT_OUTSIDE, group)  # workspace check 1
            return
        code = self.feedback_error(group, check)  # workspace check 4
        if code:
            self.fail(code, group)
            return
        if check is not None and not contains_point(check, *p1):
            self.fail(E_TARGET_OUTSIDE, group)  # workspace check 2
            return
        st, _ = inverse_point(params, *p1)
        if st != Status.OK:
            self.fail(E_KIN_CALC, group)
            return
        traj = self.inp["TrajData"]
        duration = int(traj["TrajTime"]) / 1000.0
        v_peak, a_peak = velocity_limits(distance(p0, p1), duration)
        # relative tolerance VEL_TOL: a trajectory exactly at a threshold passes despite kinematics round-off
        if v_peak > (max_velocity(traj) or 0.0) * (1.0 + VEL_TOL):
            self.fail(E_VELOCITY_ERROR, group)
            return
        if a_peak > float(traj["MaxAcceleration"]) * (1.0 + VEL_TOL):
            self.fail(E_ACCELERATION_ERROR, group)
            return
        job = new_job(self)
        start(group, job, TimeMove(p0=p0, p1=p1, duration=duration, start_cycle=group.m.cycle, params=params,
                                   workspace=check))
        self.job = job


E_CONVEYOR_AXIS = 0x571A
E_TRANSITION_RANGE = 0x5716
E_DISTANCE_RANGE = 0x5717
E_SYNC_OUT = 0x571C


def _uints(value: Any) -> list[int] | None:
    if not isinstance(value, list | tuple) or len(value) > 8 or any(
            isinstance(v, bool) or not isinstance(v, int) or not 0 <= v <= 65535 for v in value):
        return None
    return [int(v) for v in value] + [0] * (8 - len(value))


def _reals(value: Any) -> list[float] | None:
    if not isinstance(value, list | tuple) or len(value) > 8 or any(number(v) is None for v in value):
        return None
    return [float(v) for v in value] + [0.0] * (8 - len(value))


def _thresholds(traj: dict[str, Any]) -> int:
    v = max_velocity(traj)
    if v is None or not v > 0:
        return E_MAX_VEL_VALUE
    a = number(traj.get("MaxAcceleration", 0.0))
    if a is None or not a > 0:
        return E_MAX_ACC_VALUE
    return 0


class MC_SyncLinearConveyor(_RobotMotionFB):
    DEF = FBDef(
        name="MC_SyncLinearConveyor", title="Start conveyor synchronization",
        summary="Catches up with a workpiece on a conveyor (flat trajectory: rise H1 in T1, catch-up, descent in T3) "
                "and then follows it with the conveyor axis's feedback; InSync when caught up. No Done: end it with "
                "MC_SyncOut.",
        kind="execute",
        inouts=(IO_GROUP, Var("ConveyorAxis", "_sAXIS_REF", None,
                              "Conveyor axis (rotary mode, unit mm, not in a group)")),
        inputs=(I_EXECUTE,
                Var("InitWorkpiecePosition", "ARRAY[0..5] OF LREAL", [0.0] * 6,
                    "Workpiece position at the start [X, Y, Z, 0, 0, 0] in the chosen CS", "mm", "any"),
                Var("TrajData", "_sMC_SYNC_TRAJ_REF",
                    {"SyncTrajType": 0, "TrajTime": [0, 0, 0], "TrajTransition": [50, 50], "TrajDistance": [0.0],
                     "MaxVelocity": 0.0, "MaxAcceleration": 0.0},
                    "SyncTrajType (0 _mcFlatTraj), TrajTime [T1 ≥ 0, T2 > 0, T3 > 0] ms, TrajTransition [Ttrans1, "
                    "Ttrans2] 50–100 %, TrajDistance [H1] mm, MaxVelocity mm/s, MaxAcceleration mm/s²", None, "§8.2"),
                I_RBT_COORD, I_CSID, I_RBT_BUFFER, I_RBT_TRANSITION, I_TRANSITION_PARAM),
        outputs=(Var("InSync", "BOOL", False, "TRUE once the TCP has caught up with the workpiece"),
                 *MOTION_OUTPUTS[1:],
                 Var("TrajStatus", "_sMC_SYNC_TRAJ_STATUS", {"RemainTime": 0, "Phase": 0},
                     "RemainTime (ms) of T1 + T2 + T3 and Phase 0–6")),
        spec=f"{SPEC} §9.5 (seed 003 L3637–4394), §10, §11",
    )

    def input_error(self) -> int:
        code = super().input_error()
        if code:
            return code
        traj = self.inp["TrajData"]
        if traj.get("SyncTrajType", 0) != 0:
            return E_TRAJ_TYPE
        times = _uints(traj.get("TrajTime", []))
        if times is None or not (times[1] > 0 and times[2] > 0) or any(times[3:]):
            return E_TRAJ_TIME
        tr = _uints(traj.get("TrajTransition", [50, 50]))
        if tr is None or not (50 <= tr[0] <= 100 and 50 <= tr[1] <= 100) or any(tr[2:]):
            return E_TRANSITION_RANGE
        dist = _reals(traj.get("TrajDistance", [0.0]))
        if dist is None or any(dist[1:]):
            return E_DISTANCE_RANGE
        return _thresholds(traj)

    def sync_job(self) -> None:
        job = self.job
        motion = job.info.get("robot") if job is not None else None
        super().sync_job()
        o = self.out
        o["InSync"] = self.job is not None and job is not None and job.in_velocity
        if self.job is not None and isinstance(motion, ConveyorSync) and job is not None and \
                job.status == JobStatus.ACTIVE:
            o["TrajStatus"] = {"RemainTime": motion.remain_ms, "Phase": motion.phase}
        elif self.job is None:
            o["TrajStatus"] = {"RemainTime": 0, "Phase": 0}

    def execute(self, axis: Any) -> None:
        group: AxesGroup = axis
        code: int | str = self.input_error() or self.condition_error(group)
        if code == "abort":
            self._finish("CommandAborted")
            return
        if code:
            self.fail(int(code), group)
            return
        m = group.m
        conv = m.by_name.get(self.inp.get("ConveyorAxis") or "")
        if conv is None or not conv.used or conv.group is not None or any(
                conv.name in g.config.axes for g in m.groups) or \
                conv.params.UnitConversion.UnitDisplay != _eMC_UNITS._mcMm:
            self.fail(E_CONVEYOR_AXIS, group)
            return
        if not m.pd_ok[conv.i]:
            self.fail(E_CONVEYOR_READ, group)
            return
        kin = kinematics_of(group)
        assert kin is not None
        params, ws = kin
        check = ws if group.workspace_check else None
        code, ucs = self.ucs(group)
        if not code:
            code, p0 = self.current_tcp(group)
        if code:
            self.fail(int(code), group)
            return
        planar = None if ucs is None else ucs.planar()  # Rx, Ry ignored (§9.5 [Emulator])
        pos = self.inp["InitWorkpiecePosition"]
        w0 = to_mcs(planar, (float(pos[0]), float(pos[1]), float(pos[2])))
        if check is not None and not contains_point(check, *p0):
            self.fail(E_CURRENT_OUTSIDE, group)
            return
        code = self.feedback_error(group, check)  # workspace check 4
        if code:
            self.fail(code, group)
            return
        if check is not None and not contains_point(check, *w0):
            self.fail(E_INIT_WORKPIECE_OUTSIDE, group)
            return
        st, _ = inverse_point(params, *w0)
        if st != Status.OK:
            self.fail(E_KIN_CALC, group)
            return
        traj = self.inp["TrajData"]
        times = _uints(traj.get("TrajTime", []))
        tr = _uints(traj.get("TrajTransition", [50, 50]))
        dist = _reals(traj.get("TrajDistance", [0.0]))
        assert times is not None and tr is not None and dist is not None
        rz = 0.0 if planar is None else math.radians(planar.Rz)
        T = m.period_s
        motion = ConveyorSync(
            p0=p0, w0=w0, u=(math.cos(rz), math.sin(rz), 0.0), conveyor=conv.i, c0=float(m.act_pos[conv.i]),
            v0=float(m.act_vel[conv.i]), T1=times[0] / 1000.0, T2=times[1] / 1000.0, T3=times[2] / 1000.0,
            tr1=tr[0] / 100.0, tr2=tr[1] / 100.0, H1=dist[0], start_cycle=m.cycle, params=params, workspace=check,
            rates=Rates(vmax=max_velocity(traj) or 0.0, amax=float(traj["MaxAcceleration"]), prev=p0),
            tolerance=0.1 * T / 0.001, period=T)
        job = new_job(self)
        start(group, job, motion)
        self.job = job


class MC_SyncOut(_RobotMotionFB):
    DEF = FBDef(
        name="MC_SyncOut", title="End conveyor synchronization",
        summary="Ends MC_SyncLinearConveyor: _mcSyncStop (only when synchronized) leaves the workpiece velocity-"
                "continuously, decelerating in T4 and rising H4; _mcRBT_ImmediateStop stops the TCP at once.",
        kind="execute", inouts=(IO_GROUP,),
        inputs=(I_EXECUTE,
                Var("TrajData", "_sMC_SYNCOUT_TRAJ_REF",
                    {"SyncStopType": 0, "TrajTime": [0], "TrajTransition": [0], "TrajDistance": [0.0],
                     "MaxVelocity": 0.0, "MaxAcceleration": 0.0},
                    "SyncStopType (0 _mcSyncStop, 1 _mcRBT_ImmediateStop), TrajTime [T4] ms, TrajDistance [H4 ≥ 0] "
                    "mm, MaxVelocity mm/s, MaxAcceleration mm/s²", None, "§8.2"),
                I_RBT_BUFFER),
        outputs=MOTION_OUTPUTS,
        spec=f"{SPEC} §9.6 (seed 003 L4395–4703), §10, §11",
    )

    def input_error(self) -> int:
        code = super().input_error()
        if code:
            return code
        traj = self.inp["TrajData"]
        if traj.get("SyncStopType", 0) not in (0, 1):
            return E_TRAJ_TYPE
        times = _uints(traj.get("TrajTime", [0]))
        if times is None or any(times[1:]):
            return E_TRAJ_TIME
        dist = _reals(traj.get("TrajDistance", [0.0]))
        if dist is None or dist[0] < 0 or any(dist[1:]):
            return E_DISTANCE_RANGE
        return _thresholds(traj)

    def execute(self, axis: Any) -> None:
        group: AxesGroup = axis
        code: int | str = self.input_error() or self.condition_error(group)
        if code == "abort":
            self._finish("CommandAborted")
            return
        if code:
            self.fail(int(code), group)
            return
        traj = self.inp["TrajData"]
        immediate = traj.get("SyncStopType", 0) == 1
        cur = group.current
        conveyor = cur.info.get("robot") if cur is not None and cur.kind == JobKind.GROUP_ROBOT else None
        if not isinstance(conveyor, ConveyorSync) or (not immediate and conveyor.phase != 6):
            self.fail(E_SYNC_OUT, group)  # §10.1 "Error" cells and §9.6 (D84)
            return
        kin = kinematics_of(group)
        assert kin is not None
        params, ws = kin
        check = ws if group.workspace_check else None
        code, p0 = self.current_tcp(group)
        if code:
            self.fail(code, group)
            return
        if check is not None and not contains_point(check, *p0):
            self.fail(E_CURRENT_OUTSIDE, group)
            return
        m = group.m
        times = _uints(traj.get("TrajTime", [0]))
        dist = _reals(traj.get("TrajDistance", [0.0]))
        assert times is not None and dist is not None
        vc = float(m.act_vel[conveyor.conveyor])
        u = conveyor.u
        T4 = 0.0 if immediate else times[0] / 1000.0
        rates = None if T4 <= 0 else Rates(vmax=max_velocity(traj) or 0.0, amax=float(traj["MaxAcceleration"]),
                                            prev=conveyor.rates.prev, vel=conveyor.rates.vel)
        motion = SyncOutMove(p0=p0, vel=(vc * u[0], vc * u[1], 0.0), T4=T4, H4=dist[0], start_cycle=m.cycle,
                             params=params, workspace=check, rates=rates)
        job = new_job(self)
        start(group, job, motion)
        self.job = job


ROBOT_MOTION_CLASSES = (MC_MoveTimeAbsolute, MC_SyncLinearConveyor, MC_SyncOut)
