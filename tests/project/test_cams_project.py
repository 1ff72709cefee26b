"""Cam tables in the project folder: definitions in project.json, data in cams/<name>.csv (docs/project-format.md,
docs/cams.md "CSV format", D36); loading with file/line issues, the manual's generation checks with the member's
path, the data a rebuilt controller gets, atomic writes, the CLI validator."""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from mcstudio.controller.kernel import Controller
from mcstudio.controller.mc.cam.csvio import read_cam_csv
from mcstudio.controller.mc.cam.table import CamTable
from mcstudio.project.cam_models import CamDefinition, CamSource
from mcstudio.project.cams import (
    check_points,
    generate_table,
    load_cam_tables,
    sync_cam_files,
    table_from_points,
    tables_for,
    write_cam_definitions,
    write_cam_file,
)
from mcstudio.project.io import ProjectError, dump_project, load_project, parse_project
from tests.conftest import DEMO, ROOT


@pytest.fixture
def folder(tmp_path: Path) -> Path:
    shutil.copytree(DEMO, tmp_path / "demo")
    return tmp_path / "demo"


def _doc(folder: Path) -> dict:
    return json.loads((folder / "project.json").read_text())


def _write_doc(folder: Path, doc: dict) -> None:
    (folder / "project.json").write_text(json.dumps(doc, indent=2))


def test_demo_cam_tables_load(folder: Path) -> None:
    project = load_project(folder)
    assert [c.name for c in project.cams] == ["RiseDwellReturn", "FlyingSync"]
    tables = load_cam_tables(project, folder)
    rdr = tables["RiseDwellReturn"]
    # 4 segments of 120°, 60°, 120°, 60° at PhasePitch 0.1: Tcd = 1 + 3600 (§5.4.4)
    assert rdr.max_data_number == 3601 and rdr.end_point_index == 3600
    p, d = rdr.valid()
    assert p[0] == 0 and p[-1] == 360 and d.max() == 100 and d[-1] == 0
    assert rdr.evaluate(150.0) == pytest.approx(100.0)  # the dwell
    # the CSV holds exactly what MC_GenerateCamTable gives for the stored source
    regenerated = generate_table(project.cams[0].source, None)
    assert np.array_equal(regenerated.valid()[1], d)
    assert tables["FlyingSync"].end_point_index == 720


def test_missing_csv_names_the_file(folder: Path) -> None:
    (folder / "cams" / "FlyingSync.csv").unlink()
    project = load_project(folder)
    with pytest.raises(ProjectError) as exc:
        load_cam_tables(project, folder)
    [issue] = exc.value.issues
    assert issue.path == "cams[1]" and "cams/FlyingSync.csv" in issue.message and "missing" in issue.message


def test_corrupt_csv_names_file_and_line(folder: Path) -> None:
    (folder / "cams" / "RiseDwellReturn.csv").write_text("# x\nphase,distance\n0,0\n1,2\n0.5,abc\n0.7,1\n")
    with pytest.raises(ProjectError) as exc:
        load_cam_tables(load_project(folder), folder)
    msgs = [(i.path, i.message) for i in exc.value.issues]
    assert msgs[0][0] == "cams[0]" and msgs[0][1].startswith("cams/RiseDwellReturn.csv line 5: distance:")
    assert msgs[1][1].startswith("cams/RiseDwellReturn.csv line 6: phase 0.7 is below the previous phase 1.0")
    (folder / "cams" / "RiseDwellReturn.csv").write_bytes(b"phase,distance\n0,0\n\xff\xfe,1\n")
    with pytest.raises(ProjectError) as exc:
        load_cam_tables(load_project(folder), folder)
    assert "cams/RiseDwellReturn.csv: not UTF-8" in exc.value.issues[0].message


def test_size_must_hold_the_points(folder: Path) -> None:
    doc = _doc(folder)
    doc["cams"][1]["size"] = 700  # FlyingSync has 721 points
    _write_doc(folder, doc)
    with pytest.raises(ProjectError) as exc:
        load_project(folder)  # the source's 5741 check already fails
    assert exc.value.issues[0].path == "cams[1].source.nodes[2].PhasePitch" and exc.value.issues[0].code == "5741"
    doc["cams"][1]["source"] = None
    _write_doc(folder, doc)
    with pytest.raises(ProjectError) as exc:
        load_cam_tables(load_project(folder), folder)
    assert exc.value.issues[0].path == "cams[1].size" and "721 points" in exc.value.issues[0].message
    doc["cams"][1]["size"] = 1000  # a larger variable: padded with zeros, Phase 0 after the end point
    _write_doc(folder, doc)
    t = load_cam_tables(load_project(folder), folder)["FlyingSync"]
    assert t.max_data_number == 1000 and t.end_point_index == 720 and t.phase[721] == 0


def test_definitions_are_checked_with_paths_and_error_ids(folder: Path) -> None:
    doc = _doc(folder)
    doc["cams"].append(dict(doc["cams"][0], name="risedwellreturn"))
    doc["cams"][0]["source"]["nodes"][2]["Phase"] = 150  # below node 1's 180 → 5740
    doc["cams"][1]["source"]["nodes"][0]["Distance"] = 0.0004  # non-zero below 0.001 → 573D, code 0001
    doc["cams"][1]["name"] = "1st"
    with pytest.raises(ProjectError) as exc:
        parse_project(doc)
    issues = {i.path: i for i in exc.value.issues}
    assert "must be an identifier" in issues["cams[1].name"].message
    doc["cams"][1]["name"] = "FlyingSync"
    with pytest.raises(ProjectError) as exc:
        parse_project(doc)
    issues = {i.path: i for i in exc.value.issues}
    assert issues["cams[0].source.nodes[2].Phase"].code == "5740"
    assert issues["cams[1].source.nodes[0].Distance"].code == "573D/0001"
    assert "duplicate cam table name" in issues["cams[2].name"].message
    doc["cams"][0]["source"]["nodes"][0]["Curve"] = "_mcSine"
    with pytest.raises(ProjectError) as exc:
        parse_project(doc)
    assert "cams[0].source.nodes[0].Curve" in [i.path for i in exc.value.issues]


def test_points_are_checked_like_the_csv() -> None:
    assert check_points([0, 1, 2], [0, 1, 0]) == []
    issues = {i.path: i.message for i in check_points([0.5, 1, 1, 0.5], [0, 1, 0, 2])}
    assert "start point (0, 0)" in issues["points.phase[0]"]
    assert "equal to (as REAL)" in issues["points.phase[2]"] and "below" in issues["points.phase[3]"]
    assert check_points([0, 1], [0])[0].path == "points.distance"
    assert "2 … 65535 points" in check_points([0], [0])[0].message
    assert check_points([0, float("nan")], [0, 1])[0].path == "points.phase[1]"
    with pytest.raises(ProjectError) as exc:
        table_from_points([0, 1, 2], [0, 1, 0], size=2)
    assert exc.value.issues[0].path == "size"


def test_generation_error_names_the_member() -> None:
    src = CamSource.model_validate({"nodes": [{"Phase": 90, "Distance": 1e38, "Curve": "_mcPolynomic3"},
                                              {"Phase": 90.00001, "Distance": 0, "Curve": 1}]})
    with pytest.raises(ProjectError) as exc:
        generate_table(src, None)
    # 90.00001 rounds to 90.000 at the 4th decimal: not above the previous phase (§5.4.2, D37)
    assert exc.value.issues[0].path == "source.nodes[1].Phase" and exc.value.issues[0].code == "5740"


def test_tables_for_keeps_regenerates_or_refuses(folder: Path) -> None:
    project = load_project(folder)
    current = load_cam_tables(project, folder)
    same = tables_for(project, current, project)
    assert same["RiseDwellReturn"] is current["RiseDwellReturn"]  # unchanged: the downloaded data stay
    doc = _doc(folder)
    doc["cams"][0]["source"]["nodes"][0]["Distance"] = 50
    doc["cams"][1]["source"] = None
    doc["cams"][1]["size"] = 800
    changed = parse_project(doc)
    out = tables_for(changed, current, project)
    # the changed source is generated again: the rise ends at 50, the dwell keeps it
    assert out["RiseDwellReturn"].valid()[1].max() == 50
    assert out["RiseDwellReturn"].evaluate(150.0) == pytest.approx(50.0)
    assert out["FlyingSync"].max_data_number == 800 and out["FlyingSync"].end_point_index == 720
    doc["cams"].append({"name": "Nothing", "source": None})
    with pytest.raises(ProjectError) as exc:
        tables_for(parse_project(doc), current, project)
    assert exc.value.issues[0].path == "cams[2]" and "has no data" in exc.value.issues[0].message


def test_controller_gets_runtime_copies(folder: Path) -> None:
    project = load_project(folder)
    tables = load_cam_tables(project, folder)
    c = Controller(project, cams=tables)
    assert set(c.mc.cam_tables) == {"RiseDwellReturn", "FlyingSync"}
    c.mc.cam_tables["FlyingSync"].distance[5] = 999.0  # a program writing into the variable …
    assert tables["FlyingSync"].distance[5] != 999.0  # … does not touch the downloaded data


def test_writes_are_atomic_and_keep_unsaved_fields(folder: Path) -> None:
    project = load_project(folder)
    saved_text = dump_project(project)
    table = CamTable.from_points([0, 10, 20], [0, 5, 0])
    path = write_cam_file(folder, "Tri", table)
    assert path == folder / "cams" / "Tri.csv" and not list((folder / "cams").glob(".*"))
    p, d = read_cam_csv(path)
    assert p.tolist() == [0, 10, 20] and d.tolist() == [0, 5, 0]
    defs = [*project.cams, CamDefinition(name="Tri")]
    text = write_cam_definitions(folder, saved_text, defs)
    assert (folder / "project.json").read_text() == text
    assert (folder / "project.json.bak").read_text() == saved_text
    reloaded = load_project(folder)
    assert [c.name for c in reloaded.cams] == ["RiseDwellReturn", "FlyingSync", "Tri"]
    assert reloaded.axes == project.axes
    assert load_cam_tables(reloaded, folder)["Tri"].end_point_index == 2


def test_sync_writes_only_missing_or_changed_files(folder: Path) -> None:
    project = load_project(folder)
    tables = load_cam_tables(project, folder)
    rdr = folder / "cams" / "RiseDwellReturn.csv"
    before = rdr.stat().st_mtime_ns
    (folder / "cams" / "FlyingSync.csv").unlink()
    sync_cam_files(folder, project, tables)
    assert rdr.stat().st_mtime_ns == before
    assert np.array_equal(read_cam_csv(folder / "cams" / "FlyingSync.csv")[1], tables["FlyingSync"].valid()[1])


def test_cli_validate_reports_cam_files(folder: Path) -> None:
    cmd = [sys.executable, "-m", "mcstudio", "validate", str(folder)]
    ok = subprocess.run(cmd, capture_output=True, text=True, cwd=ROOT)
    assert ok.returncode == 0 and "2 cam tables" in ok.stdout
    (folder / "cams" / "FlyingSync.csv").write_text("phase,distance\n0,0\n")
    bad = subprocess.run(cmd, capture_output=True, text=True, cwd=ROOT)
    assert bad.returncode == 1
    assert "cams[1]: cams/FlyingSync.csv line 2: a cam table needs at least 2 points" in bad.stderr
