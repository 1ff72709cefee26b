"""Request and response models of the axes-group endpoints (api.md "Axes and axes groups").

`GroupVariables` is `_sGROUP_REF` with the manual's member names (omron-group-and-cam.md §5.4: Status, Details, Cmd,
MFaultLvl, Obsr, Cfg, Kinematics) plus `CmdPos`, the command positions of the composition axes A0, A1, …
Kinematics requests take one point (`position` / `axes`, the contract) or a batch (`positions` / `axes_list`, at most
`MAX_POINTS`), never both.
"""

from __future__ import annotations

from typing import Annotated

from pydantic import Field, model_validator

from ..modelbase import StrictModel
from ..project.models import AxesGroupConfig
from .models import RefEvent

MAX_POINTS = 10_000  # a batch of points per request (≈ 1 ms of numpy work; bounds the body at ~0.5 MB)

Finite = Annotated[float, Field(allow_inf_nan=False)]
Vec3 = Annotated[list[Finite], Field(min_length=3, max_length=3)]


_Model = StrictModel


# ---------------------------------------------------------------------------------------------- _sGROUP_REF
class GroupStatusVar(_Model):
    """`Status`: Ready plus the five exclusive group states (A-3 letters a–e)."""

    Ready: bool = Field(description="Standby, every composition axis servo ON, home defined and not held by MC_Stop")
    Disabled: bool
    Standby: bool
    Moving: bool
    Stopping: bool
    ErrorStop: bool


class GroupDetailsVar(_Model):
    Idle: bool = Field(description="No group instruction is running")
    InPosWaiting: bool


class GroupCmdVar(_Model):
    Vel: float = Field(description="Command interpolation velocity [command units/s]")
    AccDec: float = Field(description="Command interpolation acceleration/deceleration [command units/s²]")


class GroupCfgVar(_Model):
    GrpNo: int = Field(description="Axes group number (index into _MC_GRP[])")
    GrpEnable: str = Field(description="_eMC_GROUP_USE enumerator")
    ExecID: int


class GroupKinematicsVar(_Model):
    GrpType: str = Field(description="_eMC_GROUP_TYPE: _mcXY, _mcXYZ, _mcXYZU")
    Axis: list[int] = Field(description="Axis numbers of the logical axes A0–A3 (0 where unused)")


class GroupVariables(_Model):
    """`_sGROUP_REF`."""

    Status: GroupStatusVar
    Details: GroupDetailsVar
    Cmd: GroupCmdVar
    MFaultLvl: RefEvent
    Obsr: RefEvent
    Cfg: GroupCfgVar
    Kinematics: GroupKinematicsVar
    CmdPos: list[float] = Field(description="Command current positions of the composition axes A0, A1, …")


class GroupSummary(_Model):
    name: str
    number: int
    composition: str = Field(description="_eMC_GROUP_TYPE enumerator")
    axes: list[str] = Field(description="Composition axes for A0, A1, …")
    state: str = Field(description="The Status member that is TRUE: Disabled, Standby, Moving, Stopping, ErrorStop")
    ready: bool
    error_code: str = Field(description="MFaultLvl.Code, 0000 = none")
    kinematics: str | None = Field(description="Robot kinematics type (delta3) or null")
    cmd_pos: list[float]


class GroupDetail(_Model):
    config: AxesGroupConfig
    variables: GroupVariables
    cycle: int


# ---------------------------------------------------------------------------------------------- kinematics
class InverseKinIn(_Model):
    position: Vec3 | None = Field(None, description="TCP position [x, y, z] in the MCS [mm]")
    positions: list[Vec3] | None = Field(None, max_length=MAX_POINTS, description="A batch of TCP positions [mm]")

    @model_validator(mode="after")
    def _one_of(self) -> InverseKinIn:
        if (self.position is None) == (self.positions is None):
            raise ValueError("give either position (one point) or positions (a batch), not both")
        return self


class InverseKinOut(_Model):
    axes: list[float] | None = Field(None, description="Joint angles [A0, A1, A2] [deg] (for `position`)")
    axes_list: list[list[float]] | None = Field(None, description="Joint angles per point (for `positions`)")


class ForwardKinIn(_Model):
    axes: Vec3 | None = Field(None, description="Joint angles [A0, A1, A2] [deg]")
    axes_list: list[Vec3] | None = Field(None, max_length=MAX_POINTS, description="A batch of joint angles [deg]")

    @model_validator(mode="after")
    def _one_of(self) -> ForwardKinIn:
        if (self.axes is None) == (self.axes_list is None):
            raise ValueError("give either axes (one set of angles) or axes_list (a batch), not both")
        return self


class ForwardKinOut(_Model):
    position: list[float] | None = Field(None, description="TCP position [x, y, z] in the MCS [mm] (for `axes`)")
    positions: list[list[float]] | None = Field(None, description="TCP positions per set (for `axes_list`)")
    inside: bool | None = Field(None, description="The TCP position lies in the group's workspace (for `axes`)")
    inside_list: list[bool] | None = Field(None, description="Per TCP position: inside the workspace (`axes_list`)")
