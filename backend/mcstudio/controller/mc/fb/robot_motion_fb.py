"""Robot motion instructions of the NJ501-4□□□ (`omron-robot-delta3.md` §9.4–§9.6, §10): MC_MoveTimeAbsolute.

The instance checks its inputs and the start conditions and hands a motion of `controller/mc/robot.py` to the group;
the group's motion stage outputs one command position per period. Check order (decision D80): inputs (542B, 5432,
542C, 5715, 5714, 5712, 5713) → kinematics set (5710) → group state (543F disabled; CommandAborted in Stopping or
ErrorStop) → composition axes (5441 servo OFF, 5466 home undefined, 5442, limit inputs 6443/6444) → CSID (570B) →
start position (570F, workspace check 1: 6701) → target (workspace check 2: 571B, 570F) → 6703/6704. Every error
is a group minor fault and stops the robot immediately; re-execution is 543B (§10.2).
"""

from __future__ import annotations

import math
from typing import Any

from .. import errors as E
from ..group import AxesGroup
from ..kinematics import Status, UserCoordSystem, contains_point, forward_point, inverse_point
from ..kinematics.codes import E_CSID, E_CURRENT_OUTSIDE, E_KIN_CALC, E_TARGET_OUTSIDE
from ..robot import (
    E_ACCELERATION_ERROR,
    E_VELOCITY_ERROR,
    VEL_TOL,
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


ROBOT_MOTION_CLASSES = (MC_MoveTimeAbsolute,)
