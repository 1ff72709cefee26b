"""Cam tables: list, read, write (from nodes or points), delete, generate without saving, CSV import/export.

A write is a download of that one cam data variable (decision D45): the table is saved to the project folder
(`cams/<name>.csv` and the `cams` list of project.json, atomically) and the running controller's copy is replaced at
a cycle boundary without restarting it; refused with 409 while an instruction instance that uses the table is busy.
"""

from __future__ import annotations

import json
from typing import Annotated, Any

import numpy as np
from fastapi import APIRouter, Body, Depends, HTTPException, Path, Query, Request
from fastapi.responses import Response
from pydantic import BaseModel, Field, model_validator
from starlette.concurrency import run_in_threadpool

from ...controller.kernel import Controller
from ...controller.mc.cam.csvio import CamCsvError, format_cam_csv, parse_cam_csv
from ...controller.mc.cam.generate import generate
from ...controller.mc.cam.table import MAX_POINTS, CamTable
from ...modelbase import StrictModel
from ...project.cam_models import MAX_CAMS, CamDefinition, CamSource, error_code, error_path
from ...project.cams import (
    generate_table,
    remove_cam_file,
    table_from_points,
    write_cam_definitions,
    write_cam_file,
)
from ...project.checks import Issue
from ...project.io import ProjectError
from ..cam_views import CamGenerateIn, CamGenerateOut, generate_view, real_list
from ..deps import get_studio
from ..state import ConflictError, Studio

router = APIRouter(tags=["cams"])

MAX_CSV_BYTES = 4 * 1024 * 1024  # 65,535 points of 15-digit values fit in ~2.2 MB
MAX_JSON_BYTES = 8 * 1024 * 1024
# outputs that tell an instance is executing (MC_CamIn is Busy while it cams; others may show Active/InCam/InSync)
_BUSY_OUTPUTS = ("Busy", "Active", "InCam", "InSync", "InOperation")

CamName = Annotated[str, Path(pattern=r"^[A-Za-z_][A-Za-z0-9_]{0,62}$",
                              description="Cam data variable name (an identifier)")]


# ------------------------------------------------------------------------------------------------ models
class CamPoints(StrictModel):
    phase: list[float] = Field(max_length=MAX_POINTS, description="Master phases, from 0, strictly ascending")
    distance: list[float] = Field(max_length=MAX_POINTS, description="Slave distances, the first 0")


class CamIn(StrictModel):
    """A cam table definition and its data: from nodes (`source`) or from `points`; with neither, the current data
    are kept (only the description or size change)."""

    model_config = {"extra": "forbid"}

    description: str = Field("", max_length=500)
    size: int | None = Field(None, ge=2, le=MAX_POINTS + 1, description="MaxDataNumber; null = exactly the points")
    source: CamSource | None = Field(None, description="Cam property and nodes: the data are generated from them")
    points: CamPoints | None = Field(None, description="The cam data as points (start point (0, 0) included)")

    @model_validator(mode="after")
    def _one_kind(self) -> CamIn:
        if self.source is not None and self.points is not None:
            raise ValueError("give either source (nodes) or points, not both")
        return self


class CamInfo(BaseModel):
    name: str
    description: str
    size: int | None = Field(description="MaxDataNumber as defined (null = exactly the points)")
    max_data_number: int = Field(description="Elements of the cam data variable")
    point_count: int = Field(description="Valid cam data: start point to end point")
    end_point_index: int
    phase_end: float
    distance_end: float
    distance_min: float
    distance_max: float
    generated: bool = Field(description="Made from nodes (the definition keeps its source)")
    nodes: int = Field(description="Number of cam nodes of the source (0 when imported)")
    in_use: list[str] = Field(description="Busy instruction instances that use the table (it cannot change then)")


class CamOut(CamInfo):
    source: CamSource | None
    saved: bool = Field(description="The project folder holds this state (false for a studio without a folder)")
    phase: list[float] | None = Field(None, description="Valid cam data: phases (REAL values, shortest decimals)")
    distance: list[float] | None = Field(None, description="Valid cam data: distances")


class CamDeleted(BaseModel):
    name: str
    saved: bool


# ------------------------------------------------------------------------------------------------ helpers
def _limit_body(request: Request) -> None:
    length = request.headers.get("content-length")
    if length is not None and length.isdigit() and int(length) > MAX_JSON_BYTES:
        raise HTTPException(status_code=413, detail=f"request body larger than {MAX_JSON_BYTES // (1024 * 1024)} MB")


def _users(c: Controller, name: str) -> list[str]:
    out = []
    for fid, entry in c.program.items():
        fb = entry.fb
        if fb.inp.get("CamTable") == name and any(fb.out.get(k) is True for k in _BUSY_OUTPUTS):
            out.append(f"{fb.DEF.name} #{fid}")
    return out


def _info(c: Controller, name: str, *, full: bool = False, saved: bool = False,
          points: bool = False) -> CamInfo | CamOut:
    cam = next(d for d in c.project.cams if d.name == name)
    table = c.cams[name]
    p, d = table.valid()
    d64 = d.astype(float)
    base: dict[str, Any] = dict(
        name=name, description=cam.description, size=cam.size, max_data_number=table.max_data_number,
        point_count=int(p.size), end_point_index=int(p.size) - 1, phase_end=float(real_list(p[-1:])[0]),
        distance_end=float(real_list(d[-1:])[0]), distance_min=float(d64.min()), distance_max=float(d64.max()),
        generated=cam.source is not None, nodes=len(cam.source.nodes) if cam.source else 0, in_use=_users(c, name))
    if not full:
        return CamInfo(**base)
    return CamOut(**base, source=cam.source, saved=saved, phase=real_list(p) if points else None,
                  distance=real_list(d) if points else None)


def _get(c: Controller, name: str) -> CamDefinition:
    cam = next((d for d in c.project.cams if d.name == name), None)
    if cam is None or name not in c.cams:
        raise HTTPException(status_code=404, detail=f"no cam table named {name!r}")
    return cam


def _install(studio: Studio, name: str, cam: CamDefinition | None, table: CamTable | None) -> bool:
    """Download one cam data variable (or remove it with cam = None) into the running controller and save it to
    the project folder. Returns whether it was saved."""

    def apply(c: Controller) -> list[CamDefinition]:
        users = _users(c, name)
        if users:
            raise ConflictError(f"cam table {name!r} is used by {', '.join(users)}: stop and delete those instances "
                                "before changing it")
        defs = [d for d in c.project.cams if d.name != name]
        old = next((i for i, d in enumerate(c.project.cams) if d.name == name), len(defs))
        if cam is not None and table is not None:
            defs.insert(old, cam)
            c.cams[name] = table
            c.mc.cam_tables[name] = table.copy()
        else:
            c.cams.pop(name, None)
            c.mc.cam_tables.pop(name, None)
        c.project = c.project.model_copy(update={"cams": defs})
        return defs

    if cam is not None and len(studio.project.cams) >= MAX_CAMS and all(d.name != name for d in studio.project.cams):
        raise ProjectError("too many cam tables", [Issue("name", f"a project holds at most {MAX_CAMS} cam tables")])
    defs = studio.runner.call(apply)
    if studio.project_dir is None:
        return False
    with studio.lock:
        if table is not None:
            write_cam_file(studio.project_dir, name, table)
        studio.saved_text = write_cam_definitions(studio.project_dir, studio.saved_text, defs)
        if table is None:
            remove_cam_file(studio.project_dir, name)
    return True


def _saved(studio: Studio, c: Controller, name: str) -> bool:
    """The project folder holds the table as it is (its definition is the saved one; data change only with it)."""
    if studio.project_dir is None:
        return False
    saved = json.loads(studio.saved_text).get("cams", [])
    cam = next(d for d in c.project.cams if d.name == name)
    return cam.model_dump(mode="json") in saved


def _check_name_free(studio: Studio, name: str) -> None:
    clash = next((d.name for d in studio.project.cams if d.name.lower() == name.lower() and d.name != name), None)
    if clash is not None:
        raise ProjectError("the name is taken", [Issue("name", f"{name!r} differs from the cam table {clash!r} only "
                                                               "in case (their data files would collide)")])


# ------------------------------------------------------------------------------------------------ routes
@router.get("/cams", response_model=list[CamInfo], summary="The project's cam tables with their size and extent")
def list_cams(studio: Studio = Depends(get_studio)) -> list[CamInfo]:
    return studio.runner.call(lambda c: [_info(c, d.name) for d in c.project.cams if d.name in c.cams])


@router.post("/cams/generate", response_model=CamGenerateOut, dependencies=[Depends(_limit_body)],
             summary="MC_GenerateCamTable without saving: the profile, its characteristics and continuity",
             description="Generates the cam data from the property and nodes as the instruction does and answers the "
             "slave's distance, velocity, acceleration and jerk (from the laws, at the master velocity), the "
             "characteristic values per segment and for the whole table (dimensionless and in command units) and "
             "the jumps at segment boundaries. A generation error is a 422 naming the member, with the manual's "
             "ErrorID as `code` (e.g. `nodes[2].Phase`, 5740).",
             responses={422: {"description": "Invalid input or a generation error (ErrorID in `code`)"}})
def post_generate(body: CamGenerateIn) -> CamGenerateOut:
    source = body
    if body.phase_pitch is not None:
        source = body.model_copy(update={"nodes": [n.model_copy(update={"PhasePitch": body.phase_pitch})
                                                   for n in body.nodes]})
    nodes, prop = source.inputs()
    res = generate(nodes, prop, table_size=body.size or MAX_POINTS)
    if res.error is not None:
        raise ProjectError(f"MC_GenerateCamTable ends with {res.error.ErrorID:04X}", [Issue(
            error_path(res.error), res.error.message or f"error {res.error.ErrorID:04X}", error_code(res.error))])
    try:
        return generate_view(res, source, body.max_points)
    except ValueError as err:
        raise ProjectError("the profile cannot be computed", [Issue("nodes", str(err))]) from None


@router.get("/cams/{name}", response_model=CamOut, summary="One cam table: definition, source and points",
            responses={404: {"description": "No such cam table"}})
def get_cam(name: CamName, points: bool = Query(True, description="Include the cam data points"),
            studio: Studio = Depends(get_studio)) -> CamOut:
    def view(c: Controller) -> CamOut:
        _get(c, name)
        return _info(c, name, full=True, saved=_saved(studio, c, name), points=points)  # type: ignore[return-value]

    return studio.runner.call(view)


@router.put("/cams/{name}", response_model=CamOut, dependencies=[Depends(_limit_body)],
            summary="Create or replace a cam table (from nodes or points) and save it to the project",
            description="With `source` the data are generated by MC_GenerateCamTable's rules (an error is a 422 "
            "naming the member, e.g. `source.nodes[1].Phase`, with the ErrorID as `code`); with `points` they are "
            "checked like a CSV file (`points.phase[3]`). Saved atomically to `cams/<name>.csv` and project.json; "
            "the running controller's copy is replaced at a cycle boundary without a restart (D45); 409 while a busy "
            "instruction instance uses the table.",
            responses={409: {"description": "An instance that uses the table is busy"}, 413: {"description":
                                                                                              "Body too large"}})
def put_cam(name: CamName, body: CamIn = Body(...), studio: Studio = Depends(get_studio)) -> CamOut:
    _check_name_free(studio, name)
    if body.source is not None:
        table = generate_table(body.source, body.size)
    elif body.points is not None:
        table = table_from_points(body.points.phase, body.points.distance, body.size)
    else:
        current = studio.controller.cams.get(name)
        if current is None:
            raise ProjectError("no cam data", [Issue("source", f"cam table {name!r} does not exist: give its source "
                                                               "(nodes) or points")])
        p, d = current.valid()
        table = table_from_points(p, d, body.size)
    cam = CamDefinition(name=name, description=body.description, size=body.size,
                        source=body.source if body.points is None else None)
    if body.source is None and body.points is None:
        old = next((x for x in studio.project.cams if x.name == name), None)
        cam = cam.model_copy(update={"source": old.source if old else None})
    saved = _install(studio, name, cam, table)
    return studio.runner.call(lambda c: _info(c, name, full=True, saved=saved))  # type: ignore[return-value]


@router.delete("/cams/{name}", response_model=CamDeleted, summary="Delete a cam table (and its file)",
               responses={404: {"description": "No such cam table"}, 409: {"description": "In use"}})
def delete_cam(name: CamName, studio: Studio = Depends(get_studio)) -> CamDeleted:
    studio.runner.call(lambda c: _get(c, name))
    saved = _install(studio, name, None, None)
    return CamDeleted(name=name, saved=saved)


@router.get("/cams/{name}/csv", summary="Export the cam data as CSV (phase,distance)",
            response_class=Response, responses={200: {"content": {"text/csv": {}}}, 404: {"description": "No such cam "
                                                                                                          "table"}})
def get_cam_csv(name: CamName, studio: Studio = Depends(get_studio)) -> Response:
    def view(c: Controller) -> tuple[np.ndarray, np.ndarray]:
        _get(c, name)
        p, d = c.cams[name].valid()
        return p.copy(), d.copy()

    p, d = studio.runner.call(view)
    text = format_cam_csv(p, d, comment=f"{name}: cam table of MC Studio, {p.size} points (phase,distance)")
    return Response(text, media_type="text/csv; charset=utf-8",
                    headers={"Content-Disposition": f'attachment; filename="{name}.csv"'})


_CSV_BODY = {"requestBody": {"required": True, "content": {
    "text/csv": {"schema": {"type": "string"}},
    "text/plain": {"schema": {"type": "string"}},
    "multipart/form-data": {"schema": {"type": "object", "properties": {"file": {"type": "string", "format":
                                                                                 "binary"}}, "required": ["file"]}},
}}}


async def _csv_text(request: Request) -> str:
    length = request.headers.get("content-length")
    if length is not None and length.isdigit() and int(length) > MAX_CSV_BYTES + 64 * 1024:
        raise HTTPException(status_code=413, detail=f"cam CSV files are limited to {MAX_CSV_BYTES // 1024 ** 2} MB")
    ctype = request.headers.get("content-type", "")
    if ctype.startswith("multipart/form-data"):
        form = await request.form(max_files=1, max_fields=4)
        upload = form.get("file")
        if upload is None or isinstance(upload, str):
            raise HTTPException(status_code=422, detail=[{"loc": ["body", "file"], "type": "missing",
                                                          "msg": "upload the CSV file as the form field 'file'"}])
        data = await upload.read(MAX_CSV_BYTES + 1)
    else:
        chunks, n = [], 0
        async for chunk in request.stream():
            n += len(chunk)
            if n > MAX_CSV_BYTES:
                break
            chunks.append(chunk)
        data = b"".join(chunks) if n <= MAX_CSV_BYTES else b"x" * (MAX_CSV_BYTES + 1)
    if len(data) > MAX_CSV_BYTES:
        raise HTTPException(status_code=413, detail=f"cam CSV files are limited to {MAX_CSV_BYTES // 1024 ** 2} MB")
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as err:
        raise HTTPException(status_code=422, detail=[{"loc": ["body"], "type": "csv_error", "line": 0,
                                                      "msg": f"not UTF-8 text ({err.reason} at byte {err.start})"}]
                            ) from None


async def _import_csv(name: str, request: Request, size: int | None, description: str | None,
                      studio: Studio) -> CamOut:
    text = await _csv_text(request)
    # the rest waits for the kernel thread (a cycle boundary) and writes files: not on the event loop
    return await run_in_threadpool(_apply_csv, name, text, size, description, studio)


def _apply_csv(name: str, text: str, size: int | None, description: str | None, studio: Studio) -> CamOut:
    try:
        p, d = parse_cam_csv(text)
    except CamCsvError as err:
        raise HTTPException(status_code=422, detail=[{"loc": ["body"], "type": "csv_error", "line": pr.line,
                                                      "msg": str(pr)} for pr in err.problems]) from None
    _check_name_free(studio, name)
    old = next((x for x in studio.project.cams if x.name == name), None)
    if size is None and old is not None and old.size is not None and old.size >= p.size:
        size = old.size
    table = table_from_points(p, d, size)
    cam = CamDefinition(name=name, description=description if description is not None else
                        (old.description if old else ""), size=size)
    saved = _install(studio, name, cam, table)
    return studio.runner.call(lambda c: _info(c, name, full=True, saved=saved))  # type: ignore[return-value]


_IMPORT_DOC = dict(
    response_model=CamOut, openapi_extra=_CSV_BODY,
    description="The body is the CSV text (`text/csv`) or a multipart upload (field `file`), at most 4 MB; the "
    "format is docs/cams.md \"CSV format\". Each problem is a 422 entry with its `line`. The table (created or "
    "replaced) loses its source: the data are the file's. Saved and downloaded like PUT /cams/{name}.",
    responses={409: {"description": "In use"}, 413: {"description": "File too large"},
               422: {"description": "Not a valid cam CSV"}})


@router.put("/cams/{name}/csv", summary="Import cam data from CSV (create or replace the table)", **_IMPORT_DOC)
async def put_cam_csv(request: Request, name: CamName,
                      size: int | None = Query(None, ge=2, le=MAX_POINTS + 1, description="MaxDataNumber (default: "
                                               "the table's size if the points fit, else exactly the points)"),
                      description: str | None = Query(None, max_length=500),
                      studio: Studio = Depends(get_studio)) -> CamOut:
    return await _import_csv(name, request, size, description, studio)


@router.post("/cams/{name}/csv", summary="Import cam data from CSV (same as PUT)", **_IMPORT_DOC)
async def post_cam_csv(request: Request, name: CamName,
                       size: int | None = Query(None, ge=2, le=MAX_POINTS + 1, description="MaxDataNumber"),
                       description: str | None = Query(None, max_length=500),
                       studio: Studio = Depends(get_studio)) -> CamOut:
    return await _import_csv(name, request, size, description, studio)
