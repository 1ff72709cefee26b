"""Benchmark entry point: `python -m benchmarks <scenario> [options]` (see benchmarks/__init__.py)."""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]


def _child(args: list[str]) -> dict[str, Any]:
    """Run one scenario in its own process (its own peak memory) and return its JSON line."""
    out = subprocess.run([sys.executable, "-m", "benchmarks", *args], cwd=ROOT, capture_output=True, text=True,
                         check=True)
    sys.stderr.write(out.stderr)
    return json.loads(out.stdout.strip().splitlines()[-1])


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="python -m benchmarks")
    sub = p.add_subparsers(dest="scenario", required=True)
    k = sub.add_parser("kernel", help="N servo axes over the emulated bus, all moving, fast mode")
    k.add_argument("--axes", type=int, default=16)
    k.add_argument("--sim-seconds", type=float, default=5.0)
    k.add_argument("--period-us", type=int, default=1000)
    k.add_argument("--cam-share", type=float, default=0.25, help="share of axes following a master through a cam")
    k.add_argument("--trace", type=int, default=8, help="variables in a continuous data trace (0: no trace)")
    cams = sub.add_parser("cams", help="MC_GenerateCamTable of a 65,535-point table; cam evaluation for many axes")
    cams.add_argument("--points", type=int, default=65535)
    kin = sub.add_parser("kinematics", help="Delta3 inverse/forward kinematics on 1e6 points")
    kin.add_argument("--points", type=int, default=1_000_000)
    rob = sub.add_parser("robot", help="Delta3 + conveyor-tracking cells (pick cycles) next to plain moving axes")
    rob.add_argument("--cells", type=int, default=4)
    rob.add_argument("--axes", type=int, default=0, help="plain moving servo axes besides the cells")
    rob.add_argument("--sim-seconds", type=float, default=5.0)
    viz = sub.add_parser("viz", help="3D view of the demo robot: frame cost, and the realtime demo with the view on")
    viz.add_argument("--frames", type=int, default=2000)
    viz.add_argument("--seconds", type=float, default=10.0)
    r = sub.add_parser("realtime", help="the demo project paced to the wall clock: overruns, timing percentiles")
    r.add_argument("--seconds", type=float, default=600.0, help="wall time (default 10 minutes)")
    rest = sub.add_parser("rest", help="REST latency: FB PATCH until the output is visible (server process)")
    rest.add_argument("--repetitions", type=int, default=200)
    ws = sub.add_parser("ws", help="WebSocket fan-out while the kernel runs in realtime (server process)")
    ws.add_argument("--clients", type=int, default=10)
    ws.add_argument("--rate-hz", type=float, default=30.0)
    ws.add_argument("--seconds", type=float, default=20.0)
    sbs = sub.add_parser("side-by-side", help="the same scenario on MC Studio and on pyplcopen")
    sbs.add_argument("--axes", type=int, default=64)
    sbs.add_argument("--sim-seconds", type=float, default=5.0)
    soak = sub.add_parser("soak", help="the demo in fast mode under random valid commands for a long time (not in all)")
    soak.add_argument("--minutes", type=float, default=60.0)
    soak.add_argument("--seed", type=int, default=1)
    soak.add_argument("--tracemalloc", action="store_true",
                      help="trace Python allocations; report the sites whose memory grew after warm-up")
    a = sub.add_parser("all", help="every scenario, each in its own process, with short durations")
    a.add_argument("--realtime-seconds", type=float, default=60.0)
    args = p.parse_args(argv)

    if args.scenario == "kernel":
        from . import kernel

        result = kernel.run(axes=args.axes, sim_seconds=args.sim_seconds, period_us=args.period_us,
                            cam_share=args.cam_share, trace=args.trace)
    elif args.scenario == "cams":
        from . import cams as cams_bench

        result = cams_bench.run(points=args.points)
    elif args.scenario == "kinematics":
        from . import kinematics

        result = kinematics.run(points=args.points)
    elif args.scenario == "robot":
        from . import robot

        result = robot.run(cells=args.cells, axes=args.axes, sim_seconds=args.sim_seconds)
    elif args.scenario == "viz":
        from . import viz as viz_bench

        result = viz_bench.run(frames=args.frames, seconds=args.seconds)
    elif args.scenario == "realtime":
        from . import realtime

        result = realtime.run(seconds=args.seconds)
    elif args.scenario == "rest":
        from . import api

        result = api.run_rest(repetitions=args.repetitions)
    elif args.scenario == "ws":
        from . import api

        result = api.run_ws(clients=args.clients, rate_hz=args.rate_hz, seconds=args.seconds)
    elif args.scenario == "soak":
        from . import soak as soak_bench

        result = soak_bench.run(minutes=args.minutes, seed=args.seed, trace_memory=args.tracemalloc)
    elif args.scenario == "side-by-side":
        from . import sidebyside

        result = sidebyside.run(axes=args.axes, sim_seconds=args.sim_seconds)
    else:
        rows = [_child(["kernel", "--axes", str(n), "--sim-seconds", "5"]) for n in (1, 16, 64, 256)]
        for row in rows:
            print(f"kernel {row['axes']:4d} axes: RTF {row['rtf']:7.2f}  {row['us_per_axis_period']:8.3f} "
                  f"µs/axis-period  {row['peak_mb']:.1f} MB", flush=True)
        sbs_row = _child(["side-by-side", "--axes", "64", "--sim-seconds", "5"])
        print(f"side-by-side 64 axes: MC Studio (bus) {sbs_row['us_per_axis_period']:.3f} µs/axis-period, "
              f"ratio to pyplcopen {sbs_row['ratio_bus_vs_pyplcopen']}", flush=True)
        rt = _child(["realtime", "--seconds", str(args.realtime_seconds)])
        print(f"realtime demo {rt['wall_s']:.0f} s: {rt['overruns']} overruns, compute p99 "
              f"{rt['compute_us'].get('p99')} µs", flush=True)
        rest_row = _child(["rest", "--repetitions", "100"])
        print(f"rest: PATCH → output p50 {rest_row['patch_to_output_ms'].get('p50')} ms, → WebSocket p50 "
              f"{rest_row['patch_to_websocket_ms'].get('p50')} ms", flush=True)
        ws_row = _child(["ws", "--clients", "10", "--rate-hz", "30", "--seconds", "20"])
        print(f"ws: 10 clients × 30 Hz: {ws_row['rate_per_client_hz']} Hz each, {ws_row['overruns']} overruns",
              flush=True)
        biggest = rows[-1]
        result = {"scenario": "all", "kernel": rows, "side_by_side": sbs_row, "realtime": rt, "rest": rest_row,
                  "ws": ws_row, "rtf": biggest["rtf"], "us_per_axis_period": biggest["us_per_axis_period"],
                  "peak_mb": max(r["peak_mb"] for r in rows)}
    print(json.dumps(result))
    return 0


if __name__ == "__main__":
    sys.exit(main())
