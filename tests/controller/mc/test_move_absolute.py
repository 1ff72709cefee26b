"""MC_MoveAbsolute timing charts on the paused controller.

Spec: omron-axis-instructions.md "MC_MoveAbsolute" (seed 000 line 3491: Busy on Execute↑, Active one period later,
Done when positioning completes; Done/CommandAborted held while Execute is TRUE, one period otherwise) and
omron-mc-basics.md §2.8 (output rules), §2.6 (valid ranges), A-1 (5422).
"""

from __future__ import annotations

import math

import pytest
from ruckig import InputParameter, Ruckig, Trajectory

from mcstudio.controller.kernel import Controller
from mcstudio.controller.mc.enums import AxisState
from tests.conftest import power_on, small_project, step_until

T = 0.001


def _ruckig_duration(distance: float, v: float, a: float, j: float) -> float:
    inp = InputParameter(1)
    inp.current_position, inp.target_position = [0.0], [distance]
    inp.max_velocity, inp.max_acceleration, inp.max_jerk = [v], [a], [j]
    traj = Trajectory(1)
    Ruckig(1).calculate(inp, traj)
    return traj.duration


def test_timing_chart_trapezoid(ctrl: Controller) -> None:
    """Execute↑ (cycle 0) → Busy; cycle 1 Active; the profile 0→100 at 50/500/500 lasts 2.1 s, so Done appears at
    cycle 2100 with Busy and Active FALSE and Act.Pos exactly on target; Done holds while Execute is TRUE."""
    power_on(ctrl)
    mv = ctrl.fb("MC_MoveAbsolute", Axis="MC_Axis000", Execute=True, Position=100.0, Velocity=50.0,
                 Acceleration=500.0, Deceleration=500.0, Jerk=0.0)
    ax = ctrl.mc.axes[0]
    ctrl.step(1)  # cycle 0: Execute↑ — accepted (Busy), first command value computed in the same period
    assert (mv.Busy, mv.Active, mv.Done) == (True, False, False)
    assert ax.state == AxisState.Discrete
    assert ctrl.mc.cmd_pos[0] == pytest.approx(0.5 * 500 * T**2)
    ctrl.step(1)  # cycle 1: Active, one period after Busy
    assert (mv.Busy, mv.Active, mv.Done) == (True, True, False)
    ctrl.step(2097)  # cycles 2 … 2098
    assert (mv.Busy, mv.Active, mv.Done) == (True, True, False)
    ctrl.step(1)  # cycle 2099: the 2.1 s profile ends; its final command value goes out to the drive
    assert ctrl.mc.cmd_pos[0] == 100.0
    assert not mv.Done and ctrl.mc.act_pos[0] < 100.0
    ctrl.step(1)  # cycle 2100 = 2.100 s after Execute: the drive is on target — positioning complete
    assert (mv.Busy, mv.Active, mv.Done, mv.CommandAborted, mv.Error) == (False, False, True, False, False)
    assert abs(ctrl.mc.act_pos[0] - 100.0) <= 1e-9
    assert ax.state == AxisState.Standstill
    ctrl.step(500)
    assert mv.Done, "Done stays TRUE while Execute is TRUE"
    mv.Execute = False
    ctrl.step(1)
    assert not mv.Done, "Done falls with Execute"


def test_cruise_velocity_and_cmd_values(ctrl: Controller) -> None:
    """Cmd.Vel is the difference of command positions; + direction sets Dir.Posi (manual §2.3)."""
    power_on(ctrl)
    ctrl.fb("MC_MoveAbsolute", Axis="MC_Axis000", Execute=True, Position=100.0, Velocity=50.0,
            Acceleration=500.0, Deceleration=500.0)
    ctrl.step(1000)
    snap = ctrl.publish()
    assert snap.mc["cmd_vel"][0] == pytest.approx(50.0, abs=1e-9)
    assert snap.mc["cmd_accdec"][0] == pytest.approx(0.0, abs=1e-6)
    ctrl.step(50)  # 50 ms into... still cruising (cruise ends at 2.0 s)
    assert ctrl.mc.cmd_vel[0] == pytest.approx(50.0, abs=1e-9)


def test_done_is_a_one_period_pulse_when_execute_fell_early(ctrl: Controller) -> None:
    """Execute↓ before completion: the instruction continues; Done is TRUE for exactly one period (§2.8)."""
    power_on(ctrl)
    mv = ctrl.fb("MC_MoveAbsolute", Axis="MC_Axis000", Execute=True, Position=10.0, Velocity=100.0,
                 Acceleration=1000.0, Deceleration=1000.0)
    ctrl.step(5)
    mv.Execute = False
    ctrl.step(1)
    assert mv.Busy and mv.Active
    step_until(ctrl, mv, "Done")
    ctrl.step(1)
    assert not mv.Done and not mv.Busy


def test_s_curve_duration_equals_ruckig(ctrl: Controller) -> None:
    """With Jerk 5000 the move takes ruckig's planned duration (± 1 period): the architecture's profile rule."""
    power_on(ctrl)
    mv = ctrl.fb("MC_MoveAbsolute", Axis="MC_Axis000", Execute=True, Position=100.0, Velocity=50.0,
                 Acceleration=500.0, Deceleration=500.0, Jerk=5000.0)
    n = step_until(ctrl, mv, "Done")
    expected = _ruckig_duration(100.0, 50.0, 500.0, 5000.0)
    assert expected == pytest.approx(2.2)
    assert abs(n * T - expected) <= 2 * T
    assert abs(ctrl.mc.act_pos[0] - 100.0) <= 1e-9


def test_zero_distance_gives_done_without_motion(ctrl: Controller) -> None:
    """Position equal to the command position: no motion, Done TRUE (MC_MoveAbsolute functional rules)."""
    power_on(ctrl)
    mv = ctrl.fb("MC_MoveAbsolute", Axis="MC_Axis000", Execute=True, Position=0.0, Velocity=10.0)
    n = step_until(ctrl, mv, "Done")
    assert n <= 2
    assert ctrl.mc.cmd_pos[0] == 0.0


@pytest.mark.parametrize(
    ("inputs", "code"),
    [
        ({"Velocity": 0.0}, 0x5422),
        ({"Velocity": -5.0}, 0x5422),
        ({"Velocity": 10.0, "Acceleration": -1.0}, 0x5423),
        ({"Velocity": 10.0, "Deceleration": -1.0}, 0x5424),
        ({"Velocity": 10.0, "Jerk": -1.0}, 0x5425),
        ({"Velocity": 10.0, "BufferMode": 6}, 0x542B),
        ({"Velocity": 10.0, "Direction": 5}, 0x542E),
        ({"Velocity": 10.0, "Position": 1e9}, 0x5478),  # beyond signed 40 bits in pulses (104857.6 pulse/mm)
    ],
)
def test_input_errors(ctrl: Controller, inputs: dict, code: int) -> None:
    """Input checks at start (omron-mc-basics.md §2.6, A-1): Error + ErrorID, the axis goes to ErrorStop with
    MFaultLvl.Code = ErrorID, and an event with the 8-digit code is logged."""
    power_on(ctrl)
    mv = ctrl.fb("MC_MoveAbsolute", Axis="MC_Axis000", Execute=True, **{"Position": 10.0, **inputs})
    ctrl.step(1)
    assert mv.Error and mv.ErrorID == code and not mv.Busy
    ax = ctrl.mc.axes[0]
    assert ax.state == AxisState.ErrorStop and ax.error_code == code
    assert any(e.code == f"{code:04X}0000" and e.level == "minor fault" for e in ctrl.events.list())
    # Error is sticky: Execute↓ does not clear it (Omron deviation from PLCopen, §2.8)
    mv.Execute = False
    ctrl.step(3)
    assert mv.Error and mv.ErrorID == code


def test_error_cleared_by_reset_and_new_edge_needed(ctrl: Controller) -> None:
    """After MC_Reset the instance's Error clears; an Execute still TRUE does not start it again (§2.8)."""
    power_on(ctrl)
    mv = ctrl.fb("MC_MoveAbsolute", Axis="MC_Axis000", Execute=True, Position=10.0, Velocity=0.0)
    ctrl.step(2)
    assert mv.Error
    rs = ctrl.fb("MC_Reset", Axis="MC_Axis000", Execute=True)
    step_until(ctrl, rs, "Done")
    ctrl.step(1)
    assert not mv.Error and mv.ErrorID == 0
    assert ctrl.mc.axes[0].state == AxisState.Standstill
    mv.Velocity = 20.0
    ctrl.step(5)
    assert not mv.Busy, "no rising edge, no start"
    mv.Execute = False
    ctrl.step(1)
    mv.Execute = True
    ctrl.step(2)
    assert mv.Busy and mv.Active


def test_servo_off_axis_gives_5441() -> None:
    """Motion instruction on a Disabled (servo OFF) axis: 5441 and ErrorStop (A-3.4 column A, A-1 #34)."""
    c = Controller(small_project())
    mv = c.fb("MC_MoveAbsolute", Axis="MC_Axis000", Execute=True, Position=10.0, Velocity=10.0)
    c.step(1)
    assert mv.Error and mv.ErrorID == 0x5441
    assert c.mc.axes[0].state == AxisState.ErrorStop


def test_velocity_clamped_to_max_velocity() -> None:
    """Velocity above [Maximum Velocity] is clamped to it (§2.6)."""
    c = Controller(small_project(MaxVel=20.0, MaxJogVel=20.0))
    power_on(c)
    c.fb("MC_MoveAbsolute", Axis="MC_Axis000", Execute=True, Position=100.0, Velocity=1000.0,
         Acceleration=100000.0, Deceleration=100000.0)
    c.step(500)
    assert c.mc.cmd_vel[0] == pytest.approx(20.0, abs=1e-9)


def test_aborting_multi_execution_reverses_with_deceleration_stop(ctrl: Controller) -> None:
    """BufferMode _mcAborting: the running instruction gets CommandAborted, the new one takes over; reversing
    decelerates to a stop first (Operation Selection at Reversing = deceleration stop, MC_Move rules)."""
    power_on(ctrl)
    a = ctrl.fb("MC_MoveAbsolute", Axis="MC_Axis000", Execute=True, Position=100.0, Velocity=50.0,
                Acceleration=500.0, Deceleration=500.0)
    ctrl.step(1000)
    b = ctrl.fb("MC_MoveAbsolute", Axis="MC_Axis000", Execute=True, Position=0.0, Velocity=50.0,
                Acceleration=500.0, Deceleration=250.0)
    ctrl.step(1)  # B accepted: A is aborted in the same period
    assert b.Busy and not b.Active
    assert a.CommandAborted and not a.Busy and not a.Active
    ctrl.step(1)  # B is Active one period later
    assert b.Active
    # deceleration with the new instruction's Deceleration (250): 50 → 0 takes 0.2 s
    ctrl.step(150)
    assert ctrl.mc.cmd_vel[0] > 0
    ctrl.step(60)
    assert ctrl.mc.cmd_vel[0] < 0
    step_until(ctrl, b, "Done")
    assert ctrl.mc.act_pos[0] == pytest.approx(0.0, abs=1e-9)


def test_buffered_starts_when_previous_is_done(ctrl: Controller) -> None:
    """BufferMode _mcBuffered: the second instruction waits (Busy, not Active) and starts when the first is Done
    (its Active rises in the period the first one's Done does, as in PLCopen's buffered chart; decision D1);
    a third buffered one exceeds the buffer (5443, one buffered instruction per axis, A-3.1)."""
    power_on(ctrl)
    a = ctrl.fb("MC_MoveAbsolute", Axis="MC_Axis000", Execute=True, Position=10.0, Velocity=50.0,
                Acceleration=500.0, Deceleration=500.0)
    ctrl.step(2)
    b = ctrl.fb("MC_MoveAbsolute", Axis="MC_Axis000", Execute=True, Position=20.0, Velocity=50.0,
                Acceleration=500.0, Deceleration=500.0, BufferMode="_mcBuffered")
    ctrl.step(2)
    assert b.Busy and not b.Active and a.Active
    step_until(ctrl, a, "Done")  # A completes; B shows Active in the same period (D1) …
    assert b.Active and not b.Done
    held = float(ctrl.mc.cmd_pos[0])
    ctrl.step(1)  # … and moves from the next period
    assert ctrl.mc.cmd_pos[0] > held
    step_until(ctrl, b, "Done")
    assert ctrl.mc.act_pos[0] == pytest.approx(20.0, abs=1e-9)
    c1 = ctrl.fb("MC_MoveAbsolute", Axis="MC_Axis000", Execute=True, Position=0.0, Velocity=50.0)
    ctrl.step(2)
    c2 = ctrl.fb("MC_MoveAbsolute", Axis="MC_Axis000", Execute=True, Position=5.0, Velocity=50.0,
                 BufferMode="_mcBuffered")
    c3 = ctrl.fb("MC_MoveAbsolute", Axis="MC_Axis000", Execute=True, Position=6.0, Velocity=50.0,
                 BufferMode="_mcBuffered")
    ctrl.step(1)
    assert c3.Error and c3.ErrorID == 0x5443
    # 5443 is an axis minor fault (A-1 effect AXG-D): everything on the axis is aborted, the axis error-stops
    assert c1.CommandAborted and c2.CommandAborted and not c2.Error
    assert ctrl.mc.axes[0].state == AxisState.ErrorStop


def test_reexecution_changes_target(ctrl: Controller) -> None:
    """Re-execution (new Execute↑ while Busy) may change Position/Velocity/Acc/Dec (seed 000 line 3450)."""
    power_on(ctrl)
    mv = ctrl.fb("MC_MoveAbsolute", Axis="MC_Axis000", Execute=True, Position=100.0, Velocity=50.0,
                 Acceleration=500.0, Deceleration=500.0)
    ctrl.step(300)
    mv.Execute = False
    ctrl.step(1)
    mv.Position = 30.0
    mv.Execute = True
    ctrl.step(1)
    assert mv.Busy and not mv.Error
    step_until(ctrl, mv, "Done")
    assert ctrl.mc.act_pos[0] == pytest.approx(30.0, abs=1e-9)


def test_reexecution_with_changed_jerk_is_5458(ctrl: Controller) -> None:
    """Changing Jerk on re-execution: 5458 'Re-execution Disabled (Jerk Setting)' (A-2.3)."""
    power_on(ctrl)
    mv = ctrl.fb("MC_MoveAbsolute", Axis="MC_Axis000", Execute=True, Position=100.0, Velocity=50.0,
                 Acceleration=500.0, Deceleration=500.0)
    ctrl.step(10)
    mv.Execute = False
    ctrl.step(1)
    mv.Jerk = 1000.0
    mv.Execute = True
    ctrl.step(1)
    assert mv.Error and mv.ErrorID == 0x5458


def test_step_change_when_acceleration_is_zero(ctrl: Controller) -> None:
    """Acceleration = 0 / Deceleration = 0: the velocity changes step-wise (within one period)."""
    power_on(ctrl)
    mv = ctrl.fb("MC_MoveAbsolute", Axis="MC_Axis000", Execute=True, Position=10.0, Velocity=50.0)
    ctrl.step(3)
    assert ctrl.mc.cmd_vel[0] == pytest.approx(50.0, abs=1e-6)
    assert ctrl.mc.cmd_accdec[0] == 0.0, "Cmd.AccDec reads 0 when the instruction's acc/dec is 0 (§2.3)"
    n = step_until(ctrl, mv, "Done")
    assert math.isclose((n + 3) * T, 10.0 / 50.0, abs_tol=3 * T)
