"""The 3D tab with the demo's Delta3 (MC_Group000 on MC_Axis004–006), in a real headless Chromium: the viser scene
and the robot panel; servo on and MC_MoveAbsolute of the three arms through the REST /fb API; the panel's positions
and TCP follow, and the picture of the robot changes (docs/robot.md "3D view").

Screenshots (test-artifacts/e2e/): 3d-robot-before.png, 3d-robot-after.png (the viser frame), 3d-tab.png (the tab).
No sleeps: every wait is on something the page shows (the viser canvas is polled until two screenshots agree).
"""

from __future__ import annotations

import base64
import re
import time

import httpx
import pytest

from mcstudio.controller.mc.kinematics import Delta3Params, forward_point
from tests.e2e.conftest import ARTIFACTS, Server

pytestmark = pytest.mark.e2e

ROBOT_AXES = ("MC_Axis004", "MC_Axis005", "MC_Axis006")
TARGET = (35.0, 10.0, 55.0)  # A0, A1, A2 [deg]: the platform swings well off the axis


def _settled_shot(locator: object, path: str, *, deadline_s: float = 30.0) -> bytes:
    """Screenshot of `locator` once the 3-D frame stops changing (two consecutive shots equal)."""
    end = time.monotonic() + deadline_s
    prev = b""
    while True:  # readiness poll of the rendered picture (not a timing assertion)
        shot: bytes = locator.screenshot()  # type: ignore[attr-defined]
        if shot == prev or time.monotonic() > end:
            with open(path, "wb") as f:
                f.write(shot)
            return shot
        prev = shot


def _changed_fraction(page: object, a: bytes, b: bytes) -> float:
    """Share of pixels whose colour differs by more than 24 in a channel, compared in the browser."""
    return float(page.evaluate(  # type: ignore[attr-defined]
        """async ([a, b]) => {
            const load = async (src) => { const i = new Image(); i.src = src; await i.decode(); return i; };
            const [ia, ib] = await Promise.all([load(a), load(b)]);
            const w = Math.min(ia.width, ib.width), h = Math.min(ia.height, ib.height);
            const px = (img) => { const c = new OffscreenCanvas(w, h); const g = c.getContext("2d");
                                  g.drawImage(img, 0, 0); return g.getImageData(0, 0, w, h).data; };
            const pa = px(ia), pb = px(ib);
            let n = 0;
            for (let k = 0; k < pa.length; k += 4)
                if (Math.abs(pa[k] - pb[k]) > 24 || Math.abs(pa[k + 1] - pb[k + 1]) > 24 ||
                    Math.abs(pa[k + 2] - pb[k + 2]) > 24) n++;
            return n / (w * h);
        }""",
        ["data:image/png;base64," + base64.b64encode(x).decode() for x in (a, b)],
    ))


def _post_fb(server: Server, body: dict[str, object]) -> int:
    r = httpx.post(server.api("/fb"), json=body)
    assert r.status_code == 201, r.text
    return int(r.json()["id"])


def test_3d_tab_shows_the_robot_and_follows_a_move(page, server: Server) -> None:
    page.set_viewport_size({"width": 1600, "height": 900})
    page.goto(server.base + "/")
    page.get_by_test_id("ws-status").filter(has_text="live").wait_for(timeout=15000)
    page.get_by_test_id("nav-3d").click()
    panel = page.get_by_test_id("robot-MC_Group000")
    panel.wait_for(timeout=15000)
    assert page.get_by_test_id("robot-empty").count() == 0
    a0 = page.get_by_test_id("robot-axis-A0")
    assert "MC_Axis004" in a0.inner_text()
    page.get_by_test_id("robot-tcp").filter(has_text=re.compile(r"Z\s*0\.00")).wait_for()  # zero pose: the origin
    frame = page.get_by_test_id("viser-frame")
    page.frame_locator("[data-testid=viser-frame]").locator("canvas").first.wait_for(timeout=20000)
    before = _settled_shot(frame, str(ARTIFACTS / "3d-robot-before.png"))

    # servo on (absolute encoders: homed at power-on) and move the three arms
    for name in ROBOT_AXES:
        _post_fb(server, {"type": "MC_Power", "inputs": {"Axis": name, "Enable": True}})
    for name in ROBOT_AXES:
        page.wait_for_function(
            f"async () => (await (await fetch('/api/v1/axes/{name}')).json()).variables.Status.Standstill === true",
            timeout=10000)
    moves = [_post_fb(server, {"type": "MC_MoveAbsolute", "inputs": {
        "Axis": name, "Position": pos, "Velocity": 90.0, "Acceleration": 900.0, "Deceleration": 900.0,
        "Execute": True}}) for name, pos in zip(ROBOT_AXES, TARGET, strict=True)]
    for fid in moves:
        page.wait_for_function(
            f"async () => (await (await fetch('/api/v1/fb/{fid}')).json()).outputs.Done === true", timeout=15000)
    for logical, pos in zip(("A0", "A1", "A2"), TARGET, strict=True):
        page.get_by_test_id(f"robot-axis-{logical}").filter(has_text=f"{pos:.3f}").wait_for(timeout=10000)

    # the panel's TCP is the forward kinematics of the feedback
    _, tcp = forward_point(Delta3Params(Rf=200.0, Lf=350.0, Rm=50.0, Lm=800.0), *TARGET)
    tcp_text = page.get_by_test_id("robot-tcp")
    tcp_text.filter(has_text=f"{tcp[2]:.2f}").wait_for(timeout=10000)
    robot = httpx.get(server.api("/viz/robots")).json()["robots"][0]
    assert robot["tcp"] == pytest.approx(list(tcp), abs=0.01) and robot["alarm"] is None

    after = _settled_shot(frame, str(ARTIFACTS / "3d-robot-after.png"))
    page.screenshot(path=str(ARTIFACTS / "3d-tab.png"))
    changed = _changed_fraction(page, before, after)
    assert changed > 0.005, f"the picture hardly changed ({changed:.4f} of the pixels)"
    assert not [e for e in page.console_errors if "WebGL" not in e and "favicon" not in e], page.console_errors
