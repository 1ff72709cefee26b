"""The one-point functions (plain math, for one TCP per period) give the numbers of the vectorised ones
(`omron-robot-delta3.md` §12.3–§12.6)."""

from __future__ import annotations

import math

import numpy as np

from mcstudio.controller.mc.kinematics import (
    Delta3Params,
    Delta3Workspace,
    Status,
    contains_point,
    forward,
    forward_point,
    inverse,
    inverse_point,
    joint_velocity,
    joint_velocity_point,
    signed_distance_point,
    tcp_velocity,
    tcp_velocity_point,
)


def test_inverse_and_forward_agree_with_the_vectorised_ones(robot: Delta3Params) -> None:
    """5,000 seeded random points over and beyond the reach, and 5,000 random angle triples: same status, same
    numbers to 1e-9 (θ = 37° so that no arm sits on an axis)."""
    p = Delta3Params(Rf=robot.Rf, Lf=robot.Lf, Rm=robot.Rm, Lm=robot.Lm, theta=37.0)
    rng = np.random.default_rng(42)
    pts = rng.uniform([-900.0, -900.0, -900.0], [900.0, 900.0, 700.0], (5000, 3))
    vec = inverse(p, pts)
    for k, (x, y, z) in enumerate(pts):
        st, a = inverse_point(p, float(x), float(y), float(z))
        assert st == vec.status[k]
        if st == Status.OK:
            np.testing.assert_allclose(a, vec.angles[k], atol=1e-9)
    qs = rng.uniform(-180.0, 180.0, (5000, 3))
    fv = forward(p, qs)
    for k, q in enumerate(qs):
        st, pos = forward_point(p, *map(float, q))
        assert st == fv.status[k]
        if st == Status.OK:
            np.testing.assert_allclose(pos, fv.position[k], atol=1e-9)


def test_velocities_agree(robot: Delta3Params) -> None:
    rng = np.random.default_rng(4)
    qs = inverse(robot, rng.uniform([-200.0, -200.0, -400.0], [200.0, 200.0, -100.0], (300, 3))).angles
    qd = rng.uniform(-90.0, 90.0, (300, 3))
    v, _ = tcp_velocity(robot, qs, qd)
    back, _ = joint_velocity(robot, qs, v)
    for k in range(300):
        q = (float(qs[k, 0]), float(qs[k, 1]), float(qs[k, 2]))
        st, vk = tcp_velocity_point(robot, q, (float(qd[k, 0]), float(qd[k, 1]), float(qd[k, 2])))
        assert st == Status.OK
        np.testing.assert_allclose(vk, v[k], atol=1e-9)
        st, bk = joint_velocity_point(robot, q, vk)
        assert st == Status.OK
        np.testing.assert_allclose(bk, back[k], atol=1e-8)


def test_workspace_agrees(ws: Delta3Workspace) -> None:
    rng = np.random.default_rng(8)
    pts = rng.uniform([-320.0, -320.0, -470.0], [320.0, 320.0, -30.0], (5000, 3))
    d = ws.signed_distance(pts)
    inside = ws.contains(pts)
    for k, (x, y, z) in enumerate(pts):
        assert math.isclose(signed_distance_point(ws, x, y, z), d[k], abs_tol=1e-12)
        assert contains_point(ws, x, y, z) == inside[k]


def test_bad_input_is_a_status(robot: Delta3Params) -> None:
    """NaN/inf in, a status out; singular and unsolvable poses likewise (no exceptions)."""
    assert inverse_point(robot, math.nan, 0.0, -300.0)[0] == Status.NOT_FINITE
    assert inverse_point(robot, 0.0, 0.0, -600.0)[0] == Status.UNREACHABLE
    assert inverse_point(robot, 0.0, 0.0, 700.0)[0] == Status.UNREACHABLE  # above the motor plane
    assert inverse_point(robot, 1e308, 1e308, -1e308)[0] == Status.UNREACHABLE
    assert forward_point(robot, math.inf, 0.0, 0.0)[0] == Status.NOT_FINITE
    assert forward_point(robot, 0.0, 0.0, 180.0)[0] == Status.UNREACHABLE
    assert tcp_velocity_point(robot, (0.0, 0.0, 0.0), (math.nan, 0.0, 0.0))[0] == Status.NOT_FINITE
    assert tcp_velocity_point(robot, (0.0, 0.0, 180.0), (1.0, 0.0, 0.0))[0] == Status.UNREACHABLE
    assert joint_velocity_point(robot, (0.0, 0.0, 0.0), (math.inf, 0.0, 0.0))[0] == Status.NOT_FINITE
    q = math.degrees(math.atan2(math.sqrt((robot.Lf + robot.Lm) ** 2 - (robot.Rf - robot.Rm) ** 2),
                                robot.Rm - robot.Rf))
    assert joint_velocity_point(robot, (q, q, q), (1.0, 0.0, 0.0))[0] == Status.SINGULAR
    bad = Delta3Params(Rf=200.0, Lf=350.0, Rm=50.0, Lm=100.0)  # no zero pose: Z0 NaN
    assert inverse_point(bad, 0.0, 0.0, -300.0)[0] == Status.UNREACHABLE
    assert forward_point(bad, 0.0, 0.0, 0.0)[0] == Status.UNREACHABLE
