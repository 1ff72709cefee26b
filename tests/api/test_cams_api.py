"""REST /cams (api.md "Cams", docs/api.md): list, read, write from nodes or points, delete, generate without saving,
CSV import/export; saving to the project folder and replacing the running controller's copy (D45)."""

from __future__ import annotations

import json
from pathlib import Path
from types import SimpleNamespace
from typing import Any

import numpy as np
import pytest
from fastapi.testclient import TestClient

from mcstudio.api.routers import cams as cams_router
from mcstudio.api.state import Studio
from mcstudio.controller.mc.cam.csvio import read_cam_csv

API = "/api/v1"
RDR_NODES = [  # modified sine rise 0 → 100 over 120°, dwell, return over 120°, dwell; master 360°/s
    {"Phase": 120, "Distance": 100, "Curve": "_mcModifiedSine", "PhasePitch": 0.1},
    {"Phase": 180, "Curve": "_mcConstantLine", "PhasePitch": 0.1},
    {"Phase": 300, "Distance": 0, "Curve": "_mcModifiedSine", "PhasePitch": 0.1},
    {"Phase": 360, "Curve": "_mcConstantLine", "PhasePitch": 0.1},
]


def _gen(client: TestClient, **body: Any) -> Any:
    body.setdefault("property", {"CycleTime": 1.0})
    body.setdefault("nodes", RDR_NODES)
    return client.post(f"{API}/cams/generate", json=body)


def test_list_and_get(client: TestClient) -> None:
    cams = {c["name"]: c for c in client.get(f"{API}/cams").json()}
    assert list(cams) == ["RiseDwellReturn", "FlyingSync"]
    rdr = cams["RiseDwellReturn"]
    assert (rdr["point_count"], rdr["max_data_number"], rdr["phase_end"], rdr["distance_max"]) == (3601, 3601, 360, 100)
    assert rdr["generated"] and rdr["nodes"] == 4 and rdr["in_use"] == []
    one = client.get(f"{API}/cams/FlyingSync").json()
    assert one["source"]["nodes"][1]["Curve"] == "_mcStraightLine" and one["saved"]
    assert len(one["phase"]) == 721 and one["phase"][:3] == [0, 0.5, 1.0]  # REAL values as short decimals
    assert client.get(f"{API}/cams/FlyingSync", params={"points": False}).json()["phase"] is None
    assert client.get(f"{API}/cams/Nope").status_code == 404
    r = client.get(f"{API}/cams/1bad")
    assert r.status_code == 422 and r.json()["detail"][0]["loc"] == ["path", "name"]


def test_generate_table_points_and_characteristics(client: TestClient) -> None:
    r = _gen(client)
    assert r.status_code == 200, r.text
    g = r.json()
    n = 3601
    assert not g["sampled"] and all(len(g[k]) == n for k in ("phase", "distance", "velocity", "acceleration", "jerk"))
    assert g["phase"][1200] == pytest.approx(120) and g["distance"][1200] == pytest.approx(100)
    table = g["characteristics"]["table"]
    assert table["master_velocity"] == 360 and table["point_count"] == n and table["end_point_index"] == n - 1
    # modified sine: Vm 1.760, Am 5.528, Jm 69.47 (docs/cams.md); rise 100 over 120° at 360°/s → 1/3 s
    seg = g["characteristics"]["segments"][0]
    assert seg["curve"] == "_mcModifiedSine" and seg["Vm"] == pytest.approx(1.760, abs=1e-3)
    assert seg["v_max"] == pytest.approx(100 * 1.7596 * 3, rel=1e-3)
    assert seg["a_max"] == pytest.approx(100 * 5.5280 * 9, rel=1e-3)
    assert seg["j_max"] == pytest.approx(100 * 69.466 * 27, rel=1e-3) and seg["time_s"] == pytest.approx(1 / 3)
    assert g["characteristics"]["segments"][1]["Vm"] is None  # a dwell has no rise
    assert max(abs(v) for v in g["velocity"]) == pytest.approx(seg["v_max"], rel=1e-3)
    assert table["Vm"] == pytest.approx(1.760, abs=1e-3) and table["v_node"] in (0, 2)
    assert g["continuity"] == []  # modified sine between dwells: smooth
    # a given master speed scales v by k, a by k², j by k³
    slow = _gen(client, master_velocity=180).json()["characteristics"]["segments"][0]
    assert slow["v_max"] == pytest.approx(seg["v_max"] / 2) and slow["a_max"] == pytest.approx(seg["a_max"] / 4)
    assert slow["j_max"] == pytest.approx(seg["j_max"] / 8)


def test_generate_sampled_for_plots(client: TestClient) -> None:
    g = _gen(client, max_points=400).json()
    assert g["sampled"] and len(g["phase"]) <= 400
    assert np.all(np.diff(g["phase"]) >= 0)
    # both sides of each boundary are there: phase 120 appears twice
    assert sum(1 for p in g["phase"] if p == pytest.approx(120)) == 2
    assert g["characteristics"]["table"]["point_count"] == 3601


def test_generate_continuity_warnings(client: TestClient) -> None:
    nodes = [{"Phase": 90, "Distance": 90, "Curve": "_mcStraightLine"},  # constant velocity …
             {"Phase": 180, "Curve": "_mcConstantLine"},  # … into a dwell: the velocity jumps
             {"Phase": 360, "Distance": 0, "Curve": "_mcCycloidal"}]
    g = _gen(client, nodes=nodes, property={"CycleTime": 2}).json()
    jumps = [(j["node"], j["quantity"]) for j in g["continuity"]]
    assert (0, "velocity") in jumps and all(node == 0 for node, _ in jumps)
    j = next(j for j in g["continuity"] if j["quantity"] == "velocity")
    assert j["phase"] == 90 and j["left"] == pytest.approx(180) and j["right"] == 0 and j["size"] == pytest.approx(-180)
    assert "velocity jumps by -180" in j["message"]
    assert g["characteristics"]["segments"][0]["a_max"] == 0
    periodic = _gen(client, nodes=nodes, property={"CycleTime": 2}, periodic=True).json()["continuity"]
    assert any(j["node"] == 2 and j["quantity"] == "velocity" for j in periodic)  # the wrap: 0 → 180 mm/s


def test_generate_errors_name_the_member(client: TestClient) -> None:
    nodes = [dict(n) for n in RDR_NODES]
    nodes[2]["Phase"] = 170
    r = _gen(client, nodes=nodes)
    assert r.status_code == 422
    d = r.json()["detail"][0]
    assert d["loc"] == ["body", "nodes", 2, "Phase"] and d["code"] == "5740"
    nodes = [dict(n) for n in RDR_NODES]
    nodes[1]["PhasePitch"] = 0.0005  # below 0.001: pydantic's range, before the instruction
    d = _gen(client, nodes=nodes).json()["detail"][0]
    assert d["loc"] == ["body", "nodes", 1, "PhasePitch"]
    nodes[1]["PhasePitch"] = 0.1
    nodes[0]["Distance"] = 0.0002  # the manual's |x| ≥ 0.001 rule: 573D, ErrorParameterCode 0001
    d = _gen(client, nodes=nodes).json()["detail"][0]
    assert d["loc"] == ["body", "nodes", 0, "Distance"] and d["code"] == "573D/0001"
    nodes[0]["Distance"] = 100
    nodes[0]["Curve"] = "_mcSine"
    d = _gen(client, nodes=nodes).json()["detail"][0]
    assert d["loc"] == ["body", "nodes", 0, "Curve"] and "_mcModifiedSine" in d["msg"]
    r = _gen(client, size=3000)  # 3601 points do not fit a table of 3000 elements
    assert r.status_code == 422 and r.json()["detail"][0]["code"] == "5741"
    r = _gen(client, phase_pitch=0.001)  # 360,001 points: beyond 65,535
    assert r.status_code == 422 and r.json()["detail"][0]["code"] == "5741"
    assert _gen(client, nodes=[RDR_NODES[0]] * 360).json()["detail"][0]["loc"] == ["body", "nodes"]
    assert _gen(client, property={"CycleTime": 0}).json()["detail"][0]["loc"] == ["body", "property", "CycleTime"]


def test_put_from_nodes_saves_and_downloads_without_restart(client: TestClient, studio: Studio,
                                                            project_dir: Path) -> None:
    client.post(f"{API}/controller/step", json={"cycles": 5})
    pw = client.post(f"{API}/fb", json={"type": "MC_Power", "inputs": {"Axis": "MC_Axis000", "Enable": True}}).json()
    nodes = [{"Phase": 180, "Distance": 50, "Curve": "_mcCycloidal", "PhasePitch": 1},
             {"Phase": 360, "Distance": 0, "Curve": "_mcCycloidal", "PhasePitch": 1}]
    r = client.put(f"{API}/cams/Lift", json={"description": "up and down", "source": {"property": {"CycleTime": 2},
                                                                                       "nodes": nodes}})
    assert r.status_code == 200, r.text
    out = r.json()
    assert out["saved"] and out["point_count"] == 361 and out["distance_max"] == 50 and out["generated"]
    # saved: the CSV and the definition in project.json (atomically, with the previous document as .bak)
    p, d = read_cam_csv(project_dir / "cams" / "Lift.csv")
    assert p.size == 361 and d[180] == 50
    doc = json.loads((project_dir / "project.json").read_text())
    assert [c["name"] for c in doc["cams"]] == ["RiseDwellReturn", "FlyingSync", "Lift"]
    assert doc["cams"][2]["source"]["nodes"][0]["Curve"] == "_mcCycloidal"
    assert (project_dir / "project.json.bak").is_file()
    # downloaded into the running controller without a restart: same cycle, the instance still there
    c = studio.controller
    assert c.cycle == 5 and pw["id"] in c.program
    assert c.mc.cam_tables["Lift"].end_point_index == 360 and c.mc.cam_tables["Lift"] is not c.cams["Lift"]
    assert client.get(f"{API}/controller").json()["project_dirty"] is False
    # replace it; a reset keeps the data
    nodes[0]["Distance"] = 80
    assert client.put(f"{API}/cams/Lift", json={"source": {"property": {"CycleTime": 2}, "nodes": nodes}}).status_code \
        == 200
    client.post(f"{API}/controller/reset")
    assert studio.controller.mc.cam_tables["Lift"].valid()[1].max() == 80


def test_put_from_points_and_size(client: TestClient, studio: Studio) -> None:
    r = client.put(f"{API}/cams/Tri", json={"size": 10, "points": {"phase": [0, 1, 2], "distance": [0, 1.5, 0]}})
    assert r.status_code == 200, r.text
    assert r.json()["max_data_number"] == 10 and r.json()["point_count"] == 3 and not r.json()["generated"]
    t = studio.controller.mc.cam_tables["Tri"]
    assert t.max_data_number == 10 and t.phase[3] == 0 and t.end_point_index == 2
    r = client.put(f"{API}/cams/Tri", json={"points": {"phase": [0, 2, 1], "distance": [0, 1, 0]}})
    assert r.status_code == 422 and r.json()["detail"][0]["loc"] == ["body", "points", "phase", 2]
    r = client.put(f"{API}/cams/Tri", json={"points": {"phase": [0, 1], "distance": [0, 1]}, "source": {
        "nodes": RDR_NODES}})
    assert r.status_code == 422
    r = client.put(f"{API}/cams/Tri", json={"size": 2})  # neither: keep the data, change the size → too small
    assert r.status_code == 422 and r.json()["detail"][0]["loc"] == ["body", "size"]
    r = client.put(f"{API}/cams/Tri", json={"description": "kept", "size": 5})
    assert r.status_code == 200 and r.json()["max_data_number"] == 5 and r.json()["description"] == "kept"
    assert client.put(f"{API}/cams/tri", json={"points": {"phase": [0, 1], "distance": [0, 1]}}).status_code == 422
    assert client.put(f"{API}/cams/New", json={}).status_code == 422
    big = {"points": {"phase": list(range(65536)), "distance": [0] * 65536}}
    r = client.put(f"{API}/cams/Big", json=big)
    assert r.status_code == 422 and r.json()["detail"][0]["loc"][:3] == ["body", "points", "phase"]


def test_busy_users_of_a_table() -> None:
    """The rule: an instance whose CamTable in-out names the table and that is Busy (or Active, InCam, InSync)."""
    def inst(fid: int, table: str, **out: bool) -> Any:
        cam_in = SimpleNamespace(name="MC_CamIn")
        return SimpleNamespace(fb=SimpleNamespace(inp={"CamTable": table}, out=out, DEF=cam_in))

    c = SimpleNamespace(program={1: inst(1, "A", Busy=True), 2: inst(2, "A", Busy=False, Done=True),
                                 3: inst(3, "B", InCam=True), 4: inst(4, "A", Active=True)})
    assert cams_router._users(c, "A") == ["MC_CamIn #1", "MC_CamIn #4"]  # type: ignore[arg-type]
    assert cams_router._users(c, "C") == []  # type: ignore[arg-type]


def test_refused_while_an_instance_uses_the_table(client: TestClient, monkeypatch: pytest.MonkeyPatch) -> None:
    """409 for writes and deletion of a table in use; other tables stay writable."""
    monkeypatch.setattr(cams_router, "_users", lambda c, name: ["MC_CamIn #7"] if name == "FlyingSync" else [])
    assert client.get(f"{API}/cams").json()[1]["in_use"] == ["MC_CamIn #7"]
    r = client.put(f"{API}/cams/FlyingSync", json={"points": {"phase": [0, 1], "distance": [0, 1]}})
    assert r.status_code == 409 and "MC_CamIn #7" in r.json()["detail"]
    assert client.delete(f"{API}/cams/FlyingSync").status_code == 409
    r = client.put(f"{API}/cams/FlyingSync/csv", content="phase,distance\n0,0\n1,1\n", headers={"content-type":
                                                                                                   "text/csv"})
    assert r.status_code == 409
    assert client.put(f"{API}/cams/RiseDwellReturn", json={"description": "other table"}).status_code == 200
    monkeypatch.undo()
    assert client.delete(f"{API}/cams/FlyingSync").status_code == 200


def test_delete(client: TestClient, studio: Studio, project_dir: Path) -> None:
    r = client.delete(f"{API}/cams/FlyingSync")
    assert r.status_code == 200 and r.json() == {"name": "FlyingSync", "saved": True}
    assert not (project_dir / "cams" / "FlyingSync.csv").exists()
    assert [c["name"] for c in json.loads((project_dir / "project.json").read_text())["cams"]] == ["RiseDwellReturn"]
    assert "FlyingSync" not in studio.controller.mc.cam_tables
    assert client.delete(f"{API}/cams/FlyingSync").status_code == 404


def test_csv_export_import_round_trip(client: TestClient, studio: Studio) -> None:
    r = client.get(f"{API}/cams/FlyingSync/csv")
    assert r.status_code == 200 and r.headers["content-type"].startswith("text/csv")
    assert 'filename="FlyingSync.csv"' in r.headers["content-disposition"]
    text = r.text
    assert text.splitlines()[1] == "phase,distance" and len(text.splitlines()) == 2 + 721
    r = client.put(f"{API}/cams/Copy/csv", content=text.encode(), headers={"content-type": "text/csv"})
    assert r.status_code == 200, r.text
    assert r.json()["point_count"] == 721 and not r.json()["generated"]
    a, b = studio.controller.cams["FlyingSync"], studio.controller.cams["Copy"]
    assert np.array_equal(a.valid()[0], b.valid()[0]) and np.array_equal(a.valid()[1], b.valid()[1])
    assert client.get(f"{API}/cams/Copy/csv").text.splitlines()[2:] == text.splitlines()[2:]
    # multipart upload (POST), replacing a generated table: it loses its source
    up = client.post(f"{API}/cams/FlyingSync/csv", files={"file": ("f.csv", b"phase,distance\n0,0\n1,2\n")})
    assert up.status_code == 200 and up.json()["source"] is None and up.json()["point_count"] == 2


def test_csv_import_errors_and_limits(client: TestClient) -> None:
    bad = "phase,distance\n0,0\n1,x\n2,1\n1.5,1\n"
    r = client.put(f"{API}/cams/Bad/csv", content=bad, headers={"content-type": "text/csv"})
    assert r.status_code == 422
    assert [d["line"] for d in r.json()["detail"]] == [3, 5] and "line 3: distance" in r.json()["detail"][0]["msg"]
    r = client.put(f"{API}/cams/Bad/csv", content=b"\xff\xfe", headers={"content-type": "text/csv"})
    assert r.status_code == 422 and "not UTF-8" in r.json()["detail"][0]["msg"]
    lines = "phase,distance\n" + "".join(f"{i},0\n" for i in range(65536))
    r = client.put(f"{API}/cams/Bad/csv", content=lines, headers={"content-type": "text/csv"})
    assert r.status_code == 422 and "more than 65535 points" in r.json()["detail"][0]["msg"]
    huge = b"phase,distance\n" + b"#" * (5 * 1024 * 1024)
    assert client.put(f"{API}/cams/Bad/csv", content=huge, headers={"content-type": "text/csv"}).status_code == 413
    r = client.post(f"{API}/cams/Bad/csv", files={"other": ("f.csv", b"phase,distance\n0,0\n1,1\n")})
    assert r.status_code == 422 and r.json()["detail"][0]["loc"] == ["body", "file"]
    assert client.get(f"{API}/cams").json()[-1]["name"] == "FlyingSync"  # nothing was created


def test_project_document_and_cams(client: TestClient, studio: Studio, project_dir: Path) -> None:
    doc = client.get(f"{API}/project").json()
    assert [c["name"] for c in doc["cams"]] == ["RiseDwellReturn", "FlyingSync"]
    # a new definition with a source is generated when the document is applied, its CSV written on save
    doc["cams"].append({"name": "Extra", "source": {"nodes": [{"Phase": 10, "Distance": 1, "PhasePitch": 1}]}})
    assert client.put(f"{API}/project", json=doc).status_code == 200
    assert studio.controller.mc.cam_tables["Extra"].end_point_index == 10
    assert client.get(f"{API}/controller").json()["project_dirty"] is True
    assert client.post(f"{API}/project/save").status_code == 200
    assert read_cam_csv(project_dir / "cams" / "Extra.csv")[0].size == 11
    # a definition without source needs data
    doc["cams"].append({"name": "Empty"})
    r = client.put(f"{API}/project", json=doc)
    assert r.status_code == 422 and r.json()["detail"][0]["path"] == "cams[3]"
    # opening the project folder again reads the files
    assert client.post(f"{API}/projects/open", json={"name": "demo"}).status_code == 200
    assert set(studio.controller.mc.cam_tables) == {"RiseDwellReturn", "FlyingSync", "Extra"}


def test_busy_mc_camin_blocks_the_table(client: TestClient) -> None:
    """With a real MC_CamIn (D45): Busy while camming → 409; after MC_Stop on the slave and deleting it → writable."""
    for axis in ("MC_Axis003", "MC_Axis000"):
        pw = client.post(f"{API}/fb", json={"type": "MC_Power", "inputs": {"Axis": axis, "Enable": True}}).json()
        client.post(f"{API}/controller/step", json={"cycles": 500, "until": {"fb": pw["id"], "output": "Status",
                                                                              "equals": True}})
    cam = client.post(f"{API}/fb", json={"type": "MC_CamIn", "inputs": {
        "Master": "MC_Axis003", "Slave": "MC_Axis000", "CamTable": "FlyingSync", "Execute": True, "Periodic": True}})
    assert cam.status_code == 201, cam.text
    cid = cam.json()["id"]
    client.post(f"{API}/controller/step", json={"cycles": 5})
    assert client.get(f"{API}/fb/{cid}").json()["outputs"]["Busy"] is True
    assert client.get(f"{API}/cams").json()[1]["in_use"] == [f"MC_CamIn #{cid}"]
    r = client.put(f"{API}/cams/FlyingSync", json={"description": "changed"})
    assert r.status_code == 409 and f"MC_CamIn #{cid}" in r.json()["detail"]
    stop = client.post(f"{API}/fb", json={"type": "MC_Stop", "inputs": {"Axis": "MC_Axis000", "Execute": True,
                                                                        "Deceleration": 1000}}).json()
    client.post(f"{API}/controller/step", json={"cycles": 100, "until": {"fb": stop["id"], "output": "Done",
                                                                         "equals": True}})
    assert client.get(f"{API}/fb/{cid}").json()["outputs"]["Busy"] is False
    assert client.put(f"{API}/cams/FlyingSync", json={"description": "changed"}).status_code == 200
