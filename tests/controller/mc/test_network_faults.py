"""The MC layer over the EtherCAT network: required objects (3460), objects per instruction (3461), slave drop-out
(3003) and recovery, drive alarms (3002) and MC_Reset's drive error reset, MC_Power on a slave not in Op (600D).

Spec: omron-mc-basics.md §2.11 (required objects 3460, seed 000 L2277), omron-axis-instructions.md MC_Reset
functional rules (drive error reset, Drive Error Reset Monitoring Time), invt-ivc5.md §2.3–2.4 and §11 R2/R4–R7
(lenient topology, drop-out isolation, codes 3002/3003/600D). Decisions: docs/decisions.md D29.
"""

from __future__ import annotations

from typing import Any

import pytest

from mcstudio.controller.kernel import Controller, Until
from mcstudio.controller.mc.enums import AxisState
from mcstudio.fieldbus.builtin import servo_drive
from mcstudio.fieldbus.pdo import SlavePdoConfig, default_pdo_config
from mcstudio.project.models import EtherCATSlaveConfig, Project
from tests.conftest import power_on, small_project, step_until

A0, A1 = "MC_Axis000", "MC_Axis001"


def _without(obj: int) -> SlavePdoConfig:
    cfg = default_pdo_config(servo_drive())
    for m in cfg.mappings:
        m.entries = [e for e in m.entries if e.index != obj]
    return cfg


def _explicit(p: Project, **slave1: Any) -> Project:
    p.ethercat.slaves = [EtherCATSlaveConfig(node_address=1, **slave1), EtherCATSlaveConfig(node_address=2)]
    return p


def _state(c: Controller, axis: str) -> AxisState:
    return c.mc.by_name[axis].state


def test_required_object_missing_is_3460_and_restoring_it_works() -> None:
    """607Ah removed from the mapping of node 1: MC_Axis000 is in ErrorStop with 3460 from the start; MC_Power and
    MC_MoveAbsolute end in Error 3460; MC_Reset cannot clear it (Failure). The other axis works. With the default
    mapping back (a new download), the same program works."""
    c = Controller(_explicit(small_project(), pdo=_without(0x607A)))
    ax = c.mc.by_name[A0]
    assert ax.state == AxisState.ErrorStop and ax.error_code == 0x3460
    assert any(e.code == "34600000" and "607Ah" in e.detail for e in c.events.list())
    pw = c.fb("MC_Power", Axis=A0, Enable=True)
    mv = c.fb("MC_MoveAbsolute", Axis=A0, Execute=True, Position=1.0, Velocity=10.0, Acceleration=100.0,
              Deceleration=100.0)
    rs = c.fb("MC_Reset", Axis=A0, Execute=True)
    c.step(3)
    assert pw.Error and pw.ErrorID == 0x3460 and not pw.Status
    assert mv.Error and mv.ErrorID == 0x3460
    assert rs.Failure and not rs.Done
    power_on(c, A1)  # node 2 is unaffected
    # restore: the default mapping
    c2 = Controller(_explicit(small_project()))
    power_on(c2, A0)
    mv2 = c2.fb("MC_MoveAbsolute", Axis=A0, Execute=True, Position=1.0, Velocity=10.0, Acceleration=100.0,
                Deceleration=100.0)
    step_until(c2, mv2, "Done")
    assert float(c2.mc.act_pos[0]) == pytest.approx(1.0, abs=1e-5)  # within a pulse (104857.6 pulses/mm)


def test_instruction_object_missing_is_3461() -> None:
    """6071h (target torque) is not needed by positioning but by MC_TorqueControl (§2.11 table): 3461 at start."""
    c = Controller(_explicit(small_project(), pdo=_without(0x6071)))
    power_on(c, A0)
    tc = c.fb("MC_TorqueControl", Axis=A0, Execute=True, Torque=10.0, TorqueRamp=100.0, Velocity=10.0)
    c.step(2)
    assert tc.Error and tc.ErrorID == 0x3461
    assert 0x6071 not in c.network.mapped_objects(0) and 0x607A in c.network.mapped_objects(0)


def test_disconnect_while_two_axes_move_only_that_axis_errors() -> None:
    """Both axes move; node 1 is disconnected: MC_Axis000 goes to ErrorStop with 3003 and its move is aborted
    (CommandAborted: an axis error aborts the running instruction);
    MC_Axis001 finishes its move (Done at its target)."""
    c = Controller(small_project())
    power_on(c, A0)
    power_on(c, A1)
    kw = dict(Execute=True, Position=50.0, Velocity=100.0, Acceleration=1000.0, Deceleration=1000.0)
    m0 = c.fb("MC_MoveAbsolute", Axis=A0, **kw)
    m1 = c.fb("MC_MoveAbsolute", Axis=A1, **kw)
    c.step(100)
    assert m0.Active and m1.Active
    c.network.disconnect(1)
    c.step(1)
    assert _state(c, A0) == AxisState.ErrorStop and c.mc.by_name[A0].error_code == 0x3003
    step_until(c, m1, "Done")
    assert m0.CommandAborted and not m0.Done
    assert float(c.mc.act_pos[1]) == pytest.approx(50.0, abs=1e-5) and _state(c, A1) == AxisState.Standstill
    assert not c.mc.servo_on[0]
    assert any(e.code == "84230000" for e in c.events.list())


def test_reconnect_auto_restart_then_mc_reset() -> None:
    """auto_restart_slaves (default): the wired slave walks Init → PreOp → SafeOp → Op in successive periods; MC_Reset
    fails while it is not in Op, then clears 3003 and the drive's watchdog fault (8700h) and the axis powers again."""
    c = Controller(small_project())
    power_on(c, A0)
    c.network.disconnect(1)
    c.step(2)
    rs = c.fb("MC_Reset", Axis=A0, Execute=True)
    c.step(2)
    assert rs.Failure
    rs.set_inputs({"Execute": False})
    c.network.reconnect(1)
    seen = []
    for _ in range(5):
        c.step(1)
        seen.append(c.network.slaves[0].state.name)
    assert seen[:3] == ["PreOp", "SafeOp", "Op"]
    rs.set_inputs({"Execute": True})
    step_until(c, rs, "Done", limit=1000)
    assert c.mc.by_name[A0].error_code == 0 and not c.mc.drv_fault[0]
    pw = c.fb("MC_Power", Axis=A0, Enable=True)
    c.step(20, Until(pw.id, "Status", True))
    assert pw.Status


def test_without_auto_restart_the_connect_command_is_needed() -> None:
    p = small_project()
    p.ethercat.master.auto_restart_slaves = False
    c = Controller(p)
    c.network.disconnect(2)
    c.network.reconnect(2)
    c.step(10)
    assert c.network.slaves[1].state.name == "Init" and not c.network.pd_ok[1]
    c.network.connect(2)
    c.step(5)
    assert c.network.slaves[1].state.name == "Op" and c.network.pd_ok[1]


def test_mc_power_on_absent_slave_is_600D() -> None:
    """A configured slave that is not on the wire stays in Init (lenient topology); MC_Power on its axis: 600D,
    no axis fault; the other axis powers on."""
    p = _explicit(small_project())
    p.ethercat.slaves[0].emulation.connected = False
    c = Controller(p)
    assert c.network.slaves[0].state.name == "Init" and c.network.slaves[1].state.name == "Op"
    pw = c.fb("MC_Power", Axis=A0, Enable=True)
    c.step(3)
    assert pw.Error and pw.ErrorID == 0x600D and c.mc.by_name[A0].error_code == 0
    power_on(c, A1)


def test_identity_mismatch_keeps_the_slave_in_init() -> None:
    p = _explicit(small_project())
    p.ethercat.slaves[1].emulation.wired_device = "builtin:encoder-input"
    c = Controller(p)
    assert c.network.slaves[1].state.name == "Init" and "identity mismatch" in c.network.slaves[1].error
    assert any(e.code == "84210000" for e in c.events.list())


def test_drive_alarm_is_3002_and_mc_reset_resets_the_drive() -> None:
    """A drive alarm (603Fh 2310h): ErrorStop 3002 with the code in the event; MC_Reset sends the fault reset and
    completes (Done) when the drive has left Fault."""
    c = Controller(small_project())
    power_on(c, A0)
    c.network.drives.inject_fault(0, 0x2310)
    c.step(3)
    ax = c.mc.by_name[A0]
    assert ax.state == AxisState.ErrorStop and ax.error_code == 0x3002
    assert any(e.code == "30020000" and "2310h" in e.detail for e in c.events.list())
    rs = c.fb("MC_Reset", Axis=A0, Execute=True)
    step_until(c, rs, "Done", limit=1000)
    assert ax.error_code == 0 and int(c.network.drives.state[0]) == 1  # Switch on disabled


def test_persistent_drive_alarm_mc_reset_fails_after_the_monitoring_time() -> None:
    """The cause persists: MC_Reset keeps Busy for the Drive Error Reset Monitoring Time (200 ms), then Failure."""
    c = Controller(small_project())
    power_on(c, A0)
    c.network.drives.inject_fault(0, 0x7305, persistent=True)
    c.step(3)
    rs = c.fb("MC_Reset", Axis=A0, Execute=True)
    c.step(100)
    assert rs.Busy and not rs.Failure
    n = step_until(c, rs, "Failure", limit=1000)
    assert 90 <= n <= 110
    assert c.mc.by_name[A0].error_code == 0x3002
    c.network.drives.clear_fault_cause(0)
    rs.set_inputs({"Execute": False})
    c.step(1)
    rs.set_inputs({"Execute": True})
    step_until(c, rs, "Done", limit=1000)


def test_without_6060h_6061h_only_csp_instructions_run() -> None:
    """§2.11 (CPU ≥ v1.10): 6060h/6061h not mapped → the drive stays in its start-up mode (CSP), positioning works,
    MC_TorqueControl gives 3461; DrvStatus.CSP reads FALSE (6061h unmapped)."""
    pdo = _without(0x6060)
    for m in pdo.mappings:
        m.entries = [e for e in m.entries if e.index != 0x6061]
    c = Controller(_explicit(small_project(), pdo=pdo))
    power_on(c, A0)
    mv = c.fb("MC_MoveRelative", Axis=A0, Execute=True, Distance=2.0, Velocity=10.0, Acceleration=100.0,
              Deceleration=100.0)
    step_until(c, mv, "Done")
    assert float(c.mc.act_pos[0]) == pytest.approx(2.0, abs=1e-5)
    tc = c.fb("MC_TorqueControl", Axis=A0, Execute=True, Torque=10.0, TorqueRamp=100.0, Velocity=10.0)
    c.step(2)
    assert tc.Error and tc.ErrorID == 0x3461
    from mcstudio.controller.mc.module import drv_status

    assert not drv_status(int(c.mc.drv[0]))["CSP"] and int(c.network.drive_rx["modes_of_operation"][0]) == 8
