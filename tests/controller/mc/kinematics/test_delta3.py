"""Delta3 inverse/forward kinematics, arm geometry and velocities (`omron-robot-delta3.md` §12; D30.1–D30.5)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mcstudio.controller.mc.kinematics import (
    Delta3Params,
    Delta3Workspace,
    Status,
    WorkspaceCheck,
    arm_geometry,
    forward,
    inverse,
    jacobian,
    joint_velocity,
    tcp_velocity,
)

# §12.9 table: MCS point → (A0, A1, A2). First the values as printed (5 decimals), then the same rows as the §12.9
# reference script (`python3 delta3.py`, Delta3.ik) prints them with repr() — the 1e-6 comparison is against those.
TABLE = [
    ((0.0, 0.0, 0.0), (0.00000, 0.00000, 0.00000)),
    ((0.0, 0.0, -300.0), (42.49016, 42.49016, 42.49016)),
    ((150.0, 0.0, -300.0), (31.40296, 51.09611, 51.09611)),
    ((0.0, 150.0, -300.0), (44.87535, 33.26724, 55.37157)),
    ((-120.0, -80.0, -400.0), (70.29118, 61.64901, 49.58526)),
    ((100.0, 100.0, -150.0), (13.74845, 20.32416, 36.97728)),
    ((200.0, -100.0, -350.0), (37.67833, 70.02607, 56.86106)),
    ((0.0, 0.0, -450.0), (68.22783, 68.22783, 68.22783)),
]
REFERENCE_FULL = [
    (0.0, 0.0, 0.0),
    (42.49016234459934, 42.49016234459934, 42.49016234459934),
    (31.402963468372445, 51.09611332512017, 51.09611332512017),
    (44.875351319022585, 33.267241598706924, 55.371569766967134),
    (70.29117826108882, 61.649012848221005, 49.58525790630961),
    (13.748451125778919, 20.32416068326021, 36.97728323368554),
    (37.67833244996375, 70.02606790450244, 56.86105754335513),
    (68.22783108527767, 68.22783108527767, 68.22783108527767),
]
POINTS = np.array([p for p, _ in TABLE])


def test_zero_pose_height(robot: Delta3Params) -> None:
    """§12.2: Z0 = −√(Lm² − (Rf − Rm + Lf)²) = −624.4998 mm for the example robot (D30.2)."""
    assert abs(robot.Z0 - -624.4997998398399) < 1e-9
    assert robot.motor_plane_z == pytest.approx(624.4997998398399, abs=1e-9)


def test_reference_table_inverse(robot: Delta3Params) -> None:
    """§12.9 table, MCS → ACS: to 1e-6 deg against the reference script, to its printed rounding (5e-6) against
    the table itself."""
    r = inverse(robot, POINTS)
    assert r.ok and r.angles.shape == (8, 3)
    np.testing.assert_allclose(r.angles, REFERENCE_FULL, rtol=0, atol=1e-6)
    np.testing.assert_allclose(r.angles, [a for _, a in TABLE], rtol=0, atol=5e-6 + 1e-12)
    assert np.all(r.error_id == 0)


def test_reference_table_forward(robot: Delta3Params) -> None:
    """§12.9 table, ACS → MCS: the lower sphere intersection gives each point back to 1e-6 mm (the table's last
    column shows ≤ 2.3e-13)."""
    f = forward(robot, REFERENCE_FULL)
    assert f.ok
    np.testing.assert_allclose(f.position, POINTS, rtol=0, atol=1e-6)
    # The printed 5-decimal angles are within 5e-6°; an arm of ~1 m turns that into < 1e-4 mm.
    np.testing.assert_allclose(forward(robot, [a for _, a in TABLE]).position, POINTS, rtol=0, atol=2e-4)


def test_unreachable_point_of_the_table(robot: Delta3Params) -> None:
    """§12.9: "(0, 0, −600) is unreachable for this robot (arms would have to exceed full stretch)" → 570F."""
    r = inverse(robot, [0.0, 0.0, -600.0])
    assert r.status == Status.UNREACHABLE and r.error_id == 0x570F and np.all(np.isnan(r.angles))
    assert not r.reachable


def test_random_workspace_points_round_trip(robot: Delta3Params, ws: Delta3Workspace) -> None:
    """Seeded random points of the workspace: FK(IK(p)) = p to 1e-9 mm and IK(FK(q)) = q to 1e-9 deg (D30.3)."""
    rng = np.random.default_rng(20240607)
    n = 200_000
    r_max = ws.Rcy
    pts = np.column_stack([rng.uniform(-r_max, r_max, n), rng.uniform(-r_max, r_max, n),
                           rng.uniform(ws.z_bottom, ws.Zu, n)])
    pts = pts[ws.contains(pts)]
    assert len(pts) > 50_000
    ik = inverse(robot, pts, workspace=ws, check=WorkspaceCheck.TARGET_AT_START)
    assert ik.ok, "every point of this workspace is reachable by the example robot"
    fk = forward(robot, ik.angles)
    assert fk.ok
    assert np.max(np.abs(fk.position - pts)) < 1e-9
    assert np.max(np.abs(inverse(robot, fk.position).angles - ik.angles)) < 1e-9


def test_random_reachable_points_round_trip_beyond_the_workspace(robot: Delta3Params) -> None:
    """Every point the inverse accepts, anywhere, comes back through the forward kinematics (D30.3)."""
    rng = np.random.default_rng(7)
    pts = rng.uniform([-900.0, -900.0, -900.0], [900.0, 900.0, 700.0], (200_000, 3))
    ik = inverse(robot, pts)
    ok = ik.status == Status.OK
    assert 0.2 < ok.mean() < 0.9
    fk = forward(robot, ik.angles[ok])
    assert fk.ok
    assert np.max(np.abs(fk.position - pts[ok])) < 1e-6  # worst case sits at the edge of reach (D → 0)
    assert np.all(np.isnan(ik.angles[~ok]))


def test_points_off_the_branch_are_unreachable(robot: Delta3Params) -> None:
    """Points at/above the motor plane, and points whose elbow-out angles would put the TCP above the plane of
    the sphere centres, are unreachable (D30.3): forward() of any angles is never one of them."""
    above = inverse(robot, [[0.0, 0.0, robot.motor_plane_z], [0.0, 0.0, robot.motor_plane_z + 10.0]])
    assert np.all(above.status == Status.UNREACHABLE)
    rng = np.random.default_rng(11)
    q = rng.uniform(-180.0, 180.0, (100_000, 3))
    fk = forward(robot, q)
    ik = inverse(robot, fk.position[fk.status == Status.OK])
    ok = ik.status == Status.OK
    # What the inverse accepts it reproduces; what it refuses is a pose the elbow-out branch does not take.
    assert np.max(np.abs(forward(robot, ik.angles[ok]).position - fk.position[fk.status == Status.OK][ok])) < 1e-6


def test_theta_rotates_the_arm_layout(robot: Delta3Params) -> None:
    """§12.9: with θ = 30° the point (150, 0, −300) gives the cyclic permutation (A1, A2, A0) of the θ = 0 row of
    (0, 150, −300) (D30.1: θ adds to every arm azimuth)."""
    r30 = Delta3Params(Rf=200.0, Lf=350.0, Rm=50.0, Lm=800.0, theta=30.0)
    a = inverse(r30, [150.0, 0.0, -300.0]).angles
    np.testing.assert_allclose(a, [33.26724, 55.37157, 44.87535], atol=5e-6)
    b = inverse(robot, [0.0, 150.0, -300.0]).angles
    np.testing.assert_allclose(a, [b[1], b[2], b[0]], atol=1e-9)
    # θ = 360 is θ = 0.
    r360 = Delta3Params(Rf=200.0, Lf=350.0, Rm=50.0, Lm=800.0, theta=360.0)
    np.testing.assert_allclose(inverse(r360, POINTS).angles, REFERENCE_FULL, atol=1e-9)


def test_positive_angle_moves_the_arm_down(robot: Delta3Params) -> None:
    """§2.2: positive = link 1 swings downward; all arms equal → the TCP moves straight down the Z axis."""
    p = forward(robot, [[10.0, 10.0, 10.0], [20.0, 20.0, 20.0]]).position
    assert p[0, 2] < 0.0 and p[1, 2] < p[0, 2]
    np.testing.assert_allclose(p[:, :2], 0.0, atol=1e-9)
    g = arm_geometry(robot, [30.0, 0.0, 0.0])
    assert g.elbows[0, 2] < g.shoulders[0, 2]  # A0's elbow below its motor


def test_manual_group_mon_example_is_reachable() -> None:
    """§9.3 / §12.9: Rf 200, Rm 50, Lf 320, Lm 850, target [50, 50, −350] is reachable with the zero-pose origin
    (A ≈ 54.25024, 56.9575, 64.03726) — the reason for D30.2."""
    r = Delta3Params(Rf=200.0, Lf=320.0, Rm=50.0, Lm=850.0)
    assert abs(r.Z0 - -708.237) < 1e-3
    ik = inverse(r, [50.0, 50.0, -350.0])
    assert ik.ok
    np.testing.assert_allclose(ik.angles, [54.25024, 56.9575, 64.03726], atol=5e-6)
    np.testing.assert_allclose(forward(r, ik.angles).position, [50.0, 50.0, -350.0], atol=1e-9)


def test_angles_are_wrapped_to_the_acs_range(robot: Delta3Params) -> None:
    """§2.2: travel −180…180°; the inverse returns [−180°, 180°), and forward accepts any angle (periodic)."""
    rng = np.random.default_rng(3)
    pts = rng.uniform([-900.0, -900.0, -1500.0], [900.0, 900.0, 600.0], (100_000, 3))
    a = inverse(robot, pts).angles
    finite = a[np.isfinite(a)]
    assert finite.size and np.all((finite >= -180.0) & (finite < 180.0))
    np.testing.assert_allclose(forward(robot, np.array(REFERENCE_FULL) + 360.0).position, POINTS, atol=1e-9)


def test_inverse_status_order(robot: Delta3Params, ws: Delta3Workspace) -> None:
    """D30.5: non-finite → 570F; outside the workspace → the check's code (angles still given if reachable);
    unreachable → 570F; without a check, outside is reported but no error (MC_InverseKin's OutWorkspace)."""
    pts = [[0.0, 0.0, -300.0], [0.0, 0.0, -20.0], [0.0, 0.0, -600.0], [np.nan, 0.0, -300.0], [0.0, np.inf, -300.0],
           [0.0, 0.0, -700.0]]
    r = inverse(robot, pts, workspace=ws, check=WorkspaceCheck.COMMAND_EVERY_PERIOD)
    assert r.status.tolist() == [Status.OK, Status.OUTSIDE_WORKSPACE, Status.OUTSIDE_WORKSPACE, Status.NOT_FINITE,
                                 Status.NOT_FINITE, Status.OUTSIDE_WORKSPACE]
    assert r.error_id.tolist() == [0, 0x6700, 0x6700, 0x570F, 0x570F, 0x6700]
    assert r.reachable.tolist() == [True, True, False, False, False, False]
    assert r.inside.tolist() == [True, False, False, False, False, False]
    assert np.all(np.isfinite(r.angles[1])), "a reachable point outside the workspace still has its angles"
    kin = inverse(robot, pts, workspace=ws)
    assert kin.error_id.tolist() == [0, 0, 0, 0x570F, 0x570F, 0]
    assert kin.status[1] == Status.OUTSIDE_WORKSPACE
    no_ws = inverse(robot, pts)
    assert no_ws.status.tolist()[:3] == [Status.OK, Status.OK, Status.UNREACHABLE]


def test_degenerate_inputs_are_statuses_not_exceptions(robot: Delta3Params) -> None:
    """NaN, ±inf and huge values in positions or angles give a status (never an exception or a warning)."""
    with np.errstate(all="raise"):
        r = inverse(robot, [[np.nan] * 3, [np.inf, -np.inf, 0.0], [1e308, 1e308, -1e308], [0.0, 0.0, -1e300]])
        assert r.status.tolist() == [Status.NOT_FINITE, Status.NOT_FINITE, Status.UNREACHABLE, Status.UNREACHABLE]
        f = forward(robot, [[np.nan, 0.0, 0.0], [np.inf, 0.0, 0.0], [1e300, 0.0, 0.0]])
        assert f.status.tolist()[:2] == [Status.NOT_FINITE, Status.NOT_FINITE]
        assert f.error_id.tolist()[:2] == [0x570F, 0x570F]
        assert np.all(np.isnan(f.position[:2]))
    # Parameters without a zero pose (Z0 is NaN): everything unreachable, still no exception.
    bad = Delta3Params(Rf=200.0, Lf=350.0, Rm=50.0, Lm=100.0)
    assert math.isnan(bad.Z0)
    assert np.all(inverse(bad, POINTS).status == Status.UNREACHABLE)
    assert np.all(forward(bad, REFERENCE_FULL).status == Status.UNREACHABLE)
    # Shapes: a single point gives 0-d statuses, an empty batch empty arrays.
    assert inverse(robot, [0.0, 0.0, -300.0]).status.shape == ()
    assert inverse(robot, np.empty((0, 3))).angles.shape == (0, 3)
    assert forward(robot, np.zeros((2, 4, 3))).position.shape == (2, 4, 3)


def test_forward_without_solution(robot: Delta3Params) -> None:
    """§12.4: spheres without a common point (Z² < 0) have no TCP → 570F: one arm folded up-inward (180°) while the
    other two stretch outward (0°)."""
    f = forward(robot, [[0.0, 0.0, 180.0], [180.0, 0.0, 0.0], [0.0, 0.0, 0.0]])
    assert f.status.tolist() == [Status.UNREACHABLE, Status.UNREACHABLE, Status.OK]
    assert f.error_id.tolist() == [0x570F, 0x570F, 0]
    assert np.all(np.isnan(f.position[:2]))


def test_arm_geometry_has_the_link_lengths(robot: Delta3Params) -> None:
    """§12.2/§12.8: |M − E| = Lf, |E − W| = Lm, |W − TCP| = Rm, shoulders on the motor plane at radius Rf, and
    the two rods of each parallelogram are parallel, of length Lm, `rod_spacing` apart."""
    ik = inverse(robot, POINTS)
    g = arm_geometry(robot, ik.angles, rod_spacing=60.0)
    assert g.shoulders.shape == g.elbows.shape == g.wrists.shape == (8, 3, 3)
    assert g.rods.shape == (8, 3, 2, 2, 3)
    np.testing.assert_allclose(np.linalg.norm(g.elbows - g.shoulders, axis=-1), robot.Lf, atol=1e-9)
    np.testing.assert_allclose(np.linalg.norm(g.wrists - g.elbows, axis=-1), robot.Lm, atol=1e-9)
    np.testing.assert_allclose(np.linalg.norm(g.wrists - g.tcp[:, None, :], axis=-1), robot.Rm, atol=1e-9)
    np.testing.assert_allclose(g.shoulders[..., 2], robot.motor_plane_z, atol=1e-9)
    np.testing.assert_allclose(np.hypot(g.shoulders[..., 0], g.shoulders[..., 1]), robot.Rf, atol=1e-9)
    np.testing.assert_allclose(g.tcp, POINTS, atol=1e-9)
    rod_len = np.linalg.norm(g.rods[..., 1, :] - g.rods[..., 0, :], axis=-1)
    np.testing.assert_allclose(rod_len, robot.Lm, atol=1e-9)
    np.testing.assert_allclose(np.linalg.norm(g.rods[..., 0, 0, :] - g.rods[..., 1, 0, :], axis=-1), 60.0, atol=1e-9)
    # A0 sits on +Xm at θ = 0 (D30.1); A1 at 120°.
    np.testing.assert_allclose(g.shoulders[0, 0, :2], [200.0, 0.0], atol=1e-9)
    np.testing.assert_allclose(g.shoulders[0, 1, :2], [200.0 * math.cos(math.radians(120)),
                                                       200.0 * math.sin(math.radians(120))], atol=1e-9)
    # Angles without a TCP: arms still drawn, TCP NaN.
    bad = arm_geometry(robot, [np.nan, 0.0, 0.0])
    assert bad.status == Status.NOT_FINITE and np.all(np.isnan(bad.tcp)) and np.all(np.isfinite(bad.elbows[1:]))


def test_tcp_velocity_matches_the_reference_and_finite_differences(robot: Delta3Params) -> None:
    """§12.5/§12.9: at (−120, −80, −400) with q̇ = (10, −25, 40) deg/s the TCP moves at (−36.797425, 432.426961,
    −81.939482) mm/s, |v| = 441.6573; the Jacobian agrees with central differences of the forward kinematics."""
    q = inverse(robot, [-120.0, -80.0, -400.0]).angles
    v, st = tcp_velocity(robot, q, [10.0, -25.0, 40.0])
    assert st == Status.OK
    np.testing.assert_allclose(v, [-36.797425019102846, 432.42696086804864, -81.93948154711255], atol=1e-6)
    assert np.linalg.norm(v) == pytest.approx(441.6573, abs=1e-4)
    rng = np.random.default_rng(5)
    pts = rng.uniform([-200.0, -200.0, -400.0], [200.0, 200.0, -100.0], (500, 3))
    qs = inverse(robot, pts).angles
    qd = rng.uniform(-50.0, 50.0, (500, 3))
    J, st = jacobian(robot, qs)
    assert np.all(st == Status.OK)
    h = 1e-6
    fd = (forward(robot, qs + qd * h).position - forward(robot, qs - qd * h).position) / (2 * h)
    np.testing.assert_allclose(np.einsum("nij,nj->ni", J, qd), fd, atol=1e-5)


def test_joint_velocity_inverts_tcp_velocity(robot: Delta3Params) -> None:
    """§12.5: q̇ᵢ = (p − Sᵢ)·ṗ / Jq,i is the inverse of the Jacobian (for the 6705 axis-speed check)."""
    rng = np.random.default_rng(9)
    qs = inverse(robot, rng.uniform([-200.0, -200.0, -400.0], [200.0, 200.0, -100.0], (1000, 3))).angles
    qd = rng.uniform(-100.0, 100.0, (1000, 3))
    v, _ = tcp_velocity(robot, qs, qd)
    back, st = joint_velocity(robot, qs, v)
    assert np.all(st == Status.OK)
    np.testing.assert_allclose(back, qd, atol=1e-8)
    # Non-finite velocities or angles: a status, NaN values.
    v2, st2 = tcp_velocity(robot, [[0.0, 0.0, 0.0], [np.nan, 0.0, 0.0]], [[np.inf, 0.0, 0.0], [1.0, 1.0, 1.0]])
    assert st2.tolist() == [Status.NOT_FINITE, Status.NOT_FINITE] and np.all(np.isnan(v2))
    q3, st3 = joint_velocity(robot, [0.0, 0.0, 0.0], [np.nan, 0.0, 0.0])
    assert st3 == Status.NOT_FINITE and np.all(np.isnan(q3))


def test_stretched_arms_are_singular(robot: Delta3Params) -> None:
    """§12.5: with every arm stretched (forearm in line with the upper arm, TCP on the Z axis at
    zb = −√((Lf + Lm)² − (Rf − Rm)²)) no arm can move the TCP: Jq = 0, so the TCP velocity is 0 for any axis
    velocity and the axis velocity for a TCP velocity does not exist (status SINGULAR, NaN)."""
    q = math.degrees(math.atan2(math.sqrt((robot.Lf + robot.Lm) ** 2 - (robot.Rf - robot.Rm) ** 2),
                                robot.Rm - robot.Rf))
    v, st = tcp_velocity(robot, [q, q, q], [10.0, 20.0, 30.0])
    assert st == Status.OK
    np.testing.assert_allclose(v, 0.0, atol=1e-9)
    qd, st = joint_velocity(robot, [q, q, q], [1.0, 0.0, 0.0])
    assert st == Status.SINGULAR and np.all(np.isnan(qd))
