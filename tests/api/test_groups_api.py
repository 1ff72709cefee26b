"""Axes-group REST endpoints (design/api.md "Axes and axes groups"): `_sGROUP_REF` from the snapshot, the group
settings, and the Delta3 kinematics of the demo robot MC_Group000 (Rf 200, Rm 50, Lf 350, Lm 800 mm, θ 0; workspace
Zu -50, Rcy 300, Hcy 250, Rco 150, Hco 150 mm — projects/demo, docs/robot.md).

Spec: omron-group-and-cam.md §0.4 (group states a–e) and §5.4 (`_sGROUP_REF` members); omron-robot-delta3.md §12.3
/ §12.4 (inverse / forward kinematics), §3.2 (workspace), §11 (570F "kinematics cannot be calculated").
"""

from __future__ import annotations

from typing import Any

import pytest
from fastapi.testclient import TestClient

from mcstudio.api.group_models import MAX_POINTS

G = "/api/v1/groups"


def _step(client: TestClient, cycles: int) -> None:
    r = client.post("/api/v1/controller/step", json={"cycles": cycles})
    assert r.status_code == 200, r.text


def test_list_groups_shows_the_demo_robot(client: TestClient) -> None:
    r = client.get(G)
    assert r.status_code == 200
    g, xy = r.json()  # the Delta3 robot and the XY table of MC_Axis000/001
    assert xy["name"] == "MC_Group001" and xy["composition"] == "_mcXY" and xy["kinematics"] is None
    assert xy["axes"] == ["MC_Axis000", "MC_Axis001"] and xy["state"] == "Disabled"
    assert g["name"] == "MC_Group000" and g["number"] == 0 and g["composition"] == "_mcXYZ"
    assert g["axes"] == ["MC_Axis004", "MC_Axis005", "MC_Axis006"]
    assert g["state"] == "Disabled" and g["error_code"] == "0000" and g["kinematics"] == "delta3"
    assert len(g["cmd_pos"]) == 3


def test_get_group_has_the_sgroup_ref_shape(client: TestClient) -> None:
    """§5.4 members: Status (Ready + five exclusive states), Details, Cmd, MFaultLvl, Obsr, Cfg, Kinematics."""
    r = client.get(f"{G}/MC_Group000")
    assert r.status_code == 200
    body = r.json()
    v = body["variables"]
    assert set(v) == {"Status", "Details", "Cmd", "MFaultLvl", "Obsr", "Cfg", "Kinematics", "CmdPos"}
    states = {k: f for k, f in v["Status"].items() if k != "Ready"}
    assert states == {"Disabled": True, "Standby": False, "Moving": False, "Stopping": False, "ErrorStop": False}
    assert v["Cfg"]["GrpNo"] == 0 and v["Cfg"]["GrpEnable"] == "_mcUsedGroup"
    assert v["Kinematics"] == {"GrpType": "_mcXYZ", "Axis": [4, 5, 6, 0]}
    assert v["MFaultLvl"] == {"Active": False, "Code": "0000"}
    assert body["config"]["kinematics"]["Lm"] == 800.0


def test_get_unknown_group_is_404(client: TestClient) -> None:
    assert client.get(f"{G}/MC_Group063").status_code == 404
    assert client.post(f"{G}/Nope/kinematics/inverse", json={"position": [0, 0, -100]}).status_code == 404
    assert client.post(f"{G}/Nope/kinematics/forward", json={"axes": [0, 0, 0]}).status_code == 404


def test_group_state_follows_mc_group_enable(client: TestClient) -> None:
    """§0.4: a Disabled → b Standby on MC_GroupEnable (Done one period after Execute↑)."""
    r = client.post("/api/v1/fb", json={"type": "MC_GroupEnable", "inputs": {"AxesGroup": "MC_Group000",
                                                                               "Execute": True}})
    assert r.status_code in (200, 201), r.text
    _step(client, 3)
    v = client.get(f"{G}/MC_Group000").json()["variables"]
    assert v["Status"]["Standby"] and not v["Status"]["Disabled"]
    assert client.get(G).json()[0]["state"] == "Standby"


def test_inverse_and_forward_round_trip(client: TestClient) -> None:
    """§12.4 then §12.3: forward of joint angles, inverse of the result gives the angles back."""
    r = client.post(f"{G}/MC_Group000/kinematics/forward", json={"axes": [15.0, 20.0, 25.0]})
    assert r.status_code == 200, r.text
    out = r.json()
    assert out["inside"] is True and out["positions"] is None
    xyz = out["position"]
    r = client.post(f"{G}/MC_Group000/kinematics/inverse", json={"position": xyz})
    assert r.status_code == 200, r.text
    assert r.json()["axes"] == pytest.approx([15.0, 20.0, 25.0], abs=1e-6)


def test_inverse_of_a_point_on_the_axis_is_symmetric(client: TestClient) -> None:
    r = client.post(f"{G}/MC_Group000/kinematics/inverse", json={"position": [0.0, 0.0, -100.0]})
    a0, a1, a2 = r.json()["axes"]
    assert a0 == pytest.approx(a1) and a1 == pytest.approx(a2) and a0 == pytest.approx(15.00688481, abs=1e-6)


def test_batches(client: TestClient) -> None:
    pts = [[0.0, 0.0, -100.0], [50.0, -20.0, -150.0], [-100.0, 80.0, -200.0]]
    r = client.post(f"{G}/MC_Group000/kinematics/inverse", json={"positions": pts})
    assert r.status_code == 200, r.text
    angles = r.json()["axes_list"]
    assert len(angles) == 3 and r.json()["axes"] is None
    r = client.post(f"{G}/MC_Group000/kinematics/forward", json={"axes_list": angles})
    out = r.json()
    assert out["inside_list"] == [True, True, True]
    for p, q in zip(out["positions"], pts, strict=True):
        assert p == pytest.approx(q, abs=1e-6)


def _detail(r: Any) -> list[dict[str, Any]]:
    assert r.status_code == 422, r.text
    return r.json()["detail"]  # type: ignore[no-any-return]


def test_points_outside_the_workspace_are_422_naming_the_point(client: TestClient) -> None:
    """§3.2: above Zu (-50 mm) is outside; -2000 mm is beyond reach (outside too). Each bad point is listed."""
    d = _detail(client.post(f"{G}/MC_Group000/kinematics/inverse",
                            json={"positions": [[0, 0, -100], [0, 0, -10], [0, 0, -150], [0, 0, -2000]]}))
    assert [e["loc"] for e in d] == [["body", "positions", 1], ["body", "positions", 3]]
    assert all(e["type"] == "outside_workspace" for e in d)
    d = _detail(client.post(f"{G}/MC_Group000/kinematics/inverse", json={"position": [0, 0, -10]}))
    assert d[0]["loc"] == ["body", "position"] and "outside the workspace" in d[0]["msg"]


def test_forward_without_solution_is_570f(client: TestClient) -> None:
    """§11 570F: joint angles whose three spheres do not intersect (the arms cannot close)."""
    d = _detail(client.post(f"{G}/MC_Group000/kinematics/forward", json={"axes_list": [[0, 0, 0], [180, 0, 0]]}))
    assert d == [{"loc": ["body", "axes_list", 1], "type": "kinematics_error", "code": "570F", "msg": d[0]["msg"]}]
    r = client.post(f"{G}/MC_Group000/kinematics/forward", json={"axes": [0, 0, 0]})
    assert r.status_code == 200 and r.json()["inside"] is False  # the zero pose, TCP at z 0 above Zu


@pytest.mark.parametrize("body", [
    {},  # neither
    {"position": [0, 0, -100], "positions": [[0, 0, -100]]},  # both
    {"position": [0, 0]},  # not three coordinates
    {"positions": [[0, 0, -100]] * (MAX_POINTS + 1)},  # bounded size
    {"position": [0, 0, -100], "extra": 1},
])
def test_malformed_requests_are_422(client: TestClient, body: dict[str, Any]) -> None:
    assert client.post(f"{G}/MC_Group000/kinematics/inverse", json=body).status_code == 422


def test_nan_is_refused(client: TestClient) -> None:
    r = client.post(f"{G}/MC_Group000/kinematics/forward", content='{"axes": [NaN, 0, 0]}',
                    headers={"content-type": "application/json"})
    assert r.status_code == 422


def test_put_config_and_a_group_without_kinematics_is_409(client: TestClient) -> None:
    cfg = client.get(f"{G}/MC_Group000").json()["config"]
    cfg["kinematics"] = None
    r = client.put(f"{G}/MC_Group000/config", json=cfg)
    assert r.status_code == 200, r.text
    assert r.json()["kinematics"] is None
    assert client.get(G).json()[0]["kinematics"] is None
    r = client.post(f"{G}/MC_Group000/kinematics/inverse", json={"position": [0, 0, -100]})
    assert r.status_code == 409
    assert r.json()["detail"][0]["loc"] == ["path", "name"] and "no robot kinematics" in r.json()["detail"][0]["msg"]
    assert client.put(f"{G}/MC_Group063/config", json=cfg).status_code == 404
