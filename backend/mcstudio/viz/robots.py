"""Which robots a project has and how they stand in a snapshot — shared by the 3-D view and the REST read-out.

`robot_specs(project, groups)` lists the Delta3 robots (axes groups with Delta3 kinematics) with the kinematics **in
force** — the project's from start-up, replaced at run time by MC_SetKinTransform (D82, D94); `read_robot(spec,
snapshot)` takes the member axes' **feedback** positions (Act.Pos, degrees) and their states from a published
snapshot (never from the kernel) and adds the TCP by forward kinematics. Pure functions: no viser, no threads.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from ..controller.mc.enums import AxisState
from ..controller.mc.kinematics import Delta3Params, Delta3Workspace, Status, UserCoordSystem, forward_point

if TYPE_CHECKING:
    from ..controller.kernel import Snapshot
    from ..project.models import Project

LOGICAL = ("A0", "A1", "A2")


@dataclass(frozen=True)
class RobotSpec:
    """A Delta3 robot of the project: its axes group, the axes on A0–A2, kinematics and workspace (mm, deg)."""

    group: str
    axes: tuple[str, str, str]
    params: Delta3Params
    workspace: Delta3Workspace | None = None
    # user coordinate systems by CSID (MC_DefineCoordSystem); the robot instructions will fill these in
    coord_systems: Mapping[int, UserCoordSystem] = field(default_factory=dict)


def kinematics_in_force(project_group: Any, groups: Mapping[str, Any] | None) -> Any:
    """The Delta3 kinematics to draw for a project group: those in force in the controller (`AxesGroup.kinematics`,
    set by MC_SetKinTransform at run time), else the project's (before start-up, or after 571F deleted them)."""
    running = groups.get(project_group.name) if groups is not None else None
    kin = getattr(running, "kinematics", None) if running is not None else None
    return kin if kin is not None else getattr(project_group, "kinematics", None)


def robot_specs(project: Project, groups: Mapping[str, Any] | None = None) -> list[RobotSpec]:
    """The project's Delta3 robots: used axes groups with three composition axes and Delta3 kinematics — with
    `groups` (the MC module's `groups_by_name`) the kinematics in force (`kinematics_in_force`), so a robot whose
    kinematics MC_SetKinTransform replaced is drawn with the new parameters, and a group that got kinematics only at
    run time is drawn, too; without `groups` the project's."""
    out = []
    for g in getattr(project, "groups", None) or []:
        kin = kinematics_in_force(g, groups)
        if kin is None or getattr(kin, "type", None) != "delta3" or len(g.axes) < 3:
            continue
        if getattr(getattr(g, "use", None), "name", "_mcUsedGroup") != "_mcUsedGroup":
            continue
        out.append(RobotSpec(group=g.name, axes=(g.axes[0], g.axes[1], g.axes[2]), params=kin.params(),
                             workspace=kin.workspace_obj()))
    return out


@dataclass(frozen=True, slots=True)
class AxisReading:
    logical: str
    name: str
    act_pos: float  # degrees; NaN if the axis is not in the snapshot
    state: str  # AxisState name
    error_code: int


@dataclass(frozen=True, slots=True)
class RobotReading:
    """One robot as of a snapshot: joint feedback (deg), TCP by forward kinematics (mm, MCS; None if unsolvable),
    and the alarm (ErrorStop of the group or of a member axis) as a code and a text."""

    group: str
    angles: tuple[float, float, float]
    axes: tuple[AxisReading, ...]
    tcp: tuple[float, float, float] | None
    kin_status: Status
    group_state: str | None = None
    group_error: int = 0

    @property
    def alarm(self) -> tuple[int, str] | None:
        """(ErrorID, "MC_Group000 ErrorStop 6701" …) when the group or an axis is in ErrorStop, else None."""
        if self.group_state == "ErrorStop":
            return self.group_error, f"{self.group} ErrorStop {self.group_error:04X}"
        for a in self.axes:
            if a.state == "ErrorStop":
                return a.error_code, f"{a.logical} {a.name} ErrorStop {a.error_code:04X}"
        return None

    @property
    def key(self) -> tuple[Any, ...]:
        """What the picture depends on: equal keys draw the same frame (the viz thread skips it)."""
        return (self.angles, self.alarm, self.kin_status)


def axis_index(snapshot_axes: list[str], name: str) -> int | None:
    try:
        return snapshot_axes.index(name)
    except ValueError:
        return None


def _group_state(snap: Snapshot, group: str) -> tuple[str | None, int]:
    """The group's state and ErrorID when the snapshot carries axes groups: `mc["groups"]` is a sequence of
    `_sGROUP_REF`-shaped dicts (`name`, `Status` with one TRUE state, `MFaultLvl.Code` as 4 hex digits)."""
    groups = snap.mc.get("groups") if isinstance(snap.mc, Mapping) else None
    if not groups:
        return None, 0
    for g in groups:
        if not isinstance(g, Mapping) or g.get("name") != group:
            continue
        status = g.get("Status", {})
        state = next((k for k, on in status.items() if on and k != "Ready"), None)
        code = g.get("MFaultLvl", {}).get("Code", "0000")
        try:
            error = int(code, 16) if isinstance(code, str) else int(code)
        except ValueError:
            error = 0
        return state, error
    return None, 0


def read_robot(spec: RobotSpec, snap: Snapshot, indices: tuple[int | None, int | None, int | None]) -> RobotReading:
    """The robot in `snap`; `indices` are the member axes' positions in the snapshot arrays (None: not there)."""
    mc = snap.mc
    act = mc["act_pos"]
    discrete = mc["discrete"]
    angles = []
    axes = []
    for logical, name, i in zip(LOGICAL, spec.axes, indices, strict=True):
        if i is None or i >= len(act):
            angles.append(math.nan)
            axes.append(AxisReading(logical, name, math.nan, "Disabled", 0))
            continue
        pos = float(act[i])
        state, error = discrete[i][0], discrete[i][1]
        angles.append(pos)
        axes.append(AxisReading(logical, name, pos, AxisState(state).name, int(error)))
    status, tcp = forward_point(spec.params, *angles)
    gstate, gerror = _group_state(snap, spec.group)
    return RobotReading(group=spec.group, angles=(angles[0], angles[1], angles[2]), axes=tuple(axes),
                        tcp=tcp if status == Status.OK else None, kin_status=Status(status), group_state=gstate,
                        group_error=gerror)
