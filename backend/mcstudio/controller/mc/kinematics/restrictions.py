"""MC_SetKinTransform's parameter checks: ranges of `_sMC_KIN_REF` / `_sMC_WORKSPACE_REF` and the restrictions
(1)–(5) on usable Delta3 geometries (`omron-robot-delta3.md` §3.3, §8.2, §9.1, §12.7; seed 003 L2074–2186,
L2840–2900).

Order (§9.1 [Emulator], decision D30.6): 5707 KinType → 5708 KinParam/ExpansionParam ranges with restrictions (1)
and (3) → 5709 WorkspaceType → 570A WorkspaceParam ranges → 571F geometry: zero pose, (4) reachability of the
workspace top, (2) elbow angle β, (4) Lm > 2·cos β·Lf, (5) cylinder radius. The first failure is returned.

The robot codes carry no attached information (seed 003 "附加信息 无"), so there is no ErrorParameterCode; the result
names the offending member (`parameter`) and restriction number for the event's detail text."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field

from .codes import E_KIN_INIT, E_KIN_PARAM, E_KIN_TYPE, E_NONE, E_WORKSPACE_PARAM, E_WORKSPACE_TYPE, Status
from .params import KIN_TYPE_DELTA3, WORKSPACE_TYPE_DELTA3, Delta3Params
from .point import inverse_point
from .workspace import Delta3Workspace

RF_MAX_MM = 2000.0  # restriction (1): Rf < 2000 mm
LM_MAX_MM = 10000.0  # restriction (1): Lm < 10000 mm


@dataclass(frozen=True)
class KinCheck:
    """Result of a check: `error_id` 0 (OK) or the manual's ErrorID; `restriction` the §3.3 number (1–5) that
    failed, 0 for a plain range check or the zero-pose condition; `parameter` the member named in the event
    ("KinParam[2]", "WorkspaceParam[1]" …); `message` a one-line English reason; `values` the diagnostic numbers
    computed on the way (q_top, beta, Kr in deg/–); `params`/`workspace` set when the check passed."""

    error_id: int = E_NONE
    restriction: int = 0
    parameter: str = ""
    message: str = ""
    values: dict[str, float] = field(default_factory=dict)
    params: Delta3Params | None = None
    workspace: Delta3Workspace | None = None

    @property
    def ok(self) -> bool:
        return self.error_id == E_NONE


def _fail(code: int, parameter: str, message: str, restriction: int = 0,
          values: dict[str, float] | None = None) -> KinCheck:
    return KinCheck(error_id=code, restriction=restriction, parameter=parameter, message=message,
                    values=values or {})


def _array(values: Sequence[float], name: str, code: int) -> tuple[list[float], KinCheck | None]:
    """ARRAY[0..7] OF LREAL: at most 8 elements (missing ones are 0), all finite."""
    if len(values) > 8:
        return [], _fail(code, name, f"{name} has {len(values)} elements; ARRAY[0..7] holds 8")
    out = [float(v) for v in values] + [0.0] * (8 - len(values))
    for k, v in enumerate(out):
        if not math.isfinite(v):
            return [], _fail(code, f"{name}[{k}]", f"{name}[{k}] = {v} is not a number")
    return out, None


def check_kin_transform(*, KinType: int = KIN_TYPE_DELTA3, KinParam: Sequence[float],
                        ExpansionParam: Sequence[float] = (), WorkspaceType: int = WORKSPACE_TYPE_DELTA3,
                        WorkspaceParam: Sequence[float]) -> KinCheck:
    """All input checks of MC_SetKinTransform on its `KinTransform` and `Workspace` members, in the order above.
    KinParam is in the manual's order Rf, Lf, Rm, Lm (mm); ExpansionParam[0] is θ (deg)."""
    if KinType != KIN_TYPE_DELTA3:
        return _fail(E_KIN_TYPE, "KinType", f"KinType {KinType} is not 100 (_mcDelta3Type1)")
    kp, bad = _array(KinParam, "KinParam", E_KIN_PARAM)
    if bad:
        return bad
    names = ("Rf", "Lf", "Rm", "Lm")
    for k in range(4):
        if not kp[k] > 0.0:
            return _fail(E_KIN_PARAM, f"KinParam[{k}]", f"{names[k]} = {kp[k]} mm must be positive")
    if not kp[0] < RF_MAX_MM:
        return _fail(E_KIN_PARAM, "KinParam[0]", f"Rf = {kp[0]} mm must be below {RF_MAX_MM:.0f} mm", 1)
    if not kp[3] < LM_MAX_MM:
        return _fail(E_KIN_PARAM, "KinParam[3]", f"Lm = {kp[3]} mm must be below {LM_MAX_MM:.0f} mm", 1)
    for k in range(4, 8):
        if kp[k] != 0.0:
            return _fail(E_KIN_PARAM, f"KinParam[{k}]", f"KinParam[{k}] is reserved and must be 0")
    ep, bad = _array(ExpansionParam, "ExpansionParam", E_KIN_PARAM)
    if bad:
        return bad
    if not 0.0 <= ep[0] <= 360.0:
        return _fail(E_KIN_PARAM, "ExpansionParam[0]", f"θ = {ep[0]}° must be within 0–360°")
    for k in range(1, 8):
        if ep[k] != 0.0:
            return _fail(E_KIN_PARAM, f"ExpansionParam[{k}]", f"ExpansionParam[{k}] is reserved and must be 0")
    if not kp[2] < kp[0]:
        return _fail(E_KIN_PARAM, "KinParam[2]", f"Rm = {kp[2]} mm must be smaller than Rf = {kp[0]} mm", 3)
    if WorkspaceType != WORKSPACE_TYPE_DELTA3:
        return _fail(E_WORKSPACE_TYPE, "WorkspaceType", f"WorkspaceType {WorkspaceType} is not 100 "
                     "(_mcDelta3Workspace)")
    wp, bad = _array(WorkspaceParam, "WorkspaceParam", E_WORKSPACE_PARAM)
    if bad:
        return bad
    rules = ((wp[0] <= 0.0, "Zu must be 0 or negative"), (wp[1] > 0.0, "Rcy must be positive"),
             (wp[2] > 0.0, "Hcy must be positive"), (wp[3] >= 0.0, "Rco must be 0 or positive"),
             (wp[4] >= 0.0, "Hco must be 0 or positive"))
    for k, (good, text) in enumerate(rules):
        if not good:
            return _fail(E_WORKSPACE_PARAM, f"WorkspaceParam[{k}]", f"{text} (WorkspaceParam[{k}] = {wp[k]} mm)")
    for k in range(5, 8):
        if wp[k] != 0.0:
            return _fail(E_WORKSPACE_PARAM, f"WorkspaceParam[{k}]", f"WorkspaceParam[{k}] is reserved and must be 0")
    params = Delta3Params.from_kin_param(kp, ep)
    workspace = Delta3Workspace.from_workspace_param(wp)
    return check_restrictions(params, workspace)


def check_restrictions(params: Delta3Params, workspace: Delta3Workspace) -> KinCheck:
    """The geometric conditions (571F) for parameters whose ranges passed: zero pose, (4), (2), (4), (5)."""
    Rf, Lf, Rm, Lm = params.Rf, params.Lf, params.Rm, params.Lm
    if math.isnan(params.Z0):
        # The MCS origin is the TCP at A0 = A1 = A2 = 0 (D30.2); without that pose there is no MCS.
        return _fail(E_KIN_INIT, "KinParam[3]", f"Lm = {Lm} mm must exceed Rf − Rm + Lf = {Rf - Rm + Lf} mm "
                     "(the zero pose, origin of the MCS, must exist)")
    status, q = inverse_point(params, 0.0, 0.0, workspace.Zu)
    if status != Status.OK:
        return _fail(E_KIN_INIT, "WorkspaceParam[0]", f"the TCP cannot reach the top of the workspace "
                     f"(0, 0, Zu = {workspace.Zu}) mm", 4)
    q_top = q[0]  # all three equal on the Z axis
    beta = elbow_angle(params, q_top, workspace.Zu)
    values = {"q_top": q_top, "beta": beta}
    if not 0.0 <= beta <= 180.0:
        return _fail(E_KIN_INIT, "KinParam[3]", f"the angle β between link 1 and link 2 at the top of the "
                     f"workspace is {beta:.4f}°, outside 0–180°", 2, values)
    if not Lm > 2.0 * math.cos(math.radians(beta)) * Lf:
        return _fail(E_KIN_INIT, "KinParam[3]", f"Lm = {Lm} mm must exceed 2·cos β·Lf = "
                     f"{2.0 * math.cos(math.radians(beta)) * Lf:.4f} mm (β = {beta:.4f}° at the workspace top)",
                     4, values)
    kr = cylinder_factor(Lm, workspace.Rcy)
    values["Kr"] = kr
    if math.isnan(kr):
        return _fail(E_KIN_INIT, "WorkspaceParam[1]", f"Rcy = {workspace.Rcy} mm exceeds Lm·cos 30° = "
                     f"{Lm * math.cos(math.radians(30.0)):.4f} mm: the cylinder radius cannot be reached", 5, values)
    if not abs(Rf - Rm) >= kr * Lf:
        return _fail(E_KIN_INIT, "WorkspaceParam[1]", f"|Rf − Rm| = {abs(Rf - Rm)} mm must be ≥ Kr·Lf = "
                     f"{kr * Lf:.4f} mm (Kr = {kr:.4f} for Rcy = {workspace.Rcy} mm)", 5, values)
    return KinCheck(values=values, params=params, workspace=workspace)


def elbow_angle(params: Delta3Params, q_deg: float, z: float) -> float:
    """β (deg): the signed angle at the elbow from link 1 (elbow → motor) to link 2 (elbow → wrist) in the arm's
    vertical plane, with the TCP on the Z axis at height z (§3.3 (2), D30.6). Positive is the normal, un-folded
    arm (the wrist below the line of link 1); the range is (−180°, 180°]."""
    q = math.radians(q_deg)
    zb = z + params.Z0
    e_r, e_z = params.Rf + params.Lf * math.cos(q), -params.Lf * math.sin(q)
    v1 = (params.Rf - e_r, 0.0 - e_z)
    v2 = (params.Rm - e_r, zb - e_z)
    cross = v1[0] * v2[1] - v1[1] * v2[0]
    dot = v1[0] * v2[0] + v1[1] * v2[1]
    return math.degrees(math.atan2(cross, dot))


def cylinder_factor(Lm: float, Rcy: float) -> float:
    """Kr of restriction (5): Kr = −cos(π − arctan(tan d / cos 60°)), d = arccos((Rcy/Lm)/cos 30°) — the manual
    prints Lm/Rcy, a typo its own example (Lm 2000, Rcy 1000 → d 0.955, Kr 0.333) disproves (§3.3, D30.6).
    NaN when Rcy/Lm > cos 30° (d undefined: the radius cannot be reached)."""
    ratio = (Rcy / Lm) / math.cos(math.radians(30.0))
    if not -1.0 <= ratio <= 1.0:
        return math.nan
    d = math.acos(ratio)
    return -math.cos(math.pi - math.atan(math.tan(d) / math.cos(math.radians(60.0))))
