"""Shared fixtures: projects and controllers driven cycle by cycle (no runner thread, no wall clock)."""

from __future__ import annotations

import copy
from pathlib import Path
from typing import Any

import pytest

from mcstudio.controller.kernel import Controller, Until
from mcstudio.controller.mc.fb.base import FunctionBlock
from mcstudio.project.io import load_project
from mcstudio.project.models import AxisConfig, Project

ROOT = Path(__file__).resolve().parents[1]
DEMO = ROOT / "projects" / "demo"

MM_AXIS: dict[str, Any] = {
    "UnitConversion": {"UnitDisplay": "_mcMm", "CmdPlsCountPerMotorRotation": 1048576,
                       "WorkTravelDistancePerMotorRotation": 10.0},
    "Operation": {"MaxVel": 500.0, "MaxJogVel": 100.0, "MaxAcc": 10000.0, "MaxDec": 10000.0, "InPosRange": 0.01,
                  "ZeroPosRange": 0.01},
    "Limit": {"PosiSwLimit": 100000.0, "NegaSwLimit": -100000.0},
    "Homing": {"Vel": 50.0, "ApproachVel": 5.0, "CompensationVel": 10.0, "HomeInputMaskDistance": 10.0},
}


def small_project(**operation: Any) -> Project:
    """Two servo axes on nodes 1 and 2 (mm, 10 mm/rev, 2^20 pulses/rev) and one virtual servo axis."""
    params = copy.deepcopy(MM_AXIS)
    params["Operation"].update(operation)
    return Project(
        name="test",
        axes=[
            AxisConfig(name="MC_Axis000", number=0, type="_mcServo", node_address=1, parameters=params),
            AxisConfig(name="MC_Axis001", number=1, type="_mcServo", node_address=2, parameters=params),
            AxisConfig(name="MC_Axis002", number=2, type="_mcVirServo", parameters=params),
        ],
    )


def axis_project(*, sensors: dict[str, Any] | None = None, count_mode: str = "_mcCountModeLinear",
                 modulo: tuple[float, float] = (0.0, 360.0), encoder: str = "incremental", **groups: dict[str, Any]
                 ) -> Project:
    """One servo axis MC_Axis000 on node 1 (mm, 10 mm/rev, 2^20 pulses/rev) plus a virtual MC_Axis001, with
    parameter groups updated from `groups` (e.g. Limit={...}, Homing={...}) and simulated sensors."""
    params = copy.deepcopy(MM_AXIS)
    params["PosCount"] = {"CountMode": count_mode, "ModuloMinPosVal": modulo[0], "ModuloMaxPosVal": modulo[1]}
    for group, values in groups.items():
        params.setdefault(group, {}).update(values)
    return Project(
        name="test",
        axes=[
            AxisConfig(name="MC_Axis000", number=0, type="_mcServo", node_address=1, parameters=params,
                       sensors=sensors or {}, drive={"EncoderType": encoder}),
            AxisConfig(name="MC_Axis001", number=1, type="_mcVirServo", parameters=copy.deepcopy(params)),
        ],
    )


@pytest.fixture
def demo_project() -> Project:
    return load_project(DEMO)


@pytest.fixture
def ctrl() -> Controller:
    return Controller(small_project())


def power_on(c: Controller, axis: str = "MC_Axis000") -> FunctionBlock:
    """MC_Power with Enable TRUE, stepped until Status is TRUE."""
    pw = c.fb("MC_Power", Axis=axis, Enable=True)
    n = c.step(50, Until(pw.id, "Status", True))
    assert pw.Status, f"servo did not come on within {n} cycles"
    return pw


def step_until(c: Controller, fb: FunctionBlock, output: str, value: Any = True, limit: int = 100_000) -> int:
    """Step until `fb.<output> == value`; return the number of cycles run."""
    n = c.step(limit, Until(fb.id, output, value), publish=False)
    assert fb.out[output] == value, f"{fb.DEF.name}.{output} never became {value!r} within {limit} cycles"
    return n


def run_into_overflow(c: Controller, axis: str, sign: int, pulses_per_unit: float) -> float:
    """Drive a powered Linear-Mode axis into command position overflow (sign +1) or underflow (−1): preset 5 units
    before the end of the 40-bit pulse range, then a velocity move toward it until the MC aborts it at the edge
    (decision D28; overflow itself is no error). Returns the edge position."""
    edge = (2**39 - 1) / pulses_per_unit if sign > 0 else -(2**39) / pulses_per_unit
    sp = c.fb("MC_SetPosition", Axis=axis, Execute=True, Position=edge - sign * 5.0)
    step_until(c, sp, "Done")
    mv = c.fb("MC_MoveVelocity", Axis=axis, Execute=True, Velocity=50.0, Acceleration=1000.0, Deceleration=1000.0,
              Direction="_mcPositiveDirection" if sign > 0 else "_mcNegativeDirection")
    step_until(c, mv, "CommandAborted", limit=2000)
    return edge
