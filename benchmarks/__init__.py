"""Performance scenarios for MC Studio. Run one alone from the repository root, e.g.

    .venv/bin/python -m benchmarks kernel --axes 64 --sim-seconds 5

Each prints human-readable lines and, as its last line, one JSON object with at least `rtf`,
`us_per_axis_period` and `peak_mb`. Results are written up in docs/performance.md.
"""
