"""Side by side with pyplcopen (a C++ PLCopen motion core with a Python facade, `pip install pyplcopen`).

One scenario both can run: N axes, the even ones positioning back and forth between −50 and +50 units (complete
moves: 200 units/s, 2000 units/s², jerk 50 000 units/s³), the odd ones at a constant velocity (25 … 31 units/s),
1 ms period, the same simulated time for every axis.

* MC Studio, servo axes on the emulated EtherCAT bus (CiA402 drives, mechanism, byte-level process image), and the
  same with virtual servo axes (MC layer only), run cycle by cycle with every instance called each period; a move is
  re-executed towards the other end when it is Done (checked every 10 periods).
* pyplcopen `AxisSim`: its facade runs a positioning move to completion inside `move_absolute` and a velocity move
  with `cycle(n)`, so each axis is simulated on its own for the whole time (moves back to back). It has no fieldbus,
  drive or snapshot; the ratio is the price of the emulated hardware and of Python.
"""

from __future__ import annotations

import importlib.util
import resource
import time
from typing import Any

from mcstudio.controller.kernel import Controller
from mcstudio.project.models import AxisConfig, ControllerSettings, Project

from .kernel import PARAMS

V, A, J = 200.0, 2000.0, 50000.0
SWING = 50.0


def _mcstudio(axes: int, sim_s: float, *, virtual: bool) -> dict[str, Any]:
    project = Project(
        name=f"side-by-side-{axes}",
        controller=ControllerSettings(primary_period_us=1000),
        axes=[AxisConfig(name=f"MC_Axis{i:03d}", number=i, type="_mcVirServo" if virtual else "_mcServo",
                         node_address=None if virtual else i + 1, parameters=PARAMS) for i in range(axes)],
    )
    c = Controller(project)
    for i in range(axes):
        c.fb("MC_Power", Axis=f"MC_Axis{i:03d}", Enable=True)
    c.step(10, publish=False)
    moves = []
    for i in range(axes):
        name = f"MC_Axis{i:03d}"
        if i % 2 == 0:
            moves.append(c.fb("MC_MoveAbsolute", Axis=name, Execute=True, Position=SWING, Velocity=V,
                              Acceleration=A, Deceleration=A, Jerk=J))
        else:
            c.fb("MC_MoveVelocity", Axis=name, Execute=True, Velocity=25.0 + i % 7, Acceleration=A, Deceleration=A)
    cycles = round(sim_s / c.period_s)
    done_moves = 0
    t0 = time.perf_counter()
    for k in range(cycles):
        if k % 10 == 0:
            for mv in moves:
                if mv.Done:
                    mv.Execute = False
                    done_moves += 1
                elif not mv.Execute:
                    mv.Position = -mv.Position
                    mv.Execute = True
        c.step(1, publish=False)
    wall = time.perf_counter() - t0
    return {"engine": "mcstudio-virtual" if virtual else "mcstudio-bus", "axes": axes, "sim_s": sim_s,
            "wall_s": round(wall, 4), "rtf": round(sim_s / wall, 2),
            "us_per_axis_period": round(wall / cycles / axes * 1e6, 4), "moves": done_moves}


def _move_cycles(pp: Any, distance: float, v: float, a: float, j: float) -> int:
    """Periods pyplcopen's blocking move takes (its facade does not report them): the smallest `max_cycles` it
    completes in."""
    lo, hi = 1, 200_000
    while lo < hi:
        mid = (lo + hi) // 2
        ax = pp.AxisSim()
        ax.power_on()
        ax.cycle(2)
        try:
            ax.move_absolute(distance, v, a, a, j, mid)
            hi = mid
        except RuntimeError:
            lo = mid + 1
    return lo


def _pyplcopen(axes: int, sim_s: float) -> dict[str, Any]:
    import pyplcopen as pp

    T = 0.001
    cycles = round(sim_s / T)
    # the facade's units are per cycle: units/cycle, units/cycle², units/cycle³
    v, a, j = V * T, A * T * T, J * T**3
    per_move = _move_cycles(pp, 2 * SWING, v, a, j)
    sims = []
    for i in range(axes):
        ax = pp.AxisSim()
        ax.power_on()
        ax.cycle(10)
        if i % 2 == 0:
            ax.move_absolute(SWING, v, a, a, j)  # to the start position (not timed)
        sims.append(ax)
    done_moves = 0
    t0 = time.perf_counter()
    for i, ax in enumerate(sims):
        if i % 2 == 0:
            left, target = cycles, -SWING
            while left >= per_move:
                ax.move_absolute(target, v, a, a, j, per_move + 1)
                target = -target
                left -= per_move
                done_moves += 1
            ax.cycle(left)
        else:
            ax.move_velocity((25.0 + i % 7) * T, a, a, 1.0, 1)
            ax.cycle(cycles - 1)
    wall = time.perf_counter() - t0
    return {"engine": "pyplcopen", "version": getattr(pp, "__version__", "0.21"), "axes": axes, "sim_s": sim_s,
            "wall_s": round(wall, 4), "rtf": round(sim_s / wall, 1),
            "us_per_axis_period": round(wall / cycles / axes * 1e6, 4), "moves": done_moves,
            "cycles_per_move": per_move}


def run(*, axes: int, sim_seconds: float) -> dict[str, Any]:
    rows = [_mcstudio(axes, sim_seconds, virtual=False), _mcstudio(axes, sim_seconds, virtual=True)]
    if importlib.util.find_spec("pyplcopen") is not None:
        rows.append(_pyplcopen(axes, sim_seconds))
    else:
        rows.append({"engine": "pyplcopen", "skipped": "not installed (pip install pyplcopen)"})
    bus = rows[0]
    ref = rows[2] if "rtf" in rows[2] else None
    peak_mb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    return {
        "scenario": "side-by-side",
        "axes": axes,
        "rows": rows,
        "ratio_bus_vs_pyplcopen": round(bus["us_per_axis_period"] / ref["us_per_axis_period"], 1) if ref else None,
        "rtf": bus["rtf"],
        "us_per_axis_period": bus["us_per_axis_period"],
        "peak_mb": round(peak_mb, 1),
    }
