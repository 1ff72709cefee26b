"""Smoke test of `benchmarks/viz.py` (tiny sizes; figures are never asserted on, only their presence)."""

from __future__ import annotations

from benchmarks import viz


def test_viz_benchmark_reports_its_figures() -> None:
    r = viz.run(frames=20, seconds=0.3)
    assert {"rtf", "us_per_axis_period", "peak_mb", "frame_us_mean", "frame_us_p99", "pose_us"} <= set(r)
    assert r["frames"] == 20 and "overruns" in r["realtime_with_view"] and "frames" in r["realtime_with_view"]
