"""Hostile WebSocket messages (the WebSocket is not in the OpenAPI document, so schemathesis does not reach it):
non-JSON text, JSON that is not an object, unknown types, wrong field types, huge and deeply nested messages. Each
gets an `error` message (or is ignored) and the socket keeps serving snapshots; nothing reaches the kernel."""

from __future__ import annotations

import json
import threading
from pathlib import Path
from typing import Any

import pytest
from fastapi.testclient import TestClient

from tests.hardening.conftest import demo_app

HOSTILE = [
    "not json", "", "[1, 2]", "null", "42", '"subscribe"', "{}", '{"type": 5}', '{"type": "nope"}',
    '{"type": "subscribe", "rate_hz": "fast"}', '{"type": "subscribe", "rate_hz": 1e999}',
    '{"type": "subscribe", "rate_hz": NaN}', '{"type": "subscribe", "rate_hz": 0}',
    '{"type": "subscribe", "axes": [1, 2]}', '{"type": "subscribe", "fbs": ["x"]}',
    '{"type": "heartbeat", "fbs": "all"}', '{"type": "heartbeat", "fbs": [99999999999999999999]}',
    '{"type": "heartbeat", "fbs": [-1, 424242]}', '{"type": "ping", "extra": ' + "[" * 500 + "]" * 500 + "}",
    json.dumps({"type": "subscribe", "axes": ["MC_Axis000"] * 100_000}),
    '{"type": "subscribe", "axes": ["' + "x" * 1_000_000 + '"]}',
]


@pytest.fixture
def client(tmp_path: Path) -> TestClient:
    with TestClient(demo_app(tmp_path)) as c:
        yield c  # type: ignore[misc]


def test_hostile_messages_get_errors_and_the_socket_goes_on(client: TestClient) -> None:
    with client.websocket_connect("/api/v1/ws") as ws:
        for text in HOSTILE:
            ws.send_text(text)
        ws.send_json({"type": "subscribe", "rate_hz": 60, "axes": ["MC_Axis000"], "fbs": [], "events": False})
        kinds: list[str] = []
        for _ in range(500):
            msg = ws.receive_json()
            kinds.append(msg["type"])
            if msg["type"] == "subscribed" and msg.get("axes") == ["MC_Axis000"]:
                break
        assert kinds[-1] == "subscribed", kinds[-10:]
        assert kinds.count("error") >= 10
        for _ in range(10):  # snapshots still come
            msg = ws.receive_json()
            if msg["type"] == "snapshot":
                assert [a["name"] for a in msg["axes"]] == ["MC_Axis000"]
                break
        else:
            pytest.fail("no snapshot after the hostile messages")
    assert client.get("/api/v1/health").status_code == 200


def test_deeply_nested_message_is_an_error_not_a_dead_socket(tmp_path: Path) -> None:
    """Run in a daemon thread with its own client: if the socket hangs, the thread is abandoned (no CI hang)."""
    result: dict[str, Any] = {}

    def go() -> None:
        with TestClient(demo_app(tmp_path)) as c, c.websocket_connect("/api/v1/ws") as ws:
            ws.send_text('{"type": "ping", "extra": ' + "[" * 100_000 + "]" * 100_000 + "}")
            ws.send_json({"type": "subscribe", "rate_hz": 60, "axes": [], "fbs": [], "events": False})
            kinds = []
            for _ in range(20):
                kinds.append(ws.receive_json()["type"])
                if kinds[-1] == "subscribed":
                    break
            result["kinds"] = kinds

    t = threading.Thread(target=go, daemon=True)
    t.start()
    t.join(timeout=5)
    assert "subscribed" in result.get("kinds", []) and "error" in result["kinds"]
