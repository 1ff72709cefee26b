"""3-D view cost: one frame of the live robot view (`viz/scene.py`), and what following the snapshots does to the
realtime kernel (docs/robot.md "3D view").

* `frame_us_*`: `SceneServer.update(snapshot)` of the demo project (one Delta3 + conveyor) with new joint feedback
  every frame — readings, pose (`robot_pose`), the scene messages of one `atomic()` block; no browser connected,
  so the figure excludes viser's own sending thread. `pose_us`: `robot_pose` alone.
* `realtime`: the demo project paced to the wall clock for `seconds`, its robot arms swinging (MC_MoveAbsolute back
  and forth), once without and once with the viz thread following at 60 frames/s — overruns and the mean kernel
  compute time per period in both runs.

Run: `.venv/bin/python -m benchmarks.viz [--frames N] [--seconds S]`. Not a simulation of its own, so `rtf` is the
realtime run's; `us_per_axis_period` is the realtime kernel's compute time per axis-period with the view on.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import resource
import socket
import time
from pathlib import Path
from typing import Any

import numpy as np

from mcstudio.controller.kernel import Controller
from mcstudio.controller.runner import Runner
from mcstudio.project.io import load_project
from mcstudio.viz.geometry import robot_pose
from mcstudio.viz.scene import SceneServer

DEMO = Path(__file__).resolve().parents[1] / "projects" / "demo"
ROBOT_AXES = ("MC_Axis004", "MC_Axis005", "MC_Axis006")


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def _pct(values: list[float], q: float) -> float:
    return float(np.percentile(np.asarray(values), q)) * 1e6 if values else 0.0


def frame_cost(frames: int = 2000) -> dict[str, Any]:
    controller = Controller(load_project(DEMO))
    scene = SceneServer(port=_free_port())
    try:
        scene.rebuild(controller)
        snap = controller.snapshot
        idx = [a.i for a in controller.mc.axes if a.name in ROBOT_AXES]
        snaps = []
        for k in range(frames):
            mc = dict(snap.mc)
            act = mc["act_pos"].copy()
            act[idx] = (20 + 15 * np.sin(k / 50), 30 + 15 * np.cos(k / 70), 25 + 10 * np.sin(k / 30))
            mc["act_pos"] = act
            snaps.append(dataclasses.replace(snap, mc=mc))
        scene.update(snaps[0], force=True)  # warm-up
        times = []
        for s in snaps:
            t0 = time.perf_counter()
            scene.update(s)
            times.append(time.perf_counter() - t0)
        params = scene.robots[0].view.spec.params
        t0 = time.perf_counter()
        for k in range(frames):
            robot_pose(params, (20.0, 30.0, 25.0 + k * 1e-3))
        pose_us = (time.perf_counter() - t0) / frames * 1e6
    finally:
        scene.stop()
    return {"frames": frames, "frame_us_mean": float(np.mean(times)) * 1e6, "frame_us_p50": _pct(times, 50),
            "frame_us_p99": _pct(times, 99), "pose_us": pose_us}


def _realtime(seconds: float, with_view: bool) -> dict[str, Any]:
    controller = Controller(load_project(DEMO))
    runner = Runner(controller, mode="realtime")
    scene = SceneServer(port=_free_port()) if with_view else None
    moves = {}
    target = dict.fromkeys(ROBOT_AXES, 60.0)

    def setup(c: Controller) -> None:
        for name in ROBOT_AXES:
            c.fb("MC_Power", Axis=name, Enable=True)

    def start(c: Controller) -> None:
        for name in ROBOT_AXES:
            moves[name] = c.fb("MC_MoveAbsolute", Axis=name, Position=60.0, Velocity=120.0, Acceleration=1200.0,
                               Deceleration=1200.0, Execute=True)

    def turn(c: Controller) -> None:
        for name, fb in moves.items():
            if fb.inp["Execute"] and (fb.out["Done"] or fb.out["Error"] or fb.out["CommandAborted"]):
                c.set_inputs(fb.id, {"Execute": False})
            elif not fb.inp["Execute"]:
                target[name] = 0.0 if target[name] == 60.0 else 60.0
                c.set_inputs(fb.id, {"Execute": True, "Position": target[name]})

    try:
        if scene is not None:
            scene.attach(runner)
        runner.start()
        runner.call(setup)
        time.sleep(0.3)
        runner.call(start)
        overruns0, cycle0, t0 = runner.overruns, runner.controller.cycle, time.perf_counter()
        loads = []
        while time.perf_counter() - t0 < seconds:
            time.sleep(0.05)
            runner.call(turn)
            loads.append(runner.cycle_time_avg_s)
        wall = time.perf_counter() - t0
        cycles = runner.controller.cycle - cycle0
        out = {"overruns": runner.overruns - overruns0, "cycles": cycles, "rtf": cycles * controller.period_s / wall,
               "cycle_us_mean": float(np.mean(loads)) * 1e6 if loads else 0.0}
        if scene is not None:
            st = scene.stats
            out.update(frames=st.frames, skipped=st.skipped, fps=st.frames / wall,
                       frame_us_mean=st.mean_s * 1e6, frame_us_p99=_pct(st.recent, 99))
        return out
    finally:
        runner.stop()
        if scene is not None:
            scene.stop()


def run(frames: int = 2000, seconds: float = 10.0) -> dict[str, Any]:
    result: dict[str, Any] = frame_cost(frames)
    off = _realtime(seconds, with_view=False)
    on = _realtime(seconds, with_view=True)
    axes = len(load_project(DEMO).axes)
    result.update(realtime_without_view=off, realtime_with_view=on, rtf=on["rtf"],
                  us_per_axis_period=on["cycle_us_mean"] / axes,
                  peak_mb=resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024)
    return result


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--frames", type=int, default=2000)
    p.add_argument("--seconds", type=float, default=10.0)
    a = p.parse_args()
    print(json.dumps(run(frames=a.frames, seconds=a.seconds)))


if __name__ == "__main__":
    main()
