"""Access control (issue 9; api/auth.py, decisions D118–D119): "from another address without the token nothing moves".

The app is created as `mcstudio serve --host 0.0.0.0` creates it; requests come from 192.168.1.20 (TestClient
`client=`) to the studio at 192.168.1.5:8000.
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from fastapi.testclient import TestClient
from starlette.websockets import WebSocketDisconnect

from mcstudio.api.app import create_app
from mcstudio.api.auth import AccessPolicy, is_loopback
from mcstudio.api.state import Studio
from mcstudio.cli import _access_settings, build_parser

API = "/api/v1"
TOKEN = "s3cret-token-for-the-tests-0123"
REMOTE = ("192.168.1.20", 50123)
BASE = "http://192.168.1.5:8000"
BEARER = {"Authorization": f"Bearer {TOKEN}"}
MUTATING = {"POST", "PUT", "PATCH", "DELETE"}


@pytest.fixture
def static(tmp_path: Path) -> Path:
    (tmp_path / "index.html").write_text("<html>studio</html>")
    return tmp_path


@pytest.fixture
def remote(studio: Studio, static: Path) -> Iterator[TestClient]:
    app = create_app(studio, static_dir=static, access=AccessPolicy.for_bind("0.0.0.0", TOKEN))
    with TestClient(app, base_url=BASE, client=REMOTE) as c:
        yield c


def _mutating_routes(c: TestClient) -> list[tuple[str, str]]:
    """Every mutating API route, with its path parameters filled in."""
    out = []
    for path, ops in c.app.openapi()["paths"].items():  # type: ignore[attr-defined]
        for method in sorted(m.upper() for m in ops if m.upper() in MUTATING):
            out.append((method, re.sub(r"\{(\w+)\}", lambda m: "1" if m.group(1) in ("fb_id", "address", "trace_id")
                                       else "MC_Axis000", path)))
    return out


def _body_for(method: str, path: str) -> Any:
    if path == f"{API}/fb":
        return {"type": "MC_Power", "inputs": {"Axis": "MC_Axis000", "Enable": True}}
    if path == f"{API}/controller/step":
        return {"cycles": 10}
    if path == f"{API}/controller/mode":
        return {"mode": "fast"}
    return {}


def test_from_another_address_without_the_token_nothing_moves(remote: TestClient, studio: Studio) -> None:
    """Every mutating route answers 401 without a token and 403 with a wrong one; the controller is untouched."""
    routes = _mutating_routes(remote)
    assert len(routes) >= 25 and ("POST", f"{API}/fb") in routes and ("PATCH", f"{API}/fb/1") in routes
    for method, path in routes:
        r = remote.request(method, BASE + path, json=_body_for(method, path))
        assert r.status_code == 401, (method, path, r.status_code)
        assert "token" in r.json()["detail"] and r.headers["www-authenticate"].startswith("Bearer")
        r = remote.request(method, BASE + path, json=_body_for(method, path),
                           headers={"Authorization": "Bearer wrong-token-wrong-token"})
        assert r.status_code == 403, (method, path)
    assert studio.runner.snapshot.cycle == 0 and not studio.controller.program
    assert studio.runner.mode == "paused"
    # reads need it too; the studio's page and the health check do not
    assert remote.get(f"{API}/axes").status_code == 401
    assert remote.get(f"{API}/snapshot").status_code == 401
    assert remote.get(f"{API}/health").json()["status"] == "ok"
    assert remote.get("/").text == "<html>studio</html>"


def test_with_the_token_in_the_header_it_works(remote: TestClient, studio: Studio) -> None:
    r = remote.post(f"{API}/fb", json=_body_for("POST", f"{API}/fb"), headers=BEARER)
    assert r.status_code == 201, r.text
    r = remote.post(f"{API}/controller/step", json={"cycles": 5}, headers=BEARER)
    assert r.status_code == 200 and r.json()["cycle"] == 5
    assert remote.get(f"{API}/axes", headers={"authorization": f"bearer {TOKEN}"}).status_code == 200


def test_opening_the_printed_address_sets_the_cookie_and_drops_the_token_from_the_address(remote: TestClient) -> None:
    r = remote.get("/?token=" + TOKEN, follow_redirects=False)
    assert r.status_code == 303 and r.headers["location"] == "/"
    cookie = r.headers["set-cookie"]
    assert cookie.startswith(f"mcstudio_token={TOKEN};") and "HttpOnly" in cookie and "SameSite=Strict" in cookie
    remote.cookies.set("mcstudio_token", TOKEN)
    assert remote.post(f"{API}/controller/step", json={"cycles": 1}).status_code == 200
    assert remote.get("/?token=nope", follow_redirects=False).status_code == 403


def test_the_websocket_needs_the_token(remote: TestClient) -> None:
    with pytest.raises(WebSocketDisconnect) as err, remote.websocket_connect(f"{API}/ws"):
        pass
    assert err.value.code == 1008
    with pytest.raises(WebSocketDisconnect), remote.websocket_connect(f"{API}/ws?token=wrong"):
        pass
    for kwargs in ({"headers": BEARER}, {}):
        url = f"{API}/ws" if kwargs else f"{API}/ws?token={TOKEN}"
        with remote.websocket_connect(url, **kwargs) as ws:
            ws.send_json({"type": "subscribe", "rate_hz": 60, "axes": [], "fbs": [], "events": False})
            while ws.receive_json()["type"] != "subscribed":
                pass
    remote.cookies.set("mcstudio_token", TOKEN)
    with remote.websocket_connect(f"{API}/ws") as ws:
        assert ws.receive_json()["type"] == "snapshot"


def test_another_site_cannot_drive_the_controller_even_with_the_cookie(remote: TestClient, studio: Studio) -> None:
    """D119: a mutating request or WebSocket with a foreign Origin is refused before anything else."""
    evil = {"Origin": "http://evil.example", **BEARER}
    assert remote.post(f"{API}/controller/step", json={"cycles": 1}, headers=evil).status_code == 403
    with pytest.raises(WebSocketDisconnect), remote.websocket_connect(f"{API}/ws", headers=evil):
        pass
    assert studio.runner.snapshot.cycle == 0
    same = {"Origin": BASE, **BEARER}
    assert remote.post(f"{API}/controller/step", json={"cycles": 1}, headers=same).status_code == 200
    # reads are not refused for an Origin (the browser's same-origin policy keeps their answers from other sites)
    assert remote.get(f"{API}/axes", headers=evil).status_code == 200


def test_loopback_bind_needs_no_token_but_a_loopback_host_name(studio: Studio, static: Path) -> None:
    """D118: bound to 127.0.0.1 a local browser needs nothing; a page reaching it under another host name (DNS
    rebinding) is refused, the Vite dev server's origin is accepted."""
    app = create_app(studio, static_dir=static, access=AccessPolicy.for_bind("127.0.0.1"))
    with TestClient(app, base_url="http://127.0.0.1:8000", client=("127.0.0.1", 40000)) as c:
        assert c.post(f"{API}/controller/step", json={"cycles": 2}).json()["cycle"] == 2
        assert c.post(f"{API}/controller/step", json={"cycles": 1},
                      headers={"Origin": "http://localhost:5173"}).status_code == 200
        assert c.get(f"{API}/axes", headers={"Host": "localhost:8000"}).status_code == 200
        assert c.get(f"{API}/axes", headers={"Host": "[::1]:8000"}).status_code == 200
        r = c.post(f"{API}/controller/step", json={"cycles": 1}, headers={"Host": "attacker.example:8000"})
        assert r.status_code == 403 and "DNS rebinding" in r.json()["detail"]
        assert c.get(f"{API}/axes", headers={"Host": "attacker.example:8000"}).status_code == 403
        assert c.get(f"{API}/controller").json()["cycle"] == 3


def _args(*argv: str) -> Any:
    return build_parser().parse_args(["serve", *argv])


def test_serve_generates_a_token_for_a_network_address(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv("MCSTUDIO_TOKEN", raising=False)
    policy, token, problem = _access_settings(_args())
    assert problem is None and token is None and policy is not None and policy.token is None
    assert policy.trusted_hosts is not None and "127.0.0.1" in policy.trusted_hosts
    policy, token, problem = _access_settings(_args("--host", "0.0.0.0"))
    assert problem is None and token and len(token) >= 24 and policy is not None and policy.token == token
    assert policy.trusted_hosts is None
    assert _access_settings(_args("--host", "0.0.0.0"))[1] != token  # random per start
    monkeypatch.setenv("MCSTUDIO_TOKEN", TOKEN)
    assert _access_settings(_args("--host", "10.0.0.7"))[1] == TOKEN
    assert _access_settings(_args("--host", "10.0.0.7", "--token", "short"))[2] is not None


def test_serve_keeps_the_3d_view_on_the_loopback_unless_the_studio_has_a_token(monkeypatch: pytest.MonkeyPatch
                                                                                ) -> None:
    """D118: `--viser-host` on a network address is refused while the studio is loopback-only without a token."""
    monkeypatch.delenv("MCSTUDIO_TOKEN", raising=False)
    problem = _access_settings(_args("--viser-host", "0.0.0.0"))[2]
    assert problem is not None and "--viser-host" in problem
    assert _access_settings(_args("--viser-host", "127.0.0.1"))[2] is None
    assert _access_settings(_args("--host", "0.0.0.0", "--viser-host", "0.0.0.0"))[2] is None


def test_is_loopback() -> None:
    assert all(is_loopback(h) for h in ("127.0.0.1", "127.1.2.3", "::1", "[::1]", "localhost", "LOCALHOST"))
    assert not any(is_loopback(h) for h in ("0.0.0.0", "::", "192.168.1.5", "example.com", "10.0.0.1"))
