"""Exact sensor edges on a period's path (drives/sensing.py): zone ON/OFF edges, Z pulses, boundaries."""

from __future__ import annotations

import numpy as np
import pytest

from mcstudio.drives.sensing import DigitalInputs, SensorLayout, digital_inputs, z_edge, zone_off_edge, zone_on_edge

LO, HI = 100.0, 200.0


@pytest.mark.parametrize(("p0", "p1", "on", "off"), [
    (0, 150, LO, None), (0, 300, LO, HI), (150, 300, None, HI), (300, 150, HI, None), (300, 0, HI, LO),
    (150, 0, None, LO), (LO, 300, None, HI), (HI, 300, None, HI), (HI, 0, None, LO), (LO, 0, None, LO),
    (0, LO, LO, None), (300, HI, HI, None), (120, 180, None, None), (0, 50, None, None), (150, 150, None, None),
])
def test_zone_edges(p0: float, p1: float, on: float | None, off: float | None) -> None:
    """A zone is ON for lo ≤ p ≤ hi: starting on its boundary is inside (no ON edge), leaving it is the OFF edge."""
    a, b = np.array([p0], float), np.array([p1], float)
    lo, hi = np.array([LO]), np.array([HI])
    e_on, e_off = zone_on_edge(a, b, lo, hi)[0], zone_off_edge(a, b, lo, hi)[0]
    assert (np.isnan(e_on) if on is None else e_on == on) and (np.isnan(e_off) if off is None else e_off == off)


def test_unfitted_zone_has_no_edges() -> None:
    a, b, nan = np.array([0.0]), np.array([1e9]), np.array([np.nan])
    assert np.isnan(zone_on_edge(a, b, nan, nan)[0]) and np.isnan(zone_off_edge(a, b, nan, nan)[0])


@pytest.mark.parametrize(("p0", "p1", "z"), [(0, 500, 50), (50, 500, 450), (49, 50, 50), (500, 0, 450),
                                             (450, 0, 50), (60, 440, None), (500, 500, None)])
def test_z_pulse_edges(p0: float, p1: float, z: float | None) -> None:
    """Z pulses at 50 + k·400: the first one strictly after the start of the path."""
    e = z_edge(np.array([p0], float), np.array([p1], float), np.array([50.0]), np.array([400.0]))[0]
    assert np.isnan(e) if z is None else e == z
    assert np.isnan(z_edge(np.array([0.0]), np.array([1e9]), np.array([0.0]), np.array([np.inf]))[0])


def test_planned_digital_inputs_equal_the_full_computation() -> None:
    rng = np.random.default_rng(3)
    s = SensorLayout(50)
    s.pos_limit[:25] = rng.uniform(0, 100, 25)
    s.neg_limit[10:30] = rng.uniform(-100, 0, 20)
    s.prox[5:40] = np.sort(rng.uniform(-50, 50, (35, 2)), axis=1)
    s.ext2[::3] = np.sort(rng.uniform(-50, 50, (17, 2)), axis=1)
    di = DigitalInputs(s)
    for _ in range(20):
        p = rng.uniform(-120, 120, 50)
        assert np.array_equal(di(p), digital_inputs(p, s))


def test_cached_intervals_follow_moving_positions_exactly() -> None:
    """The inputs are recomputed only for devices that left the interval between their sensor edges; along random
    walks with small steps, jumps and positions exactly on edges they equal the full computation every period."""
    rng = np.random.default_rng(11)
    s = SensorLayout(40)
    s.pos_limit[:30] = rng.uniform(20, 60, 30)
    s.neg_limit[5:35] = rng.uniform(-60, -20, 30)
    s.prox[::2] = np.sort(rng.uniform(-30, 30, (20, 2)), axis=1)
    s.ext1[1::4] = np.sort(rng.uniform(-30, 30, (10, 2)), axis=1)
    di = DigitalInputs(s)
    p = rng.uniform(-70, 70, 40)
    changes = 0
    for k in range(3000):
        p = p + rng.normal(0.0, 0.8, 40)
        if k % 97 == 0:
            p[rng.integers(0, 40)] = rng.uniform(-80, 80)
        if k % 131 == 0:  # exactly on an edge, and back off it
            p[0] = s.pos_limit[0]
            p[2] = s.prox[2, 0]
        before = di._di.copy()
        got = di(p).copy()
        assert np.array_equal(got, digital_inputs(p, s)), k
        assert di.changed or np.array_equal(before, got), f"{k}: inputs changed without `changed`"
        changes += int(di.changed)
    assert changes > 50, "the walk really crossed sensors"
