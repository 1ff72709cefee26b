"""REST contract (api.md) through httpx, including issue #2's acceptance scenario on the paused controller."""

from __future__ import annotations

import json
import shutil
from pathlib import Path
from typing import Any

import pytest
from fastapi.testclient import TestClient
from ruckig import InputParameter, Ruckig, Trajectory

API = "/api/v1"


def post(client: TestClient, path: str, body: Any, status: int = 200) -> Any:
    r = client.post(API + path, json=body)
    assert r.status_code == status, r.text
    return r.json()


def power_on(client: TestClient, axis: str = "MC_Axis000") -> int:
    fb = post(client, "/fb", {"type": "MC_Power", "inputs": {"Axis": axis, "Enable": True}}, 201)
    st = post(client, "/controller/step", {"cycles": 100, "until": {"fb": fb["id"], "output": "Status",
                                                                      "equals": True}})
    assert st["until_met"] is True
    return int(fb["id"])


def test_health_and_status(client: TestClient) -> None:
    assert client.get(f"{API}/health").json()["status"] == "ok"
    st = client.get(f"{API}/controller").json()
    assert st["mode"] == "paused" and st["cycle"] == 0 and st["period_s"] == 0.001
    assert st["project"] == "Demo machine" and st["project_dirty"] is False


def test_acceptance_move_absolute_trapezoid(client: TestClient) -> None:
    """Issue #2: paused; MC_Power on MC_Axis000; MC_MoveAbsolute 100 / 50 / 500 / 500 / Jerk 0 → Done at 2.100 s
    ± 2 periods with Act.Pos = 100 ± 1e-9."""
    power_on(client)
    mv = post(client, "/fb", {"type": "MC_MoveAbsolute", "inputs": {
        "Axis": "MC_Axis000", "Execute": True, "Position": 100, "Velocity": 50, "Acceleration": 500,
        "Deceleration": 500, "Jerk": 0}}, 201)
    t0 = client.get(f"{API}/controller").json()["time_s"]
    st = post(client, "/controller/step", {"cycles": 10000, "until": {"fb": mv["id"], "output": "Done",
                                                                       "equals": True}})
    assert st["until_met"]
    assert abs((st["time_s"] - t0) - 2.100) <= 2 * 0.001
    ax = client.get(f"{API}/axes/MC_Axis000").json()
    assert abs(ax["variables"]["Act"]["Pos"] - 100.0) <= 1e-9
    assert ax["variables"]["Status"]["Standstill"] is True
    out = client.get(f"{API}/fb/{mv['id']}").json()["outputs"]
    assert out == {"Done": True, "Busy": False, "Active": False, "CommandAborted": False, "Error": False,
                   "ErrorID": "0000"}


def test_acceptance_move_absolute_s_curve_matches_ruckig(client: TestClient) -> None:
    power_on(client)
    mv = post(client, "/fb", {"type": "MC_MoveAbsolute", "inputs": {
        "Axis": "MC_Axis000", "Execute": True, "Position": 100, "Velocity": 50, "Acceleration": 500,
        "Deceleration": 500, "Jerk": 5000}}, 201)
    t0 = client.get(f"{API}/controller").json()["time_s"]
    st = post(client, "/controller/step", {"cycles": 10000, "until": {"fb": mv["id"], "output": "Done",
                                                                       "equals": True}})
    inp = InputParameter(1)
    inp.current_position, inp.target_position = [0.0], [100.0]
    inp.max_velocity, inp.max_acceleration, inp.max_jerk = [50.0], [500.0], [5000.0]
    traj = Trajectory(1)
    Ruckig(1).calculate(inp, traj)
    assert abs((st["time_s"] - t0) - traj.duration) <= 2 * 0.001


def test_acceptance_velocity_zero_is_5422(client: TestClient) -> None:
    power_on(client)
    mv = post(client, "/fb", {"type": "MC_MoveAbsolute", "inputs": {
        "Axis": "MC_Axis000", "Execute": True, "Position": 100, "Velocity": 0}}, 201)
    post(client, "/controller/step", {"cycles": 1})
    out = client.get(f"{API}/fb/{mv['id']}").json()["outputs"]
    assert out["Error"] is True and out["ErrorID"] == "5422"
    ax = client.get(f"{API}/axes/MC_Axis000").json()["variables"]
    assert ax["Status"]["ErrorStop"] and ax["MFaultLvl"] == {"Active": True, "Code": "5422"}
    ev = client.get(f"{API}/events").json()
    assert any(e["code"] == "54220000" and e["source"].startswith("MC_Axis000") for e in ev)
    post(client, "/controller/step", {"cycles": 1, "until": {"fb": mv["id"], "output": "ErrorID",
                                                            "equals": "5422"}})


@pytest.mark.parametrize(
    ("body", "loc"),
    [
        ({"type": "MC_MoveAbsolute", "inputs": {"Axis": "MC_Axis999", "Execute": True}}, ["body", "inputs", "Axis"]),
        ({"type": "MC_MoveAbsolute", "inputs": {"Axis": "MC_Axis000", "Position": "far"}},
         ["body", "inputs", "Position"]),
        ({"type": "MC_MoveAbsolute", "inputs": {"Axis": "MC_Axis000", "Execute": "yes"}},
         ["body", "inputs", "Execute"]),
        ({"type": "MC_MoveAbsolute", "inputs": {"Axis": "MC_Axis000", "Speed": 3}}, ["body", "inputs", "Speed"]),
        ({"type": "MC_MoveAbsolute", "inputs": {"Axis": "MC_Axis000", "BufferMode": "_mcSometimes"}},
         ["body", "inputs", "BufferMode"]),
        ({"type": "MC_MoveAbsolute", "inputs": {"Axis": 3}}, ["body", "inputs", "Axis"]),
        ({"type": "MC_Teleport", "inputs": {}}, ["body", "type"]),
        ({"type": "MC_Power", "inputs": {}, "lease_s": -1}, ["body", "lease_s"]),
        ({"inputs": {}}, ["body", "type"]),
        # a misspelt structure member is named, not silently replaced by its default
        ({"type": "MC_TouchProbe", "inputs": {"TriggerInput": {"Mode": "_mcDrive", "InputDrv": "_mcEXT"}}},
         ["body", "inputs", "TriggerInput"]),
        ({"type": "MC_HomeWithParameter", "inputs": {"HomingParameter": {"HomeVel": 10.0}}},
         ["body", "inputs", "HomingParameter"]),
    ],
)
def test_bad_fb_requests_name_the_field(client: TestClient, body: dict, loc: list) -> None:
    r = client.post(f"{API}/fb", json=body)
    assert r.status_code == 422, r.text
    assert any(d["loc"][: len(loc)] == loc for d in r.json()["detail"]), r.json()


def test_nan_and_infinity_are_refused(client: TestClient) -> None:
    r = client.post(f"{API}/fb", content=b'{"type": "MC_MoveAbsolute", "inputs": {"Position": NaN}}',
                    headers={"content-type": "application/json"})
    assert r.status_code == 422
    r = client.post(f"{API}/fb", content=b'{"type": "MC_MoveAbsolute", "inputs": {"Velocity": Infinity}}',
                    headers={"content-type": "application/json"})
    assert r.status_code == 422


def test_fb_lifecycle_and_404s(client: TestClient) -> None:
    fb = post(client, "/fb", {"type": "MC_Power", "inputs": {"Axis": "MC_Axis001"}}, 201)
    assert fb["inputs"] == {"Axis": "MC_Axis001", "Enable": False}
    r = client.patch(f"{API}/fb/{fb['id']}", json={"inputs": {"Enable": True}})
    assert r.status_code == 200 and r.json()["inputs"]["Enable"] is True
    assert [f["id"] for f in client.get(f"{API}/fb").json()] == [fb["id"]]
    assert client.delete(f"{API}/fb/{fb['id']}").status_code == 204
    assert client.get(f"{API}/fb/{fb['id']}").status_code == 404
    assert client.patch(f"{API}/fb/{fb['id']}", json={"inputs": {}}).status_code == 404
    assert client.delete(f"{API}/fb/{fb['id']}").status_code == 404
    assert client.get(f"{API}/fb/not-a-number").status_code == 422


def test_step_until_errors(client: TestClient) -> None:
    fb = post(client, "/fb", {"type": "MC_Power", "inputs": {"Axis": "MC_Axis000"}}, 201)
    r = client.post(f"{API}/controller/step", json={"cycles": 5, "until": {"fb": fb["id"], "output": "Done",
                                                                            "equals": True}})
    assert r.status_code == 422 and r.json()["detail"][0]["loc"] == ["body", "until", "output"]
    r = client.post(f"{API}/controller/step", json={"cycles": 5, "until": {"fb": 999, "output": "Done",
                                                                            "equals": True}})
    assert r.status_code == 404
    assert client.post(f"{API}/controller/step", json={"cycles": 0}).status_code == 422


def test_step_only_while_paused(client: TestClient) -> None:
    assert client.put(f"{API}/controller/mode", json={"mode": "fast"}).json()["mode"] == "fast"
    r = client.post(f"{API}/controller/step", json={"cycles": 1})
    assert r.status_code == 409 and "paused" in r.json()["detail"]
    assert client.put(f"{API}/controller/mode", json={"mode": "warp"}).status_code == 422


def test_controller_reset_restarts_at_cycle_zero(client: TestClient) -> None:
    power_on(client)
    assert client.get(f"{API}/controller").json()["cycle"] > 0
    st = client.post(f"{API}/controller/reset").json()
    assert st["cycle"] == 0
    assert client.get(f"{API}/fb").json() == []


def test_axes_list_and_detail(client: TestClient) -> None:
    axes = client.get(f"{API}/axes").json()
    # the demo: three ball-screw axes, a virtual axis, the Delta3's A0–A2 and its conveyor (nodes 4–7)
    assert [a["name"] for a in axes] == [f"MC_Axis00{k}" for k in range(8)]
    assert axes[3]["type"] == "_mcVirServo" and axes[3]["node_address"] is None
    assert [(a["units"], a["node_address"]) for a in axes[4:]] == [
        ("_mcDeg", 4), ("_mcDeg", 5), ("_mcDeg", 6), ("_mcMm", 7)]
    d = client.get(f"{API}/axes/MC_Axis001").json()
    v = d["variables"]
    assert set(v) == {"Status", "Details", "Dir", "DrvStatus", "Cmd", "Act", "MFaultLvl", "Obsr", "Cfg", "Scale"}
    assert v["Status"]["Disabled"] and v["Cfg"] == {"AxNo": 1, "AxEnable": "_mcUsedAxis", "AxType": "_mcServo",
                                                    "NodeAddress": 2, "ExecID": 1}
    assert v["Scale"]["Num"] == 1048576 and v["Scale"]["Units"] == "_mcMm"
    assert d["config"]["parameters"]["Operation"]["MaxVel"] == 500.0
    assert client.get(f"{API}/axes/Nope").status_code == 404


def test_fb_types_catalog(client: TestClient) -> None:
    types = {t["name"]: t for t in client.get(f"{API}/fb-types").json()}
    assert {"MC_Power", "MC_Reset", "MC_Stop", "MC_MoveAbsolute", "MC_MoveRelative", "MC_MoveVelocity",
            "MC_MoveJog"} <= set(types)
    ma = types["MC_MoveAbsolute"]
    names = [v["name"] for v in ma["inputs"]]
    assert names == ["Execute", "Position", "Velocity", "Acceleration", "Deceleration", "Jerk", "Direction",
                     "BufferMode"]
    bm = next(v for v in ma["inputs"] if v["name"] == "BufferMode")
    assert bm["default"] == "_mcAborting" and len(bm["enumerators"]) == 6
    assert [v["name"] for v in ma["outputs"]] == ["Done", "Busy", "Active", "CommandAborted", "Error", "ErrorID"]
    assert ma["inouts"][0]["name"] == "Axis"


def test_errors_catalog(client: TestClient) -> None:
    errs = {e["code"]: e for e in client.get(f"{API}/errors").json()}
    assert errs["5422"]["name"] == "Target Velocity Setting Out of Range"
    assert errs["5422"]["event_code"] == "54220000"
    assert len(errs) >= 161


def test_project_get_put_save_and_dirty(client: TestClient, project_dir: Path) -> None:
    doc = client.get(f"{API}/project").json()
    doc["axes"][2]["parameters"]["Operation"]["MaxJogVel"] = 42.0
    r = client.put(f"{API}/project", json=doc)
    assert r.status_code == 200, r.text
    assert client.get(f"{API}/controller").json()["project_dirty"] is True
    saved = client.post(f"{API}/project/save").json()
    assert Path(saved["path"]) == project_dir / "project.json"
    on_disk = json.loads((project_dir / "project.json").read_text())
    assert on_disk["axes"][2]["parameters"]["Operation"]["MaxJogVel"] == 42.0
    assert (project_dir / "project.json.bak").is_file()
    assert client.get(f"{API}/controller").json()["project_dirty"] is False


def test_put_project_lists_every_invalid_field(client: TestClient) -> None:
    doc = client.get(f"{API}/project").json()
    doc["axes"][0]["parameters"]["Operation"]["MaxVel"] = "fast"
    doc["axes"][1]["number"] = 300
    doc["controller"]["primary_period_us"] = 3
    r = client.put(f"{API}/project", json=doc)
    assert r.status_code == 422
    paths = {d["path"] for d in r.json()["detail"]}
    assert paths == {"axes[0].parameters.Operation.MaxVel", "axes[1].number", "controller.primary_period_us"}
    assert ["body", "axes", 1, "number"] in [d["loc"] for d in r.json()["detail"]]
    assert client.put(f"{API}/project", json=[1, 2]).status_code == 422


def test_put_project_refused_while_moving(client: TestClient) -> None:
    power_on(client)
    post(client, "/fb", {"type": "MC_MoveVelocity", "inputs": {"Axis": "MC_Axis000", "Execute": True,
                                                               "Velocity": 10}}, 201)
    post(client, "/controller/step", {"cycles": 5})
    doc = client.get(f"{API}/project").json()
    r = client.put(f"{API}/project", json=doc)
    assert r.status_code == 409 and "MC_Axis000" in r.json()["detail"]


def test_put_axis_config(client: TestClient) -> None:
    cfg = client.get(f"{API}/axes/MC_Axis001").json()["config"]
    cfg["parameters"]["Operation"]["MaxVel"] = 250.0
    r = client.put(f"{API}/axes/MC_Axis001/config", json=cfg)
    assert r.status_code == 200, r.text
    assert client.get(f"{API}/axes/MC_Axis001").json()["config"]["parameters"]["Operation"]["MaxVel"] == 250.0
    cfg["parameters"]["Operation"]["MaxJogVel"] = 300.0
    r = client.put(f"{API}/axes/MC_Axis001/config", json=cfg)
    assert r.status_code == 422
    assert r.json()["detail"][0]["path"] == "axes[1].parameters.Operation.MaxJogVel"
    assert client.put(f"{API}/axes/Nope/config", json=cfg).status_code == 404


def test_projects_list_and_open(client: TestClient, project_dir: Path) -> None:
    other = project_dir.parent / "other"
    other.mkdir()
    doc = json.loads((project_dir / "project.json").read_text())
    doc["name"] = "Other machine"
    doc["axes"] = doc["axes"][:1]
    doc["groups"] = []  # (the demo robot's axes are gone)
    (other / "project.json").write_text(json.dumps(doc))
    shutil.copytree(project_dir / "cams", other / "cams")  # the cam tables' data files
    bad = project_dir.parent / "broken"
    bad.mkdir()
    (bad / "project.json").write_text("{")
    listing = {p["name"]: p for p in client.get(f"{API}/projects").json()}
    assert listing["demo"]["current"] and listing["other"]["valid"] and not listing["broken"]["valid"]
    r = client.post(f"{API}/projects/open", json={"name": "other"})
    assert r.status_code == 200 and r.json()["name"] == "Other machine"
    assert client.get(f"{API}/controller").json()["project"] == "Other machine"
    assert client.post(f"{API}/projects/open", json={"name": "broken"}).status_code == 422
    assert client.post(f"{API}/projects/open", json={"name": "../../etc"}).status_code == 422
    assert client.post(f"{API}/projects/open", json={"name": "missing"}).status_code == 404


def test_project_schema(client: TestClient) -> None:
    schema = client.get(f"{API}/project/schema").json()
    assert schema["title"] == "Project" and "axes" in schema["properties"]
    assert "OperationSettings" in json.dumps(schema)


def test_two_identical_scripted_runs_give_identical_traces(client: TestClient) -> None:
    """Issue #2: the same REST script twice (controller reset in between) gives identical position traces."""

    def run() -> list[tuple[float, float]]:
        client.post(f"{API}/controller/reset")
        power_on(client)
        power_on(client, "MC_Axis001")
        post(client, "/fb", {"type": "MC_MoveAbsolute", "inputs": {
            "Axis": "MC_Axis000", "Execute": True, "Position": 33.3, "Velocity": 70, "Acceleration": 800,
            "Deceleration": 600, "Jerk": 9000}}, 201)
        post(client, "/fb", {"type": "MC_MoveVelocity", "inputs": {
            "Axis": "MC_Axis001", "Execute": True, "Velocity": 12.5, "Acceleration": 100, "Deceleration": 100}}, 201)
        trace = []
        for _ in range(60):
            post(client, "/controller/step", {"cycles": 13})
            axes = client.get(f"{API}/axes").json()
            trace.append((axes[0]["act_pos"], axes[1]["cmd_pos"]))
        return trace

    first, second = run(), run()
    assert first == second
    assert first[-1][0] > 30


def test_snapshot_and_websocket(client: TestClient) -> None:
    snap = client.get(f"{API}/snapshot").json()
    assert snap["type"] == "snapshot" and len(snap["axes"]) == 8
    with client.websocket_connect(f"{API}/ws") as ws:
        ws.send_json({"type": "subscribe", "rate_hz": 60, "axes": ["MC_Axis002"], "fbs": [], "events": True})
        while (msg := ws.receive_json())["type"] != "subscribed":
            pass
        assert msg["axes"] == ["MC_Axis002"]
        ws.send_json({"type": "bogus"})
        while (msg := ws.receive_json())["type"] != "error":
            pass
        assert "bogus" in msg["detail"]
        client.post(f"{API}/controller/step", json={"cycles": 3})
        while (msg := ws.receive_json())["type"] != "snapshot" or msg["controller"]["cycle"] != 3:
            pass
        assert [a["name"] for a in msg["axes"]] == ["MC_Axis002"]
        assert set(msg["controller"]) >= {"mode", "cycle", "time_s", "rtf"}


def test_websocket_pushes_the_events_of_a_new_controller(client: TestClient) -> None:
    """After a reset the new controller's event numbers start again; the stream must not filter them out by the
    old numbers, and the status says the controller was replaced (epoch)."""
    e0 = client.get(f"{API}/controller").json()["epoch"]
    with client.websocket_connect(f"{API}/ws") as ws:
        ws.send_json({"type": "subscribe", "rate_hz": 60, "axes": [], "fbs": [], "events": True})
        while ws.receive_json()["type"] != "subscribed":
            pass
        for _ in range(5):  # raise the old controller's event numbers
            post(client, "/fb", {"type": "MC_MoveAbsolute", "inputs": {"Axis": "MC_Axis000", "Execute": True,
                                                                        "Velocity": 0}}, 201)
            client.post(f"{API}/controller/step", json={"cycles": 1})
        assert post(client, "/controller/reset", {})["epoch"] == e0 + 1
        client.post(f"{API}/controller/step", json={"cycles": 2})
        seen: list[str] = []
        while True:
            msg = ws.receive_json()
            if msg["type"] != "snapshot" or msg["controller"]["epoch"] != e0 + 1:
                continue
            seen += [e["message"] for e in msg["events"]]
            if any("loaded" in m for m in seen) or msg["controller"]["cycle"] >= 2:
                break
        assert any("loaded" in m for m in seen), seen


def test_websocket_disconnect_drops_leased_enables(client: TestClient, studio: Any) -> None:
    """A browser that disappears stops its jog at once: leases it renewed drop their Enable inputs."""
    power_on(client)
    jog = post(client, "/fb", {"type": "MC_MoveJog", "lease_s": 30, "inputs": {
        "Axis": "MC_Axis000", "PositiveEnable": True, "Velocity": 10, "Acceleration": 100, "Deceleration": 100}},
        201)
    with client.websocket_connect(f"{API}/ws") as ws:
        ws.send_json({"type": "heartbeat", "fbs": [jog["id"]]})
        ws.send_json({"type": "subscribe", "rate_hz": 60})
        while ws.receive_json()["type"] != "subscribed":  # messages are handled in order: the heartbeat was seen
            pass
    for _ in range(1000):  # the server handles the disconnect asynchronously; poll the instance (no sleep)
        if client.get(f"{API}/fb/{jog['id']}").json()["inputs"]["PositiveEnable"] is False:
            break
    assert client.get(f"{API}/fb/{jog['id']}").json()["inputs"]["PositiveEnable"] is False


def test_openapi_and_docs(client: TestClient) -> None:
    spec = client.get(f"{API}/openapi.json").json()
    assert "/api/v1/fb" in spec["paths"] and "WsSubscribe" in spec["components"]["schemas"]
    assert client.get("/docs").status_code == 200
    assert client.get("/").status_code == 503  # no frontend build in this test app


def test_serves_the_built_studio(tmp_path: Path, studio: Any) -> None:
    """With a frontend build, / and unknown client routes serve index.html, assets are served, API 404s stay JSON,
    and paths cannot escape the build folder."""
    from mcstudio.api.app import create_app

    (tmp_path / "assets").mkdir()
    (tmp_path / "index.html").write_text("<html>studio</html>")
    (tmp_path / "assets" / "app.js").write_text("console.log(1)")
    (tmp_path / "favicon.svg").write_text("<svg/>")
    with TestClient(create_app(studio, static_dir=tmp_path)) as c:
        assert c.get("/").text == "<html>studio</html>"
        assert c.get("/axes/MC_Axis000").text == "<html>studio</html>"
        assert c.get("/assets/app.js").text == "console.log(1)"
        assert c.get("/favicon.svg").text == "<svg/>"
        assert c.get("/api/v1/nope").status_code == 404
        assert c.get("/api/v1/health").json()["status"] == "ok"
        assert "root:" not in c.get("/../../../../etc/passwd").text


def test_websocket_clients_subscribed_alike_share_one_encoding(client: TestClient, monkeypatch: Any) -> None:
    """Ten clients with the same subscription: each snapshot is encoded once for all of them (the encoding runs in
    the event loop thread, which shares the GIL with the kernel), and every client gets the same message."""
    from mcstudio.api.routers import live

    builds: list[int] = []
    real = live.build_snapshot

    def counting(studio: Any, snap: Any, sub: Any, since: int) -> dict[str, Any]:
        builds.append(snap.cycle)
        return real(studio, snap, sub, since)

    monkeypatch.setattr(live, "build_snapshot", counting)
    from contextlib import ExitStack

    with ExitStack() as stack:
        sockets = [stack.enter_context(client.websocket_connect(f"{API}/ws")) for _ in range(10)]
        for ws in sockets:
            ws.send_json({"type": "subscribe", "rate_hz": 60, "axes": None, "fbs": None, "events": False})
            while ws.receive_json()["type"] != "subscribed":
                pass
        client.post(f"{API}/controller/step", json={"cycles": 7})
        texts = []
        for ws in sockets:
            while (msg := ws.receive_text()) and '"cycle": 7,' not in msg:
                pass
            texts.append(msg)
    assert len(set(texts)) == 1, "every client got the same message"
    assert builds.count(7) == 1, f"cycle 7 was encoded {builds.count(7)} times for 10 clients"
