"""MC_SetKinTransform's parameter checks: ranges (§8.2, seed 003 L2840–2900), restrictions (1)–(5) of manual 3.3.3
(§3.3, §12.7, seed 003 L2074–2186) and their codes (§9.1, §11; D30.2, D30.6)."""

from __future__ import annotations

import math

import pytest

from mcstudio.controller.mc.kinematics import Delta3Params, Delta3Workspace, check_kin_transform, inverse_point
from mcstudio.controller.mc.kinematics import restrictions as rs

KP = [200.0, 350.0, 50.0, 800.0]  # Rf, Lf, Rm, Lm — the manual's order
WP = [-50.0, 300.0, 250.0, 150.0, 150.0]


def check(kp: list[float] | None = None, wp: list[float] | None = None, ep: list[float] | None = None,
          **kw: int) -> rs.KinCheck:
    return check_kin_transform(KinParam=KP if kp is None else kp, WorkspaceParam=WP if wp is None else wp,
                               ExpansionParam=[0.0] if ep is None else ep, **kw)


def test_example_robot_passes_with_the_reference_numbers() -> None:
    """§12.9: Rf 200, Rm 50, Lf 350, Lm 800, Zu −50, Rcy 300 → A(0, 0, Zu) = 7.7882°, β = 59.4016°, Kr = 0.2335, all
    five restrictions hold; KinParam is read as Rf, Lf, Rm, Lm."""
    r = check()
    assert r.ok and r.error_id == 0 and r.restriction == 0
    assert r.params == Delta3Params(Rf=200.0, Lf=350.0, Rm=50.0, Lm=800.0, theta=0.0)
    assert r.workspace == Delta3Workspace(Zu=-50.0, Rcy=300.0, Hcy=250.0, Rco=150.0, Hco=150.0)
    assert r.values["q_top"] == pytest.approx(7.7882, abs=1e-4)
    assert r.values["beta"] == pytest.approx(59.4016, abs=1e-4)
    assert r.values["Kr"] == pytest.approx(0.2335, abs=1e-4)
    assert r.params.check(r.workspace) == r


def test_manuals_own_numbers() -> None:
    """Manual 3.3.3 (4): β = 30° ⇒ Lm/Lf > 1.732; (5): Lm = 2000, Rcy = 1000 ⇒ d = 0.955, Kr = 0.333 — only with
    d = arccos((Rcy/Lm)/cos 30°); the printed Lm/Rcy gives arccos(2.31), undefined (D30.6)."""
    assert round(2 * math.cos(math.radians(30.0)), 3) == 1.732
    assert round(rs.cylinder_factor(2000.0, 1000.0), 3) == 0.333
    assert round(math.acos((1000.0 / 2000.0) / math.cos(math.radians(30.0))), 3) == 0.955
    assert math.isnan(rs.cylinder_factor(1000.0, 2000.0))  # the printed formula's reading of the example


def test_kin_type() -> None:
    """5707: KinType ≠ 100 (_mcDelta3Type1); checked before everything else."""
    r = check(kp=[-1.0, 0.0, 0.0, 0.0], KinType=101)
    assert (r.error_id, r.parameter) == (0x5707, "KinType")


@pytest.mark.parametrize(("kp", "parameter"), [
    ([0.0, 350.0, 50.0, 800.0], "KinParam[0]"), ([200.0, -1.0, 50.0, 800.0], "KinParam[1]"),
    ([200.0, 350.0, 0.0, 800.0], "KinParam[2]"), ([200.0, 350.0, 50.0, 0.0], "KinParam[3]"),
    ([math.nan, 350.0, 50.0, 800.0], "KinParam[0]"), ([200.0, math.inf, 50.0, 800.0], "KinParam[1]"),
    ([200.0, 350.0, 50.0, 800.0, 1.0], "KinParam[4]"), ([200.0, 350.0, 50.0, 800.0, 0, 0, 0, 1.0], "KinParam[7]"),
    ([200.0, 350.0, 50.0, 800.0, 0, 0, 0, 0, 0], "KinParam"),
])
def test_kin_param_ranges(kp: list[float], parameter: str) -> None:
    """5708: KinParam[0..3] positive (and finite), [4..7] reserved = 0 (§8.2)."""
    r = check(kp=kp)
    assert (r.error_id, r.parameter, r.restriction) == (0x5708, parameter, 0)


def test_restriction_1_maximum_lengths() -> None:
    """Restriction (1): Rf < 2000 mm and Lm < 10000 mm → 5708 (D30.6: a condition on KinParam alone)."""
    r = check(kp=[2000.0, 350.0, 50.0, 8000.0])
    assert (r.error_id, r.restriction, r.parameter) == (0x5708, 1, "KinParam[0]")
    r = check(kp=[200.0, 350.0, 50.0, 10000.0])
    assert (r.error_id, r.restriction, r.parameter) == (0x5708, 1, "KinParam[3]")
    assert check(kp=[1999.0, 300.0, 50.0, 9999.0], wp=[-50.0, 100.0, 100.0, 0.0, 0.0]).restriction != 1


@pytest.mark.parametrize(("ep", "parameter"), [
    ([-0.001], "ExpansionParam[0]"), ([360.001], "ExpansionParam[0]"), ([math.nan], "ExpansionParam[0]"),
    ([0.0, 1.0], "ExpansionParam[1]"), ([0.0] * 9, "ExpansionParam"),
])
def test_expansion_param_ranges(ep: list[float], parameter: str) -> None:
    """5708: ExpansionParam[0] = θ within 0–360°, [1..7] reserved = 0 ("扩展参数超过设定范围", seed 003 L6471)."""
    r = check(ep=ep)
    assert (r.error_id, r.parameter) == (0x5708, parameter)


def test_theta_limits_are_inclusive() -> None:
    assert check(ep=[0.0]).ok and check(ep=[360.0]).ok and check(ep=[123.4]).ok


def test_restriction_3_rm_below_rf() -> None:
    """Restriction (3): Rm < Rf → 5708, checked before the workspace type (D30.6 order)."""
    r = check(kp=[200.0, 350.0, 200.0, 800.0], WorkspaceType=7)
    assert (r.error_id, r.restriction, r.parameter) == (0x5708, 3, "KinParam[2]")


def test_workspace_type() -> None:
    """5709: WorkspaceType ≠ 100 (_mcDelta3Workspace)."""
    r = check(wp=[1.0], WorkspaceType=0)
    assert (r.error_id, r.parameter) == (0x5709, "WorkspaceType")


@pytest.mark.parametrize(("wp", "parameter"), [
    ([0.1, 300.0, 250.0, 150.0, 150.0], "WorkspaceParam[0]"), ([-50.0, 0.0, 250.0, 150.0, 150.0], "WorkspaceParam[1]"),
    ([-50.0, 300.0, 0.0, 150.0, 150.0], "WorkspaceParam[2]"), ([-50.0, 300.0, 250.0, -1.0, 150.0], "WorkspaceParam[3]"),
    ([-50.0, 300.0, 250.0, 150.0, -1.0], "WorkspaceParam[4]"), ([-50.0, 300.0, 250.0, 150.0, 150.0, 1.0],
                                                                "WorkspaceParam[5]"),
    ([-50.0, math.nan, 250.0, 150.0, 150.0], "WorkspaceParam[1]"), ([-50.0] + [1.0] * 8, "WorkspaceParam"),
])
def test_workspace_param_ranges(wp: list[float], parameter: str) -> None:
    """570A: Zu ≤ 0, Rcy > 0, Hcy > 0, Rco ≥ 0, Hco ≥ 0, [5..7] = 0 (§8.2, seed 003 L2880–2890)."""
    r = check(wp=wp)
    assert (r.error_id, r.parameter) == (0x570A, parameter)


def test_workspace_param_zero_values_allowed() -> None:
    """Zu = 0, Rco = 0 and Hco = 0 are in range ("负数、“0”", "正数、“0”")."""
    assert check(wp=[0.0, 300.0, 250.0, 0.0, 0.0]).ok


def test_zero_pose_must_exist() -> None:
    """D30.2: the MCS origin is the TCP at A0 = A1 = A2 = 0; Lm ≤ Rf − Rm + Lf leaves no such pose → 571F."""
    r = check(kp=[200.0, 350.0, 50.0, 500.0])
    assert (r.error_id, r.restriction, r.parameter) == (0x571F, 0, "KinParam[3]")


def test_restriction_4_top_of_the_workspace_reachable() -> None:
    """Restriction (4): the TCP must reach (0, 0, Zu) → 571F when Zu is beyond the arms' reach."""
    r = check(wp=[-2000.0, 300.0, 250.0, 150.0, 150.0])
    assert (r.error_id, r.restriction, r.parameter) == (0x571F, 4, "WorkspaceParam[0]")


def test_restriction_4_lm_against_beta() -> None:
    """Restriction (4): Lm > 2·cos β·Lf. Rf 200, Rm 190, Lf 500, Lm 520, Zu 0: β = 11.25°, 2·cos β·Lf = 980.7 mm
    > 520 → 571F."""
    r = check(kp=[200.0, 500.0, 190.0, 520.0], wp=[0.0, 10.0, 100.0, 0.0, 0.0])
    assert (r.error_id, r.restriction, r.parameter) == (0x571F, 4, "KinParam[3]")
    assert r.values["beta"] == pytest.approx(math.degrees(math.atan2(500.0 * math.sqrt(520**2 - 510**2),
                                                                     500.0 * 510.0)), abs=1e-9)


def test_restriction_2_beta_range(monkeypatch: pytest.MonkeyPatch) -> None:
    """Restriction (2): 0 ≤ β ≤ 180°, β signed (D30.6). The elbow-out root keeps β positive; the elbow-in root of
    the same point is its mirror image, β < 0 — which check_kin_transform would refuse with 571F."""
    p = Delta3Params(Rf=200.0, Lf=350.0, Rm=50.0, Lm=800.0)
    status, q = inverse_point(p, 0.0, 0.0, -50.0)
    assert status == 0
    assert rs.elbow_angle(p, q[0], -50.0) == pytest.approx(59.4016, abs=1e-4)
    # The other root of A·cos q + zb·sin q = C: q' = 2γ − q with γ = atan2(zb, A) (§12.3).
    zb = -50.0 + p.Z0
    gamma = math.atan2(zb, p.Rf - p.Rm)
    q_in = math.degrees(2 * gamma) - q[0]
    assert rs.elbow_angle(p, q_in, -50.0) == pytest.approx(-59.4016, abs=1e-4)
    monkeypatch.setattr(rs, "elbow_angle", lambda *_: -5.0)
    r = check()
    assert (r.error_id, r.restriction) == (0x571F, 2)


def test_restriction_5_cylinder_radius() -> None:
    """Restriction (5): |Rf − Rm| ≥ Kr·Lf → 571F; Rcy > Lm·cos 30° (d undefined) → 571F."""
    r = check(kp=[200.0, 350.0, 190.0, 800.0])  # |Rf − Rm| = 10 < 0.2335·350
    assert (r.error_id, r.restriction, r.parameter) == (0x571F, 5, "WorkspaceParam[1]")
    r = check(wp=[-50.0, 700.0, 250.0, 150.0, 150.0])  # 700 > 800·cos 30° = 692.8
    assert (r.error_id, r.restriction) == (0x571F, 5) and math.isnan(r.values["Kr"])
    r = check(wp=[-50.0, 692.0, 250.0, 150.0, 150.0])  # d defined, Kr = 0.995: |Rf − Rm| = 150 < 348 mm
    assert (r.error_id, r.restriction) == (0x571F, 5) and r.values["Kr"] == pytest.approx(0.995, abs=1e-3)


def test_order_of_checks() -> None:
    """D30.6: 5707 → 5708 → 5709 → 570A → 571F; the first failure is reported and no parameters come back."""
    assert check(kp=[0.0] * 4, KinType=1).error_id == 0x5707
    assert check(kp=[0.0] * 4, WorkspaceType=1).error_id == 0x5708
    assert check(wp=[1.0] * 5, WorkspaceType=1).error_id == 0x5709
    r = check(kp=[200.0, 350.0, 50.0, 500.0], wp=[1.0] * 5)
    assert r.error_id == 0x570A and r.params is None and r.workspace is None and not r.ok
