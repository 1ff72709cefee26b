"""Load, validate and save project folders.

A project is a folder holding `project.json` (and, in later versions, cam data files). Loading reports every problem
with the JSON path of the field it concerns; saving is atomic: the new document is written to a temporary file in the
same folder, flushed and fsynced, the previous version is kept as `project.json.bak`, and the new file replaces the old
one with a single `rename`, so a crash leaves either the old or the new project, never a torn file.
"""

from __future__ import annotations

import json
import os
import tempfile
from collections.abc import Iterable, Sequence
from pathlib import Path
from typing import Any

from pydantic import ValidationError

from ..fieldbus.library import DeviceLibrary
from .checks import Issue, check_project
from .models import PROJECT_FILE, Project

BACKUP_SUFFIX = ".bak"


class ProjectError(Exception):
    """A project could not be loaded or applied; `issues` name each offending field."""

    def __init__(self, message: str, issues: Sequence[Issue] = ()) -> None:
        super().__init__(message)
        self.message = message
        self.issues = list(issues)

    def __str__(self) -> str:
        if not self.issues:
            return self.message
        lines = [self.message] + [f"  {i.path}: {i.message}" + (f" [{i.code}]" if i.code else "") for i in self.issues]
        return "\n".join(lines)


def json_path(loc: Iterable[Any]) -> str:
    out = ""
    for part in loc:
        if isinstance(part, int):
            out += f"[{part}]"
        else:
            out += ("." if out else "") + str(part)
    return out or "(document)"


def issues_from_validation_error(err: ValidationError, prefix: Sequence[Any] = ()) -> list[Issue]:
    issues = []
    for e in err.errors(include_url=False):
        loc = [*prefix, *e["loc"]]
        msg = e["msg"]
        if msg.startswith("Value error, "):
            msg = msg[len("Value error, "):]
        issues.append(Issue(json_path(loc), msg))
    return issues


def parse_project(data: Any, library: DeviceLibrary | None = None) -> Project:
    """Validate a decoded JSON document; raise ProjectError listing every invalid field."""
    if not isinstance(data, dict):
        raise ProjectError("the project document must be a JSON object", [Issue("(document)", "not an object")])
    version = data.get("schema_version")
    if version is not None and version != 1:
        raise ProjectError(
            f"schema_version {version!r} is not supported by this MC Studio (it reads version 1)",
            [Issue("schema_version", "unsupported schema version")],
        )
    try:
        project = Project.model_validate(data)
    except ValidationError as err:
        raise ProjectError("the project document is invalid", issues_from_validation_error(err)) from None
    issues = check_project(project, library)
    if issues:
        raise ProjectError("the project document is invalid", issues)
    return project


def load_project(folder: str | os.PathLike[str], library: DeviceLibrary | None = None) -> Project:
    folder = Path(folder)
    path = folder / PROJECT_FILE
    if not folder.is_dir():
        raise ProjectError(f"{folder} is not a project folder (it does not exist or is not a directory)")
    if not path.is_file():
        raise ProjectError(f"{folder} holds no {PROJECT_FILE}; create one with 'mcstudio new' or copy projects/demo")
    raw = path.read_bytes()
    try:
        data = json.loads(raw.decode("utf-8"))
    except UnicodeDecodeError as err:
        raise ProjectError(f"{path} is not UTF-8 text ({err.reason} at byte {err.start})") from None
    except json.JSONDecodeError as err:
        raise ProjectError(f"{path} is not valid JSON: {err.msg} at line {err.lineno}, column {err.colno}") from None
    try:
        return parse_project(data, library if library is not None else DeviceLibrary(folder))
    except ProjectError as err:
        raise ProjectError(f"{path}: {err.message}", err.issues) from None


def dump_project(project: Project) -> str:
    return json.dumps(project.model_dump(mode="json"), indent=2, ensure_ascii=False) + "\n"


def _fsync_dir(folder: Path) -> None:
    try:
        fd = os.open(folder, os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(fd)
    finally:
        os.close(fd)


def atomic_write(path: Path, text: str | bytes, *, keep_backup: bool = True) -> None:
    """Write `text` (UTF-8) or bytes to `path` atomically (temp file + fsync + rename), keeping the old file as
    `<path>.bak`."""
    folder = path.parent
    folder.mkdir(parents=True, exist_ok=True)
    fd, tmp_name = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=folder)
    tmp = Path(tmp_name)
    try:
        data = text.encode("utf-8") if isinstance(text, str) else text
        with os.fdopen(fd, "wb") as fh:
            fh.write(data)
            fh.flush()
            os.fsync(fh.fileno())
        if keep_backup and path.exists():
            # Hard-link the current file to a temporary backup name, then rename it over the old backup: at no moment
            # is there no project.json.
            bak = path.with_name(path.name + BACKUP_SUFFIX)
            bak_tmp = path.with_name(f".{path.name}.bak.tmp")
            bak_tmp.unlink(missing_ok=True)
            os.link(path, bak_tmp)
            os.replace(bak_tmp, bak)
        os.replace(tmp, path)
        _fsync_dir(folder)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise


def save_project(folder: str | os.PathLike[str], project: Project) -> Path:
    folder = Path(folder)
    path = folder / PROJECT_FILE
    atomic_write(path, dump_project(project))
    return path
