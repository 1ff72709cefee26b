"""The robots of the 3-D view: each Delta3 group's joint feedback, TCP (forward kinematics) and alarm.

`GET /api/v1/viz/robots` reads the latest published snapshot (like `/snapshot`) — the studio's 3D tab polls it for
its status panel; scripts get the TCP of every robot in one call without knowing the group names. The kinematics are
those in force (MC_SetKinTransform replaces the project's at run time, D94) and `coord_systems` lists the user
coordinate systems MC_DefineCoordSystem defined (the robot jog's coordinate-system choice, D93).
"""

from __future__ import annotations

import math

from fastapi import APIRouter, Depends
from pydantic import Field

from ...modelbase import StrictModel
from ...viz.robots import read_robot, robot_specs
from ..deps import get_studio
from ..state import Studio

router = APIRouter(tags=["viz"])


_Model = StrictModel


class RobotAxisOut(_Model):
    logical: str = Field(description="Logical axis of the group: A0, A1, A2")
    name: str = Field(description="Axis variable name")
    act_pos: float | None = Field(description="Act.Pos [deg]; null when the axis is not in the controller")
    state: str = Field(description="Axis state (Status member that is TRUE): Standstill, Discrete, ErrorStop …")
    error_code: str = Field(description="MFaultLvl.Code (4 hex digits), 0000 = none")


class RobotAlarm(_Model):
    code: str = Field(description="ErrorID (4 hex digits)")
    message: str


class Delta3ParamsOut(_Model):
    Rf: float
    Rm: float
    Lf: float
    Lm: float
    theta: float


class CoordSystemOut(_Model):
    csid: int = Field(ge=0, le=15, description="User coordinate system number (CSID)")
    pose: list[float] = Field(min_length=6, max_length=6,
                              description="[Tx, Ty, Tz] mm, [Rx, Ry, Rz] deg: the UCS origin and rotation in the MCS "
                                          "(R = Rz·Ry·Rx, omron-robot-delta3.md §4)")


class RobotOut(_Model):
    group: str = Field(description="Axes group variable name")
    kinematics: Delta3ParamsOut = Field(description="Delta3 parameters [mm, deg]")
    axes: list[RobotAxisOut]
    tcp: list[float] | None = Field(description="TCP feedback position [x, y, z] in the MCS [mm] by forward "
                                    "kinematics of the axes' Act.Pos; null when it has no solution")
    kin_status: str = Field(description="OK, UNREACHABLE (no forward solution, 570F) or NOT_FINITE")
    alarm: RobotAlarm | None = Field(description="Set while the group or one of its axes is in ErrorStop")
    coord_systems: list[CoordSystemOut] = Field(
        description="User coordinate systems defined by MC_DefineCoordSystem (volatile, lost on a restart; D83), "
                    "by CSID")


class RobotsOut(_Model):
    cycle: int = Field(description="Cycle of the snapshot read")
    robots: list[RobotOut] = Field(description="Axes groups with Delta3 kinematics; empty when the project has none")


@router.get("/viz/robots", response_model=RobotsOut,
            summary="The robots of the 3D view: joint feedback, TCP and alarm of each Delta3 group")
def get_robots(studio: Studio = Depends(get_studio)) -> RobotsOut:
    snap = studio.runner.snapshot
    controller = studio.controller
    index = {a.name: int(a.i) for a in controller.mc.axes}
    out = []
    groups = dict(controller.mc.groups_by_name)
    for spec in robot_specs(controller.project, groups):
        r = read_robot(spec, snap, tuple(index.get(n) for n in spec.axes))  # type: ignore[arg-type]
        alarm = r.alarm
        p = spec.params
        out.append(RobotOut(
            group=spec.group,
            kinematics=Delta3ParamsOut(Rf=p.Rf, Rm=p.Rm, Lf=p.Lf, Lm=p.Lm, theta=p.theta),
            axes=[RobotAxisOut(logical=a.logical, name=a.name,
                               act_pos=a.act_pos if math.isfinite(a.act_pos) else None, state=a.state,
                               error_code=f"{a.error_code:04X}") for a in r.axes],
            tcp=[round(v, 6) for v in r.tcp] if r.tcp is not None else None,
            kin_status=r.kin_status.name,
            alarm=RobotAlarm(code=f"{alarm[0]:04X}", message=alarm[1]) if alarm is not None else None,
            coord_systems=_coord_systems(groups.get(spec.group)),
        ))
    return RobotsOut(cycle=snap.cycle, robots=out)


def _coord_systems(group: object) -> list[CoordSystemOut]:
    """The group's UCS (a copy of its dict of immutable poses: one atomic read of the kernel's state)."""
    systems = dict(getattr(group, "coord_systems", None) or {})
    return [CoordSystemOut(csid=int(csid), pose=[round(float(v), 9) for v in ucs.pose()])
            for csid, ucs in sorted(systems.items())]
