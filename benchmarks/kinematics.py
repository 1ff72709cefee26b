"""Delta3 kinematics throughput: the vectorised inverse and forward kinematics over N random points of the §12.9
example robot's workspace (`omron-robot-delta3.md` §12), plus the one-point functions the MC layer calls once per
robot per period. Not a simulation, so `rtf` is 0.0; `us_per_axis_period` is the inverse cost per point (µs).

Each vectorised figure is the best of `repeats` runs after one warm-up run (the first run also pays for page faults
on fresh arrays; it is reported as `inverse_cold_ms`)."""

from __future__ import annotations

import resource
import time
from collections.abc import Callable
from typing import Any

import numpy as np

from mcstudio.controller.mc.kinematics import (
    Delta3Params,
    Delta3Workspace,
    WorkspaceCheck,
    contains_point,
    forward,
    forward_point,
    inverse,
    inverse_point,
    tcp_velocity_point,
)

ROBOT = Delta3Params(Rf=200.0, Lf=350.0, Rm=50.0, Lm=800.0)
WORKSPACE = Delta3Workspace(Zu=-50.0, Rcy=300.0, Hcy=250.0, Rco=150.0, Hco=150.0)


def _best_ms(fn: Callable[[], object], repeats: int) -> float:
    best = float("inf")
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return best * 1e3


def _per_call_us(fn: Callable[[], object], calls: int) -> float:
    t0 = time.perf_counter()
    for _ in range(calls):
        fn()
    return (time.perf_counter() - t0) / calls * 1e6


def run(points: int = 1_000_000, repeats: int = 3, point_calls: int = 20_000) -> dict[str, Any]:
    rng = np.random.default_rng(1)
    # Points of the workspace's bounding box (about 60 % inside the workspace, ~98 % reachable).
    ws = WORKSPACE
    xyz = rng.uniform([-ws.Rcy, -ws.Rcy, ws.z_bottom], [ws.Rcy, ws.Rcy, ws.Zu], (points, 3))
    t0 = time.perf_counter()
    ik = inverse(ROBOT, xyz)
    cold_ms = (time.perf_counter() - t0) * 1e3
    angles = ik.angles
    inverse_ms = _best_ms(lambda: inverse(ROBOT, xyz), repeats)
    inverse_ws_ms = _best_ms(lambda: inverse(ROBOT, xyz, workspace=WORKSPACE,
                                             check=WorkspaceCheck.COMMAND_EVERY_PERIOD), repeats)
    forward(ROBOT, angles)
    forward_ms = _best_ms(lambda: forward(ROBOT, angles), repeats)
    fk = forward(ROBOT, angles)
    ok = ik.reachable
    round_trip = float(np.max(np.abs(fk.position[ok] - xyz[ok]))) if ok.any() else 0.0

    x, y, z = -120.0, -80.0, -400.0
    q = inverse_point(ROBOT, x, y, z)[1]
    inverse_point_us = _per_call_us(lambda: inverse_point(ROBOT, x, y, z), point_calls)
    forward_point_us = _per_call_us(lambda: forward_point(ROBOT, *q), point_calls)
    contains_point_us = _per_call_us(lambda: contains_point(WORKSPACE, x, y, z), point_calls)
    velocity_point_us = _per_call_us(lambda: tcp_velocity_point(ROBOT, q, (10.0, -25.0, 40.0)), point_calls)
    single = np.array([x, y, z])
    inverse_1_numpy_us = _per_call_us(lambda: inverse(ROBOT, single), max(1, point_calls // 10))

    peak_mb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    return {
        "scenario": "kinematics",
        "points": points,
        "rtf": 0.0,
        "us_per_axis_period": round(inverse_ms * 1e3 / max(points, 1), 4),
        "peak_mb": round(peak_mb, 1),
        "inverse_ms": round(inverse_ms, 2),
        "inverse_cold_ms": round(cold_ms, 2),
        "inverse_with_workspace_ms": round(inverse_ws_ms, 2),
        "forward_ms": round(forward_ms, 2),
        "reachable_share": round(float(ok.mean()), 4) if points else 0.0,
        "max_round_trip_mm": round_trip,
        "inverse_point_us": round(inverse_point_us, 2),
        "forward_point_us": round(forward_point_us, 2),
        "contains_point_us": round(contains_point_us, 2),
        "tcp_velocity_point_us": round(velocity_point_us, 2),
        "inverse_one_point_numpy_us": round(inverse_1_numpy_us, 2),
    }


if __name__ == "__main__":
    import json

    print(json.dumps(run()))
