"""The drive's own profile generator (drives/profile.py): trapezoids to a position, velocity ramps, reversals."""

from __future__ import annotations

import numpy as np
import pytest

from mcstudio.drives.profile import ProfileGenerator

T = 0.001
NAN = np.array([np.nan])


def _run(g: ProfileGenerator, goal: float | None, v_goal: float, vmax: float, acc: float, dec: float,
         periods: int) -> tuple[np.ndarray, np.ndarray]:
    idx = np.array([0])
    ps, vs = [], []
    for _ in range(periods):
        g.step(idx, T, NAN if goal is None else np.array([goal]), np.array([v_goal]), np.array([vmax]),
               np.array([acc]), np.array([dec]))
        ps.append(g.pos[0])
        vs.append(g.vel[0])
    return np.array(ps), np.array(vs)


@pytest.mark.parametrize(("dist", "vmax", "acc", "dec"), [(50_000, 100_000, 1e6, 2e6), (1_000, 100_000, 1e6, 1e6),
                                                           (-30_000, 80_000, 5e5, 3e6), (7, 1e5, 1e6, 1e6)])
def test_trapezoid_lands_on_the_goal_within_the_limits(dist: float, vmax: float, acc: float, dec: float) -> None:
    g = ProfileGenerator(1)
    g.start(np.array([0]), 0.0, 0.0)
    ps, vs = _run(g, dist, 0.0, vmax, acc, dec, 3000)
    assert g.at_goal[0] and ps[-1] == dist and vs[-1] == 0.0
    assert np.max(np.abs(vs)) <= vmax
    dv = np.abs(np.diff(np.concatenate([[0.0], vs])))
    assert np.max(dv[:-1]) <= max(acc, dec) * T * (1 + 1e-9), "acceleration within the profile"
    assert dv[-1] <= 2 * dec * T, "the landing step"
    v_peak = min(vmax, np.sqrt(2 * abs(dist) * acc * dec / (acc + dec)))
    t = v_peak / acc + v_peak / dec + max(0.0, abs(dist) - v_peak**2 / (2 * acc) - v_peak**2 / (2 * dec)) / vmax
    first = int(np.flatnonzero(ps == dist)[0]) + 1
    assert first * T == pytest.approx(t, abs=3 * T)


def test_goal_too_close_at_speed_overshoots_and_returns() -> None:
    """A goal the drive cannot stop at: full deceleration past it, then back (no infinite deceleration)."""
    g = ProfileGenerator(1)
    g.start(np.array([0]), 0.0, 100_000.0)
    ps, vs = _run(g, 100.0, 0.0, 100_000, 1e6, 1e6, 1000)
    assert ps.max() > 4_000 and ps[-1] == 100.0 and vs[-1] == 0.0
    dv = np.abs(np.diff(np.concatenate([[100_000.0], vs])))
    assert np.max(dv[:-1]) <= 1e6 * T * (1 + 1e-9) and dv[-1] <= 2e6 * T


def test_velocity_goal_ramps_with_acc_and_dec() -> None:
    g = ProfileGenerator(1)
    g.start(np.array([0]), 0.0, 0.0)
    _, vs = _run(g, None, 50_000.0, np.inf, 1e6, 2e6, 100)
    assert vs[49] == pytest.approx(50_000) and vs[48] < 50_000 and g.at_goal[0]
    _, vs = _run(g, None, -50_000.0, np.inf, 1e6, 2e6, 200)
    # 50 000 → 0 at dec (25 periods), 0 → −50 000 at acc (50 periods)
    assert vs[24] == pytest.approx(0.0, abs=1e-6) and vs[74] == pytest.approx(-50_000)


def test_zero_acceleration_is_a_step() -> None:
    g = ProfileGenerator(1)
    g.start(np.array([0]), 0.0, 0.0)
    _, vs = _run(g, None, 12_345.0, np.inf, 0.0, 0.0, 1)
    assert vs[0] == 12_345.0
