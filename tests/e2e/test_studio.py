"""The studio in a real headless Chromium: servo on, move an axis, see the position change, hold-to-jog, 3D tab.

Follows issue #2 "What it must show": the UI is served at /, the API answers, and a user can move an axis.
"""

from __future__ import annotations

import re

import httpx
import pytest

from tests.e2e.conftest import ARTIFACTS, Server

pytestmark = pytest.mark.e2e


def _num(text: str) -> float:
    m = re.search(r"-?\d+(?:\.\d+)?", text.replace(",", ""))
    assert m, f"no number in {text!r}"
    return float(m.group(0))


def test_servo_on_move_and_see_position(page, server: Server) -> None:
    page.goto(server.base + "/")
    page.get_by_test_id("ws-status").filter(has_text="live").wait_for(timeout=15000)
    page.get_by_test_id("cycle").wait_for()
    page.get_by_test_id("axis-row-MC_Axis000").wait_for()
    page.screenshot(path=str(ARTIFACTS / "01-overview.png"))

    page.get_by_test_id("nav-axis-MC_Axis000").click()
    page.get_by_test_id("servo-toggle").click()
    page.get_by_test_id("servo-status").filter(has_text=re.compile(r"^ON$")).wait_for(timeout=10000)
    page.get_by_test_id("axis-state").filter(has_text=re.compile(r"^Standstill$")).wait_for()

    page.get_by_test_id("abs-position").fill("25")
    page.get_by_test_id("abs-velocity").fill("50")
    page.get_by_test_id("abs-execute").click()
    page.get_by_test_id("axis-state").filter(has_text=re.compile(r"^Discrete$")).wait_for(timeout=5000)
    page.get_by_test_id("act-pos").filter(has_text=re.compile(r"25\.000")).wait_for(timeout=15000)
    page.get_by_test_id("axis-state").filter(has_text=re.compile(r"^Standstill$")).wait_for()
    page.screenshot(path=str(ARTIFACTS / "02-test-run-after-move.png"))

    # the REST view agrees with what the page shows
    ax = httpx.get(server.api("/axes/MC_Axis000")).json()["variables"]
    assert ax["Act"]["Pos"] == pytest.approx(25.0, abs=1e-6)
    assert ax["Status"]["Standstill"]

    # relative move back by 10
    page.get_by_test_id("rel-distance").fill("-10")
    page.get_by_test_id("rel-execute").click()
    page.get_by_test_id("act-pos").filter(has_text=re.compile(r"15\.000")).wait_for(timeout=15000)
    assert not page.console_errors, page.console_errors


def test_hold_to_jog_moves_and_release_stops(page, server: Server) -> None:
    page.goto(server.base + "/")
    page.get_by_test_id("nav-axis-MC_Axis001").click()
    toggle = page.get_by_test_id("servo-toggle")
    if page.get_by_test_id("servo-status").inner_text().strip() != "ON":
        toggle.click()
    page.get_by_test_id("servo-status").filter(has_text=re.compile(r"^ON$")).wait_for(timeout=10000)
    start = _num(page.get_by_test_id("act-pos").inner_text())
    jog = page.get_by_test_id("jog-plus")
    jog.hover()
    page.mouse.down()
    page.get_by_test_id("axis-state").filter(has_text=re.compile(r"^Continuous$")).wait_for(timeout=5000)
    page.wait_for_function(
        "([sel, start]) => parseFloat(document.querySelector(sel).textContent.replace(/,/g, '')) > start + 1",
        arg=["[data-testid=act-pos]", start], timeout=10000)
    page.mouse.up()
    page.get_by_test_id("axis-state").filter(has_text=re.compile(r"^Standstill$")).wait_for(timeout=10000)
    moved = _num(page.get_by_test_id("act-pos").inner_text())
    assert moved > start + 1
    page.screenshot(path=str(ARTIFACTS / "03-after-jog.png"))
    assert not page.console_errors, page.console_errors


def test_error_id_and_meaning_are_shown(page, server: Server) -> None:
    """A move with velocity 0 ends in 5422; the panel shows the code and what it means; Reset clears it."""
    page.goto(server.base + "/")
    page.get_by_test_id("nav-axis-MC_Axis002").click()
    if page.get_by_test_id("servo-status").inner_text().strip() != "ON":
        page.get_by_test_id("servo-toggle").click()
    page.get_by_test_id("servo-status").filter(has_text=re.compile(r"^ON$")).wait_for(timeout=10000)
    page.get_by_test_id("abs-position").fill("5")
    page.get_by_test_id("abs-velocity").fill("0")
    page.get_by_test_id("abs-execute").click()
    page.get_by_test_id("error-id").filter(has_text="5422").wait_for(timeout=5000)
    assert "Target Velocity" in page.get_by_test_id("error-meaning").inner_text()
    page.get_by_test_id("axis-state").filter(has_text=re.compile(r"^ErrorStop$")).wait_for()
    page.get_by_test_id("event-log").filter(has_text="54220000").wait_for(timeout=5000)
    page.screenshot(path=str(ARTIFACTS / "04-error.png"))
    page.get_by_test_id("reset-button").click()
    page.get_by_test_id("axis-state").filter(has_text=re.compile(r"^Standstill$")).wait_for(timeout=5000)
    page.get_by_test_id("error-id").filter(has_text="0000").wait_for()


def test_3d_tab_shows_viser(page, server: Server) -> None:
    assert httpx.get(f"http://127.0.0.1:{server.viser_port}/").status_code == 200
    page.goto(server.base + "/")
    page.get_by_test_id("nav-3d").click()
    frame = page.get_by_test_id("viser-frame")
    frame.wait_for(timeout=10000)
    assert f":{server.viser_port}" in (frame.get_attribute("src") or "")
    page.frame_locator("[data-testid=viser-frame]").locator("canvas").first.wait_for(timeout=20000)
    page.screenshot(path=str(ARTIFACTS / "05-3d.png"))
