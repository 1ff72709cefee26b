"""Administrative and common instructions.

Spec: omron-axis-instructions.md MC_ImmediateStop (seed 000 line 6019), MC_SetPosition (6146), MC_ResetFollowingError
(6466), MC_ZoneSwitch (11118), MC_AxesObserve (11972), MC_ChangeAxisUse (12758); omron-group-and-cam.md §5.3 MC_Write,
§5.5 MC_WriteAxisParameter (573A/573B with ErrorParameterCode), §5.6 MC_ReadAxisParameter.
"""

from __future__ import annotations

import pytest

from mcstudio.controller.kernel import Controller
from mcstudio.controller.mc.enums import AxisState
from tests.conftest import axis_project, power_on, small_project, step_until


@pytest.fixture
def c() -> Controller:
    ctrl = Controller(axis_project())
    power_on(ctrl)
    return ctrl


def _moving(c: Controller, v: float = 100.0) -> object:
    mv = c.fb("MC_MoveVelocity", Axis="MC_Axis000", Execute=True, Velocity=v, Acceleration=1000.0,
              Deceleration=1000.0)
    step_until(c, mv, "InVelocity")
    return mv


@pytest.mark.parametrize("mode", [1, 2, 3])
def test_immediate_stop_modes(c: Controller, mode: int) -> None:
    """StopMode 1: command stops at once; 2: + following error reset (Cmd := Act); 3: servo OFF. Every mode puts
    the axis in ErrorStop with 5485; the running instruction gets CommandAborted."""
    mv = _moving(c)
    st = c.fb("MC_ImmediateStop", Axis="MC_Axis000", Execute=True, StopMode=mode)
    c.step(1)
    assert st.Busy and mv.CommandAborted
    ax = c.mc.axes[0]
    assert ax.state == AxisState.ErrorStop and ax.error_code == 0x5485
    c.step(1)
    assert st.Done
    c.step(2)
    assert c.mc.cmd_vel[0] == 0.0
    if mode == 2:
        assert c.mc.cmd_pos[0] == c.mc.act_pos[0]
    assert ax.servo_on == (mode != 3)
    rs = c.fb("MC_Reset", Axis="MC_Axis000", Execute=True)
    step_until(c, rs, "Done")
    assert ax.state == (AxisState.Disabled if mode == 3 else AxisState.Standstill)


def test_immediate_stop_is_not_reexecutable(c: Controller) -> None:
    """543B (re-execution, seed 000 line 6019) cannot be reached: Done comes in the period after the edge, so the
    instance is never Busy at a new rising edge — the new edge starts it again (docs/error-coverage.md)."""
    st = c.fb("MC_ImmediateStop", Axis="MC_Axis000", Execute=True)
    c.step(1)
    assert st.Busy
    st.Execute = False
    c.step(1)
    assert st.Done and not st.Busy
    st.Execute = True
    c.step(1)
    assert st.Busy and not st.Error


def test_set_position_while_standing(c: Controller) -> None:
    """Command and actual move together (the following error is kept); home becomes undefined."""
    sp = c.fb("MC_SetPosition", Axis="MC_Axis000", Execute=True, Position=250.0)
    c.step(1)
    assert sp.Busy
    c.step(1)
    assert sp.Done
    assert c.mc.axes[0].cmd_pos == 250.0 and c.mc.axes[0].act_pos == pytest.approx(250.0)
    assert not c.mc.axes[0].homed


def test_set_position_keeps_absolute_target_of_running_move(c: Controller) -> None:
    """Moving to 400, the position 200 is changed to 800: the axis reverses and positions to 400 (seed 000
    MC_SetPosition example)."""
    mv = c.fb("MC_MoveAbsolute", Axis="MC_Axis000", Execute=True, Position=400.0, Velocity=100.0,
              Acceleration=1000.0, Deceleration=1000.0)
    step_until(c, mv, "Active")
    while c.mc.cmd_pos[0] < 200.0:
        c.step(1)
    c.fb("MC_SetPosition", Axis="MC_Axis000", Execute=True, Position=800.0 + (float(c.mc.cmd_pos[0]) - 200.0))
    c.step(3)
    step_until(c, mv, "Done")
    assert c.mc.act_pos[0] == pytest.approx(400.0, abs=1e-6)


def test_set_position_keeps_relative_motion(c: Controller) -> None:
    mr = c.fb("MC_MoveRelative", Axis="MC_Axis000", Execute=True, Distance=100.0, Velocity=100.0,
              Acceleration=1000.0, Deceleration=1000.0)
    c.step(300)
    before = float(c.mc.cmd_pos[0])
    c.fb("MC_SetPosition", Axis="MC_Axis000", Execute=True, Position=1000.0)
    c.step(2)
    step_until(c, mr, "Done")
    assert c.mc.act_pos[0] == pytest.approx(1000.0 + (100.0 - before), abs=1e-3)


def test_set_position_reference_type_must_match_axis_type(c: Controller) -> None:
    sp = c.fb("MC_SetPosition", Axis="MC_Axis000", Execute=True, Position=1.0, ReferenceType="_mcFeedback")
    c.step(1)
    assert sp.Error and sp.ErrorID == 0x5430


def test_set_position_refused_while_jogging(c: Controller) -> None:
    jog = c.fb("MC_MoveJog", Axis="MC_Axis000", PositiveEnable=True, Velocity=10.0)
    c.step(10)
    sp = c.fb("MC_SetPosition", Axis="MC_Axis000", Execute=True, Position=1.0)
    c.step(1)
    assert sp.Error and sp.ErrorID == 0x543C and jog.CommandAborted


def test_reset_following_error(c: Controller) -> None:
    """Command := actual; the running instruction is aborted; Stopping while it runs; Done after."""
    mv = _moving(c, 400.0)
    rfe = c.fb("MC_ResetFollowingError", Axis="MC_Axis000", Execute=True)
    c.step(1)
    assert mv.CommandAborted and c.mc.axes[0].state == AxisState.Stopping
    step_until(c, rfe, "Done", limit=100)
    assert c.mc.cmd_pos[0] == pytest.approx(c.mc.act_pos[0], abs=1e-9)
    c.step(1)
    assert c.mc.axes[0].state == AxisState.Standstill


@pytest.mark.parametrize(("first", "last", "ref", "inside"), [(-1.0, 1.0, 0, True), (5.0, 10.0, 1, False),
                                                             (0.0, 0.0, 0, True)])
def test_zone_switch(c: Controller, first: float, last: float, ref: int, inside: bool) -> None:
    z = c.fb("MC_ZoneSwitch", Axis="MC_Axis000", Enable=True, FirstPosition=first, LastPosition=last,
             ReferenceType=ref)
    c.step(1)
    assert z.Enabled and z.Busy and z.InZone == inside
    z.Enable = False
    c.step(1)
    assert not z.Enabled and not z.InZone


def test_zone_switch_order_in_linear_mode_is_546b(c: Controller) -> None:
    z = c.fb("MC_ZoneSwitch", Axis="MC_Axis000", Enable=True, FirstPosition=10.0, LastPosition=5.0)
    c.step(1)
    assert z.Error and z.ErrorID == 0x546B


def test_zone_switch_across_the_ring() -> None:
    c = Controller(axis_project(count_mode="_mcCountModeRotary", modulo=(0.0, 360.0)))
    power_on(c)
    z = c.fb("MC_ZoneSwitch", Axis="MC_Axis000", Enable=True, FirstPosition=350.0, LastPosition=10.0)
    c.step(1)
    assert z.InZone, "0 lies in the zone 350 … 10 across the ring limit"


def test_axes_observe() -> None:
    c = Controller(small_project())
    power_on(c)
    power_on(c, "MC_Axis001")
    ob = c.fb("MC_AxesObserve", Master="MC_Axis000", Slave="MC_Axis001", Enable=True, PermittedDeviation=5.0)
    mv = c.fb("MC_MoveRelative", Axis="MC_Axis000", Execute=True, Distance=7.0, Velocity=100.0,
              Acceleration=1000.0, Deceleration=1000.0)
    step_until(c, mv, "Done")
    c.step(1)
    assert ob.Enabled and ob.Invalid and ob.DeviatedValue == pytest.approx(7.0)
    ob.PermittedDeviation = 10.0
    c.step(1)
    assert not ob.Invalid
    ob.Enable = False
    c.step(1)
    assert not ob.Enabled and ob.DeviatedValue == pytest.approx(7.0), "DeviatedValue keeps its last value"


def test_axes_observe_negative_deviation_is_5488_mc_common() -> None:
    c = Controller(small_project())
    ob = c.fb("MC_AxesObserve", Master="MC_Axis000", Slave="MC_Axis001", Enable=True, PermittedDeviation=-1.0)
    c.step(1)
    assert ob.Error and ob.ErrorID == 0x5488
    assert c.mc.axes[0].error_code == 0, "an MC common error does not affect the axes"


def test_change_axis_use_and_write_axis_parameter() -> None:
    """MC_WriteAxisParameter only on an unused axis (573A); range errors are 573B with ErrorParameterCode;
    consistency errors too; Read returns the values in effect (Read → modify → Write)."""
    c = Controller(axis_project())
    power_on(c)
    rd = c.fb("MC_ReadAxisParameter", Axis="MC_Axis000", Execute=True)
    step_until(c, rd, "Done")
    params = rd.AxisParameter
    assert params["Operation"]["MaxVel"] == 500.0
    params["Operation"]["MaxVel"] = 250.0
    params["Operation"]["MaxJogVel"] = 50.0
    wr = c.fb("MC_WriteAxisParameter", Axis="MC_Axis000", Execute=True, AxisParameter=params)
    c.step(1)
    assert wr.Error and wr.ErrorID == 0x573A, "the axis is used"
    cu = c.fb("MC_ChangeAxisUse", Axis="MC_Axis000", Execute=True, AxisUse="_mcUnusedAxis")
    c.step(1)
    assert not cu.Error and (cu.Busy or cu.Done)  # servo ON, Standstill: allowed
    step_until(c, cu, "Done")
    assert not c.mc.axes[0].used
    bad = dict(params, Operation=dict(params["Operation"], MaxJogVel=300.0))
    wr2 = c.fb("MC_WriteAxisParameter", Axis="MC_Axis000", Execute=True, AxisParameter=bad)
    c.step(1)
    assert wr2.Error and wr2.ErrorID == 0x573B and wr2.ErrorParameterCode == 0x1102
    bad2 = dict(params, Operation=dict(params["Operation"], InPosCheckTime=20000))
    wr3 = c.fb("MC_WriteAxisParameter", Axis="MC_Axis000", Execute=True, AxisParameter=bad2)
    c.step(1)
    assert wr3.Error and wr3.ErrorParameterCode == 0x010D
    wr4 = c.fb("MC_WriteAxisParameter", Axis="MC_Axis000", Execute=True, AxisParameter=params)
    step_until(c, wr4, "Done")
    assert c.mc.axes[0].params.Operation.MaxVel == 250.0
    mv = c.fb("MC_MoveVelocity", Axis="MC_Axis000", Execute=True, Velocity=10.0)
    c.step(1)
    assert mv.Error and mv.ErrorID == 0x5460, "instructions on an unused axis: Illegal Axis Specification"
    back = c.fb("MC_ChangeAxisUse", Axis="MC_Axis000", Execute=True, AxisUse="_mcUsedAxis")
    step_until(c, back, "Done")
    assert c.mc.axes[0].used


def test_mc_write(c: Controller) -> None:
    """MC_Write: 544C parameter number, 544F setting value (range or type), success changes the setting."""
    w = c.fb("MC_Write", Target="MC_Axis000", Execute=True, ParameterNumber="_mcChkVel", SettingValue=20)
    step_until(c, w, "Done")
    assert c.mc.axes[0].params.Operation.VelWarningVal == 20
    w2 = c.fb("MC_Write", Target="MC_Axis000", Execute=True, ParameterNumber="_mcChkVel", SettingValue=150)
    c.step(1)
    assert w2.Error and w2.ErrorID == 0x544F
    assert c.mc.axes[0].error_code == 0, "MC common error: the axis keeps running"
    w3 = c.fb("MC_Write", Target="MC_Axis000", Execute=True, ParameterNumber=13, SettingValue=1)
    c.step(1)
    assert w3.Error and w3.ErrorID == 0x544C
    w4 = c.fb("MC_Write", Target="MC_Axis000", Execute=True, ParameterNumber="_mcSwLmtMode",
              SettingValue="_mcCmdImmediateStop")
    step_until(c, w4, "Done")
    assert int(c.mc.axes[0].params.Limit.SwLimitMode) == 2


def test_mc_common_errors_are_released_by_reset_mc_error(c: Controller) -> None:
    w = c.fb("MC_Write", Target="MC_Axis000", Execute=True, ParameterNumber=13, SettingValue=1)
    c.step(2)
    assert w.Error
    rs = c.fb("MC_Reset", Axis="MC_Axis000", Execute=True)
    step_until(c, rs, "Done")
    c.step(1)
    assert w.Error, "MC_Reset resets axis errors, not MC common errors"
    c.mc.reset_mc_errors()
    c.step(1)
    assert not w.Error


def test_free_run_stop_needs_a_new_power_edge(c: Controller) -> None:
    pw = next(e.fb for e in c.program.values() if e.fb.DEF.name == "MC_Power")
    c.fb("MC_ImmediateStop", Axis="MC_Axis000", Execute=True, StopMode="_mcFreeRunStop")
    c.step(5)
    rs = c.fb("MC_Reset", Axis="MC_Axis000", Execute=True)
    step_until(c, rs, "Done")
    c.step(10)
    assert not pw.Status and c.mc.axes[0].state == AxisState.Disabled
    pw.Enable = False
    c.step(1)
    pw.Enable = True
    step_until(c, pw, "Status", limit=20)


def test_absolute_encoder_home_offset() -> None:
    """An absolute-encoder axis is home-defined from the start with [Absolute encoder home offset] applied
    (omron-axis-instructions.md line 100, CPU ≥ 1.10); after MC_SetPosition (home undefined) the next servo ON
    defines home again with the offset (MC_Power rules)."""
    p = axis_project(encoder="absolute")
    p.axes[0].drive.AbsoluteEncoderHomeOffset = 12.5
    c = Controller(p)
    c.step(2)
    ax = c.mc.axes[0]
    assert ax.homed and c.mc.act_pos[0] == pytest.approx(12.5) and c.mc.cmd_pos[0] == pytest.approx(12.5)
    pw = power_on(c)
    sp = c.fb("MC_SetPosition", Axis="MC_Axis000", Execute=True, Position=100.0)
    step_until(c, sp, "Done")
    assert not ax.homed and c.mc.act_pos[0] == pytest.approx(100.0)
    c.set_inputs(pw.id, {"Enable": False})
    c.step(10)
    c.set_inputs(pw.id, {"Enable": True})
    step_until(c, pw, "Status")
    assert ax.homed and c.mc.act_pos[0] == pytest.approx(12.5)
