"""Shared control in two real browsers (issue 8: "two browsers cannot both jog"; docs/shared-control.md, D115–D117).

Alice (browser context A) servo-ons and jogs; Bob (context B) watches read-only, REST with his client id is refused;
Bob takes control → Alice's page turns read-only and her jog stops; Alice takes it back, jogs, and closes her page
while jogging → the jog stops at once and control is free; Bob's page hangs while he jogs → the lease stops the jog
and 10 s later the server drops the silent client.
"""

from __future__ import annotations

import contextlib
import re
from collections.abc import Iterator
from typing import Any

import httpx
import pytest

from tests.e2e.conftest import ARTIFACTS, Server

pytestmark = pytest.mark.e2e
AXIS = "MC_Axis001"


def _state(page: Any) -> Any:
    return page.get_by_test_id("axis-state")


def _open(browser: Any, server: Server, name: str) -> tuple[Any, Any]:
    ctx = browser.new_context(viewport={"width": 1366, "height": 768})
    ctx.add_init_script(f"localStorage.setItem('mcstudio.clientName', {name!r})")
    page = ctx.new_page()
    errors: list[str] = []
    page.on("pageerror", lambda e: errors.append(str(e)))
    page.page_errors = errors
    page.goto(server.base + "/")
    page.get_by_test_id("ws-status").filter(has_text="live").wait_for(timeout=15000)
    page.get_by_test_id(f"nav-axis-{AXIS}").click()
    _state(page).wait_for(timeout=15000)
    return ctx, page


def _client_id(server: Server, name: str) -> str:
    clients = httpx.get(server.api("/control")).json()["clients"]
    return next(c["id"] for c in clients if c["name"] == name and c["connected"])


def _events(server: Server) -> list[str]:
    return [e["message"] for e in httpx.get(server.api("/events")).json()]


@pytest.fixture
def two(browser: Any, server: Server) -> Iterator[dict[str, Any]]:
    contexts: list[Any] = []
    pages: dict[str, Any] = {"_contexts": contexts}
    for name in ("Alice", "Bob"):
        ctx, pages[name] = _open(browser, server, name)
        contexts.append(ctx)
    yield pages
    for ctx in contexts:
        with contextlib.suppress(Exception):
            ctx.close()


def test_two_browsers_cannot_both_jog(two: dict[str, Any], server: Server, browser: Any) -> None:
    alice, bob = two["Alice"], two["Bob"]
    for page in (alice, bob):
        page.get_by_test_id("control-status").filter(has_text="Control free").wait_for(timeout=15000)

    # Alice's first test-run action takes free control
    if alice.get_by_test_id("servo-status").inner_text().strip() != "ON":
        alice.get_by_test_id("servo-toggle").click()
    alice.get_by_test_id("servo-status").filter(has_text=re.compile(r"^ON$")).wait_for(timeout=15000)
    alice.get_by_test_id("control-status").filter(has_text="You have control").wait_for(timeout=15000)
    bob.get_by_test_id("control-status").filter(has_text="Controlled by Alice").wait_for(timeout=15000)
    bob.get_by_test_id("readonly-hint").filter(has_text="Alice").wait_for()
    bob.screenshot(path=str(ARTIFACTS / "shared-control-read-only.png"))  # (not while jogging: it stalls the browser)

    # Alice jogs (hold); Bob watches the axis move, his controls are disabled
    alice.get_by_test_id("jog-plus").hover()
    alice.mouse.down()
    _state(alice).filter(has_text=re.compile(r"^Continuous$")).wait_for(timeout=15000)
    _state(bob).filter(has_text=re.compile(r"^Continuous$")).wait_for(timeout=15000)
    assert bob.get_by_test_id("jog-plus").is_disabled() and bob.get_by_test_id("jog-minus").is_disabled()
    assert bob.get_by_test_id("servo-toggle").is_disabled()
    bob.get_by_test_id("jog-minus").click(force=True)  # a click on the disabled button does nothing

    # REST with Bob's client id is refused, naming the holder; Alice's jog goes on
    jog = next(f for f in httpx.get(server.api("/fb")).json() if f["type"] == "MC_MoveJog"
               and f["inputs"]["Axis"] == AXIS)
    bob_id = _client_id(server, "Bob")
    r = httpx.patch(server.api(f"/fb/{jog['id']}"), json={"inputs": {"PositiveEnable": False, "NegativeEnable": True}},
                    headers={"X-MCStudio-Client": bob_id})
    assert r.status_code == 423 and "Alice" in r.json()["detail"]
    assert httpx.get(server.api(f"/fb/{jog['id']}")).json()["inputs"]["NegativeEnable"] is False

    # Bob takes control (forced): Alice becomes read-only and her jog stops while her button is still held
    bob.get_by_test_id("control-take").click()
    bob.get_by_test_id("control-take-confirm").click()
    bob.get_by_test_id("control-status").filter(has_text="You have control").wait_for(timeout=15000)
    alice.get_by_test_id("control-status").filter(has_text="Controlled by Bob").wait_for(timeout=15000)
    _state(alice).filter(has_text=re.compile(r"^Standstill$")).wait_for(timeout=15000)
    assert alice.get_by_test_id("jog-plus").is_disabled()
    assert httpx.get(server.api(f"/fb/{jog['id']}")).json()["inputs"]["PositiveEnable"] is False
    # (the forced take drops the enable at once — tests/api/test_control.py times it; on a loaded machine the page's
    # 100 ms heartbeats may have stalled past the 0.5 s lease before, which stops the jog too)
    assert any("control taken by 'Bob'" in m or "lease of 0.5 s expired" in m for m in _events(server))
    alice.screenshot(path=str(ARTIFACTS / "shared-control-taken.png"))
    alice.mouse.up()
    assert bob.get_by_test_id("jog-plus").is_enabled()

    # Alice takes it back and jogs; closing her page while jogging stops the jog and frees control
    alice.get_by_test_id("readonly-take").click()
    alice.get_by_test_id("control-status").filter(has_text="You have control").wait_for(timeout=15000)
    bob.get_by_test_id("control-status").filter(has_text="Controlled by Alice").wait_for(timeout=15000)
    alice.get_by_test_id("jog-plus").hover()
    alice.mouse.down()
    _state(bob).filter(has_text=re.compile(r"^Continuous$")).wait_for(timeout=15000)
    alice.context.close()
    _state(bob).filter(has_text=re.compile(r"^Standstill$")).wait_for(timeout=15000)
    try:
        bob.get_by_test_id("control-status").filter(has_text="Control free").wait_for(timeout=15000)
    except Exception:
        raise AssertionError(httpx.get(server.api("/control")).json()) from None
    st = httpx.get(server.api("/control")).json()
    assert st["holder"] is None and st["change"] == {"reason": "lost", "previous": "Alice", "by": None}

    # a browser that hangs while jogging (its socket stays open, it says nothing): the lease stops the jog, and
    # after 10 s of silence the server drops the client and control is free (D117); Carol watches
    ctx, carol = _open(browser, server, "Carol")
    two["_contexts"].append(ctx)
    bob.get_by_test_id("control-take").click()
    bob.get_by_test_id("control-status").filter(has_text="You have control").wait_for(timeout=15000)
    bob.get_by_test_id("jog-minus").hover()
    bob.mouse.down()
    _state(carol).filter(has_text=re.compile(r"^Continuous$")).wait_for(timeout=15000)
    before = len(_events(server))
    bob.evaluate("() => { setTimeout(() => { for (;;) {} }, 0); }")
    _state(carol).filter(has_text=re.compile(r"^Standstill$")).wait_for(timeout=15000)
    assert any("lease of 0.5 s expired" in m for m in _events(server)[before:]), _events(server)[before:]
    assert httpx.get(server.api("/control")).json()["holder"]["name"] == "Bob"  # not yet: silent for < 10 s
    carol.get_by_test_id("control-status").filter(has_text="Control free").wait_for(timeout=30000)
    st = httpx.get(server.api("/control")).json()
    assert st["change"] == {"reason": "lost", "previous": "Bob", "by": None}
    assert not alice.page_errors and not carol.page_errors, (alice.page_errors, carol.page_errors)
