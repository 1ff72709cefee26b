"""Realtime mode: the demo project paced to the wall clock while its axes move; overruns and timing percentiles.

Every servo axis of the project is powered and positions back and forth (MC_MoveAbsolute re-executed by a sequencer
thread through the runner, as the API would), the virtual axis runs a velocity move, snapshots are published at the
runner's rate. The runner logs, for every cycle, the ideal start of its period, the start of its computation and its
end (`Runner.timing_log`). Reported:

* overruns — cycles that completed after the end of their period (the runner's own count);
* completion margin — end of the period minus completion (µs; negative = overrun), percentiles;
* start offset — computation start minus ideal period start (µs; negative = computed early inside the jitter
  buffer, see docs/decisions.md D16), percentiles;
* period jitter — start-to-start interval of consecutive cycles minus the period (µs), percentiles;
* compute time per cycle (µs), percentiles, and per axis-period;
* machine stalls — a separate probe process that sleeps 0.5 ms at a time reports every gap over 5 ms; late cycles
  whose completion falls within 60 ms after such a stall began are counted as happening during a machine stall (the
  virtual machine stopped both processes, see docs/decisions.md D16).
"""

from __future__ import annotations

import resource
import subprocess
import sys
import threading
import time
from pathlib import Path
from typing import Any

import numpy as np

from mcstudio.controller.kernel import Controller
from mcstudio.controller.runner import Runner
from mcstudio.fieldbus.library import DeviceLibrary
from mcstudio.project.io import load_project

DEMO = Path(__file__).resolve().parents[1] / "projects" / "demo"


def _program(c: Controller) -> list[tuple[Any, Any, tuple[float, float]]]:
    """Servo ON on every axis; a back-and-forth positioning instance per servo axis, a velocity move on the virtual
    ones (started by the sequencer once the servo is ON)."""
    moves = []
    for a in c.mc.axes:
        if a.encoder or not a.used:
            continue
        c.fb("MC_Power", Axis=a.name, Enable=True)
        op = a.params.Operation
        v = min(op.MaxVel or 100.0, 100.0)
        acc = min(op.MaxAcc or 1000.0, 1000.0)
        if a.virtual:
            mv = c.fb("MC_MoveVelocity", Axis=a.name, Velocity=v / 4, Acceleration=acc, Deceleration=acc)
            moves.append((mv, a, (0.0, 0.0)))
            continue
        # between the limit switches (and the software limits once homed), 10 units inside
        s, lim = a.config.sensors, a.params.Limit
        lo = max(s.NegativeLimit if s.NegativeLimit is not None else -1e9, lim.NegaSwLimit) + 10.0
        hi = min(s.PositiveLimit if s.PositiveLimit is not None else 1e9, lim.PosiSwLimit) - 10.0
        lo, hi = max(lo, 0.0), min(hi, lo + 100.0)
        mv = c.fb("MC_MoveAbsolute", Axis=a.name, Position=hi, Velocity=v, Acceleration=acc, Deceleration=acc)
        moves.append((mv, a, (lo, hi)))
    return moves


def _sequence(c: Controller, moves: list[tuple[Any, Any, tuple[float, float]]]) -> None:
    """A finished move turns round: Execute falls, then rises with the other end as its target."""
    for mv, axis, (lo, hi) in moves:
        if not axis.servo_on:
            continue
        if mv.DEF.name == "MC_MoveVelocity":
            if not mv.Execute:
                mv.Execute = True
        elif mv.Execute and (mv.Done or mv.Error or mv.CommandAborted):
            mv.Execute = False
        elif not mv.Execute and not mv.Busy:
            mv.Position = lo if mv.Position == hi else hi
            mv.Execute = True


_PROBE = """
import sys, time
end = time.perf_counter() + float(sys.argv[1])
last = time.perf_counter()
while (now := time.perf_counter()) < end:
    if now - last > 0.005:
        print(f"{last!r} {now!r}", flush=True)
    last = now
    time.sleep(0.0005)
"""


def _stall_probe(seconds: float) -> subprocess.Popen[str]:
    """A separate process that wakes every 0.5 ms and reports every gap over 5 ms (perf_counter is the system's
    monotonic clock, comparable across processes): stalls of the machine, not of the kernel."""
    return subprocess.Popen([sys.executable, "-c", _PROBE, str(seconds)], stdout=subprocess.PIPE, text=True)


def _pct(x: np.ndarray) -> dict[str, float]:
    if x.size == 0:
        return {}
    q = np.percentile(x, [1, 50, 99, 99.9])
    return {"min": round(float(x.min()), 1), "p1": round(float(q[0]), 1), "p50": round(float(q[1]), 1),
            "p99": round(float(q[2]), 1), "p99.9": round(float(q[3]), 1), "max": round(float(x.max()), 1)}


def run(*, seconds: float, project_dir: Path = DEMO) -> dict[str, Any]:
    library = DeviceLibrary(project_dir)
    project = load_project(project_dir, library)
    c = Controller(project, library=library)
    runner = Runner(c, mode="realtime")
    runner.enable_timing_log(int(seconds / c.period_s * 1.2) + 1000)
    probe = _stall_probe(seconds + 5.0)
    runner.start()
    try:
        moves = runner.call(_program)
        start = time.perf_counter()
        while time.perf_counter() - start < seconds:
            runner.call(lambda ctrl: _sequence(ctrl, moves))
            time.sleep(0.02)
        overruns = runner.overruns
        rtf_sim = c.time_s
    finally:
        runner.stop()
    wall = time.perf_counter() - start
    probe.terminate()
    out, _ = probe.communicate()
    stalls = np.array([[float(v) for v in line.split()] for line in out.splitlines() if line.strip()]).reshape(-1, 2)
    assert runner.timing_log is not None
    log = runner.timing_log[:runner.timing_rows]
    period = c.period_s
    begin, t_start, t_end = log[:, 0], log[:, 1], log[:, 2]
    margin = (begin + period - t_end) * 1e6
    offset = (t_start - begin) * 1e6
    compute = (t_end - t_start) * 1e6
    jitter = (np.diff(t_start) - period) * 1e6  # start-to-start interval minus the period
    n_axes = len(c.mc.axes)
    # overruns explained by a stall of the machine: the probe process did not run either within the 60 ms before the
    # late completion (the jitter buffer is 50 ms)
    late = t_end[t_end > begin + period]
    explained = sum(1 for t in late if ((stalls[:, 1] > t - 0.06) & (stalls[:, 0] < t)).any()) if late.size else 0
    stall_ms = (stalls[:, 1] - stalls[:, 0]) * 1e3 if stalls.size else np.zeros(0)
    peak_mb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    return {
        "scenario": "realtime",
        "project": project.name,
        "axes": n_axes,
        "period_us": round(period * 1e6),
        "wall_s": round(wall, 1),
        "cycles": int(log.shape[0]),
        "rtf": round(log.shape[0] * period / wall, 4) if wall > 0 else 0.0,
        "sim_time_s": round(rtf_sim, 3),
        "overruns": overruns,
        "late_cycles": int(late.size),
        "late_cycles_during_machine_stalls": int(explained),
        "machine_stalls_over_5ms": int(stall_ms.size),
        "machine_stall_max_ms": round(float(stall_ms.max()), 1) if stall_ms.size else 0.0,
        "completion_margin_us": _pct(margin),
        "start_offset_us": _pct(offset),
        "period_jitter_us": _pct(jitter),
        "compute_us": _pct(compute),
        "us_per_axis_period": round(float(compute.mean()) / max(n_axes, 1), 3) if compute.size else 0.0,
        "peak_mb": round(peak_mb, 1),
        "threads": threading.active_count(),
    }
