"""Performance scenarios for MC Studio. Run one alone from the repository root with the project's environment:

    .venv/bin/python -m benchmarks kernel --axes 64 --sim-seconds 5     N servo axes on the bus, fast mode
    .venv/bin/python -m benchmarks realtime --seconds 600               the demo project in realtime mode
    .venv/bin/python -m benchmarks rest --repetitions 200               FB PATCH → output visible (server process)
    .venv/bin/python -m benchmarks ws --clients 10 --rate-hz 30         WebSocket fan-out (server process)
    .venv/bin/python -m benchmarks side-by-side --axes 64               the same scenario on pyplcopen
    .venv/bin/python -m benchmarks all                                  every scenario, short (make bench)

Each prints one JSON object as its last line with at least `rtf`, `us_per_axis_period` and `peak_mb`. Results are
written up in docs/performance.md. Tests never assert on time; `tests/test_benchmarks.py` only checks that every
scenario runs and reports its figures.

Adding a scenario (the cam and robot issues do): a module here with a `run(**options) -> dict` that returns those
three keys and whatever else it measures, a sub-command in `__main__.py`, a line in `all`, a smoke test with tiny
durations, and a row in docs/performance.md. Measure wall time with `time.perf_counter()` around the simulated
periods only (not project loading), and report ratios (real-time factor, µs per axis-period) rather than raw times.
"""
