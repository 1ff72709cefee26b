"""Timing-chart scenarios of issue #3 driven only through the REST FB API on the paused controller, period by period.

Each scenario follows a chart or rule of the manual (cited per test) and reads outputs and axis variables exactly as
a user script would: POST /fb, POST /controller/step, GET /fb/{id}, GET /axes/{name}.
"""

from __future__ import annotations

from typing import Any

import pytest
from fastapi.testclient import TestClient

from tests.api.test_rest import API, post, power_on

AX = "MC_Axis000"


def fb(client: TestClient, type_: str, **inputs: Any) -> int:
    return int(post(client, "/fb", {"type": type_, "inputs": {"Axis": AX, **inputs}}, 201)["id"])


def step(client: TestClient, cycles: int = 1, until: tuple[int, str, Any] | None = None) -> dict[str, Any]:
    body: dict[str, Any] = {"cycles": cycles}
    if until is not None:
        body["until"] = {"fb": until[0], "output": until[1], "equals": until[2]}
    return post(client, "/controller/step", body)


def out(client: TestClient, fb_id: int) -> dict[str, Any]:
    return client.get(f"{API}/fb/{fb_id}").json()["outputs"]


def var(client: TestClient, axis: str = AX) -> dict[str, Any]:
    return client.get(f"{API}/axes/{axis}").json()["variables"]


def state(client: TestClient, axis: str = AX) -> str:
    st = var(client, axis)["Status"]
    names = [k for k, v in st.items() if v and k != "Ready"]
    assert len(names) == 1, st
    return names[0]


MOVE = {"Velocity": 50, "Acceleration": 500, "Deceleration": 500}


def test_buffered_move_starts_in_the_period_the_first_is_done(client: TestClient) -> None:
    """BufferMode _mcBuffered (omron-mc-basics.md §1.5, A-3.1): B waits Busy (not Active) while A runs; in the period
    A reports Done, B reports Active and the axis keeps Discrete."""
    power_on(client)
    a = fb(client, "MC_MoveAbsolute", Execute=True, Position=20, **MOVE)
    step(client, 5)
    b = fb(client, "MC_MoveRelative", Execute=True, Distance=10, BufferMode="_mcBuffered", **MOVE)
    step(client)
    ob = out(client, b)
    assert ob["Busy"] and not ob["Active"] and out(client, a)["Active"]
    step(client, 5000, (a, "Done", True))
    assert out(client, b)["Active"] and state(client) == "Discrete"
    step(client, 5000, (b, "Done", True))
    assert var(client)["Act"]["Pos"] == pytest.approx(30.0, abs=1e-9)
    assert state(client) == "Standstill"


def test_second_buffered_instruction_is_5443(client: TestClient) -> None:
    """A-3.1: one axis holds one buffered instruction; a second is an error (54430000)."""
    power_on(client)
    fb(client, "MC_MoveAbsolute", Execute=True, Position=20, **MOVE)
    step(client, 2)
    fb(client, "MC_MoveAbsolute", Execute=True, Position=30, BufferMode="_mcBuffered", **MOVE)
    step(client)
    c = fb(client, "MC_MoveAbsolute", Execute=True, Position=40, BufferMode="_mcBuffered", **MOVE)
    step(client)
    o = out(client, c)
    assert o["Error"] and o["ErrorID"] == "5443"
    assert any(e["code"] == "54430000" for e in client.get(f"{API}/events").json())


def test_blending_previous_passes_the_junction_at_speed(client: TestClient) -> None:
    """_mcBlendingPrevious: the transit velocity is A's target velocity; A's Done comes at its target without a
    stop (§1.5, decision D8)."""
    power_on(client)
    a = fb(client, "MC_MoveAbsolute", Execute=True, Position=50, Velocity=100, Acceleration=1000, Deceleration=1000)
    step(client, 5)
    b = fb(client, "MC_MoveAbsolute", Execute=True, Position=120, Velocity=40, Acceleration=1000, Deceleration=1000,
           BufferMode="_mcBlendingPrevious")
    step(client, 5000, (a, "Done", True))
    v = var(client)
    assert v["Cmd"]["Vel"] == pytest.approx(100.0, rel=0.02)
    assert v["Cmd"]["Pos"] == pytest.approx(50.0, abs=0.2)
    assert out(client, b)["Active"] and state(client) == "Discrete"
    step(client, 5000, (b, "Done", True))
    assert var(client)["Act"]["Pos"] == pytest.approx(120.0, abs=1e-9)


def test_rotary_shortest_way_through_the_api(client: TestClient) -> None:
    """Rotary mode 0–360 (ring counter) and Direction _mcShortestWay (§2.3 directions): from 350 to 10 the axis goes
    +20 through the ring end, and the position reads 10."""
    cfg = client.get(f"{API}/axes/MC_Axis003").json()["config"]
    cfg["parameters"]["PosCount"] = {"CountMode": "_mcCountModeRotary", "ModuloMinPosVal": 0.0,
                                     "ModuloMaxPosVal": 360.0}
    r = client.put(f"{API}/axes/MC_Axis003/config", json=cfg)
    assert r.status_code == 200, r.text
    power_on(client, "MC_Axis003")
    first = post(client, "/fb", {"type": "MC_MoveAbsolute", "inputs": {
        "Axis": "MC_Axis003", "Execute": True, "Position": 350, "Direction": "_mcPositiveDirection", **MOVE}}, 201)
    step(client, 10000, (first["id"], "Done", True))
    mv = post(client, "/fb", {"type": "MC_MoveAbsolute", "inputs": {
        "Axis": "MC_Axis003", "Execute": True, "Position": 10, "Direction": "_mcShortestWay", **MOVE}}, 201)
    step(client, 3)
    assert var(client, "MC_Axis003")["Cmd"]["Vel"] > 0, "shortest way from 350 to 10 is positive"
    step(client, 10000, (mv["id"], "Done", True))
    assert var(client, "MC_Axis003")["Act"]["Pos"] == pytest.approx(10.0, abs=1e-9)


def test_override_zero_pauses_and_resumes(client: TestClient) -> None:
    """MC_SetOverride VelFactor 0 %: the positioning decelerates to 0 and waits, still Discrete and Busy (§2.6,
    MC_SetOverride); 100 % resumes and the move completes on target."""
    power_on(client)
    mv = fb(client, "MC_MoveAbsolute", Execute=True, Position=100, **MOVE)
    step(client, 200)
    ov = fb(client, "MC_SetOverride", Enable=True, VelFactor=0)
    step(client, 300)
    v = var(client)
    assert v["Cmd"]["Vel"] == 0 and state(client) == "Discrete"
    assert out(client, mv)["Busy"] and not out(client, mv)["Done"]
    held = v["Cmd"]["Pos"]
    step(client, 100)
    assert var(client)["Cmd"]["Pos"] == held
    r = client.patch(f"{API}/fb/{ov}", json={"inputs": {"VelFactor": 100}})
    assert r.status_code == 200
    step(client, 10000, (mv, "Done", True))
    assert var(client)["Act"]["Pos"] == pytest.approx(100.0, abs=1e-9)


def test_jog_while_moving_is_543c_and_error_stops(client: TestClient) -> None:
    """A-3.4: MC_MoveJog on a Discrete axis → H (error 543C, decision D6); the running move is CommandAborted."""
    power_on(client)
    mv = fb(client, "MC_MoveAbsolute", Execute=True, Position=100, **MOVE)
    step(client, 10)
    jog = fb(client, "MC_MoveJog", PositiveEnable=True, Velocity=10, Acceleration=100, Deceleration=100)
    step(client)
    assert out(client, jog)["Error"] and out(client, jog)["ErrorID"] == "543C"
    step(client)
    assert out(client, mv)["CommandAborted"]
    assert state(client) == "ErrorStop" and var(client)["MFaultLvl"]["Code"] == "543C"


def test_home_against_the_demo_sensors(client: TestClient) -> None:
    """MC_Home mode 0 of the demo axis (dog −15…−8, Z phase, negative directions): Done, home defined at the Z pulse
    after the dog, Cmd.Pos = home offset 0 (MC_Home, seed 000 lines 2713–3228)."""
    power_on(client)
    assert var(client)["Details"]["Homed"] is False
    h = fb(client, "MC_Home", Execute=True)
    step(client)
    assert out(client, h)["Busy"] and state(client) == "Homing"
    st = step(client, 60000, (h, "Busy", False))
    assert st["until_met"]
    o = out(client, h)
    assert o["Done"] and not o["Error"], o
    v = var(client)
    assert v["Details"]["Homed"] and v["Cmd"]["Pos"] == 0 and state(client) == "Standstill"
