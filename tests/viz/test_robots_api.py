"""`GET /api/v1/viz/robots`: each Delta3 group's joint feedback, TCP by forward kinematics and alarm, read from the
published snapshot (paused controller, requests run inline)."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest
from fastapi.testclient import TestClient

from mcstudio.api.app import create_app
from mcstudio.api.state import Studio
from mcstudio.controller.kernel import Controller
from mcstudio.controller.mc.kinematics import Delta3Params, forward_point
from mcstudio.controller.runner import Runner
from tests.conftest import small_project
from tests.viz.conftest import delta_project


def _client(project: object) -> Iterator[tuple[TestClient, Studio]]:
    studio = Studio(runner=Runner(Controller(project), mode="paused"), project_dir=None,  # type: ignore[arg-type]
                    projects_root=None)
    with TestClient(create_app(studio, static_dir=Path("/nonexistent"))) as c:
        yield c, studio


@pytest.fixture
def delta() -> Iterator[tuple[TestClient, Studio]]:
    yield from _client(delta_project())


def test_robot_read_out_at_the_zero_pose(delta: tuple[TestClient, Studio]) -> None:
    client, _ = delta
    body = client.get("/api/v1/viz/robots").json()
    assert body["cycle"] == 0
    (robot,) = body["robots"]
    assert robot["group"] == "MC_Group000"
    assert robot["kinematics"] == {"Rf": 200.0, "Rm": 50.0, "Lf": 350.0, "Lm": 800.0, "theta": 0.0}
    assert [(a["logical"], a["name"], a["act_pos"], a["state"]) for a in robot["axes"]] == [
        ("A0", "MC_Axis000", 0.0, "Disabled"), ("A1", "MC_Axis001", 0.0, "Disabled"),
        ("A2", "MC_Axis002", 0.0, "Disabled")]
    assert robot["tcp"] == pytest.approx([0.0, 0.0, 0.0], abs=1e-9)  # zero pose = MCS origin (D30.2)
    assert robot["kin_status"] == "OK" and robot["alarm"] is None


def test_tcp_follows_a_move_through_the_fb_api(delta: tuple[TestClient, Studio]) -> None:
    """MC_Power + MC_Home (home preset) + MC_MoveAbsolute of A1 to 30° via /fb, stepped: the TCP is FK(0, 30, 0)."""
    client, _ = delta
    pw = client.post("/api/v1/fb", json={"type": "MC_Power", "inputs": {"Axis": "MC_Axis001", "Enable": True}}).json()
    client.post("/api/v1/controller/step", json={"cycles": 50, "until": {"fb": pw["id"], "output": "Status",
                                                                         "equals": True}})
    home = client.post("/api/v1/fb", json={"type": "MC_Home", "inputs": {"Axis": "MC_Axis001", "Execute": True}}).json()
    client.post("/api/v1/controller/step", json={"cycles": 1000, "until": {"fb": home["id"], "output": "Done",
                                                                           "equals": True}})
    mv = client.post("/api/v1/fb", json={"type": "MC_MoveAbsolute", "inputs": {
        "Axis": "MC_Axis001", "Position": 30.0, "Velocity": 90.0, "Acceleration": 900.0, "Deceleration": 900.0,
        "Execute": True}}).json()
    client.post("/api/v1/controller/step", json={"cycles": 5000, "until": {"fb": mv["id"], "output": "Done",
                                                                           "equals": True}})
    (robot,) = client.get("/api/v1/viz/robots").json()["robots"]
    assert robot["axes"][1]["act_pos"] == pytest.approx(30.0, abs=1e-6)
    _, tcp = forward_point(Delta3Params(Rf=200.0, Lf=350.0, Rm=50.0, Lm=800.0), 0.0, robot["axes"][1]["act_pos"], 0.0)
    assert robot["tcp"] == pytest.approx(list(tcp), abs=1e-5)
    assert robot["axes"][1]["state"] == "Standstill"


def test_project_without_robot_lists_none() -> None:
    for client, _ in _client(small_project()):
        assert client.get("/api/v1/viz/robots").json()["robots"] == []


def test_kinematics_in_force_and_user_coordinate_systems(delta: tuple[TestClient, Studio]) -> None:
    """D93/D94: the read-out gives the kinematics in force (MC_SetKinTransform's, not the project's) and the user
    coordinate systems MC_DefineCoordSystem defined (CSID, pose) — what the robot jog offers as its frames."""
    client, studio = delta
    assert client.get("/api/v1/viz/robots").json()["robots"][0]["coord_systems"] == []
    ids = []
    for name in ("MC_Axis000", "MC_Axis001", "MC_Axis002"):
        pw = client.post("/api/v1/fb", json={"type": "MC_Power", "inputs": {"Axis": name, "Enable": True}}).json()
        client.post("/api/v1/controller/step", json={"cycles": 50, "until": {"fb": pw["id"], "output": "Status",
                                                                             "equals": True}})
        home = client.post("/api/v1/fb", json={"type": "MC_Home", "inputs": {"Axis": name, "Execute": True}}).json()
        ids.append(home["id"])
    for i in ids:
        client.post("/api/v1/controller/step", json={"cycles": 1000, "until": {"fb": i, "output": "Done",
                                                                               "equals": True}})
    kin = client.post("/api/v1/fb", json={"type": "MC_SetKinTransform", "inputs": {
        "AxesGroup": "MC_Group000", "Execute": True,
        "KinTransform": {"KinType": 100, "KinParam": [200.0, 320.0, 50.0, 800.0], "ExpansionParam": [30.0]},
        "Workspace": {"WorkspaceType": 100, "WorkspaceParam": [-60.0, 250.0, 250.0, 150.0, 150.0]}}}).json()
    client.post("/api/v1/controller/step", json={"cycles": 10, "until": {"fb": kin["id"], "output": "Done",
                                                                         "equals": True}})
    for csid, pose in ((3, [10.0, 20.0, -300.0, 0.0, 0.0, 90.0]), (0, [0.0, 0.0, -280.0, 0.0, 0.0, 0.0])):
        d = client.post("/api/v1/fb", json={"type": "MC_DefineCoordSystem", "inputs": {
            "AxesGroup": "MC_Group000", "Execute": True, "CoordTransform": {"CSID": csid, "Pose": pose}}}).json()
        client.post("/api/v1/controller/step", json={"cycles": 10, "until": {"fb": d["id"], "output": "Done",
                                                                             "equals": True}})
    (robot,) = client.get("/api/v1/viz/robots").json()["robots"]
    assert robot["kinematics"] == {"Rf": 200.0, "Rm": 50.0, "Lf": 320.0, "Lm": 800.0, "theta": 30.0}
    assert robot["coord_systems"] == [{"csid": 0, "pose": [0.0, 0.0, -280.0, 0.0, 0.0, 0.0]},
                                      {"csid": 3, "pose": [10.0, 20.0, -300.0, 0.0, 0.0, 90.0]}]
    _, tcp = forward_point(Delta3Params(Rf=200.0, Lf=320.0, Rm=50.0, Lm=800.0, theta=30.0),
                           *[a["act_pos"] for a in robot["axes"]])
    assert robot["tcp"] == pytest.approx(list(tcp), abs=1e-5)
    assert studio.controller.project.groups[0].kinematics.Lf == 350.0  # type: ignore[union-attr]  # project unchanged
