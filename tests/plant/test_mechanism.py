"""The mechanism behind the drives (`plant/mechanism.py`): the ideal follower unchanged, the second-order position
loop (step overshoot, ramp following error, feed-forward), torque limits, the CSV velocity loop, validation."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mcstudio.plant.ideal import Mechanics, validate_mechanics, wrap32
from mcstudio.plant.mechanism import KIND_HOLD, KIND_POSITION, KIND_TORQUE, KIND_VELOCITY, Mechanism, transition_matrix
from tests.plant.reference_ideal import IdealPlant

T = 0.001


def _mech(n: int, **values: object) -> Mechanics:
    m = Mechanics(n)
    for name, v in values.items():
        getattr(m, name)[:] = v
    return m


def _expm(a: np.ndarray) -> np.ndarray:
    """exp(a) by scaling and squaring with a Taylor series (reference for the closed form)."""
    s = 8
    b = a / 2**s
    out = np.eye(2)
    term = np.eye(2)
    for k in range(1, 30):
        term = term @ b / k
        out = out + term
    for _ in range(s):
        out = out @ out
    return out


@pytest.mark.parametrize("zeta", [0.05, 0.3, 0.7, 1.0, 1.0 + 1e-12, 2.0, 5.0])
def test_transition_matrix_is_the_matrix_exponential(zeta: float) -> None:
    wn = 2 * math.pi * 50.0
    phi = transition_matrix(np.array([wn]), np.array([zeta]), T)[:, 0]
    ref = _expm(np.array([[0.0, 1.0], [-wn * wn, -2 * zeta * wn]]) * T)
    assert phi == pytest.approx(ref.ravel(), rel=1e-9, abs=1e-12)


def _run(m: Mechanism, refs: np.ndarray, t_hi: np.ndarray | None = None, t_lo: np.ndarray | None = None,
         ) -> tuple[np.ndarray, np.ndarray]:
    """Position references per period (rows) → continuous positions and velocities after each period."""
    pos = np.zeros(m.n, dtype=np.int64)
    xs, vs = [], []
    for r in refs:
        m.advance(pos, KIND_POSITION, np.asarray(r, dtype=float), t_hi=t_hi, t_lo=t_lo)
        xs.append(pos + m.frac)
        vs.append(m.velocity.copy())
    return np.array(xs), np.array(vs)


def test_step_response_overshoot() -> None:
    """A step of the reference (interpolated over one period): peak overshoot ≈ exp(−ζπ/√(1 − ζ²))."""
    zetas = np.array([0.2, 0.5, 0.7])
    m = Mechanism(3, _mech(3, model=1, bandwidth_hz=10.0, damping=zetas))
    xs, _ = _run(m, np.full((1000, 3), 1000.0))
    overshoot = xs.max(axis=0) / 1000.0 - 1.0
    expect = np.exp(-zetas * np.pi / np.sqrt(1 - zetas**2))
    assert overshoot == pytest.approx(expect, abs=0.003)
    assert xs[-1] == pytest.approx(1000.0, abs=0.5), "settles on the reference"
    # peak time ≈ π/(ωn√(1 − ζ²)) (+ half a period for the interpolated step)
    peak_t = (xs.argmax(axis=0) + 1) * T
    assert peak_t == pytest.approx(np.pi / (2 * np.pi * 10.0 * np.sqrt(1 - zetas**2)) + T / 2, abs=1.5 * T)


@pytest.mark.parametrize(("ff", "factor"), [(0.0, 1.0), (0.5, 0.5), (1.0, 0.0)])
def test_ramp_following_error(ff: float, factor: float) -> None:
    """A constant-velocity reference: steady-state following error 2ζ(1 − kff)·v/ωn (2ζ·v/ωn without
    feed-forward, 0 with 100 %)."""
    zeta, fn, v = 0.7, 50.0, 100_000.0  # pulse/s
    m = Mechanism(1, _mech(1, model=1, bandwidth_hz=fn, damping=zeta, feedforward=ff))
    k = np.arange(1, 501)[:, None]
    xs, vs = _run(m, k * v * T)
    err = k[-1, 0] * v * T - xs[-1, 0]
    assert err == pytest.approx(factor * 2 * zeta * v / (2 * math.pi * fn), abs=1e-6)
    assert vs[-1, 0] == pytest.approx(v, rel=1e-9)


def test_torque_limit_saturates_and_integrates_the_rigid_body() -> None:
    """When the loop asks for more than the limit, the period is integrated with the limited torque: Δω per period
    = T_lim/J, the drive lags behind the unlimited one, `limited` is set."""
    m = Mechanism(2, _mech(2, model=1, viscous=0.0))
    hi = np.array([3000.0, 100.0])
    xs, vs = _run(m, np.arange(1, 51)[:, None] * np.array([[100.0, 100.0]]), t_hi=hi, t_lo=-hi)
    assert not m.limited[0] and m.limited[1]
    assert m.torque[1] == pytest.approx(100.0)
    rad = 2 * math.pi / 8192
    assert (vs[-1, 1] - vs[-2, 1]) * rad / T == pytest.approx(0.1 * 1.27 / 2.7e-4, rel=1e-9)
    assert xs[-1, 1] < xs[-1, 0] - 1000


def test_second_order_velocity_loop() -> None:
    m = Mechanism(1, _mech(1, model=1, bandwidth_hz=5.0))
    pos = np.zeros(1, dtype=np.int64)
    for _ in range(100):
        m.advance(pos, KIND_VELOCITY, velocity_cmd=np.array([10_000.0]))
    wn = 2 * math.pi * 5.0
    assert m.velocity[0] == pytest.approx(10_000 * (1 - math.exp(-wn * 0.1)), rel=1e-12)
    x = pos[0] + m.frac[0]
    expect = 10_000 * (0.1 - (1 - math.exp(-wn * 0.1)) / wn)
    assert x == pytest.approx(expect, rel=1e-9)


def test_position_changed_from_outside_is_taken_as_it_is() -> None:
    """A mechanical stop emulated by clamping `position` after `advance` (tests do it): the next period starts
    from the clamped position."""
    m = Mechanism(1, _mech(1, model=1))
    pos = np.zeros(1, dtype=np.int64)
    m.advance(pos, KIND_POSITION, np.array([1000.0]))
    pos[0] = 0
    m.advance(pos, KIND_POSITION, np.array([1000.0]))
    assert 0 < pos[0] < 500


def test_hold_stops_the_shaft() -> None:
    m = Mechanism(1, _mech(1, model=1))
    pos = np.zeros(1, dtype=np.int64)
    for _ in range(5):
        m.advance(pos, KIND_POSITION, np.array([5000.0]))
    p = int(pos[0])
    m.advance(pos, KIND_HOLD)
    assert pos[0] == p and m.velocity[0] == 0.0 and m.torque[0] == 0.0 and m.frac[0] == 0.0


# ------------------------------------------------------------------------------------------------ ideal: unchanged
def test_ideal_model_reproduces_the_first_version_bit_for_bit() -> None:
    """Random CSP targets and CST torques, mixed per drive and period, through the previous IdealPlant and the
    Mechanism (model 0): positions, velocities, torques, fractions and limit flags are identical."""
    rng = np.random.default_rng(7)
    n = 6
    mech = _mech(n, viscous=rng.uniform(0, 1e-3, n), load=rng.uniform(-0.2, 0.2, n), inertia=rng.uniform(1e-4, 1e-3, n))
    old, new = IdealPlant(n, mech, T), Mechanism(n, mech, T)
    pa = rng.integers(-(2**40), 2**40, n)
    pb = pa.copy()
    target = wrap32(pa).astype(np.int64)
    for k in range(600):
        enabled = rng.random(n) < 0.9
        cst = enabled & (rng.random(n) < (0.5 if k > 200 else 0.0)) if k % 50 < 40 else np.zeros(n, dtype=bool)
        target = target + rng.integers(-3000, 3000, n)
        t32 = wrap32(target)
        trq = rng.uniform(-2000, 2000, n)
        t_max, t_min, vlim = rng.uniform(0, 3000, n), -rng.uniform(0, 3000, n), rng.uniform(0, 2e6, n)
        # previous version
        if cst.any():
            idx = np.flatnonzero(cst)
            old.advance(pa, t32, enabled, cst)
            old.advance_torque(idx, pa, trq[idx], t_max[idx], t_min[idx], vlim[idx])
        else:
            old.advance(pa, t32, enabled)
        # mechanism: CSP reference unwrapped around the position as the first version did
        demand = pb + ((t32.astype(np.int64) - wrap32(pb).astype(np.int64) + 2**31) % 2**32 - 2**31)
        kind = np.where(cst, KIND_TORQUE, np.where(enabled, KIND_POSITION, KIND_HOLD)).astype(np.int8)
        if (kind == KIND_POSITION).all():
            new.advance(pb, KIND_POSITION, demand)
        else:
            new.advance(pb, kind, demand.astype(float), torque_cmd=trq, t_hi=t_max, t_lo=t_min, v_limit=vlim)
        assert np.array_equal(pa, pb), k
        assert np.array_equal(old.velocity, new.velocity), k
        assert np.array_equal(old.torque, new.torque), k
        assert np.array_equal(old.frac, new.frac) and np.array_equal(old.limited, new.limited), k


def test_ideal_position_ignores_torque_limits() -> None:
    m = Mechanism(1)
    pos = np.zeros(1, dtype=np.int64)
    m.advance(pos, np.array([KIND_POSITION], dtype=np.int8), np.array([1e6]), t_hi=np.array([1.0]),
              t_lo=np.array([-1.0]))
    assert pos[0] == 1_000_000 and not m.limited[0] and m.torque[0] > 1.0


# ------------------------------------------------------------------------------------------------ validation
def test_validate_mechanics_rejects_degenerate_second_order_values() -> None:
    m = _mech(7, model=1)
    m.bandwidth_hz[:] = [0.0, 251.0, 50, 50, 50, 50, 50]
    m.damping[:] = [0.7, 0.7, 0.01, 6.0, 0.7, 0.7, 0.7]
    m.feedforward[:] = [0, 0, 0, 0, -0.1, 1.1, 0.0]
    problems = validate_mechanics(m, 0.001)
    assert [p.split(":")[0] for p in problems] == [f"drive {i}" for i in range(6)]
    assert "bandwidth_hz" in problems[1] and "250" in problems[1]
    with pytest.raises(ValueError, match="invalid mechanics"):
        Mechanism(7, m, 0.001)
    m.model[:] = 0
    assert validate_mechanics(m, 0.001) == [], "ideal drives do not use the loop parameters"
    m.inertia[0] = 0.0
    assert len(validate_mechanics(m, 0.001)) == 1
    assert validate_mechanics(_mech(1, model=1, bandwidth_hz=250.0), 0.001) == []
