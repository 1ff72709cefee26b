"""Project folders under the projects root: names, templates, new projects and copies (save-as).

* `check_project_name(name)` enforces the folder-name rules of decision D110 (one path component, no separators,
  no `..`, not hidden, no control or Windows-reserved characters, at most 64 characters) and raises `ValueError` with
  the reason; `resolve_in_root` also refuses a name whose folder resolves outside the root (a symlink).
* Templates (D111) are project folders: `empty` and `single-axis` ship in `mcstudio/project/templates/`, `demo` is
  the example project `projects/demo` (the Docker image copies it into the package's templates folder).
* `create_project_folder` / `copy_project_folder` build the new folder under a hidden temporary name in the root
  and rename it into place, so a crash leaves either no folder or a complete one, never half a project (D112).
"""

from __future__ import annotations

import os
import re
import shutil
import tempfile
import unicodedata
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path

from .io import fsync_dir
from .models import PROJECT_FILE

MAX_NAME_CHARS = 64
MAX_NAME_BYTES = 200  # UTF-8; file systems allow 255 bytes per component
_FORBIDDEN = set('/\\:*?"<>|')
_RESERVED = re.compile(r"^(con|prn|aux|nul|com[0-9]|lpt[0-9])(\..*)?$", re.IGNORECASE)

PACKAGE_TEMPLATES = Path(__file__).resolve().parent / "templates"
CHECKOUT_DEMO = Path(__file__).resolve().parents[3] / "projects" / "demo"

# Files of a project folder that are not copied to a new folder: the backup and the temporary files of saves.
_NOT_COPIED = re.compile(r"^(\..*|.*\.bak)$")


def check_project_name(name: str) -> str:
    """Return `name` if it is an acceptable project folder name, else raise ValueError saying why (D110)."""
    if not isinstance(name, str) or not name:
        raise ValueError("a project name must not be empty")
    if len(name) > MAX_NAME_CHARS or len(name.encode("utf-8")) > MAX_NAME_BYTES:
        raise ValueError(f"a project name has at most {MAX_NAME_CHARS} characters ({MAX_NAME_BYTES} bytes in UTF-8)")
    if name in (".", "..") or ".." in name.split("/") or ".." in name.split("\\"):
        raise ValueError("'..' is not a project name: a project is a folder inside the projects folder")
    if "/" in name or "\\" in name or os.path.isabs(name):
        raise ValueError("a project name is a folder name inside the projects folder, without '/' or '\\'")
    if name.startswith("."):
        raise ValueError("a project name must not start with '.' (hidden folders hold temporary files)")
    bad = sorted({c for c in name if c in _FORBIDDEN or unicodedata.category(c) in ("Cc", "Cf", "Cs", "Co", "Cn")})
    if bad:
        shown = ", ".join(repr(c) if c.isprintable() else f"U+{ord(c):04X}" for c in bad)
        raise ValueError(f"a project name must not contain {shown} (not allowed in folder names on every system)")
    if name != name.strip() or name.endswith("."):
        raise ValueError("a project name must not begin or end with a space or end with '.'")
    if _RESERVED.match(name):
        raise ValueError(f"{name!r} is a reserved device name on Windows; choose another project name")
    return name


def resolve_in_root(root: Path, name: str) -> Path:
    """The folder of project `name` inside `root` (checked name; refused if it resolves outside the root)."""
    check_project_name(name)
    base = root.resolve()
    folder = (base / name).resolve()
    if folder.parent != base:
        raise ValueError("the project name resolves outside the projects folder (a link?)")
    return folder


# ------------------------------------------------------------------ templates
@dataclass(frozen=True)
class Template:
    name: str
    folder: Path


def _template_folders() -> Iterator[Template]:
    if PACKAGE_TEMPLATES.is_dir():
        for d in sorted(PACKAGE_TEMPLATES.iterdir()):
            if d.is_dir() and (d / PROJECT_FILE).is_file():
                yield Template(d.name, d)
    if not (PACKAGE_TEMPLATES / "demo" / PROJECT_FILE).is_file() and (CHECKOUT_DEMO / PROJECT_FILE).is_file():
        yield Template("demo", CHECKOUT_DEMO)


TEMPLATE_ORDER = ("empty", "single-axis", "demo")


def list_templates() -> list[Template]:
    found = {t.name: t for t in _template_folders()}
    order = [n for n in TEMPLATE_ORDER if n in found] + sorted(n for n in found if n not in TEMPLATE_ORDER)
    return [found[n] for n in order]


def find_template(name: str) -> Template | None:
    return next((t for t in list_templates() if t.name == name), None)


# ------------------------------------------------------------------ building folders
def _copy_files(src: Path, dst: Path) -> None:
    """Copy a project folder's files (not project.json, its backup or temporary files) into `dst`."""
    for entry in sorted(src.iterdir()):
        if entry.name == PROJECT_FILE or _NOT_COPIED.match(entry.name) or entry.is_symlink():
            continue
        if entry.is_dir():
            shutil.copytree(entry, dst / entry.name, symlinks=False,
                            ignore=lambda _d, names: [n for n in names if _NOT_COPIED.match(n)])
        elif entry.is_file():
            shutil.copy2(entry, dst / entry.name)


def _fsync_tree(folder: Path) -> None:
    for dirpath, _dirs, files in os.walk(folder):
        for f in files:
            fd = os.open(os.path.join(dirpath, f), os.O_RDONLY)
            try:
                os.fsync(fd)
            finally:
                os.close(fd)
        fd = os.open(dirpath, os.O_RDONLY)
        try:
            os.fsync(fd)
        finally:
            os.close(fd)


def build_project_folder(root: Path, name: str, fill: Callable[[Path], None], *, overwrite: bool = False) -> Path:
    """Create project `name` in `root`: `fill(staging)` writes the files into a hidden staging folder, which is
    fsynced and renamed to `root/name` (D112). With `overwrite`, an existing project folder is replaced: its
    project.json is kept as the new folder's project.json.bak, the old folder is renamed aside and then removed.
    Raises FileExistsError when the folder exists (and `overwrite` is false or it is not a project folder)."""
    target = resolve_in_root(root, name)
    if target.exists() and not overwrite:
        raise FileExistsError(f"a project named {name!r} already exists in the projects folder")
    if target.exists() and not (target.is_dir() and (target / PROJECT_FILE).is_file()):
        raise FileExistsError(f"{name!r} exists in the projects folder but is not a project folder; "
                              "choose another name")
    root.mkdir(parents=True, exist_ok=True)
    staging = Path(tempfile.mkdtemp(prefix=f".{name}.new-", dir=root))
    try:
        fill(staging)
        if target.exists():
            shutil.copy2(target / PROJECT_FILE, staging / (PROJECT_FILE + ".bak"))
        _fsync_tree(staging)
        if target.exists():
            aside = Path(tempfile.mkdtemp(prefix=f".{name}.old-", dir=root))
            os.replace(target, aside / name)  # the old folder is kept (hidden) until the new one is in place
            os.replace(staging, target)
            shutil.rmtree(aside, ignore_errors=True)
        else:
            os.rename(staging, target)
        fsync_dir(root)
    except BaseException:
        shutil.rmtree(staging, ignore_errors=True)
        raise
    return target


def copy_template(template: Template, staging: Path) -> None:
    _copy_files(template.folder, staging)
    shutil.copy2(template.folder / PROJECT_FILE, staging / PROJECT_FILE)


def copy_project_files(source: Path | None, staging: Path) -> None:
    """The files of the current project folder other than project.json (cam data, ESI files, notes)."""
    if source is not None and source.is_dir():
        _copy_files(source, staging)
