"""Fixtures of the 3-D view tests: a Delta3 project (three degree axes A0–A2, a conveyor axis) and the example robot
of `omron-robot-delta3.md` §12.9 (Rf 200, Rm 50, Lf 350, Lm 800 mm, θ 0; workspace Zu −50, Rcy 300, Hcy 250,
Rco 150, Hco 150)."""

from __future__ import annotations

import copy
import socket
from typing import Any

import pytest

from mcstudio.controller.mc.kinematics import Delta3Params, Delta3Workspace
from mcstudio.project.models import Project

KIN: dict[str, Any] = {"type": "delta3", "Rf": 200.0, "Rm": 50.0, "Lf": 350.0, "Lm": 800.0, "theta": 0.0,
                       "workspace": {"Zu": -50.0, "Rcy": 300.0, "Hcy": 250.0, "Rco": 150.0, "Hco": 150.0}}

DEG_AXIS: dict[str, Any] = {
    "UnitConversion": {"UnitDisplay": "_mcDeg", "CmdPlsCountPerMotorRotation": 1048576,
                       "WorkTravelDistancePerMotorRotation": 360.0},
    "Operation": {"MaxVel": 720.0, "MaxJogVel": 90.0, "MaxAcc": 7200.0, "MaxDec": 7200.0, "InPosRange": 0.01,
                  "ZeroPosRange": 0.01},
    "Limit": {"PosiSwLimit": 170.0, "NegaSwLimit": -170.0, "SwLimitMode": "_mcCmdDecelerationStop"},
    "Homing": {"Mode": "_mcHomePreset"},
}
MM_ROTARY: dict[str, Any] = {
    "UnitConversion": {"UnitDisplay": "_mcMm", "CmdPlsCountPerMotorRotation": 1048576,
                       "WorkTravelDistancePerMotorRotation": 100.0},
    "Operation": {"MaxVel": 1000.0, "MaxJogVel": 200.0, "MaxAcc": 5000.0, "MaxDec": 5000.0},
    "PosCount": {"CountMode": "_mcCountModeRotary", "ModuloMinPosVal": 0.0, "ModuloMaxPosVal": 1000.0},
}


def delta_project(*, kinematics: dict[str, Any] | None = None, conveyor: bool = True) -> Project:
    """Virtual servo axes MC_Axis000–002 (degrees) as A0–A2 of MC_Group000 (Delta3), plus a conveyor axis."""
    axes = [{"name": f"MC_Axis00{k}", "number": k, "type": "_mcVirServo", "parameters": copy.deepcopy(DEG_AXIS)}
            for k in range(3)]
    if conveyor:
        axes.append({"name": "MC_Axis003", "number": 3, "type": "_mcVirServo", "parameters": copy.deepcopy(MM_ROTARY)})
    return Project.model_validate({
        "name": "delta",
        "axes": axes,
        "groups": [{"name": "MC_Group000", "number": 0, "composition": "_mcXYZ",
                    "axes": ["MC_Axis000", "MC_Axis001", "MC_Axis002"],
                    "kinematics": copy.deepcopy(kinematics or KIN)}],
    })


@pytest.fixture
def params() -> Delta3Params:
    return Delta3Params(Rf=200.0, Lf=350.0, Rm=50.0, Lm=800.0)


@pytest.fixture
def workspace() -> Delta3Workspace:
    return Delta3Workspace(Zu=-50.0, Rcy=300.0, Hcy=250.0, Rco=150.0, Hco=150.0)


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])
