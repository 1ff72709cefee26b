"""Benchmark entry point: `python -m benchmarks <scenario> [options]` (see benchmarks/__init__.py)."""

from __future__ import annotations

import argparse
import json
import sys

from . import kernel


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="python -m benchmarks")
    sub = p.add_subparsers(dest="scenario", required=True)
    k = sub.add_parser("kernel", help="N servo axes over the emulated bus, all moving, fast mode")
    k.add_argument("--axes", type=int, default=16)
    k.add_argument("--sim-seconds", type=float, default=5.0)
    k.add_argument("--period-us", type=int, default=1000)
    sub.add_parser("all", help="the kernel scenario at 1, 16, 64 and 256 axes (short runs)")
    args = p.parse_args(argv)
    if args.scenario == "kernel":
        result = kernel.run(axes=args.axes, sim_seconds=args.sim_seconds, period_us=args.period_us)
        print(json.dumps(result))
    else:
        rows = [kernel.run(axes=n, sim_seconds=2.0, period_us=1000) for n in (1, 16, 64, 256)]
        for r in rows:
            print(f"{r['axes']:4d} axes: RTF {r['rtf']:7.2f}  {r['us_per_axis_period']:8.2f} µs/axis-period  "
                  f"{r['peak_mb']:.1f} MB")
        print(json.dumps({"scenarios": rows, "rtf": rows[-1]["rtf"],
                          "us_per_axis_period": rows[-1]["us_per_axis_period"], "peak_mb": rows[-1]["peak_mb"]}))
    return 0


if __name__ == "__main__":
    sys.exit(main())
