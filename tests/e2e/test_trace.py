"""The data trace tab in a real headless Chromium at 1366×768 (issue 8): open it from the project tree, trace
MC_Axis000's Cmd.Vel and Cmd.Pos with a trigger on Cmd.Vel rising through 1 mm/s (20 % pre-trigger), start, run an
MC_MoveRelative through REST, and see the record complete and drawn; the CSV link serves the record.

Screenshot: test-artifacts/e2e/trace.png. Waits are on what the page or the API shows.
"""

from __future__ import annotations

import time
from collections.abc import Callable

import httpx
import pytest

from tests.e2e.conftest import ARTIFACTS, Server

pytestmark = pytest.mark.e2e


def _until(pred: Callable[[], bool], what: str, *, timeout_s: float = 15.0) -> None:
    """Poll the REST API until `pred` holds (a readiness wait on the controller, not a timing assertion)."""
    end = time.monotonic() + timeout_s
    while not pred():
        assert time.monotonic() < end, f"timed out waiting for {what}"
        time.sleep(0.02)


def test_trace_of_a_move(page, server: Server) -> None:
    page.goto(server.base + "/")
    page.get_by_test_id("ws-status").filter(has_text="live").wait_for(timeout=15000)
    page.get_by_test_id("nav-trace").click()
    page.get_by_test_id("trace-view").wait_for(timeout=10000)

    # variables: the default MC_Axis000.Cmd.Vel, plus Cmd.Pos picked from the searchable list
    add = page.get_by_test_id("trace-add-variable")
    add.click()
    add.fill("MC_Axis000.Cmd.Pos")
    page.get_by_role("option", name="MC_Axis000.Cmd.Pos [mm]", exact=True).click()
    page.get_by_test_id("trace-variables").get_by_text("MC_Axis000.Cmd.Pos").wait_for()
    page.get_by_test_id("trace-name").fill("Move trace")
    page.get_by_test_id("trace-samples").fill("3000")
    page.get_by_test_id("trace-trigger-enable").click()
    page.get_by_test_id("trace-trigger-level").fill("1")
    page.get_by_test_id("trace-trigger-pre").fill("20")
    page.get_by_test_id("trace-start").click()
    # the trigger is armed once the 600 pre-trigger samples are in (0.6 s of the realtime controller)
    page.get_by_test_id("trace-state").filter(has_text="Waiting for trigger").wait_for(timeout=10000)

    traces = httpx.get(server.api("/traces")).json()
    assert len(traces) == 1
    tr = traces[0]
    s = tr["settings"]
    assert [v["name"] for v in s["variables"]] == ["Cmd.Vel", "Cmd.Pos"] and s["samples"] == 3000
    assert s["trigger"]["level"] == 1 and s["trigger"]["pre_trigger_percent"] == 20 and s["name"] == "Move trace"

    # a move through REST: servo ON, then 100 mm at 100 mm/s
    pw = httpx.post(server.api("/fb"), json={"type": "MC_Power", "inputs": {"Axis": "MC_Axis000", "Enable": True}})
    assert pw.status_code == 201, pw.text
    _until(lambda: httpx.get(server.api(f"/fb/{pw.json()['id']}")).json()["outputs"]["Status"], "servo ON")
    assert httpx.get(server.api(f"/traces/{tr['id']}"), params={"max_points": 2}).json()["armed"]
    mv = httpx.post(server.api("/fb"), json={"type": "MC_MoveRelative", "inputs": {
        "Axis": "MC_Axis000", "Execute": True, "Distance": 100, "Velocity": 100, "Acceleration": 1000,
        "Deceleration": 1000}})
    assert mv.status_code == 201, mv.text
    page.get_by_test_id("trace-state").filter(has_text="Done").wait_for(timeout=20000)
    page.get_by_test_id("trace-info").filter(has_text="trigger at cycle").wait_for()

    d = httpx.get(server.api(f"/traces/{tr['id']}")).json()
    assert d["state"] == "done" and d["sample_count"] == 3000 and d["trigger_index"] == 600
    vel = d["series"][0]["values"]
    assert max(vel) == pytest.approx(100.0, abs=1e-6)
    assert vel[599] <= 1.0 < vel[600]

    chart = page.get_by_test_id("trace-chart")
    assert chart.locator("canvas").count() >= 1
    assert chart.locator(".u-legend").inner_text().count("MC_Axis000") == 2
    # a cursor: click in the plot
    box = chart.locator(".u-over").bounding_box()
    assert box is not None
    page.mouse.click(box["x"] + box["width"] * 0.5, box["y"] + box["height"] * 0.5)
    page.get_by_test_id("trace-cursors").wait_for()
    page.mouse.move(box["x"] + box["width"] * 0.3, box["y"] + box["height"] * 0.4)
    page.screenshot(path=str(ARTIFACTS / "trace.png"))

    href = page.get_by_test_id("trace-csv").get_attribute("href")
    assert href == f"/api/v1/traces/{tr['id']}/csv"
    csv = httpx.get(server.base + href)
    assert csv.status_code == 200 and len(csv.text.strip().splitlines()) == 3001
    assert csv.text.splitlines()[0] == "cycle,time_s,MC_Axis000.Cmd.Vel [mm/s],MC_Axis000.Cmd.Pos [mm]"

    # settings into the project
    page.get_by_test_id("trace-save").click()
    _until(lambda: [t["name"] for t in httpx.get(server.api("/project/traces")).json()] == ["Move trace"],
           "the settings in the project")
    assert page.console_errors == [], page.console_errors
    httpx.delete(server.api(f"/traces/{tr['id']}"))
