"""Axes groups: list, `_sGROUP_REF` variables, settings, and the Delta3 kinematics of a robot group (api.md "Axes and
axes groups").

The variables come from the latest published snapshot (`mc["groups"]`, written by `AxesGroup.capture`). The
kinematics endpoints compute with the running group's Delta3 parameters and workspace (`controller/mc/kinematics`,
docs/robot.md) without touching the controller: angles in degrees (ACS), positions in mm (MCS).
"""

from __future__ import annotations

from typing import Any, NoReturn

import numpy as np
from fastapi import APIRouter, Depends, HTTPException

from ...controller.mc.kinematics import Status, forward, inverse
from ...project.io import parse_project
from ...project.models import AxesGroupConfig, Delta3KinematicsConfig
from ..deps import get_studio
from ..group_models import (
    ForwardKinIn,
    ForwardKinOut,
    GroupDetail,
    GroupSummary,
    GroupVariables,
    InverseKinIn,
    InverseKinOut,
)
from ..state import Studio

router = APIRouter(prefix="/groups", tags=["groups"])

MAX_REPORTED = 20  # at most this many offending points are listed in a 422
_NOT_FOUND = {404: {"description": "No such (used) axes group"}}
_KIN_ERRORS = {
    **_NOT_FOUND,
    409: {"description": "The group has no robot kinematics"},
    422: {"description": "A point outside the workspace or without a kinematic solution; `loc` names it"},
}


def _views(studio: Studio) -> tuple[int, dict[str, dict[str, Any]]]:
    snap = studio.runner.snapshot
    return snap.cycle, {g["name"]: g for g in snap.mc.get("groups", ())}


def _not_found(name: str) -> NoReturn:
    raise HTTPException(status_code=404, detail=f"no used axes group named {name!r} in this project")


def _state(view: dict[str, Any]) -> str:
    return next(k for k, flag in view["Status"].items() if flag and k != "Ready")


def _variables(view: dict[str, Any]) -> GroupVariables:
    return GroupVariables(**{k: v for k, v in view.items() if k != "name"})


@router.get("", response_model=list[GroupSummary], summary="All used axes groups with their state")
def list_groups(studio: Studio = Depends(get_studio)) -> list[GroupSummary]:
    _, views = _views(studio)
    out = []
    for g in studio.controller.mc.groups:
        v = views.get(g.name)
        if v is None:
            continue
        cfg = g.config
        out.append(GroupSummary(
            name=g.name, number=g.number, composition=cfg.composition.name, axes=list(cfg.axes), state=_state(v),
            ready=v["Status"]["Ready"], error_code=v["MFaultLvl"]["Code"],
            kinematics=cfg.kinematics.type if cfg.kinematics is not None else None, cmd_pos=list(v["CmdPos"]),
        ))
    return out


@router.get("/{name}", response_model=GroupDetail, summary="Axes group settings and its `_sGROUP_REF` variables",
            responses=_NOT_FOUND)
def get_group(name: str, studio: Studio = Depends(get_studio)) -> GroupDetail:
    cycle, views = _views(studio)
    cfg = studio.project.group(name)
    if cfg is None or name not in views:
        _not_found(name)
    return GroupDetail(config=cfg, variables=_variables(views[name]), cycle=cycle)


@router.put(
    "/{name}/config",
    response_model=AxesGroupConfig,
    summary="Replace the settings of one axes group",
    description="Composition, composition axes, operation settings (limits), Delta3 kinematics and workspace. "
    "Validated like the whole project (paths in `detail` are relative to the project document); applying restarts "
    "the controller at cycle 0 and is refused with 409 while an axis moves.",
    responses={404: {"description": "No such axes group"}, 409: {"description": "Axes are moving"}},
)
def put_group_config(name: str, body: AxesGroupConfig, studio: Studio = Depends(get_studio)) -> AxesGroupConfig:
    project = studio.project
    idx = next((i for i, g in enumerate(project.groups) if g.name == name), None)
    if idx is None:
        raise HTTPException(status_code=404, detail=f"no axes group named {name!r} in this project")
    doc = project.model_dump(mode="json")
    doc["groups"][idx] = body.model_dump(mode="json")
    new = parse_project(doc)
    studio.apply_project(new)
    return new.groups[idx]


# ---------------------------------------------------------------------------------------------- kinematics
def _kinematics(studio: Studio, name: str) -> Delta3KinematicsConfig:
    group = studio.controller.mc.groups_by_name.get(name)
    if group is None:
        _not_found(name)
    kin = group.kinematics
    if kin is None:
        raise HTTPException(status_code=409, detail=[{
            "loc": ["path", "name"], "type": "no_kinematics",
            "msg": f"{name} has no robot kinematics; set `kinematics` with PUT /api/v1/groups/{name}/config",
        }])
    return kin


def _reject(bad: list[dict[str, Any]]) -> NoReturn:
    more = len(bad) - MAX_REPORTED
    detail = bad[:MAX_REPORTED]
    if more > 0:
        detail.append({"loc": ["body"], "type": "value_error", "msg": f"… and {more} more points"})
    raise HTTPException(status_code=422, detail=detail)


def _loc(field: str, single: bool, k: int) -> list[Any]:
    return ["body", field] if single else ["body", field, k]


@router.post(
    "/{name}/kinematics/inverse",
    response_model=InverseKinOut,
    summary="Inverse kinematics: TCP positions [mm, MCS] → joint angles A0–A2 [deg]",
    description="With the group's Delta3 parameters (Rf, Lf, Rm, Lm, θ). A point outside the workspace (shrunk by "
    "0.1 mm, docs/robot.md) or without a solution (570F) is a 422 naming the point; nothing is computed then.",
    responses=_KIN_ERRORS,
)
def inverse_kin(name: str, body: InverseKinIn, studio: Studio = Depends(get_studio)) -> InverseKinOut:
    kin = _kinematics(studio, name)
    single = body.position is not None
    field = "position" if single else "positions"
    pts = np.array([body.position] if single else body.positions, dtype=float).reshape(-1, 3)
    res = inverse(kin.params(), pts, workspace=kin.workspace_obj())
    bad = []
    for k in np.flatnonzero(res.status != Status.OK):
        st = Status(int(res.status[k]))
        p = ", ".join(f"{v:g}" for v in pts[k])
        if st == Status.OUTSIDE_WORKSPACE:
            bad.append({"loc": _loc(field, single, int(k)), "type": "outside_workspace",
                        "msg": f"[{p}] mm is outside the workspace of {name}"})
        else:
            bad.append({"loc": _loc(field, single, int(k)), "type": "kinematics_error", "code": "570F",
                        "msg": f"[{p}] mm cannot be reached by {name} (no inverse kinematics solution, 570F)"})
    if bad:
        _reject(bad)
    angles = [[float(v) for v in row] for row in res.angles]
    return InverseKinOut(axes=angles[0]) if single else InverseKinOut(axes_list=angles)


@router.post(
    "/{name}/kinematics/forward",
    response_model=ForwardKinOut,
    summary="Forward kinematics: joint angles A0–A2 [deg] → TCP positions [mm, MCS]",
    description="With the group's Delta3 parameters. Angles without a solution (570F) are a 422 naming them; a "
    "position outside the workspace is returned with `inside` FALSE.",
    responses=_KIN_ERRORS,
)
def forward_kin(name: str, body: ForwardKinIn, studio: Studio = Depends(get_studio)) -> ForwardKinOut:
    kin = _kinematics(studio, name)
    single = body.axes is not None
    field = "axes" if single else "axes_list"
    q = np.array([body.axes] if single else body.axes_list, dtype=float).reshape(-1, 3)
    res = forward(kin.params(), q)
    bad = []
    for k in np.flatnonzero(res.status != Status.OK):
        a = ", ".join(f"{v:g}" for v in q[k])
        bad.append({"loc": _loc(field, single, int(k)), "type": "kinematics_error", "code": "570F",
                    "msg": f"[{a}] deg: no forward kinematics solution for {name} (570F)"})
    if bad:
        _reject(bad)
    inside = kin.workspace_obj().contains(res.position)
    pos = [[float(v) for v in row] for row in res.position]
    flags = [bool(v) for v in np.atleast_1d(inside)]
    if single:
        return ForwardKinOut(position=pos[0], inside=flags[0])
    return ForwardKinOut(positions=pos, inside_list=flags)
