"""Axes-group state machine and administration instructions, as timing charts on the paused controller.

Spec: omron-group-and-cam.md §0.4 (group states, A-3-2 table, seed 000 lines 21676–21700), §4.1 MC_GroupEnable
(line 14384), §4.2 MC_GroupDisable (14486), §4.7 MC_GroupStop (16384), §4.8 MC_GroupImmediateStop (16589), §4.10
MC_GroupReadPosition (16812), §4.11 MC_ChangeAxesInGroup (16923), §4.12 MC_GroupSyncMoveAbsolute (17041), §4.13
MC_GroupReset (17219); decisions D50–D56.
"""

from __future__ import annotations

import pytest

from mcstudio.controller.kernel import Controller
from mcstudio.controller.mc.enums import AxisState
from mcstudio.controller.mc.group import GroupState
from tests.conftest import step_until
from tests.controller.mc.group_helpers import group_project, positions, ready

G = GroupState


@pytest.fixture
def c() -> Controller:
    return Controller(group_project())


def test_enable_makes_axes_coordinated_and_disable_releases_them(c: Controller) -> None:
    """§4.1: Done one period after Execute↑; members Coordinated (I); single-axis motion then gives 543E (A-3 note,
    seed 000 line 21525). §4.2: Disable → a, members back to Standstill."""
    ready(c, enable=False)
    g = c.mc.groups_by_name["MC_Group000"]
    assert g.state == G.Disabled
    en = c.fb("MC_GroupEnable", AxesGroup="MC_Group000", Execute=True)
    c.step(1)
    assert (en.Busy, en.Done) == (True, False)
    c.step(1)
    assert (en.Busy, en.Done) == (False, True)
    assert g.state == G.Standby and all(a.state == AxisState.Coordinated for a in g.axes)
    assert c.publish().mc["groups"][0]["Status"]["Ready"]
    mv = c.fb("MC_MoveAbsolute", Axis="MC_Axis000", Execute=True, Position=10.0, Velocity=10.0)
    c.step(1)
    assert mv.Error and mv.ErrorID == 0x543E
    # column I: the axis stays Coordinated, the group goes b → e (543E is the group's error, decision D70)
    assert g.state == G.ErrorStop and g.error_code == 0x543E and g.axes[0].state == AxisState.Coordinated
    assert g.axes[0].error_code == 0
    dis = c.fb("MC_GroupDisable", AxesGroup="MC_Group000", Execute=True)
    step_until(c, dis, "Done")
    assert g.state == G.ErrorStop  # MC_GroupDisable in e: the group stays e (D50)
    assert all(a.state == AxisState.Standstill for a in g.axes)
    rs = c.fb("MC_GroupReset", AxesGroup="MC_Group000", Execute=True)
    step_until(c, rs, "Done")
    assert g.state == G.Disabled and not mv.Error  # MC_GroupReset releases the instruction's Error


def test_enable_refused_while_a_member_moves(c: Controller) -> None:
    """§4.1 / A-1 5440: every composition axis must be Disabled or Standstill."""
    ready(c, enable=False)
    c.fb("MC_MoveVelocity", Axis="MC_Axis000", Execute=True, Velocity=10.0, Acceleration=100.0, Deceleration=100.0)
    c.step(5)
    en = c.fb("MC_GroupEnable", AxesGroup="MC_Group000", Execute=True)
    c.step(1)
    assert en.Error and en.ErrorID == 0x5440
    assert c.mc.groups_by_name["MC_Group000"].state == G.ErrorStop


def test_motion_on_a_disabled_group_is_543f_and_unknown_group_5461(c: Controller) -> None:
    """A-3-2: interpolation from a (Disabled) → error (543F); an AxesGroup that is not a used group → 5461."""
    ready(c, enable=False)
    mv = c.fb("MC_MoveLinear", AxesGroup="MC_Group000", Execute=True, Position=[1.0, 1.0], Velocity=10.0)
    c.step(1)
    assert mv.Error and mv.ErrorID == 0x543F
    with pytest.raises(ValueError, match="no axes group"):
        c.fb("MC_GroupEnable", AxesGroup="Nope", Execute=True)


def test_group_stop_holds_stopping_and_aborts_motion(c: Controller) -> None:
    """§4.7: the running interpolation is CommandAborted, the path decelerates at Deceleration, Done at velocity 0,
    Stopping while Execute stays TRUE (motion started then is CommandAborted), Standby after Execute↓."""
    ready(c)
    g = c.mc.groups_by_name["MC_Group000"]
    mv = c.fb("MC_MoveLinearAbsolute", AxesGroup="MC_Group000", Execute=True, Position=[300.0, 400.0],
              Velocity=100.0, Acceleration=1000.0, Deceleration=1000.0)
    c.step(500)  # cruising at 100 mm/s along (0.6, 0.8)
    st = c.fb("MC_GroupStop", AxesGroup="MC_Group000", Execute=True, Deceleration=500.0)
    c.step(1)
    assert mv.CommandAborted and st.Busy and g.state == G.Stopping
    n = step_until(c, st, "Done")
    assert n == pytest.approx(200, abs=2)  # 100 mm/s at 500 mm/s²
    p = positions(c)
    assert abs(p[0] * 0.8 - p[1] * 0.6) < 1e-6  # stopped on the line
    mv2 = c.fb("MC_MoveLinearRelative", AxesGroup="MC_Group000", Execute=True, Distance=[1.0, 0.0], Velocity=10.0)
    c.step(1)
    assert mv2.CommandAborted and g.state == G.Stopping
    st.Execute = False
    c.step(1)
    assert g.state == G.Standby


def test_immediate_stop_error_stop_and_group_reset(c: Controller) -> None:
    """§4.8: the axes stop at once, ErrorStop with 5486; motion then CommandAborted (A-3-2 e); §4.13: MC_GroupReset
    → Standby and the motion instruction's Error is released."""
    ready(c)
    g = c.mc.groups_by_name["MC_Group000"]
    mv = c.fb("MC_MoveLinearAbsolute", AxesGroup="MC_Group000", Execute=True, Position=[300.0, 400.0],
              Velocity=100.0, Acceleration=1000.0, Deceleration=1000.0)
    c.step(300)
    ist = c.fb("MC_GroupImmediateStop", AxesGroup="MC_Group000", Execute=True)
    c.step(1)
    here = positions(c)
    c.step(1)
    assert ist.Done and mv.CommandAborted and g.state == G.ErrorStop and g.error_code == 0x5486
    assert positions(c) == here
    assert c.publish().mc["groups"][0]["MFaultLvl"] == {"Active": True, "Code": "5486"}
    again = c.fb("MC_MoveLinearRelative", AxesGroup="MC_Group000", Execute=True, Distance=[1.0, 0.0], Velocity=10.0)
    c.step(1)
    assert again.CommandAborted
    rs = c.fb("MC_GroupReset", AxesGroup="MC_Group000", Execute=True)
    step_until(c, rs, "Done")
    assert g.state == G.Standby and g.error_code == 0


def test_error_of_a_motion_instruction_is_a_group_error(c: Controller) -> None:
    """A-1 5422 (Velocity 0) with source Group: the instance shows Error until MC_GroupReset; the group stops."""
    ready(c)
    mv = c.fb("MC_MoveLinear", AxesGroup="MC_Group000", Execute=True, Position=[1.0, 1.0], Velocity=0.0)
    c.step(1)
    assert mv.Error and mv.ErrorID == 0x5422
    g = c.mc.groups_by_name["MC_Group000"]
    assert g.state == G.ErrorStop
    rs = c.fb("MC_GroupReset", AxesGroup="MC_Group000", Execute=True)
    step_until(c, rs, "Done")
    c.step(1)
    assert not mv.Error


def test_unhomed_member_is_5466_and_servo_off_5441(c: Controller) -> None:
    """A-1 5466 / 5441 at the start of a group motion instruction; the event's attached information 1 is the
    logical axis number of the composition axis concerned (basics L1199)."""
    ready(c)
    g = c.mc.groups_by_name["MC_Group000"]
    c.mc.axes[1].homed = False
    mv = c.fb("MC_MoveLinear", AxesGroup="MC_Group000", Execute=True, Position=[1.0, 1.0], Velocity=10.0)
    c.step(1)
    assert mv.ErrorID == 0x5466
    assert c.events.list()[-1].detail == f"attached information 1: 1 (logical axis A1, {g.axes[1].name})"
    c.mc.axes[1].homed = True
    rs = c.fb("MC_GroupReset", AxesGroup="MC_Group000", Execute=True)
    step_until(c, rs, "Done")
    power = next(e.fb for e in c.program.values() if e.fb.DEF.name == "MC_Power" and e.fb.inp["Axis"] == g.axes[0].name)
    c.set_inputs(power.id, {"Enable": False})
    c.step(5)
    mv2 = c.fb("MC_MoveLinear", AxesGroup="MC_Group000", Execute=True, Position=[1.0, 1.0], Velocity=10.0)
    c.step(1)
    assert mv2.ErrorID == 0x5441
    assert c.events.list()[-1].detail == f"attached information 1: 0 (logical axis A0, {g.axes[0].name})"


def test_reexecution_is_543b_and_stops_the_group(c: Controller) -> None:
    """§4.3 Re-execution: not allowed → 543B and all axes of the interpolation stop."""
    ready(c)
    mv = c.fb("MC_MoveLinearAbsolute", AxesGroup="MC_Group000", Execute=True, Position=[100.0, 0.0],
              Velocity=50.0, Acceleration=500.0, Deceleration=500.0)
    c.step(50)
    mv.Execute = False
    c.step(1)
    mv.Execute = True
    c.step(1)
    assert mv.Error and mv.ErrorID == 0x543B
    assert c.mc.groups_by_name["MC_Group000"].state == G.ErrorStop


def test_member_axis_error_stops_the_group_with_7430(c: Controller) -> None:
    """Robot manual A-1 7430: an axis error during group motion; the composition axes stop immediately."""
    ready(c)
    mv = c.fb("MC_MoveLinearAbsolute", AxesGroup="MC_Group000", Execute=True, Position=[100.0, 0.0],
              Velocity=50.0, Acceleration=500.0, Deceleration=500.0)
    c.step(100)
    c.mc.axes[0].raise_error(0x6452, stop="immediate")
    c.step(1)
    g = c.mc.groups_by_name["MC_Group000"]
    assert mv.CommandAborted and g.state == G.ErrorStop and g.error_code == 0x7430
    rs = c.fb("MC_GroupReset", AxesGroup="MC_Group000", Execute=True)
    step_until(c, rs, "Done")
    assert g.state == G.Standby and c.mc.axes[0].state == AxisState.Coordinated and c.mc.axes[0].error_code == 0


def test_disable_during_motion_aborts_and_decelerates_each_axis(c: Controller) -> None:
    """§4.2: the running and the buffered instruction are CommandAborted; each axis decelerates at its Maximum
    Deceleration (10000 mm/s²) and ends in Standstill."""
    ready(c)
    a = c.fb("MC_MoveLinearAbsolute", AxesGroup="MC_Group000", Execute=True, Position=[300.0, 400.0],
             Velocity=100.0, Acceleration=1000.0, Deceleration=1000.0)
    b = c.fb("MC_MoveLinearAbsolute", AxesGroup="MC_Group000", Execute=True, Position=[0.0, 0.0],
             Velocity=100.0, BufferMode="_mcBuffered")
    c.step(500)
    dis = c.fb("MC_GroupDisable", AxesGroup="MC_Group000", Execute=True)
    c.step(1)
    assert a.CommandAborted and b.CommandAborted
    assert c.mc.axes[1].state == AxisState.Stopping
    step_until(c, dis, "Done")
    c.step(20)
    assert all(ax.state == AxisState.Standstill for ax in c.mc.axes[:2])


def test_deleting_a_holding_group_stop_releases_the_group(c: Controller) -> None:
    """D133: MC_GroupStop holds the group in Stopping while Execute stays TRUE (§4.7); deleting the instance acts
    like Execute falling — Standby, and a new move runs. Before, the group stayed in Stopping for good."""
    ready(c)
    g = c.mc.groups_by_name["MC_Group000"]
    st = c.fb("MC_GroupStop", AxesGroup="MC_Group000", Execute=True, Deceleration=500.0)
    step_until(c, st, "Done")
    assert g.state == G.Stopping
    c.delete_fb(st.id)
    c.step(1)
    assert g.state == G.Standby
    mv = c.fb("MC_MoveLinearRelative", AxesGroup="MC_Group000", Execute=True, Distance=[1.0, 0.0], Velocity=10.0,
              Acceleration=1000.0, Deceleration=1000.0)
    step_until(c, mv, "Done", limit=1000)


def test_read_position_change_axes_and_sync_move(c: Controller) -> None:
    """§4.10 positions of A0–A3 while Enable (disabled group too); §4.11 only while disabled (543C otherwise), new
    axes in Kinematics.Axis; §4.12 the target each period, InPosition, no Done, MC_GroupStop stops it at once."""
    ready(c, enable=False)
    rp = c.fb("MC_GroupReadPosition", AxesGroup="MC_Group001", Enable=True)
    c.step(1)
    assert rp.Valid and rp.CommandPosition[:3] == [0.0, 0.0, 0.0]
    ch = c.fb("MC_ChangeAxesInGroup", AxesGroup="MC_Group001", Axes=[4, 3, 2], Execute=True)
    step_until(c, ch, "Done")
    assert c.publish().mc["groups"][1]["Kinematics"]["Axis"] == [4, 3, 2, 0]
    en = c.fb("MC_GroupEnable", AxesGroup="MC_Group001", Execute=True)
    step_until(c, en, "Done")
    ch2 = c.fb("MC_ChangeAxesInGroup", AxesGroup="MC_Group001", Axes=[2, 3, 4], Execute=True)
    c.step(1)
    assert ch2.Error and ch2.ErrorID == 0x543C
    rs = c.fb("MC_GroupReset", AxesGroup="MC_Group001", Execute=True)
    step_until(c, rs, "Done")
    sm = c.fb("MC_GroupSyncMoveAbsolute", AxesGroup="MC_Group001", Execute=True, Position=[0.1, 0.2, 0.3])
    c.step(1)
    assert sm.Busy and c.mc.cmd_pos[4] == pytest.approx(0.1)  # A0 is axis 4 now
    c.step(2)
    assert sm.Active and sm.InPosition and rp.CommandPosition[:3] == pytest.approx([0.1, 0.2, 0.3])
    sm.Position = [10.0, 0.2, 0.3]
    c.step(1)
    assert c.mc.cmd_pos[4] == pytest.approx(0.1 + 500.0 * 0.001)  # saturated at MaxVel
    st = c.fb("MC_GroupStop", AxesGroup="MC_Group001", Execute=True, Deceleration=100.0)
    c.step(1)
    assert sm.CommandAborted and not sm.InPosition
    held = c.mc.cmd_pos[4]
    step_until(c, st, "Done")
    assert c.mc.cmd_pos[4] == held  # stopped immediately
