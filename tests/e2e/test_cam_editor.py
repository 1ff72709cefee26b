"""The cam editor in a real headless Chromium (docs/cams.md, "The cam editor").

The tests run in order on one server with the demo project (cam tables RiseDwellReturn and FlyingSync):

* a node edit updates the plots and the characteristic values at once (debounced POST /cams/generate), shows the
  unsaved-changes marks; Save writes the table to the project, and after a reload the edit is there;
* a straight line into a dwell is flagged on its segment row (continuity warning); Revert brings the saved nodes back;
* CSV export (a download) and import of the same file give the same points (the table becomes imported data);
* a cam table is added from the project tree and deleted again;
* the test run cams MC_Axis000 on the virtual MC_Axis003 (MC_CamIn + MC_MoveVelocity through /fb): InSync, the slave
  follows the table, the save is refused while it runs (409), Stop ends it and removes its instances.

No sleeps: every wait is on something the page shows.
"""

from __future__ import annotations

import re
from pathlib import Path

import httpx
import pytest
from playwright.sync_api import expect

from tests.e2e.conftest import ARTIFACTS, Server

pytestmark = pytest.mark.e2e

_EXPECTED_HTTP = re.compile(r"Failed to load resource: the server responded with a status of (409|422)")


def _unexpected(errors: list[str]) -> list[str]:
    return [e for e in errors if not _EXPECTED_HTTP.search(e)]


def _open_cam(page, server: Server, name: str) -> None:
    page.goto(server.base + "/")
    page.get_by_test_id("ws-status").filter(has_text="live").wait_for(timeout=15000)
    page.get_by_test_id(f"nav-cam-{name}").click()
    page.get_by_test_id(f"cam-editor-{name}").wait_for()
    expect(page.get_by_test_id("cam-point-count")).not_to_have_text("", timeout=10000)


def test_edit_node_plots_characteristics_save_reload(page, server: Server) -> None:
    _open_cam(page, server, "RiseDwellReturn")
    expect(page.get_by_test_id("cam-point-count")).to_have_text("3601")
    expect(page.get_by_test_id("cam-saved")).to_be_visible()
    velocity = page.get_by_test_id("cam-plot-velocity")
    expect(velocity).not_to_have_attribute("data-points", "0")
    assert velocity.locator("canvas").count() == 1
    # modified sine, 100 mm over 120° at 360°/s: v max = 100 · 1.76 · 3 = 527.9
    expect(page.get_by_test_id("cam-node-0-max")).to_contain_text("527.9")
    expect(page.get_by_test_id("cam-node-0-dim")).to_contain_text("1.76")

    page.get_by_test_id("cam-node-0-distance").fill("150")
    page.get_by_test_id("cam-node-2-distance").click()  # leave the field
    expect(page.get_by_test_id("cam-node-0-max")).to_contain_text("791.8")  # 1.5 × the rise
    expect(page.get_by_test_id("cam-table-max")).to_contain_text("v max 791.8")
    expect(page.get_by_test_id("cam-dirty")).to_be_visible()
    expect(page.get_by_test_id("tab-dirty-cam-RiseDwellReturn")).to_be_visible()
    expect(page.get_by_test_id("cam-node-1-dim")).to_have_text("no rise")
    page.screenshot(path=str(ARTIFACTS / "cam-editor.png"))

    page.get_by_test_id("cam-save").click()
    expect(page.get_by_test_id("cam-saved")).to_be_visible()
    cam = httpx.get(server.api("/cams/RiseDwellReturn"), params={"points": False}).json()
    assert cam["source"]["nodes"][0]["Distance"] == 150 and cam["distance_max"] == 150
    assert "150" in (server.project_dir / "cams" / "RiseDwellReturn.csv").read_text().splitlines()[1202]

    page.reload()
    page.get_by_test_id("ws-status").filter(has_text="live").wait_for(timeout=15000)
    page.get_by_test_id("nav-cam-RiseDwellReturn").click()
    expect(page.get_by_test_id("cam-node-0-distance")).to_have_value("150")
    expect(page.get_by_test_id("cam-node-0-max")).to_contain_text("791.8")
    expect(page.get_by_test_id("cam-saved")).to_be_visible()
    assert _unexpected(page.console_errors) == []


def test_continuity_warning_on_the_segment_row_and_revert(page, server: Server) -> None:
    _open_cam(page, server, "RiseDwellReturn")
    row = page.get_by_test_id("cam-node-0")
    expect(row).to_have_attribute("data-warning", "false")
    page.get_by_test_id("cam-node-0-curve").click()
    page.get_by_role("option", name="Straight line", exact=True).click()
    expect(row).to_have_attribute("data-warning", "true")  # a straight line into the dwell: v jumps to 0
    expect(page.get_by_test_id("cam-continuity")).to_contain_text("velocity jumps")
    expect(page.get_by_test_id("cam-node-0-warning")).to_be_visible()
    page.get_by_test_id("cam-node-2-phase").fill("170")  # below node 1's 180: 5740 on that field
    expect(page.get_by_test_id("cam-node-2")).to_have_attribute("data-error", "true")
    page.get_by_test_id("cam-revert").click()
    expect(row).to_have_attribute("data-warning", "false")
    expect(page.get_by_test_id("cam-node-2")).to_have_attribute("data-error", "false")
    expect(page.get_by_test_id("cam-saved")).to_be_visible()
    assert _unexpected(page.console_errors) == []


def test_csv_export_import_round_trip(page, server: Server, tmp_path: Path) -> None:
    _open_cam(page, server, "FlyingSync")
    with page.expect_download() as dl:
        page.get_by_test_id("cam-export").click()
    path = tmp_path / "FlyingSync.csv"
    dl.value.save_as(path)
    assert dl.value.suggested_filename == "FlyingSync.csv"
    before = httpx.get(server.api("/cams/FlyingSync")).json()
    text = path.read_text()
    assert text.splitlines()[1] == "phase,distance" and len(text.splitlines()) == 2 + before["point_count"]
    with page.expect_file_chooser() as fc:
        page.get_by_test_id("cam-import").click()
    fc.value.set_files(str(path))
    expect(page.get_by_test_id("cam-imported")).to_contain_text(f"{before['point_count']} points imported")
    expect(page.get_by_test_id("cam-plot-distance")).to_have_attribute("data-points", str(before["point_count"]))
    after = httpx.get(server.api("/cams/FlyingSync")).json()
    assert after["source"] is None and after["phase"] == before["phase"] and after["distance"] == before["distance"]
    assert httpx.get(server.api("/cams/FlyingSync/csv")).text.splitlines()[1:] == text.splitlines()[1:]
    assert _unexpected(page.console_errors) == []


def test_add_and_delete_from_the_tree(page, server: Server) -> None:
    page.goto(server.base + "/")
    page.get_by_test_id("ws-status").filter(has_text="live").wait_for(timeout=15000)
    page.get_by_test_id("nav-cam-add").click()
    page.get_by_test_id("cam-new-name").fill("2bad")
    expect(page.get_by_test_id("cam-new-create")).to_be_disabled()
    page.get_by_test_id("cam-new-name").fill("Knife")
    page.get_by_test_id("cam-new-create").click()
    page.get_by_test_id("cam-editor-Knife").wait_for()
    expect(page.get_by_test_id("cam-point-count")).to_have_text("3601")
    assert (server.project_dir / "cams" / "Knife.csv").is_file()
    page.get_by_test_id("nav-cam-delete-Knife").click()
    page.get_by_test_id("cam-delete-confirm").click()
    expect(page.get_by_test_id("nav-cam-Knife")).to_have_count(0)
    expect(page.get_by_test_id("cam-editor-Knife")).to_have_count(0)
    assert not (server.project_dir / "cams" / "Knife.csv").exists()
    assert [c["name"] for c in httpx.get(server.api("/cams")).json()] == ["RiseDwellReturn", "FlyingSync"]
    assert _unexpected(page.console_errors) == []


def test_cam_test_run_on_a_virtual_master(page, server: Server) -> None:
    _open_cam(page, server, "RiseDwellReturn")
    panel = page.get_by_test_id("cam-test-run")
    panel.scroll_into_view_if_needed()
    expect(page.get_by_test_id("cam-run-master")).to_have_value("MC_Axis003")
    expect(page.get_by_test_id("cam-run-slave")).to_have_value("MC_Axis000")
    page.get_by_test_id("cam-run-start").click()
    expect(page.get_by_test_id("cam-run-insync")).to_have_text("InSync", timeout=10000)
    expect(page.get_by_test_id("cam-run-stop")).to_be_visible()
    expect(page.get_by_test_id("cam-run-index")).not_to_have_text("Index 0")
    slave = httpx.get(server.api("/axes/MC_Axis000")).json()["variables"]
    assert slave["Status"]["Synchronized"] and -0.001 <= slave["Cmd"]["Pos"] <= 150.001  # within the table's range
    master = httpx.get(server.api("/axes/MC_Axis003")).json()["variables"]
    assert master["Status"]["Continuous"] and master["Cmd"]["Vel"] > 0
    # the table is in use: a write is refused with 409 (D45)
    r = httpx.put(server.api("/cams/RiseDwellReturn"), json={"description": "x"})
    assert r.status_code == 409 and "MC_CamIn" in r.json()["detail"]
    page.screenshot(path=str(ARTIFACTS / "cam-test-run.png"))
    page.get_by_test_id("cam-run-stop").click()
    expect(page.get_by_test_id("cam-run-start")).to_be_visible(timeout=10000)
    fbs = httpx.get(server.api("/snapshot")).json()["fbs"]
    assert sorted(f["type"] for f in fbs.values()) == ["MC_Power", "MC_Power"]
    assert httpx.get(server.api("/cams")).json()[0]["in_use"] == []
    assert _unexpected(page.console_errors) == []
