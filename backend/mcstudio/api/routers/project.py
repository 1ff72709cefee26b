"""The project document: read, replace (validated), save atomically, schema, and the projects folder."""

from __future__ import annotations

from typing import Any

from fastapi import APIRouter, Body, Depends

from ...project.io import ProjectError, parse_project
from ...project.models import Project
from ..deps import get_studio
from ..models import OpenProjectIn, ProjectInfo, SaveOut
from ..state import Studio

router = APIRouter(tags=["project"])


@router.get("/project", response_model=Project, summary="The whole project document")
def get_project(studio: Studio = Depends(get_studio)) -> Project:
    return studio.project


@router.put(
    "/project",
    response_model=Project,
    summary="Validate and apply a project document",
    description="Every invalid field is listed in `detail` with its JSON path (`loc`, `path`). Applying restarts the "
    "controller at cycle 0 (like a download) and is refused with 409 while an axis moves. The document is not "
    "saved until POST /project/save.",
    responses={409: {"description": "Axes are moving"}},
)
def put_project(doc: dict[str, Any] = Body(..., description="Project document (project.json)"),
                studio: Studio = Depends(get_studio)) -> Project:
    project = parse_project(doc, studio.library)
    studio.apply_project(project)
    return project


@router.post("/project/save", response_model=SaveOut, summary="Save the project to its folder (atomic write)")
def save_project(studio: Studio = Depends(get_studio)) -> SaveOut:
    path = studio.save()
    return SaveOut(path=str(path))


@router.get("/project/schema", summary="JSON Schema of the project document")
def project_schema() -> dict[str, Any]:
    schema = Project.model_json_schema(mode="validation")
    schema["$id"] = "https://mcstudio.dev/schema/project-v1.json"
    schema["$schema"] = "https://json-schema.org/draft/2020-12/schema"
    return schema


@router.get("/projects", response_model=list[ProjectInfo], summary="Project folders under the projects root")
def list_projects(studio: Studio = Depends(get_studio)) -> list[ProjectInfo]:
    return [ProjectInfo(**p) for p in studio.list_projects()]


@router.post("/projects/open", response_model=Project, summary="Open a project folder by name",
             responses={404: {"description": "No such project"}, 409: {"description": "Axes are moving"}})
def open_project(body: OpenProjectIn, studio: Studio = Depends(get_studio)) -> Project:
    try:
        folder = studio.resolve_project_name(body.name)
    except ValueError as err:
        raise ProjectError(str(err)) from None
    if not (folder / "project.json").is_file():
        from fastapi import HTTPException

        raise HTTPException(status_code=404, detail=f"no project named {body.name!r} in the projects folder")
    return studio.open_project(body.name)
