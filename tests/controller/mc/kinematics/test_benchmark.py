"""Smoke test of `benchmarks/kinematics.py` with a tiny point count: it runs and reports the keys docs/robot.md and
`make bench` rely on. Nothing here asserts on time."""

from __future__ import annotations

from benchmarks import kinematics


def test_kinematics_benchmark_reports_its_figures() -> None:
    r = kinematics.run(points=2000, repeats=1, point_calls=10)
    assert set(r) >= {"rtf", "us_per_axis_period", "peak_mb", "inverse_ms", "forward_ms"}
    assert r["rtf"] == 0.0 and r["points"] == 2000
    assert 0.3 < r["reachable_share"] <= 1.0
    assert r["max_round_trip_mm"] < 1e-6
