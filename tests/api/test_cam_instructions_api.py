"""Cam table instructions through the REST API on the demo project: MC_GenerateCamTable regenerates a project cam
table, MC_SaveCamTable writes it to the project's cams/<name>.csv (omron-group-and-cam.md §5.2, §5.4; D44)."""

from __future__ import annotations

from pathlib import Path

from fastapi.testclient import TestClient

from mcstudio.controller.mc.cam.csvio import read_cam_csv


def _post(client: TestClient, path: str, body: dict) -> dict:
    r = client.post(f"/api/v1{path}", json=body)
    assert r.status_code < 300, r.text
    return r.json()


def test_generate_then_save_writes_the_project_csv(client: TestClient, project_dir: Path) -> None:
    csv = project_dir / "cams" / "RiseDwellReturn.csv"
    before = csv.read_text()
    gen = _post(client, "/fb", {"type": "MC_GenerateCamTable", "inputs": {
        "CamTable": "RiseDwellReturn", "CamProperty": {"CycleTime": 1.0}, "Execute": True,
        "CamNodes": [{"Phase": 360.0, "Distance": 90.0, "Curve": "_mcStraightLine", "PhasePitch": 1.0}]}})
    _post(client, "/controller/step", {"cycles": 10, "until": {"fb": gen["id"], "output": "Done", "equals": True}})
    out = client.get(f"/api/v1/fb/{gen['id']}").json()["outputs"]
    assert out["Done"] and out["EndPointIndex"] == 360
    save = _post(client, "/fb", {"type": "MC_SaveCamTable", "inputs": {"CamTable": "RiseDwellReturn",
                                                                      "Execute": True}})
    for _ in range(200):  # the save runs in a background thread; the kernel steps until it reports Done
        _post(client, "/controller/step", {"cycles": 1})
        if client.get(f"/api/v1/fb/{save['id']}").json()["outputs"]["Done"]:
            break
    assert client.get(f"/api/v1/fb/{save['id']}").json()["outputs"]["Done"]
    after = csv.read_text()
    assert after != before
    phase, distance = read_cam_csv(csv)
    assert phase[-1] == 360.0 and distance[-1] == 90.0 and len(phase) == 361


def test_bad_cam_nodes_are_a_422_naming_the_member(client: TestClient) -> None:
    r = client.post("/api/v1/fb", json={"type": "MC_GenerateCamTable", "inputs": {
        "CamTable": "RiseDwellReturn", "CamNodes": [{"Phase": 1.0, "Bogus": 2}]}})
    assert r.status_code == 422
    assert "CamNodes[0]" in r.text and "Bogus" in r.text
