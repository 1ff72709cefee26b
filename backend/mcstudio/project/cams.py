"""Cam tables of a project folder: `cams/<name>.csv` files (the data) and the `cams` definitions of project.json.

* `load_cam_tables(project, folder)` reads every defined table's CSV into a `CamTable` (REAL data, the end point in
  force, padded to the definition's size), or raises `ProjectError` naming each missing or corrupt file with the
  line of each problem;
* `generate_table(source, size)` runs MC_GenerateCamTable on a definition's source (the cam editor's nodes);
* `tables_for(project, current)` gives the tables a controller built from `project` gets: the current data of every
  defined table (re-sized if the definition changed), generated from its source when there are none;
* `write_cam_file` / `remove_cam_file` / `write_cam_definitions` save atomically (`atomic_write`): the CSV first,
  then project.json with only its `cams` list changed.
"""

from __future__ import annotations

import json
import os
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from ..controller.mc.cam.csvio import CamCsvError, format_cam_csv, read_cam_csv
from ..controller.mc.cam.generate import GenerateError, generate
from ..controller.mc.cam.table import MAX_POINTS, REAL, CamTable
from .cam_models import CAM_FOLDER, CamDefinition, CamSource, error_code, error_path
from .checks import Issue
from .io import ProjectError, atomic_write, dump_project
from .models import PROJECT_FILE, Project

__all__ = ["cam_file", "check_points", "generate_table", "load_cam_tables", "remove_cam_file", "sync_cam_files",
           "table_from_points", "tables_for", "write_cam_definitions", "write_cam_file"]

MAX_POINT_PROBLEMS = 20


def cam_file(folder: str | os.PathLike[str], name: str) -> Path:
    return Path(folder) / CAM_FOLDER / f"{name}.csv"


def check_points(phase: Sequence[float] | np.ndarray, distance: Sequence[float] | np.ndarray,
                 prefix: str = "points") -> list[Issue]:
    """The CSV file's rules for points given as arrays (docs/cams.md "CSV format"): as many phases as distances,
    2 … 65,535 points, the start point (0, 0), phases strictly ascending as REAL. Paths name the element."""
    p64 = np.asarray(phase, dtype=float)
    d64 = np.asarray(distance, dtype=float)
    if p64.size != d64.size:
        return [Issue(f"{prefix}.distance", f"{d64.size} distances for {p64.size} phases: give one per phase")]
    if not 2 <= p64.size <= MAX_POINTS:
        return [Issue(f"{prefix}.phase", f"a cam table has 2 … {MAX_POINTS} points, not {p64.size}")]
    issues: list[Issue] = []
    for name, v in (("phase", p64), ("distance", d64)):
        bad = np.flatnonzero(~np.isfinite(v) | (np.abs(v) > float(np.finfo(REAL).max)))
        issues.extend(Issue(f"{prefix}.{name}[{k}]", f"{v[k]} is not a finite REAL") for k in bad[:MAX_POINT_PROBLEMS])
    if issues:
        return issues
    p = p64.astype(REAL)
    if p[0] != 0 or d64[0] != 0:
        issues.append(Issue(f"{prefix}.phase[0]", f"the first point is the start point (0, 0), found ({p64[0]}, "
                                                  f"{d64[0]})"))
    for k in np.flatnonzero(~(p[1:] > p[:-1]))[:MAX_POINT_PROBLEMS]:
        what = "equal to (as REAL)" if p[k + 1] == p[k] else "below"
        issues.append(Issue(f"{prefix}.phase[{k + 1}]", f"phase {p64[k + 1]} is {what} the previous phase "
                                                        f"{p64[k]}: phases must ascend"))
    return issues


def table_from_points(phase: Sequence[float] | np.ndarray, distance: Sequence[float] | np.ndarray,
                      size: int | None, prefix: str = "points") -> CamTable:
    """A cam table holding checked points (ProjectError naming the element otherwise), padded to `size`."""
    issues = check_points(phase, distance, prefix)
    n = len(phase)
    if not issues and size is not None and n > size:
        issues.append(Issue("size", f"{n} points do not fit a table of {size} elements (MaxDataNumber)"))
    if issues:
        raise ProjectError("the cam data are invalid", issues)
    return CamTable.from_points(phase, distance, size=size)


def generate_table(source: CamSource, size: int | None, prefix: str = "source") -> CamTable:
    """MC_GenerateCamTable on a source, for a table of `size` elements (null: exactly the generated points).

    A generation error is a ProjectError naming the member (`source.nodes[2].Phase`) with the ErrorID as code."""
    nodes, prop = source.inputs()
    res = generate(nodes, prop, table_size=size or MAX_POINTS)
    if res.error is not None:
        raise ProjectError(f"MC_GenerateCamTable would end with {res.error.ErrorID:04X}", [Issue(
            f"{prefix}.{error_path(res.error)}", res.error.message or _generic(res.error), error_code(res.error))])
    return CamTable.from_points(res.phase, res.distance, size=size)


def _generic(err: GenerateError) -> str:
    return f"error {err.ErrorID:04X}"


def load_cam_tables(project: Project, folder: str | os.PathLike[str]) -> dict[str, CamTable]:
    """Every cam table the project defines, read from `cams/<name>.csv` in the project folder.

    Raises ProjectError with one issue per problem (`cams[1]: cams/Cut.csv line 7: phase 1.0 is below …`)."""
    folder = Path(folder)
    issues: list[Issue] = []
    out: dict[str, CamTable] = {}
    for i, cam in enumerate(project.cams):
        path = cam_file(folder, cam.name)
        rel = f"{CAM_FOLDER}/{path.name}"
        if not path.is_file():
            issues.append(Issue(f"cams[{i}]", f"{rel}: the data file of cam table {cam.name!r} is missing"))
            continue
        try:
            phase, distance = read_cam_csv(path)
        except CamCsvError as err:
            issues.extend(Issue(f"cams[{i}]", f"{rel} {p}") if p.line else Issue(f"cams[{i}]", f"{rel}: {p}")
                          for p in err.problems)
            continue
        except OSError as err:
            issues.append(Issue(f"cams[{i}]", f"{rel}: cannot be read ({err.strerror})"))
            continue
        if cam.size is not None and phase.size > cam.size:
            issues.append(Issue(f"cams[{i}].size", f"{rel} holds {phase.size} points: they do not fit a table of "
                                                   f"{cam.size} elements (MaxDataNumber)"))
            continue
        out[cam.name] = CamTable.from_points(phase, distance, size=cam.size)
    if issues:
        raise ProjectError(f"{folder}: the cam data cannot be loaded", issues)
    return out


def _resized(table: CamTable, size: int | None) -> CamTable:
    if size == table.max_data_number or (size is None and table.end_point_index == table.max_data_number - 1):
        return table
    p, d = table.valid()
    return CamTable.from_points(p, d, size=size)


def tables_for(project: Project, current: Mapping[str, CamTable],
               previous: Project | None = None) -> dict[str, CamTable]:
    """The cam data a controller built from `project` gets: the current data of each defined table (re-sized to its
    definition); a table whose source is new or changed since `previous` (or that has no data) is generated from its
    source; a table with neither data nor source is an error naming it."""
    before = {c.name: c for c in previous.cams} if previous is not None else {}
    issues: list[Issue] = []
    out: dict[str, CamTable] = {}
    for i, cam in enumerate(project.cams):
        table = current.get(cam.name)
        old = before.get(cam.name)
        changed = previous is not None and (old is None or old.source != cam.source or old.size != cam.size)
        try:
            if cam.source is not None and (table is None or changed):
                out[cam.name] = generate_table(cam.source, cam.size, prefix=f"cams[{i}].source")
            elif table is not None and table.end_point_index is not None:
                p, _ = table.valid()
                if cam.size is not None and p.size > cam.size:
                    issues.append(Issue(f"cams[{i}].size", f"the table's {p.size} points do not fit {cam.size} "
                                                           "elements (MaxDataNumber)"))
                    continue
                out[cam.name] = _resized(table, cam.size)
            else:
                issues.append(Issue(f"cams[{i}]", f"cam table {cam.name!r} has no data: give its source, or write "
                                                  f"its points with PUT /api/v1/cams/{cam.name}"))
        except ProjectError as err:
            issues.extend(err.issues)
    if issues:
        raise ProjectError("the cam tables are invalid", issues)
    return out


def write_cam_file(folder: str | os.PathLike[str], name: str, table: CamTable) -> Path:
    """Write a table's valid points to `cams/<name>.csv` atomically."""
    path = cam_file(folder, name)
    p, d = table.valid()
    text = format_cam_csv(p, d, comment=f"{name}: cam table of MC Studio, {p.size} points (phase,distance)")
    atomic_write(path, text, keep_backup=False)
    return path


def sync_cam_files(folder: str | os.PathLike[str], project: Project, tables: Mapping[str, CamTable]) -> None:
    """Write the CSV of every defined table whose file is missing or holds other data (a table generated when a
    project document was applied), so that the project.json saved next never names data it does not have."""
    for cam in project.cams:
        table = tables.get(cam.name)
        if table is None:
            continue
        path = cam_file(folder, cam.name)
        p, d = table.valid()
        try:
            fp, fd = read_cam_csv(path)
            if np.array_equal(fp, p) and np.array_equal(fd, d):
                continue
        except (CamCsvError, OSError):
            pass
        write_cam_file(folder, cam.name, table)


def remove_cam_file(folder: str | os.PathLike[str], name: str) -> None:
    cam_file(folder, name).unlink(missing_ok=True)


def write_cam_definitions(folder: str | os.PathLike[str], saved_text: str, cams: list[CamDefinition]) -> str:
    """Replace the `cams` list of the saved project document (`saved_text`, what project.json holds) and write it
    atomically; returns the new saved text. The rest of the document stays as saved: edits of the running project
    not saved yet stay unsaved."""
    doc: dict[str, Any] = json.loads(saved_text)
    doc["cams"] = [c.model_dump(mode="json") for c in cams]
    text = dump_project(Project.model_validate(doc))
    atomic_write(Path(folder) / PROJECT_FILE, text)
    return text
