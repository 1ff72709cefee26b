"""The event log over REST (issue 8; api.md "EtherCAT, ESI, faults, events, trace"): every event names what it is
about (source kind axis / group / slave / instruction / controller, decision D125), the manual's eight-digit code,
the event name, the cause and the correction of the error catalog (`omron-mc-basics.md` §A-1, seed 000 lines
19141–19382); GET filters by level and source kind; DELETE clears.
"""

from __future__ import annotations

from typing import Any

from fastapi.testclient import TestClient

from mcstudio.controller.mc.errors import ERRORS

API = "/api/v1"


def post(client: TestClient, path: str, body: Any, status: int = 200) -> Any:
    r = client.post(API + path, json=body)
    assert r.status_code == status, r.text
    return r.json()


def step(client: TestClient, cycles: int) -> None:
    post(client, "/controller/step", {"cycles": cycles})


def events(client: TestClient, **params: Any) -> list[dict[str, Any]]:
    r = client.get(f"{API}/events", params=params)
    assert r.status_code == 200, r.text
    return r.json()


def test_every_source_kind_with_code_cause_and_correction(client: TestClient) -> None:
    # cycle 0: the project is loaded — a controller event
    first = events(client)[0]
    assert first["source_kind"] == "controller" and first["code"] == "00000000" and first["level"] == "information"

    # an axis error raised by an instruction: 5422 (seed 000 L19481) on MC_Axis000, the instance named
    pw = post(client, "/fb", {"type": "MC_Power", "inputs": {"Axis": "MC_Axis000", "Enable": True}}, 201)
    post(client, "/controller/step", {"cycles": 100, "until": {"fb": pw["id"], "output": "Status", "equals": True}})
    mv = post(client, "/fb", {"type": "MC_MoveAbsolute", "inputs": {
        "Axis": "MC_Axis000", "Execute": True, "Position": 100, "Velocity": 0}}, 201)
    step(client, 1)
    ev = [e for e in events(client) if e["code"] == "54220000"][-1]
    d = ERRORS["5422"]
    assert ev["source_kind"] == "axis" and ev["source_name"] == "MC_Axis000"
    assert ev["instruction"] == f"fb {mv['id']} MC_MoveAbsolute"
    assert ev["level"] == "minor fault" and ev["message"] == d.name == "Target Velocity Setting Out of Range"
    assert ev["cause"] == d.cause and ev["correction"] == d.correction and ev["correction"]

    # an MC common error of an instance: MC_Write with ParameterNumber out of range → 544C (seed 000 L19989)
    wr = post(client, "/fb", {"type": "MC_Write", "inputs": {
        "Target": "MC_Axis001", "Execute": True, "ParameterNumber": 99, "SettingValue": 1}}, 201)
    step(client, 1)
    ev = [e for e in events(client) if e["code"] == "544C0000"][-1]
    assert ev["source_kind"] == "instruction" and ev["source_name"] == ev["instruction"] == f"fb {wr['id']} MC_Write"
    assert ev["correction"] == ERRORS["544C"].correction

    # a group error: a linear interpolation on the disabled MC_Group001 → 543F (seed 000 L19835)
    ml = post(client, "/fb", {"type": "MC_MoveLinear", "inputs": {
        "AxesGroup": "MC_Group001", "Execute": True, "Position": [10, 10], "Velocity": 10, "Acceleration": 100,
        "Deceleration": 100}}, 201)
    step(client, 1)
    ev = [e for e in events(client) if e["code"] == "543F0000"][-1]
    assert ev["source_kind"] == "group" and ev["source_name"] == "MC_Group001"
    assert ev["instruction"] == f"fb {ml['id']} MC_MoveLinear" and ev["cause"] == ERRORS["543F"].cause

    # a slave: disconnecting node 2 → the master's 84230000 (D29 (6)) with its catalog text; its axis gets 3003
    assert client.post(f"{API}/faults", json={"kind": "slave_disconnect", "node_address": 2}).status_code == 200
    step(client, 3)
    ev = [e for e in events(client) if e["code"] == "84230000"][-1]
    assert ev["source_kind"] == "slave" and ev["source_name"] == "E002" and ev["source"] == "EtherCAT master"
    assert ev["message"].endswith("disconnected") and ev["cause"] == ERRORS["8423"].cause
    assert ev["correction"] == ERRORS["8423"].correction


def test_filters_and_clear(client: TestClient) -> None:
    assert client.post(f"{API}/faults", json={"kind": "slave_disconnect", "node_address": 3}).status_code == 200
    step(client, 3)
    slave = events(client, source_kind="slave")
    assert slave and {e["source_kind"] for e in slave} == {"slave"}
    faults = events(client, level="minor fault")
    assert faults and {e["level"] for e in faults} == {"minor fault"}
    assert {e["code"] for e in faults} >= {"84230000", "30030000"}  # the slave's and its axis's (MC_Axis002)
    both = events(client, level=["minor fault", "information"], source_kind=["axis", "controller"])
    assert {e["source_kind"] for e in both} == {"axis", "controller"}
    assert events(client, source_kind="slave", limit=1) == slave[-1:]
    bad = client.get(f"{API}/events", params={"source_kind": "robot"})
    assert bad.status_code == 422 and bad.json()["detail"][0]["loc"] == ["query", "source_kind", 0]

    last = events(client)[-1]["seq"]
    assert client.delete(f"{API}/events").status_code == 204
    assert events(client) == []
    step(client, 1)
    assert client.post(f"{API}/faults", json={"kind": "slave_reconnect", "node_address": 3}).status_code == 200
    step(client, 10)
    after = events(client)
    assert after and after[0]["seq"] > last  # numbering continues after a clear
