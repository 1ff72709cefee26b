"""Axis settings editor and the commissioning panels of the test run, in a real headless Chromium.

Follows issue #3: parameters are edited in the UI and checked like the controller checks them (573B detail
1102: MaxJogVel > MaxVel, appendix A-1 / docs/decisions.md), homing from the test run, the velocity override
(MC_SetOverride, VelFactor 0 % pauses an axis in motion, spec/single-axis.md) and MC_ImmediateStop (5485).

No sleeps: every wait is on something the page shows (a state, a value or the controller's cycle counter).
"""

from __future__ import annotations

import re

import httpx
import pytest

from tests.e2e.conftest import ARTIFACTS, Server

pytestmark = pytest.mark.e2e

# Chromium logs every non-2xx fetch as a console error; the refusals below are intended.
_EXPECTED_HTTP = re.compile(r"Failed to load resource: the server responded with a status of (409|422)")


def _unexpected(errors: list[str]) -> list[str]:
    return [e for e in errors if not _EXPECTED_HTTP.search(e)]


def _wait_cycles(page, n: int) -> None:
    """Wait until the controller (shown in the toolbar) has run `n` more control periods."""
    start = int(page.get_by_test_id("cycle").inner_text())
    page.wait_for_function(
        "([start, n]) => parseInt(document.querySelector('[data-testid=cycle]').textContent) >= start + n",
        arg=[start, n], timeout=15000)


def test_settings_editor_shows_573B_on_the_field_and_applies(page, server: Server) -> None:
    page.goto(server.base + "/")
    page.get_by_test_id("ws-status").filter(has_text="live").wait_for(timeout=15000)
    page.get_by_test_id("nav-axis-settings-MC_Axis001").click()
    field = page.get_by_test_id("param-Operation.MaxJogVel")
    page.wait_for_function(
        "() => document.querySelector('[data-testid=\"param-Operation.MaxJogVel\"]')?.value === '100'",
        timeout=10000)

    # MaxJogVel above MaxVel (500): refused by the controller's check with 573B detail 1102, shown on the field
    field.fill("1000")
    page.get_by_test_id("tab-dirty-MC_Axis001").wait_for()
    page.get_by_test_id("settings-apply").click()
    err = page.get_by_test_id("param-error-Operation.MaxJogVel")
    err.filter(has_text="573B/1102").wait_for(timeout=10000)
    assert "573B" in page.get_by_test_id("settings-issues").inner_text()
    page.screenshot(path=str(ARTIFACTS / "10-settings-573B.png"))
    # nothing was applied
    cfg = httpx.get(server.api("/axes/MC_Axis001")).json()
    assert cfg["config"]["parameters"]["Operation"]["MaxJogVel"] == 100

    # a value the browser can check itself is refused before it is sent
    field.fill("0")
    err.filter(has_text="greater than 0").wait_for()

    # a valid value is applied (the controller restarts, like a download) and the tab is clean again
    field.fill("50")
    page.get_by_test_id("settings-apply").click()
    page.get_by_test_id("settings-clean").wait_for(timeout=10000)
    assert page.get_by_test_id("tab-dirty-MC_Axis001").count() == 0
    cfg = httpx.get(server.api("/axes/MC_Axis001")).json()
    assert cfg["config"]["parameters"]["Operation"]["MaxJogVel"] == 50
    page.screenshot(path=str(ARTIFACTS / "11-settings-applied.png"))
    assert not _unexpected(page.console_errors), page.console_errors


def test_home_override_and_immediate_stop_from_the_test_run(page, server: Server) -> None:
    page.goto(server.base + "/")
    page.get_by_test_id("ws-status").filter(has_text="live").wait_for(timeout=15000)
    page.get_by_test_id("nav-axis-MC_Axis000").click()
    page.get_by_test_id("homed").filter(has_text=re.compile(r"^Not homed$")).wait_for(timeout=10000)
    page.get_by_test_id("servo-toggle").click()
    page.get_by_test_id("servo-status").filter(has_text=re.compile(r"^ON$")).wait_for(timeout=10000)

    # homing mode 0 of the demo project: proximity reverse turning / Z phase after the dog
    page.get_by_test_id("home-button").click()
    page.get_by_test_id("axis-state").filter(has_text=re.compile(r"^Homing$")).wait_for(timeout=5000)
    page.get_by_test_id("homed").filter(has_text=re.compile(r"^Homed$")).wait_for(timeout=30000)
    page.get_by_test_id("axis-state").filter(has_text=re.compile(r"^Standstill$")).wait_for(timeout=5000)
    ax = httpx.get(server.api("/axes/MC_Axis000")).json()["variables"]
    assert ax["Details"]["Homed"] and ax["Cmd"]["Pos"] == pytest.approx(0.0, abs=1e-9)
    page.screenshot(path=str(ARTIFACTS / "12-homed.png"))

    # an absolute move, paused with the override at 0 %: still Discrete, command velocity 0, position frozen
    page.get_by_test_id("abs-position").fill("100")
    page.get_by_test_id("abs-velocity").fill("50")
    page.get_by_test_id("abs-execute").click()
    page.get_by_test_id("axis-state").filter(has_text=re.compile(r"^Discrete$")).wait_for(timeout=5000)
    page.get_by_test_id("override-value").fill("0")
    page.get_by_test_id("override-effective").filter(has_text=re.compile(r"^0 %$")).wait_for(timeout=5000)
    page.wait_for_function(
        "() => parseFloat(document.querySelector('[data-testid=cmd-vel]').textContent) === 0", timeout=10000)
    frozen = page.get_by_test_id("cmd-pos").inner_text()
    _wait_cycles(page, 250)  # 0.25 s of controller time at 1 ms
    assert page.get_by_test_id("cmd-pos").inner_text() == frozen
    assert page.get_by_test_id("axis-state").inner_text().strip() == "Discrete"
    page.screenshot(path=str(ARTIFACTS / "13-override-0.png"))

    # back to 100 %: the move goes on
    page.get_by_test_id("override-value").fill("100")
    page.wait_for_function(
        "() => parseFloat(document.querySelector('[data-testid=cmd-vel]').textContent) > 0", timeout=10000)

    # MC_ImmediateStop while moving: ErrorStop with 5485, Reset brings the axis back to Standstill
    page.get_by_test_id("immediate-stop-button").click()
    page.get_by_test_id("axis-state").filter(has_text=re.compile(r"^ErrorStop$")).wait_for(timeout=5000)
    page.get_by_test_id("error-id").filter(has_text="5485").wait_for(timeout=5000)
    page.screenshot(path=str(ARTIFACTS / "14-immediate-stop.png"))
    page.get_by_test_id("reset-button").click()
    page.get_by_test_id("axis-state").filter(has_text=re.compile(r"^Standstill$")).wait_for(timeout=5000)
    page.get_by_test_id("error-id").filter(has_text="0000").wait_for()
    assert not _unexpected(page.console_errors), page.console_errors


def test_torque_control_from_the_test_run(page, server: Server) -> None:
    """MC_TorqueControl from the test run: the drive goes to CST (DrvStatus.CST), the axis is Continuous, the actual
    torque follows the command and the speed limit holds the velocity (omron-axis-instructions.md MC_TorqueControl);
    MC_Stop brings it back to position control at Standstill."""
    page.goto(server.base + "/")
    page.get_by_test_id("ws-status").filter(has_text="live").wait_for(timeout=15000)
    page.get_by_test_id("nav-axis-MC_Axis002").click()
    if page.get_by_test_id("servo-status").inner_text().strip() != "ON":
        page.get_by_test_id("servo-toggle").click()
    page.get_by_test_id("servo-status").filter(has_text=re.compile(r"^ON$")).wait_for(timeout=10000)
    page.get_by_test_id("trq-torque").fill("10")
    page.get_by_test_id("trq-ramp").fill("100")
    page.get_by_test_id("trq-velocity").fill("20")
    page.get_by_test_id("trq-execute").click()
    page.get_by_test_id("axis-state").filter(has_text=re.compile(r"^Continuous$")).wait_for(timeout=5000)
    page.locator("[data-testid=drv-CST][data-active=true]").wait_for(timeout=5000)
    # the ramp reaches 10 % after 0.1 s; the speed limit then caps the velocity at 20 mm/s
    page.wait_for_function(
        "() => parseFloat(document.querySelector('[data-testid=cmd-trq]').textContent) === 10", timeout=10000)
    page.wait_for_function(
        "() => Math.abs(parseFloat(document.querySelector('[data-testid=act-vel]').textContent) - 20) < 0.5",
        timeout=15000)
    page.screenshot(path=str(ARTIFACTS / "15-torque-control.png"))
    page.get_by_test_id("stop-button").click()
    page.get_by_test_id("axis-state").filter(has_text=re.compile(r"^Standstill$")).wait_for(timeout=10000)
    page.locator("[data-testid=drv-CSP][data-active=true]").wait_for(timeout=5000)
    assert not _unexpected(page.console_errors), page.console_errors
