"""MC_MoveVelocity, MC_MoveRelative and MC_MoveJog.

Spec: omron-axis-instructions.md "MC_MoveVelocity" (seed 000 line 4486), "MC_MoveRelative" (line 4307),
"MC_MoveJog" (line 2573); api.md (lease_s dead-man).
"""

from __future__ import annotations

import pytest

from mcstudio.controller.kernel import Controller
from mcstudio.controller.mc.enums import AxisState
from tests.conftest import power_on, small_project, step_until


def test_move_velocity_in_velocity_timing(ctrl: Controller) -> None:
    """Busy on Execute↑, Active next period, InVelocity when the target velocity is reached; never Done."""
    power_on(ctrl)
    mv = ctrl.fb("MC_MoveVelocity", Axis="MC_Axis000", Execute=True, Velocity=20.0, Acceleration=200.0,
                 Deceleration=200.0, Direction="_mcNegativeDirection")
    ctrl.step(1)
    assert mv.Busy and not mv.Active
    assert ctrl.mc.axes[0].state == AxisState.Continuous
    ctrl.step(1)
    assert mv.Active and not mv.InVelocity
    n = step_until(ctrl, mv, "InVelocity")
    assert abs((n + 2) * 0.001 - 0.1) <= 0.002
    assert ctrl.mc.cmd_vel[0] == pytest.approx(-20.0)
    ctrl.step(1000)
    assert mv.Busy and mv.Active and mv.InVelocity
    assert ctrl.mc.axes[0].state == AxisState.Continuous
    assert ctrl.publish().mc["cmd_vel"][0] < 0


def test_move_velocity_reexecution_drops_in_velocity(ctrl: Controller) -> None:
    power_on(ctrl)
    mv = ctrl.fb("MC_MoveVelocity", Axis="MC_Axis000", Execute=True, Velocity=20.0, Acceleration=200.0,
                 Deceleration=200.0)
    step_until(ctrl, mv, "InVelocity")
    mv.Execute = False
    ctrl.step(1)
    mv.Velocity = 40.0
    mv.Execute = True
    ctrl.step(1)
    assert not mv.InVelocity and mv.Busy
    step_until(ctrl, mv, "InVelocity")
    assert ctrl.mc.cmd_vel[0] == pytest.approx(40.0)


@pytest.mark.parametrize(("inputs", "code"), [({"Velocity": -1.0}, 0x5422), ({"Direction": 1}, 0x542E),
                                               ({"BufferMode": 2}, 0x542B)])
def test_move_velocity_input_errors(ctrl: Controller, inputs: dict, code: int) -> None:
    power_on(ctrl)
    mv = ctrl.fb("MC_MoveVelocity", Axis="MC_Axis000", Execute=True, **{"Velocity": 10.0, **inputs})
    ctrl.step(1)
    assert mv.Error and mv.ErrorID == code


def test_move_relative_and_reexecution_from_original_start(ctrl: Controller) -> None:
    """Distance is measured from the command position at start; on re-execution from the *original* start, so
    re-executing with Distance 0 returns to the start position (MC_MoveRelative functional rules)."""
    power_on(ctrl)
    mr = ctrl.fb("MC_MoveRelative", Axis="MC_Axis000", Execute=True, Distance=10.0, Velocity=20.0,
                 Acceleration=200.0, Deceleration=200.0)
    step_until(ctrl, mr, "Done")
    assert ctrl.mc.act_pos[0] == pytest.approx(10.0, abs=1e-9)
    mr.Execute = False
    ctrl.step(1)
    mr.Execute = True
    ctrl.step(200)
    assert 10.0 < ctrl.mc.cmd_pos[0] < 20.0
    mr.Execute = False
    ctrl.step(1)
    mr.Distance = 0.0
    mr.Execute = True
    step_until(ctrl, mr, "Done")
    assert ctrl.mc.act_pos[0] == pytest.approx(10.0, abs=1e-9)


def test_move_relative_distance_out_of_range(ctrl: Controller) -> None:
    power_on(ctrl)
    mr = ctrl.fb("MC_MoveRelative", Axis="MC_Axis000", Execute=True, Distance=2e7, Velocity=20.0)
    ctrl.step(1)
    assert mr.Error and mr.ErrorID == 0x5479


def test_jog_timing_and_release(ctrl: Controller) -> None:
    """PositiveEnable↑ → Busy, jog at Velocity (clamped to Maximum Jog Velocity); release → decelerate, Busy↓ when
    stopped; the axis is Continuous while jogging and Standstill afterwards."""
    power_on(ctrl)
    jog = ctrl.fb("MC_MoveJog", Axis="MC_Axis000", PositiveEnable=True, Velocity=500.0, Acceleration=1000.0,
                  Deceleration=1000.0)
    ctrl.step(1)
    assert jog.Busy
    assert ctrl.mc.axes[0].state == AxisState.Continuous
    ctrl.step(300)
    assert ctrl.mc.cmd_vel[0] == pytest.approx(100.0), "clamped to MaxJogVel = 100"
    jog.PositiveEnable = False
    ctrl.step(50)
    assert jog.Busy and 0 < ctrl.mc.cmd_vel[0] < 100.0
    step_until(ctrl, jog, "Busy", False, limit=200)
    assert ctrl.mc.cmd_vel[0] == 0.0
    assert ctrl.mc.axes[0].state == AxisState.Standstill


def test_deleting_a_jogging_instance_stops_the_jog(ctrl: Controller) -> None:
    """D58: DELETE of a jogging MC_MoveJog acts like its enable falling — the axis decelerates at the instance's
    Deceleration to Standstill instead of jogging on with nothing left to stop it."""
    power_on(ctrl)
    jog = ctrl.fb("MC_MoveJog", Axis="MC_Axis000", PositiveEnable=True, Velocity=50.0, Acceleration=1000.0,
                  Deceleration=1000.0)
    ctrl.step(200)
    assert ctrl.mc.cmd_vel[0] == pytest.approx(50.0)
    ctrl.delete_fb(jog.id)
    ctrl.step(10)
    assert 0.0 < ctrl.mc.cmd_vel[0] < 50.0, "decelerating"
    ctrl.step(100)  # 50 / 1000 = 0.05 s = 50 periods of 1 ms
    assert ctrl.mc.cmd_vel[0] == 0.0
    assert ctrl.mc.axes[0].state == AxisState.Standstill


def test_jog_reverse_with_other_enable(ctrl: Controller) -> None:
    """Jogging + and NegativeEnable↑: the axis reverses; dropping NegativeEnable while PositiveEnable is still TRUE
    does not resume + (the axis stops)."""
    power_on(ctrl)
    jog = ctrl.fb("MC_MoveJog", Axis="MC_Axis000", PositiveEnable=True, Velocity=50.0, Acceleration=1000.0,
                  Deceleration=1000.0)
    ctrl.step(200)
    jog.NegativeEnable = True
    ctrl.step(300)
    assert ctrl.mc.cmd_vel[0] == pytest.approx(-50.0)
    jog.NegativeEnable = False
    step_until(ctrl, jog, "Busy", False, limit=200)
    assert ctrl.mc.cmd_vel[0] == 0.0


def test_jog_only_from_standstill() -> None:
    """MC_MoveJog on a moving axis (Discrete) is an error (A-3.4: MC_MoveJog C → H)."""
    c = Controller(small_project())
    power_on(c)
    c.fb("MC_MoveAbsolute", Axis="MC_Axis000", Execute=True, Position=50.0, Velocity=10.0)
    c.step(10)
    jog = c.fb("MC_MoveJog", Axis="MC_Axis000", PositiveEnable=True, Velocity=10.0)
    c.step(1)
    assert jog.Error and jog.ErrorID == 0x543C


class FakeClock:
    def __init__(self) -> None:
        self.now = 1000.0

    def __call__(self) -> float:
        return self.now


def test_lease_expiry_stops_a_jog() -> None:
    """api.md lease_s: without renewal the dead-man inputs drop to FALSE; the jog decelerates and ends."""
    clock = FakeClock()
    c = Controller(small_project(), clock=clock)
    power_on(c)
    jog = c.fb("MC_MoveJog", lease_s=0.5, Axis="MC_Axis000", PositiveEnable=True, Velocity=50.0,
               Acceleration=1000.0, Deceleration=1000.0)
    c.step(200)
    clock.now += 0.4
    c.renew_lease(jog.id)
    c.step(200)
    clock.now += 0.4  # 0.4 s since the last renewal: still valid
    c.step(1)
    assert jog.PositiveEnable and c.mc.cmd_vel[0] == pytest.approx(50.0)
    clock.now += 0.2  # 0.6 s since the renewal: expired
    c.step(1)
    assert not jog.PositiveEnable
    assert any("lease" in e.message for e in c.events.list())
    step_until(c, jog, "Busy", False, limit=200)
    assert c.mc.cmd_vel[0] == 0.0
    assert c.mc.axes[0].state == AxisState.Standstill


def test_current_direction_uses_the_last_motion(ctrl: Controller) -> None:
    """_mcCurrentDirection on a stopped axis moves in the last direction of travel (MC_MoveVelocity rules)."""
    power_on(ctrl)
    mr = ctrl.fb("MC_MoveRelative", Axis="MC_Axis000", Execute=True, Distance=-5.0, Velocity=50.0,
                 Acceleration=500.0, Deceleration=500.0)
    step_until(ctrl, mr, "Done")
    mv = ctrl.fb("MC_MoveVelocity", Axis="MC_Axis000", Execute=True, Velocity=10.0, Acceleration=100.0,
                 Deceleration=100.0, Direction="_mcCurrentDirection")
    step_until(ctrl, mv, "InVelocity")
    assert ctrl.mc.cmd_vel[0] == pytest.approx(-10.0)
