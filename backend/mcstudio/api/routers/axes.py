"""Axes: list, `_sAXIS_REF` variables, and settings (api.md "Axes and axes groups")."""

from __future__ import annotations

from fastapi import APIRouter, Depends, HTTPException

from ...project.io import parse_project
from ...project.models import AxisConfig
from ..deps import get_studio
from ..models import AxisDetail, AxisSummary, AxisVariables
from ..state import Studio

router = APIRouter(prefix="/axes", tags=["axes"])


@router.get("", response_model=list[AxisSummary], summary="All used axes with live command/actual values")
def list_axes(studio: Studio = Depends(get_studio)) -> list[AxisSummary]:
    return studio.axis_summaries(studio.runner.snapshot)


@router.get("/{name}", response_model=AxisDetail, summary="Axis settings and its `_sAXIS_REF` variables",
            responses={404: {"description": "No such axis"}})
def get_axis(name: str, studio: Studio = Depends(get_studio)) -> AxisDetail:
    snap = studio.runner.snapshot
    cfg = studio.project.axis(name)
    views = dict(studio.axis_views(snap, [name]))
    if cfg is None or name not in views:
        raise HTTPException(status_code=404, detail=f"no axis named {name!r} in this project")
    return AxisDetail(config=cfg, variables=AxisVariables(**views[name]), cycle=snap.cycle)


@router.put(
    "/{name}/config",
    response_model=AxisConfig,
    summary="Replace the settings of one axis",
    description="Validated like the whole project (paths in `detail` are relative to the project document); applying "
    "restarts the controller at cycle 0 and is refused with 409 while an axis moves.",
    responses={404: {"description": "No such axis"}, 409: {"description": "Axes are moving"}},
)
def put_axis_config(name: str, body: AxisConfig, studio: Studio = Depends(get_studio)) -> AxisConfig:
    project = studio.project
    idx = next((i for i, a in enumerate(project.axes) if a.name == name), None)
    if idx is None:
        raise HTTPException(status_code=404, detail=f"no axis named {name!r} in this project")
    doc = project.model_dump(mode="json")
    doc["axes"][idx] = body.model_dump(mode="json")
    new = parse_project(doc)
    studio.apply_project(new)
    return new.axes[idx]
