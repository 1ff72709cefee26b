"""The project document: read, replace (validated), save atomically, save-as, revert, schema, templates and the projects
folder (docs/project-format.md)."""

from __future__ import annotations

from typing import Any

from fastapi import APIRouter, Body, Depends, HTTPException

from ...project.folders import find_template, list_templates
from ...project.io import ProjectError, load_project, parse_project
from ...project.models import PROJECT_FILE, Project
from ..deps import get_studio
from ..models import NewProjectIn, OpenProjectIn, ProjectInfo, ProjectTemplateOut, SaveAsIn, SaveOut
from ..state import Studio

router = APIRouter(tags=["project"])

_REFUSED_FILE = {
    422: {"description": "The project on disk is corrupt (bad JSON, invalid fields, missing or corrupt cam data): "
                         "`detail` lists every problem with its path in the file; the open project stays open and the "
                         "files are not modified"},
    409: {"description": "Axes are moving"},
}


def _name_error(field: list[str | int], msg: str) -> HTTPException:
    return HTTPException(status_code=422, detail=[{"loc": field, "msg": msg, "type": "value_error"}])


def _file_refused(err: ProjectError, field: list[str | int]) -> HTTPException:
    """A project on disk that cannot be opened: the summary, then one entry per problem with its path in the file."""
    detail: list[dict[str, Any]] = [{"loc": field, "msg": err.message, "type": "project_file_error"}]
    for i in err.issues:
        detail.append({"loc": field, "msg": f"{i.path}: {i.message}" + (f" [{i.code}]" if i.code else ""),
                       "type": "project_file_error", "path": i.path, "code": i.code})
    return HTTPException(status_code=422, detail=detail)


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


@router.post(
    "/project/save-as", response_model=SaveOut, summary="Save the project as a new folder and continue in it",
    description="Writes the running project (with its unsaved changes), its cam data and the current folder's other "
    "files (ESI files) to a new folder of the projects root, built under a hidden name and renamed into place; the "
    "studio then works in the new folder. An existing name is refused (409) unless `overwrite`.",
    responses={409: {"description": "A project of that name exists (and overwrite is false)"},
               422: {"description": "The name breaks the folder-name rules (decision D110)"}},
)
def save_project_as(body: SaveAsIn, studio: Studio = Depends(get_studio)) -> SaveOut:
    try:
        path = studio.save_as(body.name, overwrite=body.overwrite)
    except FileExistsError as err:
        raise HTTPException(status_code=409, detail=str(err)) from None
    except ValueError as err:
        raise _name_error(["body", "name"], str(err)) from None
    return SaveOut(path=str(path))


@router.post(
    "/project/revert", response_model=Project, summary="Reload the project from its folder, discarding unsaved changes",
    description="Like opening the project again: the controller restarts at cycle 0 with the saved document. "
    "Refused with 409 while an axis moves; if the saved file is corrupt nothing changes (422 listing the problems).",
    responses=_REFUSED_FILE,
)
def revert_project(studio: Studio = Depends(get_studio)) -> Project:
    try:
        return studio.revert()
    except ProjectError as err:
        raise _file_refused(err, [PROJECT_FILE]) from None


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
             responses={404: {"description": "No such project"}, **_REFUSED_FILE})
def open_project(body: OpenProjectIn, studio: Studio = Depends(get_studio)) -> Project:
    try:
        folder = studio.resolve_project_name(body.name)
    except ValueError as err:
        raise _name_error(["body", "name"], str(err)) from None
    if not (folder / PROJECT_FILE).is_file():
        raise HTTPException(status_code=404, detail=f"no project named {body.name!r} in the projects folder")
    try:
        return studio.open_folder(folder)
    except ProjectError as err:
        raise _file_refused(err, ["body", "name"]) from None


@router.get("/project-templates", response_model=list[ProjectTemplateOut],
            summary="Templates for a new project (decision D111)")
def project_templates() -> list[ProjectTemplateOut]:
    out = []
    for t in list_templates():
        try:
            p = load_project(t.folder)
        except ProjectError:
            continue  # a broken template is not offered (tests/project/test_folders.py keeps them valid)
        out.append(ProjectTemplateOut(name=t.name, title=p.name, description=p.description, axes=len(p.axes),
                                      groups=len(p.groups), cams=len(p.cams)))
    return out


@router.post(
    "/projects/new", response_model=Project, status_code=201, summary="Create a project from a template and open it",
    description="Copies the template into a new folder of the projects root (the document's name becomes the folder "
    "name) and opens it: the controller restarts at cycle 0 with it. 409 if the name exists or axes move (then "
    "nothing is created).",
    responses={409: {"description": "The name exists, or axes are moving"},
               422: {"description": "Bad name (D110) or unknown template"}},
)
def new_project(body: NewProjectIn, studio: Studio = Depends(get_studio)) -> Project:
    template = find_template(body.template)
    if template is None:
        names = ", ".join(t.name for t in list_templates())
        raise _name_error(["body", "template"], f"no template named {body.template!r} (templates: {names})")
    try:
        return studio.new_project(body.name, template)
    except FileExistsError as err:
        raise HTTPException(status_code=409, detail=str(err)) from None
    except ValueError as err:
        raise _name_error(["body", "name"], str(err)) from None
