"""Project format v1: loading with path-named errors, cross-field checks (573B), atomic save, the CLI validator."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from mcstudio.project import io as pio
from mcstudio.project.checks import check_axis_parameters
from mcstudio.project.io import ProjectError, load_project, parse_project, save_project
from mcstudio.project.models import AxisParameters, Project
from tests.conftest import DEMO


def _doc() -> dict:
    return json.loads((DEMO / "project.json").read_text())


def test_demo_project_loads(demo_project: Project) -> None:
    assert [a.name for a in demo_project.axes] == [f"MC_Axis00{k}" for k in range(8)]
    robot, xy = demo_project.groups  # MC_Axis004–006 are the Delta3's A0–A2 (docs/robot.md "3D view")
    assert xy.name == "MC_Group001" and xy.composition.name == "_mcXY" and xy.axes == ["MC_Axis000", "MC_Axis001"]
    assert xy.kinematics is None and xy.operation.MaxInterpolationVel == 500.0
    assert robot.name == "MC_Group000" and robot.axes == ["MC_Axis004", "MC_Axis005", "MC_Axis006"]
    assert robot.kinematics is not None and (robot.kinematics.Rf, robot.kinematics.Rm, robot.kinematics.Lf,
                                             robot.kinematics.Lm, robot.kinematics.theta) == (200, 50, 350, 800, 0)
    assert demo_project.schema_version == 1
    assert demo_project.controller.primary_period_us == 1000


def test_round_trip_is_stable(demo_project: Project) -> None:
    assert parse_project(json.loads(pio.dump_project(demo_project))) == demo_project
    assert pio.dump_project(demo_project) == (DEMO / "project.json").read_text()


def test_errors_name_the_json_path() -> None:
    doc = _doc()
    doc["axes"][1]["parameters"]["Operation"]["MaxVel"] = -5
    doc["axes"][2]["type"] = "_mcStepper"
    doc["controller"]["primary_period_us"] = 777
    with pytest.raises(ProjectError) as exc:
        parse_project(doc)
    paths = {i.path: i.message for i in exc.value.issues}
    assert "axes[1].parameters.Operation.MaxVel" in paths
    assert "axes[2].type" in paths and "_mcServo" in paths["axes[2].type"]
    assert "controller.primary_period_us" in paths


def test_enum_accepted_as_name_or_number_and_returned_as_name() -> None:
    doc = _doc()
    doc["axes"][0]["type"] = 0
    doc["axes"][3]["type"] = "_mcVirServo"
    project = parse_project(doc)
    assert project.model_dump(mode="json")["axes"][0]["type"] == "_mcServo"


def test_cross_field_rules_report_573b_codes() -> None:
    doc = _doc()
    doc["axes"][0]["parameters"]["Operation"]["MaxJogVel"] = 1000.0  # > MaxVel 500
    doc["axes"][1]["number"] = 0
    doc["axes"][3]["node_address"] = 9  # virtual axis with a node
    with pytest.raises(ProjectError) as exc:
        parse_project(doc)
    issues = {i.path: i for i in exc.value.issues}
    assert issues["axes[0].parameters.Operation.MaxJogVel"].code == "573B/1102"
    assert "duplicate axis number" in issues["axes[1].number"].message
    assert "virtual" in issues["axes[3].node_address"].message


def test_consistency_check_order_and_codes() -> None:
    p = AxisParameters.model_validate({"Operation": {"MaxVel": 100.0, "StartVel": 200.0, "MaxJogVel": 50.0},
                                       "Homing": {"Vel": 10.0, "ApproachVel": 20.0, "CompensationVel": 5.0}})
    assert [c for c, _, _ in check_axis_parameters(p)] == [0x1101, 0x1501]


def test_unknown_schema_version_refused() -> None:
    doc = _doc()
    doc["schema_version"] = 2
    with pytest.raises(ProjectError, match="schema_version 2"):
        parse_project(doc)


def test_corrupt_file_is_refused_and_untouched(tmp_path: Path) -> None:
    folder = tmp_path / "broken"
    folder.mkdir()
    text = '{"format": "mcstudio-project", "name": "x", "axes": [ }'
    (folder / "project.json").write_text(text)
    with pytest.raises(ProjectError, match=r"not valid JSON: .* line 1, column"):
        load_project(folder)
    assert (folder / "project.json").read_text() == text


def test_missing_folder_and_file(tmp_path: Path) -> None:
    with pytest.raises(ProjectError, match="not a project folder"):
        load_project(tmp_path / "nope")
    with pytest.raises(ProjectError, match=r"holds no project\.json"):
        load_project(tmp_path)


def test_atomic_save_keeps_previous_version(tmp_path: Path, demo_project: Project) -> None:
    folder = tmp_path / "p"
    shutil.copytree(DEMO, folder)
    old = (folder / "project.json").read_text()
    changed = demo_project.model_copy(update={"description": "changed"})
    save_project(folder, changed)
    assert load_project(folder).description == "changed"
    assert (folder / "project.json.bak").read_text() == old
    assert [p.name for p in folder.iterdir() if p.name.startswith(".")] == []


def test_failed_save_leaves_the_old_file(tmp_path: Path, demo_project: Project,
                                         monkeypatch: pytest.MonkeyPatch) -> None:
    """A crash between writing the temporary file and the rename leaves the old project intact, no temp files."""
    folder = tmp_path / "p"
    shutil.copytree(DEMO, folder)
    old = (folder / "project.json").read_text()
    real_replace = os.replace

    def boom(src: str, dst: str) -> None:
        if str(dst).endswith("project.json"):
            raise OSError("disk pulled")
        real_replace(src, dst)

    monkeypatch.setattr(pio.os, "replace", boom)
    with pytest.raises(OSError, match="disk pulled"):
        save_project(folder, demo_project.model_copy(update={"description": "new"}))
    assert (folder / "project.json").read_text() == old
    assert not [p for p in folder.iterdir() if p.suffix == ".tmp"]


def _cli(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-m", "mcstudio", *args], capture_output=True, text=True, check=False)


def test_cli_validate_ok() -> None:
    r = _cli("validate", str(DEMO))
    assert r.returncode == 0, r.stderr
    assert "OK" in r.stdout and "8 axes" in r.stdout


def test_cli_validate_reports_paths(tmp_path: Path) -> None:
    doc = _doc()
    doc["axes"][0]["parameters"]["Limit"]["FollowingErrorWarningVal"] = 99.0
    (tmp_path / "project.json").write_text(json.dumps(doc))
    r = _cli("validate", str(tmp_path))
    assert r.returncode == 1
    assert "axes[0].parameters.Limit.FollowingErrorWarningVal" in r.stderr and "573B/1304" in r.stderr
