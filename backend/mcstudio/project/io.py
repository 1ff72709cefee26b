"""Load, validate and save project folders.

A project is a folder holding `project.json`, the cam data files `cams/*.csv` and imported ESI files `esi/*.xml`.
Loading reports every problem with the JSON path of the field it concerns and never writes; saving is atomic: the new
document is written to a temporary file in the same folder, flushed and fsynced, the previous version is kept as
`project.json.bak`, and the new file replaces the old one with a single `rename`, so a crash leaves either the old or
the new project, never a torn file (docs/project-format.md "Saving").
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
    try:
        raw = path.read_bytes()
    except OSError as err:
        raise ProjectError(f"{path} cannot be read ({err.strerror or err})") from None
    try:
        text = raw.decode("utf-8-sig")  # a byte-order mark (Windows editors write one) is skipped; saves write none
    except UnicodeDecodeError as err:
        raise ProjectError(f"{path} is not UTF-8 text ({err.reason} at byte {err.start})") from None
    try:
        data = json.loads(text)
    except json.JSONDecodeError as err:
        raise ProjectError(f"{path} is not valid JSON: {err.msg} at line {err.lineno}, column {err.colno}") from None
    except RecursionError:
        raise ProjectError(f"{path} nests arrays or objects too deeply to be a project document") from None
    except ValueError as err:  # e.g. an integer of more than 4300 digits
        raise ProjectError(f"{path} is not a valid project document: {err}") from None
    try:
        return parse_project(data, library if library is not None else DeviceLibrary(folder))
    except ProjectError as err:
        raise ProjectError(f"{path}: {err.message}", err.issues) from None


def dump_project(project: Project) -> str:
    data = project.model_dump(mode="json", by_alias=True)
    if data.get("$schema") is None:  # written only when the document names its schema (for editors, D113)
        data.pop("$schema", None)
    return json.dumps(data, indent=2, ensure_ascii=False) + "\n"


def fsync_dir(folder: Path) -> None:
    """Make a rename or new entry in `folder` durable (best effort where directories cannot be opened)."""
    try:
        fd = os.open(folder, os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(fd)
    finally:
        os.close(fd)


WRITE_CHUNK = 1 << 16


def _temp_prefix(path: Path) -> str:
    return f".{path.name}."


def remove_stale_temp_files(path: Path) -> list[Path]:
    """Remove the temporary files a killed save of `path` left behind (`.<name>.<pid>.<random>.tmp` of another
    process). Files of this process are left alone: another thread may be writing them. (A left-over
    `.<name>.bak.tmp` is replaced by the next save.)"""
    removed = []
    prefix = _temp_prefix(path)
    mine = f"{prefix}{os.getpid()}."
    try:
        entries = list(path.parent.iterdir())
    except OSError:
        return removed
    for entry in entries:
        name = entry.name
        pid = name[len(prefix):].split(".", 1)[0]
        if not (name.startswith(prefix) and name.endswith(".tmp") and pid.isdigit()) or name.startswith(mine):
            continue
        try:
            entry.unlink()
            removed.append(entry)
        except OSError:
            pass
    return removed


def atomic_write(path: Path, text: str | bytes, *, keep_backup: bool = True) -> None:
    """Write `text` (UTF-8) or bytes to `path` atomically (temp file + fsync + rename), keeping the old file as
    `<path>.bak`.

    Steps (a kill between any two leaves either the old or the new file at `path`, tested by
    tests/project/test_kill_save.py): write `.<name>.<pid>.<random>.tmp` in the same folder and fsync it; hard-link the
    current file as the backup; rename the temporary file over `path`; fsync the folder."""
    folder = path.parent
    folder.mkdir(parents=True, exist_ok=True)
    remove_stale_temp_files(path)
    fd, tmp_name = tempfile.mkstemp(prefix=f"{_temp_prefix(path)}{os.getpid()}.", suffix=".tmp", dir=folder)
    tmp = Path(tmp_name)
    try:
        data = memoryview(text.encode("utf-8") if isinstance(text, str) else text)
        try:
            for start in range(0, len(data), WRITE_CHUNK):
                chunk = data[start:start + WRITE_CHUNK]
                while chunk:
                    chunk = chunk[os.write(fd, chunk):]
            os.fsync(fd)
        finally:
            os.close(fd)
        if keep_backup and path.exists():
            # Hard-link the current file to a temporary backup name, then rename it over the old backup: at no moment
            # is there no project.json, and the backup is always a complete earlier version.
            bak = path.with_name(path.name + BACKUP_SUFFIX)
            bak_tmp = path.with_name(f"{_temp_prefix(path)}bak.tmp")
            bak_tmp.unlink(missing_ok=True)
            os.link(path, bak_tmp)
            os.replace(bak_tmp, bak)
            # rename() does nothing when both names are links to one file (a save killed after this step left the
            # backup linked to the current document): then the temporary name is still there
            bak_tmp.unlink(missing_ok=True)
        os.replace(tmp, path)
        fsync_dir(folder)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise


def save_project(folder: str | os.PathLike[str], project: Project) -> Path:
    folder = Path(folder)
    path = folder / PROJECT_FILE
    atomic_write(path, dump_project(project))
    return path
