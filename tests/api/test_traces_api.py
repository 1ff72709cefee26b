"""Data trace REST API (api.md "traces") on the paused demo controller: configure, read, CSV, stop/restart/delete,
errors naming the field, settings saved in the project."""

from __future__ import annotations

import csv
import io
import json
from pathlib import Path
from typing import Any

from fastapi.testclient import TestClient

from tests.api.test_rest import API, post, power_on


def trace_body(**kw: Any) -> dict[str, Any]:
    body: dict[str, Any] = {
        "name": "Move",
        "variables": [{"kind": "axis", "target": "MC_Axis000", "name": "Cmd.Vel"},
                      {"kind": "axis", "target": "MC_Axis000", "name": "Cmd.Pos"}],
        "samples": 2500,
        "trigger": {"variable": {"kind": "axis", "target": "MC_Axis000", "name": "Cmd.Vel"},
                    "condition": "rising", "level": 0.001, "pre_trigger_percent": 20},
    }
    body.update(kw)
    return body


def test_trace_of_a_move_through_rest(client: TestClient, project_dir: Path) -> None:
    """A trace of Cmd.Vel triggered on Cmd.Vel rising through 0.001: the record holds 2500 samples with the trigger
    at sample 500 (20 %), the first period of the 0 → 100 move at 50 / 500 / 500 (Cmd.Vel ½·a·T / T = 0.25); the
    plateau is at Velocity; decimated reads and the CSV agree with the full record."""
    power_on(client)
    tr = post(client, "/traces", trace_body(), 201)
    assert tr["state"] == "waiting" and tr["id"] == 1 and tr["armed"] is False
    post(client, "/controller/step", {"cycles": 499})
    assert client.get(f"{API}/traces/1").json()["armed"] is False, "499 of the 500 pre-trigger samples"
    post(client, "/controller/step", {"cycles": 1})
    assert client.get(f"{API}/traces/1").json()["armed"] is True
    post(client, "/controller/step", {"cycles": 100})
    mv = post(client, "/fb", {"type": "MC_MoveAbsolute", "inputs": {
        "Axis": "MC_Axis000", "Execute": True, "Position": 100, "Velocity": 50, "Acceleration": 500,
        "Deceleration": 500, "Jerk": 0}}, 201)
    move_cycle = client.get(f"{API}/controller").json()["cycle"]  # the instance's first call is in this period
    post(client, "/controller/step", {"cycles": 1})
    assert client.get(f"{API}/traces/1").json()["state"] == "triggered"
    post(client, "/controller/step", {"cycles": 2500})
    d = client.get(f"{API}/traces/1").json()
    assert d["state"] == "done" and d["sample_count"] == 2500 and d["decimation"] == 1
    assert d["trigger_index"] == 500 and d["trigger_cycle"] == move_cycle
    assert d["cycles"][500] == move_cycle and d["time_s"][500] == move_cycle * 0.001
    vel = d["series"][0]["values"]
    assert vel[499] == 0.0 and abs(vel[500] - 0.25) < 1e-9 and abs(max(vel) - 50.0) < 1e-9
    assert d["series"][0]["label"] == "MC_Axis000.Cmd.Vel" and d["series"][0]["unit"] == "mm/s"
    assert mv["id"] >= 1
    small = client.get(f"{API}/traces/1", params={"max_points": 500}).json()
    assert small["decimation"] == 5 and len(small["cycles"]) == 500 and small["cycles"][100] == d["cycles"][500]
    r = client.get(f"{API}/traces/1/csv")
    assert r.status_code == 200 and r.headers["content-type"].startswith("text/csv")
    rows = list(csv.reader(io.StringIO(r.text)))
    assert rows[0] == ["cycle", "time_s", "MC_Axis000.Cmd.Vel [mm/s]", "MC_Axis000.Cmd.Pos [mm]"]
    assert len(rows) == 2501 and int(rows[501][0]) == move_cycle and float(rows[501][2]) == vel[500]
    listed = client.get(f"{API}/traces").json()
    assert [t["id"] for t in listed] == [1] and listed[0]["state"] == "done"


def test_stop_restart_delete_and_404(client: TestClient) -> None:
    tr = post(client, "/traces", trace_body(mode="continuous", trigger=None, samples=100), 201)
    assert tr["state"] == "running"
    post(client, "/controller/step", {"cycles": 150})
    d = client.get(f"{API}/traces/{tr['id']}").json()
    assert d["sample_count"] == 100 and d["cycles"][0] == 50
    assert post(client, f"/traces/{tr['id']}/stop", None)["state"] == "stopped"
    post(client, "/controller/step", {"cycles": 10})
    assert client.get(f"{API}/traces/{tr['id']}").json()["cycles"][-1] == 149
    re = post(client, f"/traces/{tr['id']}/restart", None)
    assert re["state"] == "running" and re["sample_count"] == 0 and re["start_cycle"] == 160
    assert client.delete(f"{API}/traces/{tr['id']}").status_code == 204
    for r in (client.get(f"{API}/traces/{tr['id']}"), client.get(f"{API}/traces/{tr['id']}/csv"),
              client.post(f"{API}/traces/{tr['id']}/stop"), client.delete(f"{API}/traces/{tr['id']}")):
        assert r.status_code == 404 and "no trace" in r.json()["detail"]


def test_bad_requests_name_the_field(client: TestClient) -> None:
    cases = [
        (trace_body(variables=[{"kind": "axis", "target": "MC_Axis099", "name": "Cmd.Vel"}]),
         ["body", "variables", 0, "target"], "MC_Axis099"),
        (trace_body(variables=[{"kind": "axis", "target": "MC_Axis000", "name": "Cmd.Speed"}]),
         ["body", "variables", 0, "name"], "Cmd.Speed"),
        (trace_body(variables=[{"kind": "fb", "target": "42", "name": "Busy"}]),
         ["body", "variables", 0, "target"], "instance 42"),
        (trace_body(variables=[{"kind": "pdo", "target": "99", "name": "6064:00"}]),
         ["body", "variables", 0, "target"], "node address 99"),
        (trace_body(trigger={"variable": {"kind": "group", "target": "NoGroup", "name": "Cmd.Vel"}}),
         ["body", "trigger", "variable", "target"], "NoGroup"),
    ]
    for body, loc, text in cases:
        r = client.post(f"{API}/traces", json=body)
        assert r.status_code == 422, r.text
        assert r.json()["detail"][0]["loc"] == loc and text in r.json()["detail"][0]["msg"]
    r = client.post(f"{API}/traces", json=trace_body(samples=10_000_000))
    assert r.status_code == 422 and r.json()["detail"][0]["loc"] == ["body", "samples"]
    r = client.post(f"{API}/traces", json=trace_body(variables=[{"kind": "motor", "target": "x", "name": "y"}]))
    assert r.status_code == 422 and r.json()["detail"][0]["loc"][:3] == ["body", "variables", 0]
    assert client.get(f"{API}/traces").json() == []


def test_variable_catalog_lists_axes_groups_instances_and_slaves(client: TestClient) -> None:
    fb = post(client, "/fb", {"type": "MC_Power", "inputs": {"Axis": "MC_Axis000"}}, 201)
    cat = client.get(f"{API}/traces/variables").json()
    ax = next(t for t in cat["axes"] if t["target"] == "MC_Axis000")
    names = {v["name"]: v for v in ax["variables"]}
    assert names["Cmd.Vel"]["unit"] == "mm/s" and names["Status.Standstill"]["type"] == "BOOL"
    assert {"Cmd.Pos", "Cmd.AccDec", "Cmd.Jerk", "Cmd.Trq", "Act.Pos", "Act.Vel", "Act.Trq"} <= set(names)
    assert any(g["target"] == "MC_Group000" for g in cat["groups"])
    inst = next(t for t in cat["instances"] if t["target"] == str(fb["id"]))
    assert {v["name"] for v in inst["variables"]} >= {"Status", "Busy", "Error", "ErrorID"}
    node1 = next(s for s in cat["slaves"] if s["target"] == "1")
    pos = next(v for v in node1["variables"] if v["name"] == "6064:00")
    assert pos["description"] == "Position actual value"
    assert cat["max_traces"] == 8 and cat["max_samples"] >= 100_000


def test_trace_settings_are_saved_in_the_project(client: TestClient, project_dir: Path) -> None:
    """PUT /project/traces changes the document (dirty, controller not restarted); POST /project/save writes it."""
    post(client, "/controller/step", {"cycles": 5})
    saved = [trace_body(), trace_body(name="Ring", mode="continuous", trigger=None)]
    r = client.put(f"{API}/project/traces", json=saved)
    assert r.status_code == 200 and [t["name"] for t in r.json()] == ["Move", "Ring"]
    st = client.get(f"{API}/controller").json()
    assert st["project_dirty"] is True and st["cycle"] == 5, "no restart"
    post(client, "/project/save", None)
    doc = json.loads((project_dir / "project.json").read_text())
    assert [t["name"] for t in doc["traces"]] == ["Move", "Ring"]
    assert doc["traces"][0]["trigger"]["pre_trigger_percent"] == 20
    assert client.get(f"{API}/project/traces").json()[1]["mode"] == "continuous"
    bad = client.put(f"{API}/project/traces", json=[trace_body(mode="continuous")])
    assert bad.status_code == 422
