"""Shared control of the test run (issue 8; api/control.py, decisions D115–D117).

Timing charts on the paused controller: requests run inline at a cycle boundary (no runner thread), so "A jogs; B
takes control; the next period the jog's PositiveEnable is FALSE and the axis decelerates" is exact.
"""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from fastapi.testclient import TestClient
from starlette.websockets import WebSocketDisconnect

from mcstudio.api.app import create_app
from mcstudio.api.control import ControlRegistry
from mcstudio.api.state import Studio

API = "/api/v1"
A = {"X-MCStudio-Client": "browser-a"}
B = {"X-MCStudio-Client": "browser-b"}
JOG = {"type": "MC_MoveJog", "lease_s": 30, "inputs": {
    "Axis": "MC_Axis000", "PositiveEnable": True, "Velocity": 10, "Acceleration": 100, "Deceleration": 100}}


class FakeClock:
    def __init__(self) -> None:
        self.t = 1000.0

    def __call__(self) -> float:
        return self.t


@pytest.fixture
def clock() -> FakeClock:
    return FakeClock()


@pytest.fixture
def cc(studio: Studio, clock: FakeClock) -> Iterator[TestClient]:
    """A client on an app whose control registry reads a fake clock (client silence)."""
    registry = ControlRegistry(clock=clock, client_timeout_s=10.0)
    with TestClient(create_app(studio, static_dir=Path("/nonexistent"), control_registry=registry)) as c:
        yield c


def req(c: TestClient, method: str, path: str, body: Any = None, headers: dict[str, str] | None = None,
        status: int = 200) -> Any:
    r = c.request(method, API + path, json=body, headers=headers)
    assert r.status_code == status, r.text
    return r.json() if r.content else None


def holder(c: TestClient) -> dict[str, Any] | None:
    return c.get(f"{API}/control").json()["holder"]  # type: ignore[no-any-return]


def power_on(c: TestClient, headers: dict[str, str] | None = None) -> int:
    pw = req(c, "POST", "/fb", {"type": "MC_Power", "inputs": {"Axis": "MC_Axis000", "Enable": True}}, headers, 201)
    st = req(c, "POST", "/controller/step", {"cycles": 100, "until": {"fb": pw["id"], "output": "Status",
                                                                       "equals": True}}, headers)
    assert st["until_met"]
    return int(pw["id"])


def axis(c: TestClient) -> dict[str, Any]:
    return c.get(f"{API}/axes/MC_Axis000").json()["variables"]  # type: ignore[no-any-return]


def test_nobody_holds_control_scripts_pass_and_a_client_takes_it_with_its_first_test_run_request(
        cc: TestClient) -> None:
    """D116: without a client id everything works while control is free (scripts, CI); the first test-run request
    with a client id takes control, so a single browser never sees a lock."""
    assert cc.get(f"{API}/control").json()["holder"] is None
    power_on(cc)  # no header: allowed, nobody takes control
    assert holder(cc) is None
    req(cc, "PUT", "/controller/mode", {"mode": "paused"}, A)
    h = holder(cc)
    assert h is not None and h["id"] == "browser-a" and h["name"].startswith("client ")
    assert h["since_s"] > 1e9  # UNIX time
    out = cc.get(f"{API}/control", headers=A).json()
    assert out["you"] == "browser-a" and out["change"] == {"reason": "taken", "previous": None,
                                                            "by": h["name"]}


def test_others_may_only_watch_while_a_client_holds_control(cc: TestClient) -> None:
    """Every test-run request and every configuration write of another client is refused with 423 naming the holder;
    reads and non-test-run writes stay open."""
    pw = power_on(cc, A)
    name = holder(cc)["name"]  # type: ignore[index]
    refused = [
        ("POST", "/fb", {"type": "MC_Power", "inputs": {"Axis": "MC_Axis001", "Enable": True}}),
        ("PATCH", f"/fb/{pw}", {"inputs": {"Enable": False}}),
        ("DELETE", f"/fb/{pw}", None),
        ("PUT", "/controller/mode", {"mode": "fast"}),
        ("POST", "/controller/step", {"cycles": 1}),
        ("POST", "/controller/reset", {}),
        ("POST", "/controller/reset-errors", {}),
        ("POST", "/faults", {"kind": "slave_disconnect", "node_address": 1}),
        ("PUT", "/axes/MC_Axis001/config", cc.get(f"{API}/axes/MC_Axis001").json()["config"]),
        ("POST", "/project/revert", {}),
    ]
    for method, path, body in refused:
        r = cc.request(method, API + path, json=body, headers=B)
        assert r.status_code == 423, (method, path, r.text)
        assert name in r.json()["detail"] and "take control" in r.json()["detail"]
    # nothing changed: the servo is on, the holder unchanged
    assert axis(cc)["DrvStatus"]["ServoOn"] is True
    assert holder(cc)["id"] == "browser-a"  # type: ignore[index]
    # watching and non-test-run requests are open to everybody
    assert cc.get(f"{API}/fb/{pw}", headers=B).status_code == 200
    assert cc.get(f"{API}/snapshot", headers=B).json()["control"]["holder"]["id"] == "browser-a"
    assert cc.post(f"{API}/groups/MC_Group000/kinematics/inverse", json={"position": [0, 0, -100]},
                   headers=B).status_code == 200
    # the holder goes on
    req(cc, "PATCH", f"/fb/{pw}", {"inputs": {"Enable": False}}, A)


def test_requests_without_a_client_id_are_not_arbitrated(cc: TestClient) -> None:
    """D116: the automation channel (scripts, CI, the REST examples) works while a browser holds control, and does
    not take control either."""
    pw = power_on(cc, A)
    req(cc, "PATCH", f"/fb/{pw}", {"inputs": {"Enable": False}})
    req(cc, "POST", "/controller/step", {"cycles": 10})
    assert axis(cc)["DrvStatus"]["ServoOn"] is False
    assert holder(cc)["id"] == "browser-a"  # type: ignore[index]
    req(cc, "POST", "/control/release", {}, A)
    req(cc, "POST", "/controller/step", {"cycles": 1})
    assert holder(cc) is None


def test_a_malformed_client_id_is_a_422_naming_the_header(cc: TestClient) -> None:
    r = cc.post(f"{API}/controller/step", json={"cycles": 1}, headers={"X-MCStudio-Client": "no spaces please"})
    assert r.status_code == 422 and r.json()["detail"][0]["loc"] == ["header", "X-MCStudio-Client"]
    r = cc.post(f"{API}/control/take", json={})
    assert r.status_code == 400 and r.json()["detail"][0]["loc"] == ["header", "X-MCStudio-Client"]
    r = cc.post(f"{API}/control/take", json={"force": "yes"}, headers=A)
    assert r.status_code == 422


def test_take_release_and_a_forced_take_stops_the_previous_holders_jog(cc: TestClient) -> None:
    """Timing chart: cycle k A's MC_MoveJog has PositiveEnable TRUE and the axis moves at 10 mm/s; B takes control
    with force at the boundary before cycle k+1 → PositiveEnable is FALSE at once (an event says why), the jog
    decelerates at 100 mm/s² and the axis is at Standstill 0.1 s later. A is refused from then on."""
    power_on(cc, A)
    jog = req(cc, "POST", "/fb", JOG, A, 201)
    req(cc, "POST", "/controller/step", {"cycles": 300}, A)
    assert axis(cc)["Status"]["Continuous"] and axis(cc)["Cmd"]["Vel"] == pytest.approx(10.0)

    r = cc.post(f"{API}/control/take", json={}, headers=B)
    assert r.status_code == 409 and "force" in r.json()["detail"]
    assert holder(cc)["id"] == "browser-a"  # type: ignore[index]
    out = req(cc, "POST", "/control/take", {"force": True, "name": "Bea"}, B)
    assert out["holder"]["id"] == "browser-b" and out["holder"]["name"] == "Bea"
    assert out["change"]["reason"] == "forced" and out["change"]["by"] == "Bea"
    fb = cc.get(f"{API}/fb/{jog['id']}").json()
    assert fb["inputs"]["PositiveEnable"] is False
    events = cc.get(f"{API}/events").json()
    assert any("control taken by 'Bea'" in e["message"] for e in events), events[-3:]

    req(cc, "POST", "/controller/step", {"cycles": 1}, B)
    assert 0 < axis(cc)["Cmd"]["Vel"] < 10.0  # decelerating
    req(cc, "POST", "/controller/step", {"cycles": 100}, B)
    assert axis(cc)["Status"]["Standstill"]
    # A may only watch now
    r = cc.patch(f"{API}/fb/{jog['id']}", json={"inputs": {"PositiveEnable": True}}, headers=A)
    assert r.status_code == 423 and "Bea" in r.json()["detail"]

    # release: nobody holds control, A may take it with its next test-run request
    out = req(cc, "POST", "/control/release", {}, B)
    assert out["holder"] is None and out["change"] == {"reason": "released", "previous": "Bea", "by": None}
    req(cc, "POST", "/controller/step", {"cycles": 1}, A)
    assert holder(cc)["id"] == "browser-a"  # type: ignore[index]
    req(cc, "POST", "/control/release", {}, A)
    # releasing what one does not hold changes nothing
    assert req(cc, "POST", "/control/release", {}, A)["holder"] is None


def test_release_while_jogging_stops_the_jog(cc: TestClient) -> None:
    power_on(cc, A)
    jog = req(cc, "POST", "/fb", JOG, A, 201)
    req(cc, "POST", "/controller/step", {"cycles": 10}, A)
    req(cc, "POST", "/control/release", {}, A)
    assert cc.get(f"{API}/fb/{jog['id']}").json()["inputs"]["PositiveEnable"] is False


def _until_released(c: TestClient) -> None:
    for _ in range(2000):  # the server handles a disconnect asynchronously; poll (no sleep)
        if holder(c) is None:
            return
    raise AssertionError(f"control still held: {holder(c)}")


def test_closing_the_holders_websocket_releases_control_and_stops_its_jog(cc: TestClient) -> None:
    """A browser that goes away (tab closed) releases control; every leased instance it created drops its dead-man
    inputs at once — even one it never renewed over this socket."""
    with cc.websocket_connect(f"{API}/ws?client=browser-a&name=Alice") as ws:
        hello = ws.receive_json()
        assert hello == {"type": "hello", "client": {"id": "browser-a", "name": "Alice"}}
        power_on(cc, A)
        jog = req(cc, "POST", "/fb", JOG, A, 201)
        req(cc, "POST", "/controller/step", {"cycles": 50}, A)
        assert holder(cc)["name"] == "Alice"  # type: ignore[index]
        clients = cc.get(f"{API}/control").json()["clients"]
        assert {"id": "browser-a", "name": "Alice", "connected": True} in clients
    _until_released(cc)
    assert cc.get(f"{API}/fb/{jog['id']}").json()["inputs"]["PositiveEnable"] is False
    st = cc.get(f"{API}/control").json()
    assert st["change"] == {"reason": "lost", "previous": "Alice", "by": None}
    assert any("client 'Alice' disconnected" in e["message"] for e in cc.get(f"{API}/events").json())
    req(cc, "POST", "/controller/step", {"cycles": 120})
    assert axis(cc)["Status"]["Standstill"]


def test_a_second_socket_of_the_same_client_keeps_control(cc: TestClient) -> None:
    """A reconnecting browser may open its new socket before the server noticed the old one closing."""
    with cc.websocket_connect(f"{API}/ws?client=browser-a") as ws1:
        ws1.receive_json()
        req(cc, "PUT", "/controller/mode", {"mode": "paused"}, A)
        with cc.websocket_connect(f"{API}/ws?client=browser-a") as ws2:
            assert ws2.receive_json()["type"] == "hello"
        for _ in range(200):
            if not any(c["connected"] is False for c in cc.get(f"{API}/control").json()["clients"]):
                break
        assert holder(cc)["id"] == "browser-a"  # type: ignore[index]
    _until_released(cc)


def test_a_silent_client_is_lost(cc: TestClient, clock: FakeClock) -> None:
    """D117: a client whose socket stays open but sends nothing (suspended laptop, half-open connection) for the
    client timeout (10 s on the registry's clock) is closed with 4408 and loses control; its jog stops."""
    with cc.websocket_connect(f"{API}/ws?client=browser-a") as ws:
        ws.receive_json()
        power_on(cc, A)
        jog = req(cc, "POST", "/fb", JOG, A, 201)
        ws.send_json({"type": "ping"})
        ws.send_json({"type": "subscribe", "rate_hz": 60, "axes": [], "fbs": [], "events": False})
        while ws.receive_json()["type"] != "subscribed":
            pass
        clock.t += 9.9  # not yet
        assert holder(cc) is not None
        clock.t += 0.2
        with pytest.raises(WebSocketDisconnect) as err:
            while True:
                ws.receive_json()
        assert err.value.code == 4408
    _until_released(cc)
    assert cc.get(f"{API}/fb/{jog['id']}").json()["inputs"]["PositiveEnable"] is False


def test_only_the_holder_may_renew_leases_and_every_browser_is_told_of_a_change(cc: TestClient) -> None:
    power_on(cc, A)
    jog = req(cc, "POST", "/fb", JOG, A, 201)
    with cc.websocket_connect(f"{API}/ws?client=browser-b&name=Bea") as wb:
        assert wb.receive_json()["type"] == "hello"
        wb.send_json({"type": "heartbeat", "fbs": [jog["id"]]})
        while (msg := wb.receive_json())["type"] != "error":
            pass
        assert "held by" in msg["detail"]
        # snapshots carry who holds control
        while (msg := wb.receive_json())["type"] != "snapshot":
            pass
        assert msg["control"]["holder"]["id"] == "browser-a"
        req(cc, "POST", "/control/take", {"force": True}, B)
        while (msg := wb.receive_json())["type"] != "control" or msg["holder"]["id"] != "browser-b":
            pass
        assert msg["change"]["reason"] == "forced" and msg["change"]["by"] == "Bea"
    _until_released(cc)


def test_create_fb_notes_the_owner_only_for_a_valid_client_id(cc: TestClient, studio: Studio) -> None:
    """Instances created without a client id belong to nobody: a client's loss does not touch them."""
    power_on(cc)
    jog = req(cc, "POST", "/fb", JOG, None, 201)
    with cc.websocket_connect(f"{API}/ws?client=browser-a") as ws:
        ws.receive_json()
        req(cc, "POST", "/controller/step", {"cycles": 1}, A)  # A holds control now
    _until_released(cc)
    assert cc.get(f"{API}/fb/{jog['id']}").json()["inputs"]["PositiveEnable"] is True
