"""REST: GET /ethercat, PUT /ethercat/slaves/{address}/pdo, POST /esi, POST /faults, the device library (api.md)."""

from __future__ import annotations

import gzip
from pathlib import Path

from fastapi.testclient import TestClient

FIXTURES = Path("/work/shared/fixtures/esi")
SOES = FIXTURES / "soes-cia402.xml"


def _default_pdo(client: TestClient, address: int) -> dict:
    s = next(s for s in client.get("/api/v1/ethercat").json()["slaves"] if s["node_address"] == address)
    mappings = [{"index": p["index"], "entries": [{k: e[k] for k in ("index", "subindex", "bit_len")}
                                                   for e in p["entries"]]}
                for p in s["rx_pdos"] + s["tx_pdos"] if p["assigned"]]
    return {"rx_assign": s["rx_assign"], "tx_assign": s["tx_assign"], "mappings": mappings}


def test_get_ethercat_lists_slaves_in_op_with_offsets(client: TestClient) -> None:
    r = client.get("/api/v1/ethercat")
    assert r.status_code == 200
    body = r.json()
    assert body["master"]["cycle_time_us"] == 1000 and body["master"]["slaves_in_op"] == 7
    s = body["slaves"][0]
    assert s["state"] == "Op" and s["pd_ok"] and s["axis"] == "MC_Axis000" and s["device_id"] == "builtin:cia402-servo"
    assert s["rx_assign"] == [0x1600] and s["tx_assign"] == [0x1A00] and s["rx_bytes"] == 23
    rx = next(p for p in s["rx_pdos"] if p["index"] == 0x1600)
    assert [(e["index"], e["byte_offset"]) for e in rx["entries"][:3]] == [(0x6040, 0.0), (0x607A, 2.0), (0x60FF, 6.0)]
    img = client.get("/api/v1/ethercat/slaves/1/image").json()
    assert len(bytes.fromhex(img["rx_hex"])) == 23


def test_put_pdo_invalid_edit_names_the_field(client: TestClient) -> None:
    body = _default_pdo(client, 1)
    body["mappings"][0]["entries"][1]["bit_len"] = 16  # 607Ah is 32 bits
    r = client.put("/api/v1/ethercat/slaves/1/pdo", json=body)
    assert r.status_code == 422
    d = r.json()["detail"]
    assert d[0]["path"] == "mappings[0].entries[1].bit_len" and "32 bits" in d[0]["msg"]
    body = _default_pdo(client, 1)
    body["rx_assign"] = [0x1600, 0x1702]
    r = client.put("/api/v1/ethercat/slaves/1/pdo", json=body)
    assert r.status_code == 422 and "excludes" in r.json()["detail"][0]["msg"]
    assert client.put("/api/v1/ethercat/slaves/99/pdo", json=body).status_code == 404


def test_remove_607a_then_restore(client: TestClient) -> None:
    body = _default_pdo(client, 1)
    body["mappings"][0]["entries"] = [e for e in body["mappings"][0]["entries"] if e["index"] != 0x607A]
    r = client.put("/api/v1/ethercat/slaves/1/pdo", json=body)
    assert r.status_code == 200, r.text
    assert 0x607A not in [e["index"] for e in r.json()["rx_pdos"][0]["entries"]]
    ax = client.get("/api/v1/axes/MC_Axis000").json()["variables"]
    assert ax["MFaultLvl"]["Code"] == "3460" and ax["Status"]["ErrorStop"]
    fb = client.post("/api/v1/fb", json={"type": "MC_Power", "inputs": {"Axis": "MC_Axis000", "Enable": True}}).json()
    client.post("/api/v1/controller/step", json={"cycles": 3})
    out = client.get(f"/api/v1/fb/{fb['id']}").json()["outputs"]
    assert out["Error"] and out["ErrorID"] == "3460"
    # the project keeps the network explicitly now; restore the default mapping
    assert client.get("/api/v1/project").json()["ethercat"]["slaves"][0]["pdo"] is not None
    r = client.put("/api/v1/ethercat/slaves/1/pdo", json=_default_pdo(client, 2))
    assert r.status_code == 200
    ax = client.get("/api/v1/axes/MC_Axis000").json()["variables"]
    assert ax["MFaultLvl"]["Code"] == "0000"


def test_esi_import_adds_devices(client: TestClient, project_dir: Path) -> None:
    with SOES.open("rb") as fh:
        r = client.post("/api/v1/esi", files={"file": ("soes-cia402.xml", fh, "application/xml")})
    assert r.status_code == 200, r.text
    esi = r.json()
    assert esi["devices"]
    dev = esi["devices"][0]
    assert (project_dir / "esi" / "soes-cia402.xml").is_file()
    ids = [d["id"] for d in client.get("/api/v1/devices").json()]
    assert dev["id"] in ids
    assert client.get(f"/api/v1/devices/{dev['id']}").json()["name"] == dev["name"]


def test_malformed_esi_is_422(client: TestClient) -> None:
    r = client.post("/api/v1/esi", files={"file": ("bad.xml", b"<EtherCATInfo><Vendor>", "application/xml")})
    assert r.status_code == 422
    assert r.json()["detail"][0]["loc"] == ["body", "file"]


def test_odd_esi_uploads_are_4xx_never_5xx(client: TestClient) -> None:
    good = SOES.read_bytes()
    odd = [b"", b"\x00" * 64, gzip.compress(good), bytes(range(256)), b"<html/>", b"<EtherCATInfo/>",
           b'<?xml version="1.0"?><!DOCTYPE x [<!ENTITY a "b">]><EtherCATInfo/>',
           good.decode().encode("utf-32")]
    for data in odd:
        r = client.post("/api/v1/esi", files={"file": ("odd.xml", data, "application/xml")})
        assert r.status_code == 422, (data[:20], r.status_code)
    assert client.post("/api/v1/esi", data={"x": "1"}).status_code == 422  # no file part


def test_esi_file_names_are_kept_loadable(client: TestClient, project_dir: Path) -> None:
    """The project loads `esi/*.xml` on opening: an upload named `Drive.XML` is kept as `Drive.xml`, a name of dots
    only as `device.xml` (not the hidden `.xml`); a UTF-16 file that declares UTF-8 (re-saved by an editor) imports."""
    text = SOES.read_text(encoding="utf-8")
    for name, data in (("OMRON R88D.XML", SOES.read_bytes()), ("....", text.encode("utf-16"))):
        assert client.post("/api/v1/esi", files={"file": (name, data, "application/xml")}).status_code == 200
    assert sorted(p.name for p in (project_dir / "esi").iterdir()) == ["OMRON_R88D.xml", "device.xml"]


def test_faults(client: TestClient) -> None:
    r = client.post("/api/v1/faults", json={"kind": "slave_disconnect", "node_address": 2})
    assert r.status_code == 200 and r.json()["slave_state"] == "Init"
    client.post("/api/v1/controller/step", json={"cycles": 1})
    slaves = client.get("/api/v1/ethercat").json()["slaves"]
    assert not slaves[1]["pd_ok"] and slaves[0]["pd_ok"]
    r = client.post("/api/v1/faults", json={"kind": "slave_reconnect", "node_address": 2})
    client.post("/api/v1/controller/step", json={"cycles": 4})
    assert client.get("/api/v1/ethercat").json()["slaves"][1]["state"] == "Op"
    assert client.post("/api/v1/faults", json={"kind": "slave_disconnect", "node_address": 77}).status_code == 404
    r = client.post("/api/v1/faults", json={"kind": "encoder_velocity", "node_address": 1, "value": 5})
    assert r.status_code == 422 and r.json()["detail"][0]["loc"] == ["body", "kind"]
    r = client.post("/api/v1/faults", json={"kind": "meteor", "node_address": 1})
    assert r.status_code == 422
    r = client.post("/api/v1/faults", json={"kind": "drive_fault", "node_address": 1, "code": 0x2310})
    client.post("/api/v1/controller/step", json={"cycles": 3})
    assert client.get("/api/v1/ethercat").json()["slaves"][0]["drive_state"] == "Fault"
