"""Project format: axes groups (basic settings, operation settings, Delta3 kinematics) and their checks.

Group basic settings follow `_sGROUP_REF.Cfg`/`.Kinematics` (omron-mc-basics.md §2.4, seed 000 lines 1716–1767);
composition axes are servo or virtual servo axes only (omron-group-and-cam.md §0.3, 543D)."""

from __future__ import annotations

import json

import pytest

from mcstudio.project import io as pio
from mcstudio.project.io import ProjectError, parse_project
from tests.conftest import DEMO

KIN = {"type": "delta3", "Rf": 200.0, "Rm": 50.0, "Lf": 350.0, "Lm": 800.0, "theta": 0.0,
       "workspace": {"Zu": -50.0, "Rcy": 300.0, "Hcy": 250.0, "Rco": 150.0, "Hco": 150.0}}


def _doc() -> dict:
    return json.loads((DEMO / "project.json").read_text())


def _issues(doc: dict) -> dict[str, pio.Issue]:
    with pytest.raises(ProjectError) as exc:
        parse_project(doc)
    return {i.path: i for i in exc.value.issues}


def test_group_round_trip_with_defaults() -> None:
    doc = _doc()
    doc["groups"] = [{"name": "MC_Group000", "number": 0, "composition": "_mcXY", "axes": ["MC_Axis000", "MC_Axis001"],
                      "operation": {"MaxInterpolationVel": 1000.0}}]
    project = parse_project(doc)
    g = project.groups[0]
    assert g.axis_count == 2 and g.kinematics is None
    assert g.operation.MaxInterpolationAcc == 0.0 and g.operation.CorrectionAllowanceRatio == 0.1
    dumped = json.loads(pio.dump_project(project))
    assert dumped["groups"][0]["composition"] == "_mcXY"
    assert dumped["groups"][0]["operation"]["GroupStopMethod"] == "_mcImmediateStop"
    assert parse_project(dumped) == project


def test_composition_membership_and_uniqueness_issues() -> None:
    doc = _doc()
    doc["axes"][2]["type"] = "_mcVirEncdr"
    doc["axes"][2]["node_address"] = None
    doc["groups"] = [
        {"name": "MC_Group000", "number": 0, "composition": "_mcXYZ", "axes": ["MC_Axis000", "MC_Axis001"]},
        {"name": "MC_Group000", "number": 0, "composition": 1, "axes": ["MC_Axis001", "MC_Axis002", "Nope"]},
        {"name": "MC_Axis003", "number": 5, "composition": "_mcXY", "axes": ["MC_Axis003", "MC_Axis003"]},
    ]
    issues = _issues(doc)
    assert "needs 3 axes" in issues["groups[0].axes"].message
    assert "duplicate axes group name" in issues["groups[1].name"].message
    assert "duplicate axes group number" in issues["groups[1].number"].message
    assert "groups[0]" in issues["groups[1].axes[0]"].message
    assert issues["groups[1].axes[1]"].code == "543D"
    assert "no axis named" in issues["groups[1].axes[2]"].message
    assert "name of an axis" in issues["groups[2].name"].message
    assert "twice" in issues["groups[2].axes[1]"].message


def test_group_number_and_composition_ranges() -> None:
    doc = _doc()
    doc["groups"] = [{"name": "G", "number": 64, "composition": "_mcXYZUV", "axes": []}]
    issues = _issues(doc)
    assert "groups[0].number" in issues and "groups[0].composition" in issues


def test_interpolation_velocity_pulse_limit() -> None:
    """Seed 000 line 1945: the maximum interpolation velocity is at most twice the axis MaxVel upper limit."""
    doc = _doc()
    doc["groups"] = [{"name": "G", "number": 0, "composition": "_mcXY", "axes": ["MC_Axis000", "MC_Axis001"],
                      "operation": {"MaxInterpolationVel": 1e12}}]
    assert "pulse/s" in _issues(doc)["groups[0].operation.MaxInterpolationVel"].message


def test_delta3_kinematics_checks() -> None:
    doc = _doc()
    for k in range(3):
        doc["axes"][k]["parameters"]["UnitConversion"]["UnitDisplay"] = "_mcDeg"
    group = {"name": "Robot", "number": 1, "composition": "_mcXYZ",
             "axes": ["MC_Axis000", "MC_Axis001", "MC_Axis002"], "kinematics": KIN,
             "operation": {"MaxInterpolationVel": 1000.0}}
    doc["groups"] = [group]
    project = parse_project(doc)
    assert project.groups[0].kinematics is not None
    assert project.groups[0].kinematics.params().Lm == 800.0
    bad = json.loads(json.dumps(KIN))
    bad["Rm"] = 250.0  # restriction (3): Rm < Rf → 5708
    group["kinematics"] = bad
    assert _issues(doc)["groups[0].kinematics.Rm"].code == "5708"
    bad = json.loads(json.dumps(KIN))
    bad["workspace"]["Rcy"] = -1.0
    group["kinematics"] = bad
    assert _issues(doc)["groups[0].kinematics.workspace.Rcy"].code == "570A"
    group["kinematics"] = KIN
    doc["axes"][1]["parameters"]["UnitConversion"]["UnitDisplay"] = "_mcMm"
    group["composition"] = "_mcXYZU"
    group["axes"].append("MC_Axis003")
    issues = _issues(doc)
    assert issues["groups[0].axes[1]"].code == "5706" and issues["groups[0].composition"].code == "5706"
