"""The group test run in a real headless Chromium at 1366×768: the 3D tab's robot panel (servo ON, MC_GroupEnable,
ready pose, hold +X on the Cartesian jog MC_RobotJog — the TCP moves along X only and the picture changes; a UCS
defined by MC_DefineCoordSystem chosen as the jog frame and one 10 mm step along its X axis; the settings still there
after a reload (localStorage, D93); the pick-and-place demo with its settings), and the XY group MC_Group001's tab
from the project tree (MC_MoveLinear to (120, 60) mm).

Screenshots (test-artifacts/e2e/): robot-jog-before.png, robot-jog-after.png (the viser frame), robot-testrun.png
(the 3D tab with the panel), robot-jog-ucs-step.png, robot-demo.png, group-xy-testrun.png. Waits are on what the page
or the API shows.
"""

from __future__ import annotations

import re
import time
from collections.abc import Callable

import httpx
import pytest

from tests.e2e.conftest import ARTIFACTS, Server
from tests.e2e.test_viz import _changed_fraction, _settled_shot

pytestmark = pytest.mark.e2e

ROBOT = "MC_Group000"
XY = "MC_Group001"


def _robot(server: Server) -> dict:
    return httpx.get(server.api("/viz/robots")).json()["robots"][0]


def _until(page: object, pred: Callable[[], bool], what: str, *, timeout_s: float = 15.0) -> None:
    """Poll the REST API until `pred` holds (a readiness wait on the controller, not a timing assertion). The page's
    event loop keeps running between polls (Playwright's sync API only pumps while it is called)."""
    end = time.monotonic() + timeout_s
    while not pred():
        assert time.monotonic() < end, f"timed out waiting for {what}"
        page.wait_for_timeout(20)  # type: ignore[attr-defined]


def _group_state(page: object, name: str, state: str) -> None:
    page.get_by_test_id(f"group-state-{name}").filter(has_text=re.compile(f"^{state}$")).first.wait_for(  # type: ignore[attr-defined]
        timeout=15000)


def _api_group(server: Server, name: str) -> dict:
    return next(g for g in httpx.get(server.api("/groups")).json() if g["name"] == name)


def _fb_done(server: Server, fb_type: str, inputs: dict) -> None:
    """Run a one-shot instruction through /fb and wait (on the API) until it is Done."""
    fb = httpx.post(server.api("/fb"), json={"type": fb_type, "inputs": inputs}).json()
    end = time.monotonic() + 30.0
    while not httpx.get(server.api(f"/fb/{fb['id']}")).json()["outputs"].get("Done"):
        assert time.monotonic() < end, f"{fb_type} not Done"
        time.sleep(0.02)
    httpx.delete(server.api(f"/fb/{fb['id']}"))


def _jog_in_a_ucs_by_steps(page: object, server: Server) -> None:
    """D93: UCS 2 (MC_DefineCoordSystem, Rz 90°: its +X is the MCS's +Y) is offered as the jog frame; in Step mode
    one click on +X moves the TCP 10 mm along MCS +Y, X and Z unchanged; the settings survive a reload."""
    _fb_done(server, "MC_DefineCoordSystem", {"AxesGroup": ROBOT, "Execute": True,
                                              "CoordTransform": {"CSID": 2, "Pose": [0, 0, -300, 0, 0, 90]}})
    page.get_by_test_id("robot-jog-frame").click()  # type: ignore[attr-defined]
    page.get_by_role("option", name="UCS 2").click()  # type: ignore[attr-defined]
    page.get_by_test_id("robot-jog-frame-note").filter(has_text="UCS 2").wait_for(timeout=30000)  # type: ignore[attr-defined]
    page.get_by_test_id("robot-jog-mode").get_by_text("Step").click()  # type: ignore[attr-defined]
    page.get_by_test_id("robot-jog-step").fill("10")  # type: ignore[attr-defined]
    p0 = _robot(server)["tcp"]
    page.get_by_test_id("robot-jog-plus-x").filter(has_text="10 mm").click()  # type: ignore[attr-defined]
    _until(page, lambda: _robot(server)["tcp"][1] > p0[1] + 9.9, "one 10 mm step along +X of UCS 2 (= MCS +Y)",
           timeout_s=60.0)
    # the step ended (InPosition), the page dropped Enable: the group is Standby again (on the API: the page's
    # read-out can lag behind while software WebGL holds its main thread)
    _until(page, lambda: _api_group(server, ROBOT)["state"] == "Standby", "the group Standby after the step",
           timeout_s=60.0)
    page.wait_for_timeout(300)  # type: ignore[attr-defined]  # the drives settle on the command
    p1 = _robot(server)["tcp"]
    assert p1[1] == pytest.approx(p0[1] + 10.0, abs=0.05)
    assert p1[0] == pytest.approx(p0[0], abs=0.05) and p1[2] == pytest.approx(p0[2], abs=0.05)
    page.screenshot(path=str(ARTIFACTS / "robot-jog-ucs-step.png"), timeout=90000)  # type: ignore[attr-defined]
    # a demo setting, then reload: everything is read back from localStorage (per project and group)
    page.get_by_test_id("robot-demo-settings-toggle").click()  # type: ignore[attr-defined]
    page.get_by_test_id("robot-demo-speed").fill("450")  # type: ignore[attr-defined]
    stored = page.evaluate(  # type: ignore[attr-defined]
        "() => Object.keys(localStorage).filter((k) => k.startsWith('mcstudio.robotTestRun.v1:') "
        "&& k.endsWith(':MC_Group000')).map((k) => JSON.parse(localStorage.getItem(k)))")
    assert len(stored) == 1
    assert stored[0]["velocity"] == 100 and stored[0]["mode"] == "step" and stored[0]["step"] == 10
    assert stored[0]["frame"] == "ucs:2" and stored[0]["demo"]["velocity"] == 450
    page.reload()  # type: ignore[attr-defined]
    page.get_by_test_id("ws-status").filter(has_text="live").wait_for(timeout=60000)  # type: ignore[attr-defined]
    page.get_by_test_id("nav-3d").click()  # type: ignore[attr-defined]
    page.get_by_test_id("robot-testrun").wait_for(timeout=60000)  # type: ignore[attr-defined]
    assert page.get_by_test_id("robot-jog-speed").input_value() == "100"  # type: ignore[attr-defined]
    assert page.get_by_test_id("robot-jog-step").input_value() == "10"  # type: ignore[attr-defined]
    page.get_by_test_id("robot-jog-frame-note").filter(has_text="UCS 2").wait_for(timeout=30000)  # type: ignore[attr-defined]
    assert page.get_by_test_id("robot-jog-frame").input_value() == "UCS 2"  # type: ignore[attr-defined]
    page.get_by_test_id("robot-demo-settings-toggle").click()  # type: ignore[attr-defined]
    assert page.get_by_test_id("robot-demo-speed").input_value() == "450"  # type: ignore[attr-defined]
    page.get_by_test_id("robot-demo-settings-toggle").click()  # type: ignore[attr-defined]


def test_robot_jog_demo_and_xy_move(page, server: Server) -> None:
    page.set_viewport_size({"width": 1366, "height": 768})
    page.goto(server.base + "/")
    page.get_by_test_id("ws-status").filter(has_text="live").wait_for(timeout=15000)
    page.get_by_test_id("nav-3d").click()
    page.get_by_test_id("robot-testrun").wait_for(timeout=15000)
    frame = page.get_by_test_id("viser-frame")
    page.frame_locator("[data-testid=viser-frame]").locator("canvas").first.wait_for(timeout=20000)

    # servo ON, enable, into the workspace (the zero pose is above it)
    page.get_by_test_id(f"group-servo-{ROBOT}").click()
    page.get_by_test_id(f"group-servo-{ROBOT}").filter(has_text="Servo OFF").wait_for(timeout=10000)
    page.get_by_test_id(f"group-enable-{ROBOT}").click()
    _group_state(page, ROBOT, "Standby")
    page.get_by_test_id(f"robot-ready-{ROBOT}").click()
    page.get_by_test_id("robot-tcp").filter(has_text=re.compile(r"Z\s*-300\.00")).wait_for(timeout=15000)
    _group_state(page, ROBOT, "Standby")
    p0 = _robot(server)["tcp"]
    tcp_before = page.get_by_test_id("robot-tcp").inner_text()
    before = _settled_shot(frame, str(ARTIFACTS / "robot-jog-before.png"))

    # hold +X until the TCP is 60 mm further along X, then release: the robot stops, Y and Z unchanged
    page.get_by_test_id("robot-jog-speed").fill("100")
    button = page.get_by_test_id("robot-jog-plus-x")
    button.hover()
    page.mouse.down()
    _until(page, lambda: _robot(server)["tcp"][0] > p0[0] + 60.0, "the TCP 60 mm along +X")
    page.mouse.up()
    _group_state(page, ROBOT, "Standby")
    p1 = _robot(server)["tcp"]
    assert p1[0] > p0[0] + 60.0
    assert p1[1] == pytest.approx(p0[1], abs=0.05) and p1[2] == pytest.approx(p0[2], abs=0.05)
    # the readout shows the new X (≥ 60 mm; how far past depends on when the release arrives)
    page.get_by_test_id("robot-tcp").filter(has_text=re.compile(r"X\s*([6-9]\d|[1-9]\d{2,})\.\d\d")).wait_for(
        timeout=10000)
    assert page.get_by_test_id("robot-tcp").inner_text() != tcp_before
    after = _settled_shot(frame, str(ARTIFACTS / "robot-jog-after.png"))
    page.screenshot(path=str(ARTIFACTS / "robot-testrun.png"), timeout=90000)  # the 3D frame renders in software
    changed = _changed_fraction(page, before, after)
    assert changed > 0.003, f"the picture hardly changed ({changed:.4f} of the pixels)"

    _jog_in_a_ucs_by_steps(page, server)

    # the pick-and-place demo: one full cycle, then stop (the conveyor stops too)
    page.get_by_test_id(f"robot-demo-run-{ROBOT}").click()
    page.get_by_test_id(f"robot-demo-status-{ROBOT}").filter(has_text="1 cycles").wait_for(timeout=30000)
    conveyor = httpx.get(server.api("/axes/MC_Axis007")).json()["variables"]
    assert conveyor["Status"]["Continuous"] is True
    page.screenshot(path=str(ARTIFACTS / "robot-demo.png"), timeout=90000)  # the 3D frame renders in software
    page.get_by_test_id(f"robot-demo-stop-{ROBOT}").click()
    page.get_by_test_id(f"robot-demo-run-{ROBOT}").wait_for(timeout=10000)
    _group_state(page, ROBOT, "Standby")

    # the XY group from the project tree: servo ON, enable, MC_MoveLinear to (120, 60) mm
    page.get_by_test_id(f"nav-group-{XY}").click()
    page.get_by_test_id(f"group-testrun-{XY}").wait_for(timeout=10000)
    page.get_by_test_id(f"group-servo-{XY}").click()
    page.get_by_test_id(f"group-servo-{XY}").filter(has_text="Servo OFF").wait_for(timeout=10000)
    page.get_by_test_id(f"group-home-{XY}").click()  # incremental encoders: MC_Home against the demo's dog
    page.get_by_test_id(f"group-home-{XY}").wait_for(state="detached", timeout=30000)
    page.get_by_test_id(f"group-enable-{XY}").click()
    _group_state(page, XY, "Standby")
    page.get_by_test_id("group-move-pos-0").fill("120")
    page.get_by_test_id("group-move-pos-1").fill("60")
    page.get_by_test_id(f"group-move-run-{XY}").click()
    page.get_by_test_id("group-pos-A0").filter(has_text="120.000").wait_for(timeout=15000)
    page.get_by_test_id("group-pos-A1").filter(has_text="60.000").wait_for(timeout=15000)
    _group_state(page, XY, "Standby")
    g = next(x for x in httpx.get(server.api("/groups")).json() if x["name"] == XY)
    assert g["cmd_pos"] == pytest.approx([120.0, 60.0], abs=1e-6) and g["error_code"] == "0000"
    page.get_by_test_id(f"group-last-{XY}").filter(has_text="MC_MoveLinear").wait_for(timeout=5000)
    page.screenshot(path=str(ARTIFACTS / "group-xy-testrun.png"), timeout=90000)  # the 3D frame renders in software
    assert not [e for e in page.console_errors if "WebGL" not in e and "favicon" not in e], page.console_errors
