"""The cams benchmark runs (tiny sizes) and returns the keys `make bench` and docs/performance.md rely on; no
timing is asserted (figures are measured, not tested)."""

from __future__ import annotations

from benchmarks import cams


def test_cams_scenario() -> None:
    r = cams.run(points=2001, axes=8, tables=2, periods=5, repeat=1)
    assert set(r) >= {"rtf", "us_per_axis_period", "peak_mb", "generate_ms"}
    assert r["rtf"] == 0.0 and r["generate"]["modified_sine"]["points"] == 2001
    assert r["generate"]["all_curves"]["points"] == 2001
