"""The README's "First 10 minutes", followed as a new user would, in a real headless Chromium at 1366×768 (issue 8).

Every step is done through the page — clicks, typing, holding a button or a key; the REST API is only read, for the
assertions. Steps (README.md "First 10 minutes"):

1. open the studio with the demo machine;
2. MC_Axis000's test run from the project tree: Servo ON;
3. Home (MC_Home against the demo's proximity dog) → Homed at 0 mm;
4. jog: hold "Jog +" (MC_MoveJog), then hold → with the test run focused; the axis stops on release and on a window
   blur; Zero position brings it back to 0;
5. run a cam: the cam table RiseDwellReturn's test run (MC_CamIn of MC_Axis000 on the virtual MC_Axis003) → InSync,
   Stop;
6. trace a move: the Data trace of Cmd.Vel and Cmd.Pos with a trigger on Cmd.Vel rising through 1 mm/s, then
   MC_MoveAbsolute to 300 mm at Velocity 100 mm/s, Acceleration = Deceleration 1000 mm/s² from the test run. The
   trace shows the trapezoid the settings imply: peak Cmd.Vel = Velocity (±1 %), the acceleration phase lasts
   V/A = 0.1 s (±2 periods), Cmd.Pos ends at the target and the distance travelled is target − start
   (`omron-axis-instructions.md` MC_MoveAbsolute: trapezoid with Jerk 0; decision D100 for the trace's sampling);
7. the robot in the 3D tab: Servo ON, Enable, Ready pose, the pick-and-place demo runs, Stop;
8. Save (the project file is written);
9. a fault drill: a drive alarm from the EtherCAT view pops a notification; "Show in event log" opens the log at the
   event with the manual's cause and correction; Reset (MC_Reset) clears it.

No console error or warning of the studio's page during the whole walkthrough (the 3D view's iframe is viser's own
client on another port; its WebGL driver notices are not the studio's). Screenshots: test-artifacts/walkthrough/
NN-step.png; three of them are in docs/img/ for the README.
"""

from __future__ import annotations

import contextlib
import re
import time
from collections.abc import Callable

import httpx
import pytest
from playwright.sync_api import TimeoutError as PlaywrightTimeoutError

from tests.conftest import ROOT
from tests.e2e.conftest import Server

pytestmark = pytest.mark.e2e

SHOTS = ROOT / "test-artifacts" / "walkthrough"
AXIS = "MC_Axis000"
TARGET, VEL, ACC = 300.0, 100.0, 1000.0
PERIOD_S = 0.001  # the demo's primary period (projects/demo/project.json controller.primary_period_us)


def _axis(server: Server, name: str = AXIS) -> dict:
    return httpx.get(server.api(f"/axes/{name}")).json()["variables"]


def _until(page: object, pred: Callable[[], bool], what: str, *, timeout_s: float = 15.0) -> None:
    """Poll the REST API until `pred` holds (a readiness wait on the controller, not a timing assertion); the page's
    event loop runs between polls."""
    end = time.monotonic() + timeout_s
    while not pred():
        assert time.monotonic() < end, f"timed out waiting for {what}"
        page.wait_for_timeout(20)  # type: ignore[attr-defined]


T0 = [0.0]


def _shot(page: object, name: str) -> None:
    print(f"{time.monotonic() - T0[0]:6.1f} s  {name}")  # step timings in the test log (pytest -s)
    page.screenshot(path=str(SHOTS / f"{name}.png"), timeout=60000)  # type: ignore[attr-defined]


def _state(page: object, state: str) -> None:
    page.get_by_test_id("axis-state").filter(has_text=re.compile(f"^{state}$")).wait_for(timeout=15000)  # type: ignore[attr-defined]


def _studio_console(page: object, server: Server) -> list[str]:
    """Errors and warnings of the studio's own page (not of the viser iframe, a separate client on its port)."""
    msgs: list[str] = []
    viser = f":{server.viser_port}/"

    def on(m: object) -> None:
        if m.type not in ("error", "warning"):  # type: ignore[attr-defined]
            return
        url = (m.location or {}).get("url", "")  # type: ignore[attr-defined]
        if viser in url or m.text.startswith("THREE."):  # type: ignore[attr-defined]
            return  # viser's client (three.js inside the 3D iframe) — not the studio's code
        msgs.append(f"{m.type}: {m.text} ({url})")  # type: ignore[attr-defined]

    page.on("console", on)  # type: ignore[attr-defined]
    page.on("pageerror", lambda e: msgs.append(f"pageerror: {e}"))  # type: ignore[attr-defined]
    return msgs


def test_first_ten_minutes(page, server: Server) -> None:
    try:
        _walkthrough(page, server)
    except Exception:
        with contextlib.suppress(Exception):
            page.screenshot(path=str(SHOTS / "failure.png"), timeout=30000)  # what the page showed
        raise


def _walkthrough(page, server: Server) -> None:
    SHOTS.mkdir(parents=True, exist_ok=True)
    T0[0] = time.monotonic()
    console = _studio_console(page, server)
    project_file = server.project_dir / "project.json"
    saved_before = project_file.stat().st_mtime_ns

    # 1. open the studio with the demo
    page.goto(server.base + "/")
    page.get_by_test_id("ws-status").filter(has_text="live").wait_for(timeout=15000)
    page.get_by_test_id(f"axis-row-{AXIS}").wait_for()
    assert page.evaluate("document.documentElement.scrollWidth <= window.innerWidth"), "horizontal page scroll"
    _shot(page, "01-open")

    # 2. servo ON from the axis's test run
    page.get_by_test_id(f"nav-axis-{AXIS}").click()
    page.get_by_test_id(f"testrun-{AXIS}").wait_for()
    page.get_by_test_id("servo-toggle").click()
    page.get_by_test_id("servo-status").filter(has_text=re.compile("^ON$")).wait_for(timeout=10000)
    _state(page, "Standstill")
    assert page.evaluate("document.documentElement.scrollWidth <= window.innerWidth"), "horizontal page scroll"

    # 3. home: MC_Home with the axis's homing settings (proximity dog, Z phase) → home defined at 0
    page.get_by_test_id("home-button").click()
    page.get_by_test_id("homed").filter(has_text=re.compile("^Homed$")).wait_for(timeout=30000)  # not "Not homed"
    _state(page, "Standstill")
    v = _axis(server)
    assert v["Details"]["Homed"] is True and v["Cmd"]["Pos"] == pytest.approx(0.0, abs=1e-9), v
    page.get_by_test_id("jog-panel").scroll_into_view_if_needed()  # the top of the test run, for the picture
    page.mouse.move(700, 700)  # no tooltip in the picture
    _shot(page, "02-servo-on-homed")

    # 4. jog: hold Jog + (dead-man MC_MoveJog at the jog velocity), release → stops
    page.get_by_test_id("jog-plus").hover()
    page.mouse.down()
    _until(page, lambda: _axis(server)["Cmd"]["Pos"] > 2.0, "the jog to pass 2 mm")
    page.mouse.up()
    _state(page, "Standstill")
    after_button = _axis(server)["Cmd"]["Pos"]
    assert after_button > 2.0
    # … and with the keyboard: → held while the test run has the focus; a window blur stops it like a key-up
    page.get_by_test_id("position-panel").click()
    page.keyboard.down("ArrowRight")
    _until(page, lambda: _axis(server)["Cmd"]["Pos"] > after_button + 2.0, "the → jog to pass 2 mm more")
    page.evaluate("window.dispatchEvent(new Event('blur'))")
    _state(page, "Standstill")
    page.keyboard.up("ArrowRight")
    assert _axis(server)["Cmd"]["Pos"] > after_button + 2.0
    page.get_by_test_id("jog-panel").get_by_text(re.compile(r"mm/s")).first.wait_for()  # units on the fields
    _shot(page, "03-jog")
    page.get_by_test_id("zero-position-button").click()  # MC_MoveZeroPosition: back to 0 for the cam
    _until(page, lambda: _axis(server)["Cmd"]["Pos"] == pytest.approx(0.0, abs=1e-9), "the axis back at 0")
    _state(page, "Standstill")

    # 5. run a cam: RiseDwellReturn's test run cams MC_Axis000 on the virtual MC_Axis003
    page.get_by_test_id("nav-cam-RiseDwellReturn").click()
    page.get_by_test_id("cam-editor-RiseDwellReturn").wait_for()
    run = page.get_by_test_id("cam-test-run")
    run.scroll_into_view_if_needed()
    assert page.get_by_test_id("cam-run-slave").input_value() == AXIS
    page.get_by_test_id("cam-run-start").click()
    page.get_by_test_id("cam-run-insync").filter(has_text="InSync").wait_for(timeout=15000)
    _until(page, lambda: _axis(server)["Cmd"]["Pos"] > 20.0, "the slave to follow the rise")
    assert _axis(server)["Status"]["Synchronized"] is True
    _shot(page, "04-cam")
    page.get_by_test_id("cam-run-stop").click()
    page.get_by_test_id("cam-run-start").wait_for(timeout=15000)
    _until(page, lambda: _axis(server)["Status"]["Standstill"], "the slave to stop")

    # 6. trace a move: Cmd.Vel (the default) and Cmd.Pos, trigger on Cmd.Vel rising through 1 mm/s
    page.get_by_test_id("nav-trace").click()
    page.get_by_test_id("trace-view").wait_for()
    add = page.get_by_test_id("trace-add-variable")
    add.click()
    add.fill(f"{AXIS}.Cmd.Pos")
    page.get_by_role("option", name=f"{AXIS}.Cmd.Pos [mm]", exact=True).click()
    page.get_by_test_id("trace-variables").get_by_text(f"{AXIS}.Cmd.Pos").wait_for()
    page.get_by_test_id("trace-samples").fill("5000")
    page.get_by_test_id("trace-trigger-enable").click()
    page.get_by_test_id("trace-trigger-level").fill("1")
    page.get_by_test_id("trace-trigger-pre").fill("10")
    page.get_by_test_id("trace-start").click()
    page.get_by_test_id("trace-state").filter(has_text="Waiting for trigger").wait_for(timeout=10000)

    # the move from the test run: MC_MoveAbsolute 300 mm at 100 mm/s, 1000 mm/s² both ways
    start = _axis(server)["Cmd"]["Pos"]
    page.get_by_test_id(f"tab-axis-{AXIS}").click()
    page.get_by_test_id("abs-position").fill(f"{TARGET:g}")
    page.get_by_test_id("abs-velocity").fill(f"{VEL:g}")
    page.get_by_test_id("abs-acceleration").fill(f"{ACC:g}")
    page.get_by_test_id("abs-deceleration").fill(f"{ACC:g}")
    page.get_by_test_id("abs-jerk").fill("0")
    page.get_by_test_id("abs-execute").click()
    page.get_by_test_id("cmd-pos").filter(has_text="300.000").wait_for(timeout=20000)
    _state(page, "Standstill")
    page.get_by_test_id("tab-trace").click()
    page.get_by_test_id("trace-state").filter(has_text="Done").wait_for(timeout=20000)
    chart = page.get_by_test_id("trace-chart")
    assert chart.locator(".u-legend").inner_text().count(AXIS) == 2
    _shot(page, "05-trace")

    tr = httpx.get(server.api("/traces")).json()[-1]
    d = httpx.get(server.api(f"/traces/{tr['id']}")).json()
    assert d["state"] == "done" and d["sample_count"] == 5000 and d["trigger_index"] == 500
    vel, pos = d["series"][0]["values"], d["series"][1]["values"]
    assert [s["label"] for s in d["series"]] == [f"{AXIS}.Cmd.Vel", f"{AXIS}.Cmd.Pos"]
    peak = max(vel)
    assert peak == pytest.approx(VEL, rel=0.01), f"peak Cmd.Vel {peak}"
    first = next(i for i, x in enumerate(vel) if x > 0)  # the first period of the move
    full = next(i for i, x in enumerate(vel) if x >= VEL * (1 - 1e-9))  # cruise velocity reached
    assert abs((full - first + 1) - VEL / ACC / PERIOD_S) <= 2, f"acceleration phase {full - first + 1} periods"
    assert pos[0] == pytest.approx(start, abs=1e-9) and pos[-1] == pytest.approx(TARGET, abs=1e-9)
    travelled = sum(vel) * PERIOD_S  # Cmd.Vel is the difference of positions per period
    assert travelled == pytest.approx(TARGET - start, abs=1e-6)

    # 7. the robot in the 3D tab: servo ON, enable, ready pose, the pick-and-place demo
    page.get_by_test_id("tab-3d").click()
    page.get_by_test_id("robot-testrun").wait_for(timeout=15000)
    page.frame_locator("[data-testid=viser-frame]").locator("canvas").first.wait_for(timeout=20000)
    robot = "MC_Group000"
    # the first interaction waits for viser's first scene load, which software WebGL renders on the page's CPU
    page.get_by_test_id(f"group-servo-{robot}").click(timeout=90000)
    page.get_by_test_id(f"group-servo-{robot}").filter(has_text="Servo OFF").wait_for(timeout=10000)
    page.get_by_test_id(f"group-enable-{robot}").click()
    page.get_by_test_id(f"group-state-{robot}").filter(has_text=re.compile("^Standby$")).wait_for(timeout=30000)
    page.get_by_test_id(f"robot-ready-{robot}").click()
    # the ready pose is a realtime move of the arms (a few seconds; more while the machine is loaded, RTF < 1)
    page.get_by_test_id("robot-tcp").filter(has_text=re.compile(r"Z\s*-300\.00")).wait_for(timeout=45000)
    page.get_by_test_id(f"robot-demo-run-{robot}").click()
    page.get_by_test_id(f"robot-demo-stop-{robot}").wait_for(timeout=10000)
    tcp0 = httpx.get(server.api("/viz/robots")).json()["robots"][0]["tcp"]
    _until(page, lambda: httpx.get(server.api("/viz/robots")).json()["robots"][0]["tcp"] != tcp0,
           "the robot to move", timeout_s=20)
    assert _axis(server, "MC_Axis007")["Status"]["Continuous"] is True  # the conveyor runs
    close = page.frame_locator("[data-testid=viser-frame]").locator(".mantine-Notification-closeButton")
    with contextlib.suppress(PlaywrightTimeoutError):  # viser's "software WebGL" notice covers the picture (it
        close.first.click(timeout=3000)  # also closes itself after a while)
    _shot(page, "06-robot")
    page.get_by_test_id(f"robot-demo-stop-{robot}").click()
    page.get_by_test_id(f"robot-demo-run-{robot}").wait_for(timeout=15000)
    page.get_by_test_id(f"tab-axis-{AXIS}").click()  # leave the software-rendered 3D view

    # 8. save the project
    page.get_by_test_id("save-project").click()
    page.get_by_text("Project saved").first.wait_for(timeout=10000)
    assert project_file.stat().st_mtime_ns > saved_before
    _shot(page, "07-saved")

    # 9. a fault drill: a drive alarm on node 1 from the EtherCAT view (its 603Fh code, as a drive reports it); the
    # notification names it, "Show in event log" opens the log at the event with the manual's correction, Reset clears
    page.get_by_test_id("nav-ethercat").click()
    page.get_by_test_id("ecat-fault-alarm-1").click()
    note = page.get_by_test_id("fault-notification").filter(has_text="Servo Alarm")
    note.wait_for(timeout=10000)
    note.get_by_test_id("notification-show-event").click()
    row = page.locator("tr[data-focused=true]")
    row.wait_for(timeout=5000)
    assert "30020000" in row.inner_text() and "Servo Alarm" in row.inner_text() and "MC_Axis000" in row.inner_text()
    page.locator("[data-testid^=event-detail-]").get_by_text("Correction:").wait_for()
    _shot(page, "08-fault")
    page.get_by_test_id(f"tab-axis-{AXIS}").click()
    page.get_by_test_id("reset-button").click()  # MC_Reset: the CiA402 fault reset, then the axis error
    _until(page, lambda: _axis(server)["MFaultLvl"]["Active"] is False, "the axis error reset")

    assert console == [], console
