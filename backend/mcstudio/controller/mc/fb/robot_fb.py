"""Robot instructions of the NJ501-4□□□ (`omron-robot-delta3.md` §9): MC_SetKinTransform, MC_InverseKin,
MC_DefineCoordSystem and MC_GroupMon (the motion instructions are in `robot_motion_fb.py`).

MC_SetKinTransform registers Delta3 kinematics and a workspace on a group at run time (volatile, like the
controller: the project's `kinematics` is the set-up applied at start-up). The checks and their order are §9.1's
[Emulator] list: 5461 → 5706 → 543E → 5466 → 5707 → 5708 → 5709 → 570A → 571E → restrictions (§3.3, 5708/571F) →
forward kinematics of the axes' actual positions (571F). A 571F deletes the kinematics registered before. The new
kinematics are usable by the robot instructions one period after Done (§9.1). MC_InverseKin (§9.7) converts an MCS
position to ACS angles every period while Enable is TRUE. Readings: docs/decisions.md D71.
"""

from __future__ import annotations

import math
from typing import Any

from ....project.models import Delta3KinematicsConfig, Delta3WorkspaceConfig
from ..enums import _eMC_COUNT_MODE, _eMC_UNITS
from ..errors import E_COORDINATED, E_HOME_UNDEFINED
from ..group import E_ILLEGAL_GROUP, AxesGroup
from ..kinematics import (
    Status,
    UserCoordSystem,
    check_kin_transform,
    check_pose,
    contains_point,
    forward_point,
    inverse_point,
    tcp_velocity_point,
)
from ..kinematics.codes import (
    E_CSID,
    E_KIN_CALC,
    E_KIN_INIT,
    E_KIN_PARAM,
    E_KIN_TYPE,
    E_POSE,
    E_WORKSPACE_PARAM,
    E_WORKSPACE_TYPE,
)
from ..kinematics.params import KIN_TYPE_DELTA3, WORKSPACE_TYPE_DELTA3
from ..kinematics.ucs import CSID_MAX
from ..robot import from_mcs, kinematics_of, vector_from_mcs
from .admin import I_ENABLE, _EnableFB
from .base import I_EXECUTE, O_BUSY, O_ERROR, O_ERRORID, FBDef, Var
from .group_fb import IO_GROUP, ONESHOT_OUTPUTS, _GroupOneShot, _GroupRef

SPEC = "omron-robot-delta3.md"
E_KIN_COMPOSITION = 0x5706  # group and kinematics composition mismatch (§11)
E_KIN_NOT_SET = 0x5710  # kinematics not set (§11)
E_TOO_MANY_KIN = 0x571E  # more than 8 kinematics (NJ501-4300/4400/4500)
MAX_KINEMATICS = 8
DELTA3_AXES = 3
KIN_TYPES = {"_mcDelta3Type1": KIN_TYPE_DELTA3}
WORKSPACE_TYPES = {"_mcDelta3Workspace": WORKSPACE_TYPE_DELTA3}

I_KIN = Var("KinTransform", "_sMC_KIN_REF",
            {"KinType": KIN_TYPE_DELTA3, "KinParam": [0.0] * 8, "ExpansionParam": [0.0] * 8},
            "Kinematics: KinType (100 _mcDelta3Type1), KinParam [Rf, Lf, Rm, Lm, 0…] (mm), ExpansionParam [θ (deg), "
            "0…]", None, "§8.2")
I_WORKSPACE = Var("Workspace", "_sMC_WORKSPACE_REF", {"WorkspaceType": WORKSPACE_TYPE_DELTA3,
                                                      "WorkspaceParam": [0.0] * 8},
                  "Workspace: WorkspaceType (100 _mcDelta3Workspace), WorkspaceParam [Zu, Rcy, Hcy, Rco, Hco, 0…] (mm)",
                  None, "§8.2")


def _enum(value: Any, names: dict[str, int]) -> int | None:
    if isinstance(value, str):
        return names.get(value, int(value) if value.lstrip("-").isdigit() else None)
    if isinstance(value, int) and not isinstance(value, bool):
        return value
    return None


def _numbers(value: Any) -> list[float] | None:
    """ARRAY[0..7] OF LREAL given as a JSON list; None when it is not a list of numbers (length: the checks')."""
    if not isinstance(value, list | tuple) or any(isinstance(v, bool) or not isinstance(v, int | float)
                                                  for v in value):
        return None
    return [float(v) for v in value]


class MC_SetKinTransform(_GroupOneShot):
    DEF = FBDef(
        name="MC_SetKinTransform", title="Set kinematics transformation",
        summary="Registers Delta3 kinematics (Rf, Lf, Rm, Lm, θ) and the workspace on a disabled, homed 3-axis group; "
                "robot instructions can use them one period after Done. Volatile (lost at power-off).",
        kind="execute", inouts=(IO_GROUP,),
        inputs=(I_EXECUTE, I_KIN, I_WORKSPACE,
                Var("EnableWorkspace", "BOOL", True, "TRUE: workspace check on (the workspace is stored either way)")),
        outputs=ONESHOT_OUTPUTS,
        spec=f"{SPEC} §9.1 (seed 003 L2735–2977), §3.3, §11",
    )

    def execute(self, axis: Any) -> None:
        group: AxesGroup = axis
        m = group.m
        if len(group.axes) != DELTA3_AXES or any(
                a.params.UnitConversion.UnitDisplay != _eMC_UNITS._mcDeg
                or a.params.PosCount.CountMode != _eMC_COUNT_MODE._mcCountModeLinear for a in group.axes):
            self.fail(E_KIN_COMPOSITION, group)  # 3 axes, degrees, linear count mode (§9.1)
            return
        if group.enabled:
            self.fail(E_COORDINATED, group)  # only on a disabled group (§9.1, §11 543E)
            return
        if not all(a.homed for a in group.axes):
            self.fail(E_HOME_UNDEFINED, group)
            return
        # a member of the wrong JSON type fails its own range check, in the manual's order (NaN / -1 stand in)
        kin, ws = self.inp["KinTransform"], self.inp["Workspace"]
        kin_type, ws_type = _enum(kin.get("KinType", KIN_TYPE_DELTA3), KIN_TYPES), _enum(
            ws.get("WorkspaceType", WORKSPACE_TYPE_DELTA3), WORKSPACE_TYPES)
        kp, ep, wp = (_numbers(kin.get("KinParam", [])), _numbers(kin.get("ExpansionParam", [])),
                      _numbers(ws.get("WorkspaceParam", [])))
        nan = [float("nan")]
        check = check_kin_transform(KinType=-1 if kin_type is None else kin_type, KinParam=nan if kp is None else kp,
                                    ExpansionParam=nan if ep is None else ep,
                                    WorkspaceType=-1 if ws_type is None else ws_type,
                                    WorkspaceParam=nan if wp is None else wp)
        if check.error_id in (E_KIN_TYPE, E_KIN_PARAM, E_WORKSPACE_TYPE, E_WORKSPACE_PARAM):
            self.fail(check.error_id, group)
            return
        others = sum(1 for g in m.groups if g is not group and g.kinematics is not None)
        if group.kinematics is None and others >= MAX_KINEMATICS:
            self.fail(E_TOO_MANY_KIN, group)
            return
        if not check.ok or check.params is None or check.workspace is None:
            self._init_error(group, f"{check.parameter}: {check.message}")
            return
        act = [float(m.act_pos[a.i]) for a in group.axes]
        status, _ = forward_point(check.params, act[0], act[1], act[2])
        if status != Status.OK:
            self._init_error(group, f"no forward kinematics at the axes' positions {act} deg")
            return
        p, w = check.params, check.workspace
        group.kinematics = Delta3KinematicsConfig(
            Rf=p.Rf, Lf=p.Lf, Rm=p.Rm, Lm=p.Lm, theta=p.theta,
            workspace=Delta3WorkspaceConfig(Zu=w.Zu, Rcy=w.Rcy, Hcy=w.Hcy, Rco=w.Rco, Hco=w.Hco))
        group.workspace_check = bool(self.inp["EnableWorkspace"])
        group.kin_from_cycle = m.cycle + 2  # Done shows next period; usable the period after (§9.1)
        m.log_info(None, f"{group.name}: Delta3 kinematics set (Rf {p.Rf}, Lf {p.Lf}, Rm {p.Rm}, Lm {p.Lm} mm, "
                         f"θ {p.theta}°)", group=group.name)
        self.done_next()

    def _init_error(self, group: AxesGroup, detail: str) -> None:
        """571F: the kinematics registered before are deleted (§9.1)."""
        group.kinematics = None
        self._set_error(E_KIN_INIT, group)  # type: ignore[arg-type]
        group.raise_error(E_KIN_INIT, source=self.label, detail=detail)


class MC_InverseKin(_GroupRef, _EnableFB):
    DEF = FBDef(
        name="MC_InverseKin", title="Inverse kinematics",
        summary="Every period while Enable is TRUE: the ACS angles A0–A2 of an MCS position (mm → deg); OutWorkspace "
                "when the position is outside the workspace. Moves nothing.",
        kind="enable", inouts=(IO_GROUP,),
        inputs=(I_ENABLE, Var("Position", "ARRAY[0..5] OF LREAL", [0.0] * 6,
                              "MCS position [X, Y, Z, 0, 0, 0]", "mm", "any")),
        outputs=(Var("Valid", "BOOL", False, "TRUE while AxesPosition is valid"), O_BUSY, O_ERROR, O_ERRORID,
                 Var("AxesPosition", "ARRAY[0..5] OF LREAL", [0.0] * 6, "ACS angles [A0, A1, A2, 0, 0, 0]", "deg"),
                 Var("OutWorkspace", "BOOL", False, "TRUE while Position is outside the workspace")),
        spec=f"{SPEC} §9.7 (seed 003 L4704–4902), §11",
    )

    def enabled(self, changed: bool) -> None:
        group: AxesGroup | None = self.resolve_axis()
        if group is None:
            self.fail(E_ILLEGAL_GROUP, None)
            return
        kin = group.kinematics
        if kin is None or group.m.cycle < group.kin_from_cycle:
            self.fail(E_KIN_NOT_SET, group)
            return
        x, y, z = self.inp["Position"][:3]
        outside = not contains_point(kin.workspace_obj(), x, y, z)  # whether or not the check is enabled (§9.7)
        status, angles = inverse_point(kin.params(), x, y, z)
        o = self.out
        if status != Status.OK and not outside:
            self.fail(E_KIN_CALC, group)  # 570F: no solution for a target inside the workspace
            return
        if status == Status.OK:
            o["AxesPosition"] = [*angles, 0.0, 0.0, 0.0]
        o["OutWorkspace"] = outside
        o["Valid"] = not outside

    def call(self) -> None:
        super().call()
        o = self.out
        if not o["Busy"] or o["Error"]:
            o["Valid"] = False
            o["OutWorkspace"] = False


def kinematics_set(group: AxesGroup) -> bool:
    """Kinematics registered and usable (the project's from cycle 0, MC_SetKinTransform's from the period after Done,
    §9.1); otherwise the robot instructions give 5710."""
    return group.kinematics is not None and group.m.cycle >= group.kin_from_cycle


class MC_DefineCoordSystem(_GroupOneShot):
    DEF = FBDef(
        name="MC_DefineCoordSystem", title="Define coordinate system",
        summary="Registers user coordinate system CSID (0–15) of a robot by its pose Tx, Ty, Tz (mm), Rx, Ry, Rz (deg) "
                "relative to the MCS, rotated Rz → Ry → Rx (§4). Volatile.",
        kind="execute", inouts=(IO_GROUP,),
        inputs=(I_EXECUTE, Var("CoordTransform", "_sMC_COORD_REF", {"CSID": 0, "Pose": [0.0] * 6},
                               "CSID (0–15) and Pose [Tx, Ty, Tz (mm), Rx (−180…180°), Ry (−90…90°), Rz (−180…180°)]",
                               None, "§8.2")),
        outputs=ONESHOT_OUTPUTS,
        spec=f"{SPEC} §9.2 (seed 003 L2978–3101), §4, §11",
    )

    def execute(self, axis: Any) -> None:
        group: AxesGroup = axis
        if not kinematics_set(group):
            self.fail(E_KIN_NOT_SET, group)
            return
        ct = self.inp["CoordTransform"]
        csid = ct.get("CSID", 0)
        if isinstance(csid, bool) or not isinstance(csid, int) or not 0 <= csid <= CSID_MAX:
            self.fail(E_CSID, group)  # out of range or wrong data type (§11 570B)
            return
        pose = _numbers(ct.get("Pose", [0.0] * 6))
        code, reason = (E_POSE, "Pose is not an array of numbers") if pose is None else check_pose(pose)
        if code:
            # 570C: source MC common, no effect on the group (§9.2 [Emulator]); ResetMCError releases Error
            self._set_error(code, None)
            m = group.m
            m.log_error(code, axis=None, source=f"{group.name} / {self.label}", detail=reason)
            return
        assert pose is not None
        ucs = UserCoordSystem.from_pose(pose)
        group.coord_systems[csid] = ucs
        group.m.log_info(None, f"{group.name}: user coordinate system {csid} defined, pose {ucs.pose()}",
                         group=group.name)
        self.done_next()


_POSITION_REF = {"CommandPosition": [0.0] * 6, "ActualPosition": [0.0] * 6}
_VELOCITY_REF = {"ActualVelocityTCP": 0.0, "ActualVelocity": [0.0] * 6}


class MC_GroupMon(_GroupRef, _EnableFB):
    DEF = FBDef(
        name="MC_GroupMon", title="Group monitor",
        summary="Every period while Enable is TRUE: the TCP command and feedback positions and the feedback velocity "
                "of the robot in the MCS or a UCS (forward kinematics of the axes).",
        kind="enable", inouts=(IO_GROUP,),
        inputs=(I_ENABLE,
                Var("CoordSystem", "_eMC_RBT_COORD_SYSTEM", 1, "Coordinate system: _mcRBT_MCS or _mcRBT_UCS", None,
                    "1, 3"),
                Var("CSID", "UINT", 0, "User coordinate system ID (CoordSystem = _mcRBT_UCS)", None, "0–15")),
        outputs=(Var("Valid", "BOOL", False, "TRUE while Position and Velocity are valid"), O_BUSY, O_ERROR, O_ERRORID,
                 Var("Position", "_sMC_POSITION_REF", _POSITION_REF,
                     "TCP CommandPosition and ActualPosition [X, Y, Z, 0, 0, 0]", "mm"),
                 Var("Velocity", "_sMC_VELOCITY_REF", _VELOCITY_REF,
                     "TCP feedback speed ActualVelocityTCP and components ActualVelocity [Vx, Vy, Vz, 0, 0, 0]",
                     "mm/s")),
        spec=f"{SPEC} §9.3 (seed 003 L3102–3337), §12.5, §11",
    )

    def __init__(self, mc: Any, fb_id: int, inputs: dict[str, Any] | None = None) -> None:
        super().__init__(mc, fb_id, inputs)
        self.out["Position"] = {k: list(v) for k, v in _POSITION_REF.items()}
        self.out["Velocity"] = {"ActualVelocityTCP": 0.0, "ActualVelocity": [0.0] * 6}

    def enabled(self, changed: bool) -> None:
        group: AxesGroup | None = self.resolve_axis()
        if group is None:
            self.fail(E_ILLEGAL_GROUP, None)
            return
        if not kinematics_set(group):
            self.fail(E_KIN_NOT_SET, group)
            return
        if not all(a.homed for a in group.axes):
            self.fail(E_HOME_UNDEFINED, group)
            return
        i = self.inp
        if i["CoordSystem"] not in (1, 3):
            self.fail(0x542C, group)
            return
        ucs = None
        if i["CoordSystem"] == 3:
            ucs = group.coord_systems.get(int(i["CSID"]))
            if ucs is None:
                self.fail(E_CSID, group)
                return
        kin = kinematics_of(group)
        assert kin is not None
        params = kin[0]
        m = group.m
        act_q = (float(m.act_pos[group.idx[0]]), float(m.act_pos[group.idx[1]]), float(m.act_pos[group.idx[2]]))
        act_v = (float(m.act_vel[group.idx[0]]), float(m.act_vel[group.idx[1]]), float(m.act_vel[group.idx[2]]))
        st_a, p_act = forward_point(params, *act_q)
        st_v, v_act = tcp_velocity_point(params, act_q, act_v)
        if group.enabled:
            st_c, p_cmd = forward_point(params, *(float(m.cmd_pos[k]) for k in group.idx))
        else:  # the command position holds while the group is disabled (§9.3)
            st_c, p_cmd = Status.OK, None
        if st_a != Status.OK or st_v != Status.OK or st_c != Status.OK:
            self.fail(E_KIN_CALC, group)
            return
        # new structures every period (a published snapshot may still hold the previous ones)
        held = self.out["Position"]["CommandPosition"]
        self.out["Position"] = {
            "CommandPosition": held if p_cmd is None else [*from_mcs(ucs, p_cmd), 0.0, 0.0, 0.0],
            "ActualPosition": [*from_mcs(ucs, p_act), 0.0, 0.0, 0.0]}
        v = vector_from_mcs(ucs, v_act)
        self.out["Velocity"] = {"ActualVelocityTCP": math.sqrt(v[0] ** 2 + v[1] ** 2 + v[2] ** 2),
                                "ActualVelocity": [*v, 0.0, 0.0, 0.0]}
        self.out["Valid"] = True

    def call(self) -> None:
        super().call()
        o = self.out
        if not o["Busy"] or o["Error"]:
            o["Valid"] = False


ROBOT_CLASSES = (MC_SetKinTransform, MC_InverseKin, MC_DefineCoordSystem, MC_GroupMon)
