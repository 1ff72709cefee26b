"""Editing the EtherCAT network in the studio, in a real headless Chromium (docs/ethercat.md, "Editing the network in
the studio").

The demo project starts with an implicit network: seven built-in CiA402 drives, on nodes 1-3 for MC_Axis000-002
(MC_Axis003 is virtual) and on nodes 4-7 for the Delta3's arms and its conveyor (MC_Axis004-007). The tests run in
order on one server:

* the master settings (DC off, then on with another SYNC0 shift) are applied and the network stays implicit;
* a device imported from an ESI file is added as a new slave (next free node 8, name E008) and reaches Op;
* a node address already in use is refused, with the reason on the node address field; a node address change of a
  slave that an axis uses moves the axis along (or, without that, is refused with the axis' problem on the field);
* a start-up SDO line that the drive aborts (2999h does not exist) keeps that slave in Pre-Op with its reason, and
  without "abort on error" the slave reaches Op;
* a slave marked "not on the wire" stays in Init with its reason, a different device at its position too;
* an edit while an axis moves is refused with 409, shown as such.

No sleeps: every wait is on something the page shows.
"""

from __future__ import annotations

import re
from pathlib import Path

import httpx
import pytest

from tests.e2e.conftest import ARTIFACTS, Server

pytestmark = pytest.mark.e2e

SOES = Path("/work/shared/fixtures/esi/soes-cia402.xml")
# Chromium logs every non-2xx fetch as a console error; the refusals below are intended.
_EXPECTED_HTTP = re.compile(r"Failed to load resource: the server responded with a status of (409|422)")


def _unexpected(errors: list[str]) -> list[str]:
    return [e for e in errors if not _EXPECTED_HTTP.search(e)]


def _state(page, node: int, state: str, timeout: float = 15000) -> None:
    page.locator(f'[data-testid="ecat-state-{node}"][data-state="{state}"]').wait_for(timeout=timeout)


def _open_network(page, server: Server) -> None:
    page.goto(server.base + "/")
    page.get_by_test_id("ws-status").filter(has_text="live").wait_for(timeout=15000)
    page.get_by_test_id("nav-ethercat").click()
    page.get_by_test_id("ecat-network").wait_for()
    _state(page, 1, "Op")


def _project(server: Server) -> dict:
    return httpx.get(server.api("/project")).json()


def _slave(server: Server, node: int) -> dict | None:
    return next((s for s in httpx.get(server.api("/ethercat")).json()["slaves"] if s["node_address"] == node), None)


def _configure(page, node: int, tab: str) -> None:
    """Open the configuration of a slave (if closed) on one of its tabs."""
    if page.get_by_test_id(f"slave-config-{node}").count() == 0:
        page.get_by_test_id(f"ecat-edit-{node}").click()
    page.get_by_test_id(f"slave-tab-{tab}-{node}").click()


def _apply_slave(page, node: int) -> None:
    page.get_by_test_id(f"slave-apply-{node}").click()
    page.get_by_test_id(f"slave-clean-{node}").wait_for(timeout=15000)


def test_master_settings_dc_and_sync0_shift(page, server: Server) -> None:
    _open_network(page, server)
    page.get_by_test_id("ecat-cycle-time").filter(has_text="1000").wait_for()
    page.get_by_test_id("ecat-dc").filter(has_text="On · SYNC0 shift 20 %").wait_for()

    page.get_by_test_id("ecat-master-edit").click()
    assert page.get_by_test_id("master-apply").is_disabled()  # nothing changed yet
    page.get_by_test_id("master-dc").uncheck()
    assert page.get_by_test_id("master-sync-offset").is_disabled()  # the shift is a DC setting
    page.get_by_test_id("master-apply").click()
    page.locator('[data-testid="ecat-dc"][data-active="false"]').filter(has_text="Off").wait_for(timeout=15000)
    master = httpx.get(server.api("/ethercat")).json()["master"]
    assert master["settings"]["dc_enabled"] is False
    assert master["explicit"] is False  # master settings alone keep the implicit slaves
    assert _project(server)["ethercat"]["slaves"] == []
    page.get_by_test_id("project-dirty").wait_for()  # saved by the toolbar's Save

    # the shift is checked as it is typed (0-80 %), then DC on again with 35 %
    page.get_by_test_id("ecat-master-edit").click()
    page.get_by_test_id("master-dc").check()
    page.get_by_test_id("master-sync-offset").fill("90")
    page.get_by_test_id("master-error-sync_offset_pct").filter(has_text="0 to 80").wait_for()
    assert page.get_by_test_id("master-apply").is_disabled()
    page.get_by_test_id("master-sync-offset").fill("35")
    page.get_by_test_id("master-apply").click()
    dc_on = page.locator('[data-testid="ecat-dc"][data-active="true"]')
    dc_on.filter(has_text="SYNC0 shift 35 %").wait_for(timeout=15000)
    settings = _project(server)["ethercat"]["master"]
    assert settings["dc_enabled"] is True and settings["sync_offset_pct"] == 35
    for node in (1, 2, 3):
        _state(page, node, "Op")
    assert not _unexpected(page.console_errors), page.console_errors


def test_add_an_imported_esi_device_as_a_new_slave(page, server: Server) -> None:
    _open_network(page, server)
    page.get_by_test_id("ecat-import-esi").click()
    page.get_by_test_id("esi-file-input").set_input_files(str(SOES))
    page.get_by_test_id("esi-submit").click()
    page.get_by_test_id("esi-result").wait_for(timeout=10000)
    device = next(d for d in httpx.get(server.api("/devices")).json() if d["source"] == "soes-cia402.xml")
    page.get_by_test_id(f"esi-add-{device['id']}").wait_for()  # imported devices can go straight to the network
    page.get_by_test_id("esi-close").click()

    # Add slave: the device library lists built-in and imported devices; node and name default to the next free ones
    page.get_by_test_id("ecat-add-slave").click()
    dialog = page.get_by_test_id("add-slave-dialog")
    dialog.get_by_test_id("add-slave-node").wait_for()
    assert dialog.get_by_test_id("add-slave-node").input_value() == "8"
    assert dialog.get_by_test_id("add-slave-name").input_value() == "E008"
    assert page.get_by_test_id("add-slave-confirm").is_disabled()  # no device chosen yet
    dialog.get_by_test_id("add-slave-device").click()
    page.get_by_role("option", name=re.compile("Generic CiA402 Servo Drive")).wait_for()
    page.get_by_role("option", name=re.compile(re.escape(device["name"]))).click()
    dialog.get_by_test_id("add-slave-device-info").filter(has_text=device["id"]).wait_for()
    page.screenshot(path=str(ARTIFACTS / "network-add-slave.png"))
    page.get_by_test_id("add-slave-confirm").click()
    dialog.wait_for(state="hidden", timeout=15000)

    # the new slave is in the network view, after E007, and reaches Op (start-up: identity, PDO map, Safe-Op, Op)
    _state(page, 8, "Op")
    assert page.get_by_test_id("ecat-name-8").inner_text() == "E008"
    assert page.get_by_test_id("ecat-device-8").inner_text() == device["name"]
    assert page.get_by_test_id("ecat-slave-8").locator(".ecat-port").inner_text() == "8"
    page.get_by_test_id("ecat-slaves-in-op").filter(has_text=re.compile(r"8\s*/\s*8")).wait_for()
    page.locator('[data-testid="nav-slave-state-8"][data-state="Op"]').wait_for()
    slaves = _project(server)["ethercat"]["slaves"]  # the network is explicit now, the implicit slaves listed
    assert [(s["node_address"], s["device"]) for s in slaves] == [
        *[(n, "builtin:cia402-servo") for n in range(1, 8)], (8, device["id"])]
    page.screenshot(path=str(ARTIFACTS / "network-slave-added.png"))
    assert not _unexpected(page.console_errors), page.console_errors


def test_node_address_in_use_is_refused_on_the_field(page, server: Server) -> None:
    _open_network(page, server)
    _state(page, 8, "Op")
    _configure(page, 8, "general")
    page.get_by_test_id("slave-axis-8").filter(has_text="No axis").wait_for()
    page.get_by_test_id("slave-node-8").fill("2")
    page.get_by_test_id("slave-dirty-8").wait_for()
    page.get_by_test_id("slave-apply-8").click()
    err = page.get_by_test_id("slave-error-8-node_address")
    err.filter(has_text="node address 2 is already used by E002").wait_for(timeout=10000)
    assert "on the marked field" in page.get_by_test_id("slave-issues-8").inner_text()
    page.screenshot(path=str(ARTIFACTS / "network-node-in-use.png"))
    assert _slave(server, 8) is not None and _slave(server, 2)["name"] == "E002"  # nothing was applied
    page.get_by_test_id("slave-revert-8").click()
    assert page.get_by_test_id("slave-node-8").input_value() == "8"
    assert err.count() == 0

    # node 1 is MC_Axis000's drive: a new address without the axis is refused with the axis' problem on the field
    _configure(page, 1, "general")
    page.get_by_test_id("slave-axis-1").filter(has_text="MC_Axis000").wait_for()
    page.get_by_test_id("slave-node-1").fill("9")
    page.get_by_test_id("slave-move-axis-1").uncheck()
    page.get_by_test_id("slave-apply-1").click()
    page.get_by_test_id("slave-error-1-node_address").filter(
        has_text="MC_Axis000: no slave with node address 1").wait_for(timeout=10000)
    # moving the axis along applies both (the axis refers to its slave by node address)
    page.get_by_test_id("slave-move-axis-1").check()
    page.get_by_test_id("slave-apply-1").click()
    _state(page, 9, "Op")
    page.get_by_test_id("slave-config-9").wait_for()  # the configuration follows the slave to its new address
    page.get_by_test_id("ecat-axis-9").filter(has_text="MC_Axis000").wait_for()
    assert next(a for a in _project(server)["axes"] if a["name"] == "MC_Axis000")["node_address"] == 9
    assert page.get_by_test_id("ecat-slave-1").count() == 0
    # and back
    page.get_by_test_id("slave-node-9").fill("1")
    page.get_by_test_id("slave-apply-9").click()
    _state(page, 1, "Op")
    page.get_by_test_id("ecat-axis-1").filter(has_text="MC_Axis000").wait_for()
    assert not _unexpected(page.console_errors), page.console_errors


def test_startup_sdo_that_aborts_keeps_the_slave_in_preop(page, server: Server) -> None:
    _open_network(page, server)
    _configure(page, 3, "sdo")
    page.get_by_test_id("sdo-empty-3").wait_for()

    # a valid line first: 6065h (following error window) is written in Pre-Op and the slave reaches Op
    page.get_by_test_id("sdo-add-3").click()
    row = page.get_by_test_id("slave-config-3").get_by_test_id("sdo-row-0")
    row.get_by_test_id("sdo-index").fill("zz")
    page.get_by_test_id("slave-config-3").get_by_test_id("sdo-error-0").filter(has_text="hex").wait_for()
    assert page.get_by_test_id("slave-apply-3").is_disabled()  # checked before it is sent
    row.get_by_test_id("sdo-index").fill("6065")
    row.get_by_test_id("sdo-value").fill("5000")
    row.get_by_test_id("sdo-object").filter(has_text="ollowing").wait_for()
    row.get_by_test_id("sdo-comment").fill("following error window")
    _apply_slave(page, 3)
    _state(page, 3, "Op")
    page.get_by_test_id("sdo-log-3").filter(has_text="6065h:00h ← 5000").wait_for(timeout=10000)

    # a line the drive aborts (2999h is not in its object dictionary) with "abort on error": Pre-Op with the reason
    page.get_by_test_id("sdo-add-3").click()
    row = page.get_by_test_id("slave-config-3").get_by_test_id("sdo-row-1")
    row.get_by_test_id("sdo-index").fill("2999")
    row.get_by_test_id("sdo-value").fill("1")
    row.get_by_test_id("sdo-object").filter(has_text="not in the device's object dictionary").wait_for()
    assert row.get_by_test_id("sdo-abort").is_checked()
    _apply_slave(page, 3)
    _state(page, 3, "PreOp")
    err = page.get_by_test_id("ecat-error-3")
    err.filter(has_text="start-up SDO line 2 (2999h:00h) aborted").wait_for()
    assert "06020000h" in err.inner_text()
    page.get_by_test_id("sdo-log-3").filter(has_text="abort").wait_for()
    _state(page, 1, "Op")  # the other slaves run
    page.get_by_test_id("ecat-slave-3").scroll_into_view_if_needed()
    page.screenshot(path=str(ARTIFACTS / "network-sdo-abort.png"))
    assert _slave(server, 3)["state"] == "PreOp"

    # without "abort on error" the failed write is logged and the start-up goes on
    page.get_by_test_id("slave-config-3").get_by_test_id("sdo-row-1").get_by_test_id("sdo-abort").uncheck()
    _apply_slave(page, 3)
    _state(page, 3, "Op")
    # remove both lines again
    cfg = page.get_by_test_id("slave-config-3")
    cfg.get_by_test_id("sdo-row-1").get_by_test_id("sdo-delete").click()
    cfg.get_by_test_id("sdo-row-0").get_by_test_id("sdo-delete").click()
    page.get_by_test_id("sdo-empty-3").wait_for()
    _apply_slave(page, 3)
    _state(page, 3, "Op")
    assert next(s for s in _project(server)["ethercat"]["slaves"] if s["node_address"] == 3)["startup_sdos"] == []
    assert not _unexpected(page.console_errors), page.console_errors


def test_slave_not_connected_stays_in_init(page, server: Server) -> None:
    _open_network(page, server)
    _configure(page, 2, "drill")
    page.get_by_test_id("slave-connected-2").uncheck()
    _apply_slave(page, 2)
    _state(page, 2, "Init")
    page.get_by_test_id("ecat-error-2").filter(has_text="not found on the wire").wait_for()
    page.locator('[data-testid="ecat-wired-2"][data-active="false"]').wait_for()
    for node in (1, 3, 4, 5, 6, 7, 8):
        _state(page, node, "Op")
    page.get_by_test_id("ecat-slaves-in-op").filter(has_text=re.compile(r"7\s*/\s*8")).wait_for()
    page.get_by_test_id("ecat-slave-2").scroll_into_view_if_needed()
    page.screenshot(path=str(ARTIFACTS / "network-not-connected.png"))

    # on the wire, but an encoder input where the servo drive should be: the identity check keeps it in Init
    page.get_by_test_id("slave-connected-2").check()
    page.get_by_test_id("slave-wired-device-2").click()
    page.get_by_role("option", name=re.compile("Encoder Input")).click()
    _apply_slave(page, 2)
    _state(page, 2, "Init")
    page.get_by_test_id("ecat-error-2").filter(has_text="identity mismatch").wait_for()

    # the configured device again: Op
    page.get_by_test_id("slave-wired-device-2").click()
    page.get_by_role("option", name=re.compile("The configured device")).click()
    _apply_slave(page, 2)
    _state(page, 2, "Op")
    assert page.get_by_test_id("ecat-error-2").count() == 0
    assert not _unexpected(page.console_errors), page.console_errors


def test_edit_while_an_axis_moves_is_refused_with_409(page, server: Server) -> None:
    _open_network(page, server)
    pw = httpx.post(server.api("/fb"), json={"type": "MC_Power", "inputs": {"Axis": "MC_Axis003", "Enable": True}})
    assert pw.status_code == 201, pw.text
    page.wait_for_function(
        f"async () => (await (await fetch('/api/v1/fb/{pw.json()['id']}')).json()).outputs.Status === true",
        timeout=10000)
    mv = httpx.post(server.api("/fb"), json={"type": "MC_MoveVelocity", "inputs": {
        "Axis": "MC_Axis003", "Execute": True, "Velocity": 10, "Acceleration": 100, "Deceleration": 100}})
    assert mv.status_code == 201, mv.text
    page.wait_for_function(
        "async () => (await (await fetch('/api/v1/axes/MC_Axis003')).json()).variables.Status.Continuous === true",
        timeout=10000)

    _configure(page, 8, "general")
    page.get_by_test_id("slave-name-8").fill("Gripper")
    page.get_by_test_id("slave-apply-8").click()
    refusal = page.get_by_test_id("slave-refusal-8")
    refusal.filter(has_text="an axis is moving").wait_for(timeout=10000)
    assert "409" in refusal.inner_text()
    assert page.get_by_test_id("slave-name-8").input_value() == "Gripper"  # the edit is kept
    page.screenshot(path=str(ARTIFACTS / "network-409.png"))
    assert _slave(server, 8)["name"] == "E008"

    # stopped, the same edit is applied
    stop = httpx.post(server.api("/fb"), json={"type": "MC_Stop", "inputs": {
        "Axis": "MC_Axis003", "Execute": True, "Deceleration": 1000}})
    assert stop.status_code == 201, stop.text
    page.wait_for_function(
        f"async () => (await (await fetch('/api/v1/fb/{stop.json()['id']}')).json()).outputs.Done === true",
        timeout=10000)
    assert httpx.patch(server.api(f"/fb/{stop.json()['id']}"), json={"inputs": {"Execute": False}}).status_code == 200
    page.wait_for_function(
        "async () => (await (await fetch('/api/v1/axes/MC_Axis003')).json()).variables.Status.Standstill === true",
        timeout=10000)
    _apply_slave(page, 8)
    page.get_by_test_id("ecat-name-8").filter(has_text="Gripper").wait_for(timeout=10000)
    assert not _unexpected(page.console_errors), page.console_errors


def test_remove_slaves(page, server: Server) -> None:
    _open_network(page, server)
    # MC_Axis000 uses node 1: removing it is refused, the reason shown in the dialog
    page.get_by_test_id("ecat-remove-1").click()
    dialog = page.get_by_test_id("remove-slave-dialog")
    dialog.get_by_test_id("remove-slave-axis").filter(has_text="MC_Axis000").wait_for()
    page.get_by_test_id("remove-slave-confirm").click()
    page.get_by_test_id("remove-slave-refusal").filter(
        has_text="MC_Axis000: no slave with node address 1").wait_for(timeout=10000)
    page.get_by_test_id("remove-slave-cancel").click()
    dialog.wait_for(state="hidden")
    _state(page, 1, "Op")

    # node 8 has no axis: removed, the network view and the tree follow
    _state(page, 8, "Op")
    page.get_by_test_id("ecat-remove-8").click()
    page.get_by_test_id("remove-slave-confirm").click()
    page.get_by_test_id("ecat-slave-8").wait_for(state="detached", timeout=15000)
    page.get_by_test_id("nav-slave-8").wait_for(state="detached")
    page.get_by_test_id("ecat-slaves-in-op").filter(has_text=re.compile(r"7\s*/\s*7")).wait_for()
    assert [s["node_address"] for s in _project(server)["ethercat"]["slaves"]] == [1, 2, 3, 4, 5, 6, 7]
    assert not _unexpected(page.console_errors), page.console_errors
