"""Cam table definitions in the project document (`project.json` → `cams`).

A cam table is a cam data variable (`ARRAY[0..N] OF _sMC_CAM_REF`, docs/cams.md). The project keeps its data as a
CSV file `cams/<name>.csv` (the points the controller uses, decision D36) and its definition here: the name, the
table size (`MaxDataNumber`) and, for a table made in the cam editor, the generation source — the cam property and
cam nodes of MC_GenerateCamTable with the manual's member names — so the editor can re-open the nodes.

The models check types and plain ranges; the manual's rules for the nodes (the ranges of §5.4.1/§5.4.2, ascending
phases, the point count) are checked by `check_cams` with MC_GenerateCamTable's own `plan()`, and reported with the
JSON path of the member and the ErrorID it would give (`cams[0].source.nodes[2].Phase [5740]`).
"""

from __future__ import annotations

import re

from pydantic import ConfigDict, Field, field_validator

from ..controller.mc.cam.generate import MAX_NODE_ELEMENTS, NODE_CODES, PROPERTY_CODES, GenerateError, plan
from ..controller.mc.cam.generate import _sMC_CAM_NODE as CamNodeData
from ..controller.mc.cam.generate import _sMC_CAM_PROPERTY as CamPropertyData
from ..controller.mc.cam.table import MAX_POINTS
from ..controller.mc.enums import _eMC_CAM_CURVE
from ..modelbase import StrictModel
from .enumtypes import ManualEnum

__all__ = ["CAM_FOLDER", "MAX_CAMS", "CamDefinition", "CamNode", "CamProperty", "CamSource", "check_cams",
           "error_code", "error_path", "plan_source"]

CAM_FOLDER = "cams"
MAX_CAMS = 256
REAL_MAX = 3.4028234663852886e38
REAL_MIN_NORMAL = 1.1754943508222875e-38  # the smallest positive normal REAL
_IDENT = re.compile(r"^[A-Za-z_][A-Za-z0-9_]{0,62}$")


class _Strict(StrictModel):
    model_config = ConfigDict(extra="forbid", validate_assignment=True, allow_inf_nan=False)


class CamProperty(_Strict):
    """`_sMC_CAM_PROPERTY` (§5.4.1): the conditions MC_GenerateCamTable assumes for the polynomial curves."""

    InitVel: float = Field(0.0, ge=-REAL_MAX, le=REAL_MAX, description="Initial velocity [command units/s]: the "
                           "velocity at the start of a cubic/quintic first segment")
    InitAcc: float = Field(0.0, ge=-REAL_MAX, le=REAL_MAX, description="Initial acceleration [command units/s²] of "
                           "a quintic first segment")
    CycleTime: float = Field(1.0, ge=0.001, le=REAL_MAX, description="Cycle time [s]: one pass of the master over "
                             "the table, so the master velocity is the last node's Phase / CycleTime")


class CamNode(_Strict):
    """`_sMC_CAM_NODE` (§5.4.2): the end point of one curve segment, reached from the previous node (or (0, 0))."""

    Phase: float = Field(gt=0, le=REAL_MAX, description="Master phase at the end of the segment [command units of "
                         "the master]; ascending, ≥ 0.001")
    Distance: float = Field(0.0, ge=-REAL_MAX, le=REAL_MAX, description="Slave distance at the end of the segment "
                            "[command units of the slave]; ignored for _mcConstantLine (the dwell keeps the previous "
                            "node's distance)")
    Curve: ManualEnum(_eMC_CAM_CURVE) = Field(  # type: ignore[valid-type]
        _eMC_CAM_CURVE._mcStraightLine, description="Curve law of the segment (_eMC_CAM_CURVE)")
    ConnectingVelEnable: bool = Field(False, description="Cubic/quintic: use ConnectingVel as the end velocity")
    ConnectingVel: float = Field(0.0, ge=-REAL_MAX, le=REAL_MAX, description="End velocity [command units/s]")
    ConnectingAccEnable: bool = Field(False, description="Quintic: use ConnectingAcc as the end acceleration")
    ConnectingAcc: float = Field(0.0, ge=-REAL_MAX, le=REAL_MAX, description="End acceleration [command units/s²]")
    PhasePitch: float = Field(0.1, ge=0.001, le=REAL_MAX, description="Phase interval of the generated cam data in "
                              "this segment [command units of the master]")

    def data(self) -> CamNodeData:
        return CamNodeData(Phase=self.Phase, Distance=self.Distance, Curve=int(self.Curve),
                           ConnectingVelEnable=self.ConnectingVelEnable, ConnectingVel=self.ConnectingVel,
                           ConnectingAccEnable=self.ConnectingAccEnable, ConnectingAcc=self.ConnectingAcc,
                           PhasePitch=self.PhasePitch)


class CamSource(_Strict):
    """How a cam table was made in the cam editor: MC_GenerateCamTable's inputs, plus the editor's view settings."""

    property: CamProperty = Field(default_factory=CamProperty, description="CamProperty")
    nodes: list[CamNode] = Field(min_length=1, max_length=MAX_NODE_ELEMENTS, description="CamNodes, in order")
    master_velocity: float | None = Field(
        None, ge=REAL_MIN_NORMAL, le=REAL_MAX, description="Master velocity for the characteristic values [master "
        "units/s], a positive REAL; null = the last node's Phase / CycleTime")
    periodic: bool = Field(False, description="Check continuity across the wrap to the next cycle (a periodic cam)")

    def inputs(self) -> tuple[list[CamNodeData], CamPropertyData]:
        p = self.property
        return ([n.data() for n in self.nodes],
                CamPropertyData(InitVel=p.InitVel, InitAcc=p.InitAcc, CycleTime=p.CycleTime))


class CamDefinition(_Strict):
    """One cam table of the project: its data are in `cams/<name>.csv`."""

    name: str = Field(description="Cam data variable name (an identifier, unique); the data file is cams/<name>.csv")
    description: str = Field("", max_length=500)
    size: int | None = Field(
        None, ge=2, le=MAX_POINTS + 1, description="MaxDataNumber: elements of the cam data variable (the points are "
        "padded with zeros, so the element after the last point ends the table); null = exactly the points")
    source: CamSource | None = Field(
        None, description="Cam property and nodes the data were generated from (the cam editor); null = the data were "
        "imported or written as points")

    @field_validator("name")
    @classmethod
    def _name_is_identifier(cls, v: str) -> str:
        if not _IDENT.match(v):
            raise ValueError("must be an identifier: a letter or _, then letters, digits or _ (max 63)")
        return v


_MEMBER_OF_CODE = {**{v: k for k, v in NODE_CODES.items()}}
_PROPERTY_OF_CODE = {v: k for k, v in PROPERTY_CODES.items()}


def error_path(err: GenerateError) -> str:
    """The member a MC_GenerateCamTable error is about, as a path relative to the source ("nodes[2].Phase")."""
    m = err.ErrorNodePointIndex
    if err.ErrorID == 0x573C:
        return f"property.{_PROPERTY_OF_CODE.get(err.ErrorParameterCode, 'CycleTime')}"
    if err.ErrorID == 0x573D:
        return f"nodes[{m}].{_MEMBER_OF_CODE.get(err.ErrorParameterCode, 'Phase')}"
    if err.ErrorID in (0x573F, 0x5740):
        return f"nodes[{m}].Phase"
    if err.ErrorID == 0x5742:
        return f"nodes[{m}].Distance"
    if err.ErrorID == 0x5741:
        return f"nodes[{m}].PhasePitch"
    return "nodes"


def error_code(err: GenerateError) -> str:
    """ "573D/0001" (with the ErrorParameterCode where the error has one) or "5740"."""
    if err.ErrorID in (0x573C, 0x573D):
        return f"{err.ErrorID:04X}/{err.ErrorParameterCode:04X}"
    return f"{err.ErrorID:04X}"


def plan_source(source: CamSource, size: int | None) -> GenerateError | int:
    """Check a source as MC_GenerateCamTable would for a table of `size` elements (default the largest):
    the point count Tcd it generates, or the error (5742 needs sampling and is not checked here)."""
    nodes, prop = source.inputs()
    profile = plan(nodes, prop)
    if isinstance(profile, GenerateError):
        return profile
    limit = min(size or MAX_POINTS, MAX_POINTS)
    total = 1
    for s in profile.segments:
        total += s.count
        if total > limit:
            return GenerateError(0x5741, 0, s.node, f"CamNodes[{s.node}] brings the cam data to {total} points: "
                                                     f"the table holds {size or MAX_POINTS} (at most {MAX_POINTS})")
    return total


def check_cams(cams: list[CamDefinition]) -> list[tuple[str, str, str | None]]:
    """Project rules for the cam definitions: unique names, generation sources MC_GenerateCamTable accepts.
    (path, message, ErrorID or None) per problem."""
    out: list[tuple[str, str, str | None]] = []
    seen: dict[str, int] = {}
    for i, cam in enumerate(cams):
        base = f"cams[{i}]"
        key = cam.name.lower()  # the data files must not collide on a case-insensitive file system
        if key in seen:
            out.append((f"{base}.name", f"duplicate cam table name {cam.name!r} (also cams[{seen[key]}], names are "
                                        "compared without case)", None))
        seen.setdefault(key, i)
        if cam.source is not None:
            res = plan_source(cam.source, cam.size)
            if isinstance(res, GenerateError):
                out.append((f"{base}.source.{error_path(res)}", res.message, error_code(res)))
    return out
