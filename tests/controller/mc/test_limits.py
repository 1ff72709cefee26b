"""Software limits, limit inputs, following error and warnings.

Spec: omron-group-and-cam.md §5.5.5 (SwLimitMode, limits, following error values), omron-mc-basics.md A-1 #142–146
(6440/6441 target beyond a software limit, 6443/6444 limit input at start), MC_SetPosition (software limits need
home defined). Run-time fault codes 6450–6463 are MC Studio assignments (docs/decisions.md D19).
"""

from __future__ import annotations

import pytest

from mcstudio.controller.kernel import Controller
from mcstudio.controller.mc.enums import AxisState
from tests.conftest import axis_project, power_on, step_until

SW = {"SwLimitMode": "_mcCmdDecelerationStop", "PosiSwLimit": 100.0, "NegaSwLimit": -50.0}


def _homed(**kw) -> Controller:
    c = Controller(axis_project(encoder="absolute", **kw))  # absolute encoder: home defined at servo ON
    power_on(c)
    return c


@pytest.mark.parametrize(("position", "code"), [(100.5, 0x6440), (-60.0, 0x6441)])
def test_target_beyond_software_limit_at_start(position: float, code: int) -> None:
    c = _homed(Limit=SW)
    mv = c.fb("MC_MoveAbsolute", Axis="MC_Axis000", Execute=True, Position=position, Velocity=10.0)
    c.step(1)
    assert mv.Error and mv.ErrorID == code
    assert c.mc.axes[0].state == AxisState.ErrorStop


def test_software_limits_need_home_defined() -> None:
    c = Controller(axis_project(Limit=SW))  # incremental encoder, not homed
    power_on(c)
    mv = c.fb("MC_MoveAbsolute", Axis="MC_Axis000", Execute=True, Position=150.0, Velocity=100.0,
              Acceleration=1000.0, Deceleration=1000.0)
    step_until(c, mv, "Done")
    assert not mv.Error


def test_command_deceleration_stop_stops_on_the_limit() -> None:
    """Mode 1 (command position, deceleration stop): a velocity move stops exactly at the limit, software-limit
    error, ErrorStop."""
    c = _homed(Limit=SW)
    mv = c.fb("MC_MoveVelocity", Axis="MC_Axis000", Execute=True, Velocity=100.0, Acceleration=1000.0,
              Deceleration=500.0)
    step_until(c, mv, "CommandAborted", limit=5000)
    ax = c.mc.axes[0]
    assert ax.error_code == 0x6450 and ax.state == AxisState.ErrorStop
    c.step(500)
    assert c.mc.cmd_vel[0] == 0.0
    assert float(c.mc.cmd_pos[0]) == pytest.approx(100.0, abs=1e-6)


def test_command_immediate_stop_at_the_limit() -> None:
    c = _homed(Limit={**SW, "SwLimitMode": "_mcCmdImmediateStop"})
    mv = c.fb("MC_MoveVelocity", Axis="MC_Axis000", Execute=True, Velocity=-100.0 * -1, Acceleration=1000.0,
              Deceleration=1000.0, Direction="_mcNegativeDirection")
    step_until(c, mv, "CommandAborted", limit=5000)
    assert c.mc.axes[0].error_code == 0x6451
    c.step(3)
    assert c.mc.cmd_vel[0] == 0.0
    assert float(c.mc.cmd_pos[0]) == pytest.approx(-50.0, abs=0.1 + 1e-9)


def test_actual_position_limit_decelerates_after_crossing() -> None:
    c = _homed(Limit={**SW, "SwLimitMode": "_mcActDecelerationStop"})
    c.fb("MC_MoveVelocity", Axis="MC_Axis000", Execute=True, Velocity=100.0, Acceleration=1000.0,
         Deceleration=1000.0)
    c.step(3000)
    assert c.mc.axes[0].error_code == 0x6450
    assert float(c.mc.act_pos[0]) > 100.0, "checked on the actual position: it stops beyond the limit"


def test_jog_into_software_limit_is_refused_at_start() -> None:
    c = _homed(Limit=SW)
    mv = c.fb("MC_MoveAbsolute", Axis="MC_Axis000", Execute=True, Position=100.0, Velocity=100.0,
              Acceleration=1000.0, Deceleration=1000.0)
    step_until(c, mv, "Done")
    jog = c.fb("MC_MoveJog", Axis="MC_Axis000", PositiveEnable=True, Velocity=10.0)
    c.step(1)
    assert jog.Error and jog.ErrorID == 0x6440
    c.fb("MC_Reset", Axis="MC_Axis000", Execute=True)
    c.step(3)
    back = c.fb("MC_MoveJog", Axis="MC_Axis000", NegativeEnable=True, Velocity=10.0)
    c.step(2)
    assert back.Busy and not back.Error, "moving back into the range is allowed"


def test_limit_input_at_start_and_during_motion() -> None:
    """6443 when starting towards an active positive limit input; hitting it while moving stops the axis with
    the Limit Input Stop Method and raises the limit-input error."""
    c = Controller(axis_project(sensors={"PositiveLimit": 30.0, "NegativeLimit": -30.0}))
    power_on(c)
    mv = c.fb("MC_MoveVelocity", Axis="MC_Axis000", Execute=True, Velocity=50.0, Acceleration=1000.0)
    step_until(c, mv, "CommandAborted", limit=3000)
    ax = c.mc.axes[0]
    assert ax.error_code == 0x6453 and ax.state == AxisState.ErrorStop
    assert c.publish().mc["drv"][0] & (1 << 3), "DrvStatus.P_OT"
    rs = c.fb("MC_Reset", Axis="MC_Axis000", Execute=True)
    step_until(c, rs, "Done")
    fwd = c.fb("MC_MoveRelative", Axis="MC_Axis000", Execute=True, Distance=5.0, Velocity=10.0)
    c.step(1)
    assert fwd.Error and fwd.ErrorID == 0x6443
    c.fb("MC_Reset", Axis="MC_Axis000", Execute=True)
    c.step(3)
    back = c.fb("MC_MoveRelative", Axis="MC_Axis000", Execute=True, Distance=-5.0, Velocity=10.0)
    step_until(c, back, "Done")


def test_limit_input_logic_inversion() -> None:
    """PosiLimitInputLogicInversion: the input reads ON where the switch is not actuated."""
    c = Controller(axis_project(sensors={"PositiveLimit": 30.0},
                                OtherOperation={"PosiLimitInputLogicInversion": True}))
    power_on(c)
    mv = c.fb("MC_MoveRelative", Axis="MC_Axis000", Execute=True, Distance=5.0, Velocity=10.0)
    c.step(1)
    assert mv.Error and mv.ErrorID == 0x6443


def test_following_error_over_and_warning() -> None:
    """Following error above the warning value → observation (Obsr); above the over value → error, ErrorStop.
    With the one-period delay of the drive, Cmd − Act = velocity × period."""
    c = Controller(axis_project(Limit={"FollowingErrorOverVal": 0.4, "FollowingErrorWarningVal": 0.2}))
    power_on(c)
    mv = c.fb("MC_MoveVelocity", Axis="MC_Axis000", Execute=True, Velocity=500.0, Acceleration=1000.0)
    c.step(250)  # 250 mm/s → FE 0.25
    ax = c.mc.axes[0]
    assert ax.obsr_code == 0x6460 and ax.error_code == 0
    step_until(c, mv, "CommandAborted", limit=1000)
    assert ax.error_code == 0x6452 and ax.state == AxisState.ErrorStop


def test_velocity_warning_is_an_observation() -> None:
    c = Controller(axis_project(Operation={"VelWarningVal": 10}))  # 10 % of 500 = 50 mm/s
    power_on(c)
    c.fb("MC_MoveVelocity", Axis="MC_Axis000", Execute=True, Velocity=60.0, Acceleration=1000.0)
    c.step(200)
    ax = c.mc.axes[0]
    assert ax.obsr_code == 0x6461 and ax.state == AxisState.Continuous, "a warning does not stop the axis"
    assert any(e.code == "64610000" and e.level == "observation" for e in c.events.list())


def test_in_position_check_time() -> None:
    """In-position check time > 0: Done waits for |Act − target| ≤ In-position Range (Details.InPosWaiting),
    and errors when it does not get there in time."""
    c = Controller(axis_project(Operation={"InPosCheckTime": 5, "InPosRange": 0.001}))
    power_on(c)
    mv = c.fb("MC_MoveAbsolute", Axis="MC_Axis000", Execute=True, Position=10.0, Velocity=100.0,
              Acceleration=1000.0, Deceleration=1000.0)
    step_until(c, mv, "Done")
    assert c.mc.act_pos[0] == pytest.approx(10.0, abs=1e-9)
