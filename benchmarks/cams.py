"""Cam tables: MC_GenerateCamTable for a table of `points` cam data (one modified-sine rise and a mix of all curve
types), and the per-period evaluation of cam tables for many axes (`CamTableSet`, as the MC layer will call it).

`rtf` is not meaningful here (nothing is simulated) and is 0.0; `us_per_axis_period` is the cost of evaluating one
axis's table in one period with 64 axes on 4 tables, the master advancing one 1 ms period at 360°/s."""

from __future__ import annotations

import resource
import time
from typing import Any

import numpy as np

from mcstudio.controller.mc.cam.curves import _eMC_CAM_CURVE
from mcstudio.controller.mc.cam.generate import _sMC_CAM_NODE, _sMC_CAM_PROPERTY, generate
from mcstudio.controller.mc.cam.table import CamTable, CamTableSet


def _best_ms(fn: Any, repeat: int) -> tuple[float, float]:
    """(best, median) wall time of `fn()` in ms over `repeat` runs."""
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append((time.perf_counter() - t0) * 1e3)
    return min(times), float(np.median(times))


def _nodes(points: int) -> dict[str, list[_sMC_CAM_NODE]]:
    pitch = 0.001
    span = (points - 1) * pitch
    mixed = []
    curves = [c for c in _eMC_CAM_CURVE if c != _eMC_CAM_CURVE._mcConstantLine]
    for i, c in enumerate(curves):  # every curve type, equal spans; distances alternate up and down
        mixed.append(_sMC_CAM_NODE(Phase=round(span * (i + 1) / len(curves), 3), Distance=10.0 * (i % 2),
                                   Curve=int(c), PhasePitch=pitch))
    mixed[-1].Phase = round(span, 3)
    return {"modified_sine": [_sMC_CAM_NODE(Phase=round(span, 3), Distance=100.0,
                                            Curve=int(_eMC_CAM_CURVE._mcModifiedSine), PhasePitch=pitch)],
            "all_curves": mixed}


def run(points: int = 65535, *, axes: int = 64, tables: int = 4, periods: int = 2000,
        repeat: int = 15) -> dict[str, Any]:
    prop = _sMC_CAM_PROPERTY(CycleTime=1.0)
    gen: dict[str, Any] = {}
    result = None
    for name, nodes in _nodes(points).items():
        result = generate(nodes, prop, table_size=points)
        if not result.ok:
            raise RuntimeError(f"{name}: {result.error}")
        best, median = _best_ms(lambda nodes=nodes: generate(nodes, prop, table_size=points), repeat)
        gen[name] = {"best_ms": round(best, 2), "median_ms": round(median, 2),
                     "points": int(result.end_point_index + 1)}
    assert result is not None
    cams = [CamTable.from_points(result.phase, result.distance * (k + 1)) for k in range(tables)]
    cam_set = CamTableSet(cams)
    table_of_axis = np.arange(axes) % tables
    p_end = float(result.phase[-1])
    phase = np.linspace(0.0, p_end, axes, endpoint=False)
    step = p_end / 1000.0  # one 1 ms period with the master crossing the table in 1 s
    t0 = time.perf_counter()
    for _ in range(periods):
        phase = (phase + step) % p_end
        cam_set.evaluate(table_of_axis, phase)
    wall = time.perf_counter() - t0
    peak_mb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    return {
        "scenario": "cams",
        "points": points,
        "generate_ms": gen["modified_sine"]["best_ms"],
        "generate": gen,
        "axes": axes,
        "tables": tables,
        "rtf": 0.0,
        "us_per_axis_period": round(wall / periods / axes * 1e6, 3),
        "us_per_period": round(wall / periods * 1e6, 2),
        "peak_mb": round(peak_mb, 1),
    }


if __name__ == "__main__":  # `python -m benchmarks.cams` until the lead wires the sub-command in
    import json

    print(json.dumps(run()))
