"""Shared set-up of the axes-group tests: a project with a 2-axis and a 3-axis group, powered and homed axes."""

from __future__ import annotations

import copy
import math
from typing import Any

from mcstudio.controller.kernel import Controller
from mcstudio.controller.mc.fb.base import FunctionBlock
from mcstudio.project.models import AxesGroupConfig, AxisConfig, Project
from tests.conftest import MM_AXIS, step_until

T = 0.001


def group_project(**operation: Any) -> Project:
    """MC_Axis000/001 servo (nodes 1, 2), MC_Axis002/003/004 virtual servo; MC_Group000 = (000, 001) _mcXY,
    MC_Group001 = (002, 003, 004) _mcXYZ. Group operation settings from `operation`."""
    params = copy.deepcopy(MM_AXIS)
    axes = [AxisConfig(name="MC_Axis000", number=0, type="_mcServo", node_address=1, parameters=params),
            AxisConfig(name="MC_Axis001", number=1, type="_mcServo", node_address=2, parameters=params)]
    axes += [AxisConfig(name=f"MC_Axis00{k}", number=k, type="_mcVirServo", parameters=params) for k in (2, 3, 4)]
    op = {"MaxInterpolationVel": 1000.0, **operation}
    return Project(name="groups", axes=axes, groups=[
        AxesGroupConfig(name="MC_Group000", number=0, composition="_mcXY", axes=["MC_Axis000", "MC_Axis001"],
                        operation=op),
        AxesGroupConfig(name="MC_Group001", number=1, composition="_mcXYZ",
                        axes=["MC_Axis002", "MC_Axis003", "MC_Axis004"], operation=op),
    ])


def ready(c: Controller, group: str = "MC_Group000", *, enable: bool = True) -> FunctionBlock | None:
    """Servo ON and home defined on every axis (standing in for MC_Home), then MC_GroupEnable of `group`."""
    for a in c.mc.axes:
        c.fb("MC_Power", Axis=a.name, Enable=True)
    c.step(20)
    for a in c.mc.axes:
        assert a.servo_on
        a.homed = True
    if not enable:
        return None
    en = c.fb("MC_GroupEnable", AxesGroup=group, Execute=True)
    step_until(c, en, "Done")
    return en


def positions(c: Controller, group: str = "MC_Group000") -> tuple[float, ...]:
    return c.mc.groups_by_name[group].point()


def line_distance(p: tuple[float, ...], a: tuple[float, ...], b: tuple[float, ...]) -> float:
    """Distance of point p from the straight line a–b."""
    d = [y - x for x, y in zip(a, b, strict=True)]
    n = math.sqrt(sum(x * x for x in d))
    u = [x / n for x in d]
    w = [y - x for x, y in zip(a, p, strict=True)]
    t = sum(x * y for x, y in zip(w, u, strict=True))
    return math.sqrt(max(sum(x * x for x in w) - t * t, 0.0))
