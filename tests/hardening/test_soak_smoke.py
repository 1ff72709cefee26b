"""The soak benchmark (benchmarks/soak.py) runs and reports its figures — a few seconds here; the hour-long run is
`python -m benchmarks soak --minutes 60` (docs/hardening.md). Nothing is asserted on time."""

from __future__ import annotations

from benchmarks import soak


def test_soak_runs_briefly_without_errors() -> None:
    r = soak.run(minutes=0.05, seed=3)
    assert {"rtf", "us_per_axis_period", "peak_mb", "rss_mb", "events_total", "commands"} <= set(r)
    assert r["commands"] > 0 and r["cycles"] > 0 and len(r["rss_mb"]) >= 2
    assert r["http_5xx"] == 0 and r["exceptions"] == 0, r["exception_samples"]
    assert r["kernel_paused"] == 0 and r["major_faults"] == 0 and r["contained_faults"] == 0
    assert r["event_log_len"] <= 10_000
