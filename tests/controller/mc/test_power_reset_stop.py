"""MC_Power, MC_Reset and MC_Stop timing charts.

Spec: omron-axis-instructions.md "MC_Power" (seed 000 line 2456), "MC_Stop" (line 5817), "MC_Reset" (line 12664);
omron-mc-basics.md §A-3.4 (state after each instruction), §2.8 (output rules).
"""

from __future__ import annotations

import pytest

from mcstudio.controller.kernel import Controller
from mcstudio.controller.mc.enums import AxisState
from mcstudio.project.models import AxisConfig
from tests.conftest import power_on, small_project, step_until


def test_power_timing_chart(ctrl: Controller) -> None:
    """Enable↑ → Busy at once; Status when the drive reports Operation enabled (CiA402 sequence over the PDOs:
    Shutdown → Switch on → Enable operation); Enable↓ → Busy↓ at once, Status↓ when released."""
    pw = ctrl.fb("MC_Power", Axis="MC_Axis000", Enable=True)
    ctrl.step(1)
    assert pw.Busy and not pw.Status
    assert ctrl.mc.axes[0].state == AxisState.Disabled
    n = step_until(ctrl, pw, "Status")
    assert 2 <= n <= 5, "three PDS transitions, one per exchange"
    assert ctrl.mc.axes[0].state == AxisState.Standstill
    pw.Enable = False
    ctrl.step(1)
    assert not pw.Busy
    step_until(ctrl, pw, "Status", False, limit=5)
    assert ctrl.mc.axes[0].state == AxisState.Disabled


def test_virtual_axis_power(ctrl: Controller) -> None:
    pw = ctrl.fb("MC_Power", Axis="MC_Axis002", Enable=True)
    n = step_until(ctrl, pw, "Status")
    assert n == 2
    assert ctrl.mc.axes[2].state == AxisState.Standstill


def test_servo_off_while_moving_aborts(ctrl: Controller) -> None:
    """Releasing the ready state while moving: the instruction gets CommandAborted, the axis becomes Disabled."""
    pw = power_on(ctrl)
    mv = ctrl.fb("MC_MoveVelocity", Axis="MC_Axis000", Execute=True, Velocity=10.0)
    ctrl.step(50)
    pw.Enable = False
    ctrl.step(1)
    assert mv.CommandAborted and not mv.Busy
    step_until(ctrl, pw, "Status", False, limit=5)
    assert ctrl.mc.axes[0].state == AxisState.Disabled
    pos = float(ctrl.mc.act_pos[0])
    ctrl.step(10)
    assert ctrl.mc.act_pos[0] == pos and ctrl.mc.cmd_pos[0] == pos, "Cmd.Pos reads Act.Pos when servo OFF"


def test_stop_timing_chart(ctrl: Controller) -> None:
    """MC_Stop aborts the move (CommandAborted), decelerates at Deceleration, Done at standstill; the axis stays
    Stopping while Execute is TRUE and returns to Standstill when it falls; motion instructions started while
    Stopping get CommandAborted."""
    power_on(ctrl)
    mv = ctrl.fb("MC_MoveVelocity", Axis="MC_Axis000", Execute=True, Velocity=100.0, Acceleration=1000.0)
    step_until(ctrl, mv, "InVelocity")
    st = ctrl.fb("MC_Stop", Axis="MC_Axis000", Execute=True, Deceleration=500.0)
    ctrl.step(1)
    assert st.Busy and mv.CommandAborted and not mv.Busy
    assert ctrl.mc.axes[0].state == AxisState.Stopping
    ctrl.step(1)
    assert st.Active
    n = step_until(ctrl, st, "Done")
    assert abs((n + 2) * 0.001 - 100.0 / 500.0) <= 0.003
    assert ctrl.mc.cmd_vel[0] == 0.0
    assert ctrl.mc.axes[0].state == AxisState.Stopping, "Stopping while MC_Stop.Execute is TRUE"
    other = ctrl.fb("MC_MoveAbsolute", Axis="MC_Axis000", Execute=True, Position=0.0, Velocity=10.0)
    ctrl.step(1)
    assert other.CommandAborted and not other.Error
    st.Execute = False
    ctrl.step(1)
    assert not st.Done
    assert ctrl.mc.axes[0].state == AxisState.Standstill


def test_stop_with_zero_deceleration_is_immediate(ctrl: Controller) -> None:
    power_on(ctrl)
    mv = ctrl.fb("MC_MoveVelocity", Axis="MC_Axis000", Execute=True, Velocity=100.0, Acceleration=1000.0)
    step_until(ctrl, mv, "InVelocity")
    st = ctrl.fb("MC_Stop", Axis="MC_Axis000", Execute=True, Deceleration=0.0)
    ctrl.step(2)
    assert ctrl.mc.cmd_vel[0] == 0.0
    step_until(ctrl, st, "Done", limit=3)


def test_stop_in_error_stop_is_command_aborted(ctrl: Controller) -> None:
    """MC_Stop cannot start while Status.ErrorStop is TRUE: CommandAborted (MC_Stop functional rules)."""
    power_on(ctrl)
    bad = ctrl.fb("MC_MoveAbsolute", Axis="MC_Axis000", Execute=True, Position=1.0, Velocity=0.0)
    ctrl.step(1)
    assert bad.Error
    st = ctrl.fb("MC_Stop", Axis="MC_Axis000", Execute=True, Deceleration=100.0)
    ctrl.step(1)
    assert st.CommandAborted and not st.Error


def test_reset_clears_error_and_returns_to_standstill(ctrl: Controller) -> None:
    """MC_Reset: Done; MFaultLvl cleared; ErrorStop → Standstill with servo ON (A-3.4 footnote *10)."""
    power_on(ctrl)
    bad = ctrl.fb("MC_MoveAbsolute", Axis="MC_Axis000", Execute=True, Position=1.0, Velocity=0.0)
    ctrl.step(2)
    ax = ctrl.mc.axes[0]
    assert ax.state == AxisState.ErrorStop and ax.error_code == 0x5422
    rs = ctrl.fb("MC_Reset", Axis="MC_Axis000", Execute=True)
    ctrl.step(1)
    assert rs.Busy and not rs.Done
    ctrl.step(1)
    assert rs.Done and not rs.Busy and not rs.Failure
    assert ax.state == AxisState.Standstill and ax.error_code == 0
    assert not bad.Error


def test_reset_fails_while_decelerating_from_error() -> None:
    """Reset during the error deceleration stop: Failure (MC_Reset functional rules)."""
    c = Controller(small_project(MaxDec=100.0))
    power_on(c)
    mv = c.fb("MC_MoveVelocity", Axis="MC_Axis000", Execute=True, Velocity=100.0, Acceleration=1000.0)
    step_until(c, mv, "InVelocity")
    bad = c.fb("MC_MoveAbsolute", Axis="MC_Axis000", Execute=True, Position=1.0, Velocity=0.0)
    c.step(2)
    assert bad.Error and mv.CommandAborted
    assert c.mc.cmd_vel[0] > 0, "error stop decelerates at the maximum deceleration (100 mm/s²)"
    rs = c.fb("MC_Reset", Axis="MC_Axis000", Execute=True)
    c.step(2)
    assert rs.Failure and not rs.Done
    assert c.mc.axes[0].state == AxisState.ErrorStop
    c.step(1100)  # 100 mm/s at 100 mm/s² → 1 s to stop
    assert c.mc.cmd_vel[0] == 0.0
    rs.Execute = False
    c.step(1)
    rs.Execute = True
    c.step(2)
    assert rs.Done
    assert c.mc.axes[0].state == AxisState.Standstill


def test_power_on_encoder_axis_is_543d() -> None:
    proj = small_project()
    proj.axes.append(AxisConfig(name="Enc", number=7, type="_mcEncdr", node_address=9))
    c = Controller(proj)
    pw = c.fb("MC_Power", Axis="Enc", Enable=True)
    c.step(1)
    assert pw.Error and pw.ErrorID == 0x543D


@pytest.mark.parametrize("deceleration", [-1.0])
def test_stop_negative_deceleration_is_5424(ctrl: Controller, deceleration: float) -> None:
    power_on(ctrl)
    st = ctrl.fb("MC_Stop", Axis="MC_Axis000", Execute=True, Deceleration=deceleration)
    ctrl.step(1)
    assert st.Error and st.ErrorID == 0x5424


def test_second_stop_ends_the_first_with_done(ctrl: Controller) -> None:
    """MC_Stop multi-executed on MC_Stop: the running one gets Done (seed 000 line 5980; the output table's
    'CommandAborted when aborted by another MC_Stop' is the other reading — see docs/decisions.md)."""
    power_on(ctrl)
    mv = ctrl.fb("MC_MoveVelocity", Axis="MC_Axis000", Execute=True, Velocity=100.0, Acceleration=1000.0)
    step_until(ctrl, mv, "InVelocity")
    s1 = ctrl.fb("MC_Stop", Axis="MC_Axis000", Execute=True, Deceleration=100.0)
    ctrl.step(50)
    s2 = ctrl.fb("MC_Stop", Axis="MC_Axis000", Execute=True, Deceleration=1000.0)
    ctrl.step(1)
    assert s1.Done and not s1.CommandAborted and s2.Busy
    step_until(ctrl, s2, "Done")
    s1.Execute = False
    ctrl.step(1)
    assert ctrl.mc.axes[0].state == AxisState.Stopping, "s2 still holds Execute"
    s2.Execute = False
    ctrl.step(1)
    assert ctrl.mc.axes[0].state == AxisState.Standstill


def test_servo_off_ends_stop_with_done(ctrl: Controller) -> None:
    """MC_Stop's Done becomes TRUE when the axis is turned servo OFF during the stop (seed 000 MC_Stop rules)."""
    pw = power_on(ctrl)
    mv = ctrl.fb("MC_MoveVelocity", Axis="MC_Axis000", Execute=True, Velocity=100.0, Acceleration=1000.0)
    step_until(ctrl, mv, "InVelocity")
    st = ctrl.fb("MC_Stop", Axis="MC_Axis000", Execute=True, Deceleration=10.0)
    ctrl.step(10)
    pw.Enable = False
    ctrl.step(1)
    assert st.Done and not st.CommandAborted


def test_deleting_a_holding_stop_releases_the_axis(ctrl: Controller) -> None:
    """D133: MC_Stop holds the axis in Stopping while Execute stays TRUE (seed 000 MC_Stop, omron-axis-instructions.md
    MC_Stop); deleting the instance then acts like Execute falling. Before, the axis stayed in Stopping with nothing
    left to release it and every motion instruction was CommandAborted. Deleted mid-deceleration, the stop still
    decelerates to 0 before Standstill."""
    power_on(ctrl)
    mv = ctrl.fb("MC_MoveVelocity", Axis="MC_Axis000", Execute=True, Velocity=50.0, Acceleration=1000.0,
                 Deceleration=1000.0)
    step_until(ctrl, mv, "InVelocity")
    st = ctrl.fb("MC_Stop", Axis="MC_Axis000", Execute=True, Deceleration=500.0)
    ctrl.step(10)
    ax = ctrl.mc.axes[0]
    assert ax.state == AxisState.Stopping and 0.0 < ctrl.mc.cmd_vel[0] < 50.0
    ctrl.delete_fb(st.id)  # mid-deceleration
    ctrl.step(1)
    assert ax.state == AxisState.Stopping and ctrl.mc.cmd_vel[0] > 0.0, "the stop itself goes on"
    ctrl.step(100)  # 50 mm/s at 500 mm/s² = 100 periods in all
    assert ctrl.mc.cmd_vel[0] == 0.0 and ax.state == AxisState.Standstill
    st2 = ctrl.fb("MC_Stop", Axis="MC_Axis000", Execute=True, Deceleration=500.0)
    step_until(ctrl, st2, "Done")
    ctrl.delete_fb(st2.id)  # stopped, Execute still TRUE: the hold ends at once
    ctrl.step(1)
    assert ax.state == AxisState.Standstill
    again = ctrl.fb("MC_MoveRelative", Axis="MC_Axis000", Execute=True, Distance=1.0, Velocity=10.0,
                    Acceleration=100.0, Deceleration=100.0)
    step_until(ctrl, again, "Done", limit=1000)
