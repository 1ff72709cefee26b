"""MC_TorqueControl and MC_SetTorqueLimit, as timing charts on the paused controller.

Spec: omron-axis-instructions.md "MC_TorqueControl (seed line 10597)" and "MC_SetTorqueLimit (seed line 10917)"
(seed 000 lines 10597–11117), the re-execution/multi-execution summary (digest line ~2086), omron-mc-basics.md §2.3
(Cmd.Trq/Act.Trq, DrvStatus.CST/ILA), §2.11 (objects each instruction needs, 3461), A-1 (5422, 5427, 542B, 542E,
543D, 5441, 7439), A-3.4 (MC_TorqueControl row; MC_SetPosition footnote *5). Decisions: docs/decisions.md D24–D27.

Axis MC_Axis000 (tests/conftest.py axis_project): 10 mm per motor revolution, 2^20 pulses per revolution, on a
CiA402 drive with the default mechanism (rated torque 1.27 N·m, inertia 2.7e-4 kg·m²) unless a test changes it.
"""

from __future__ import annotations

import math
from typing import Any

import pytest

from mcstudio.api.state import Studio
from mcstudio.controller.kernel import Controller
from mcstudio.controller.mc.enums import AxisState
from mcstudio.controller.mc.fb.base import FunctionBlock
from mcstudio.controller.mc.module import drv_status
from mcstudio.controller.runner import Runner
from mcstudio.project.models import Project
from tests.conftest import axis_project, power_on, step_until

AX = "MC_Axis000"
PPU = 1048576 / 10.0  # pulses per mm
MM_PER_RAD = 10.0 / (2 * math.pi)
CSP, CST = 8, 10


def _ctrl(project: Project | None = None, **drive: Any) -> Controller:
    p = project or axis_project()
    for k, v in drive.items():
        setattr(p.axes[0].drive, k, v)
    c = Controller(p)
    power_on(c)
    return c


def _tc(c: Controller, **inputs: Any) -> FunctionBlock:
    return c.fb("MC_TorqueControl", Axis=AX, Execute=True, **inputs)


def _drv(c: Controller, i: int = 0) -> dict[str, bool]:
    return drv_status(int(c.mc.drv[i]))


def _rx(c: Controller, name: str) -> int:
    return int(c.network.rx[name][0])


def _tx(c: Controller, name: str) -> int:
    return int(c.network.tx[name][0])


# ---------------------------------------------------------------------------------------------- start and InTorque

def test_start_timing_chart_and_in_torque_after_the_ramp() -> None:
    """Busy with Execute↑, CST requested (6060h = 10) and the first ramp value (6071h) in the same period; the drive
    reports CST (6061h, DrvStatus.CST) one period later, when Active rises; the command torque ramps at TorqueRamp
    from the current torque and InTorque rises once the drive has received the target torque (seed 10597 output
    table; D24). Status.Continuous; Cmd.Pos = Act.Pos of one period earlier in CST (seed "positions during torque
    control")."""
    c = _ctrl()
    m = c.mc
    tc = _tc(c, Torque=10.0, TorqueRamp=100.0, Velocity=200.0)  # 0.1 % per 1 ms period: 100 periods to 10 %
    c.step(1)  # period E: the Execute edge
    assert tc.Busy and not tc.Active and not tc.InTorque and not tc.CommandAborted and not tc.Error
    assert m.axes[0].state == AxisState.Continuous
    assert _rx(c, "modes_of_operation") == CST and _rx(c, "target_torque") == 1  # 0.1 % in 0.1 % units
    assert m.trq_cmd[0] == pytest.approx(0.1) and m.act_trq[0] == 0.0
    assert _drv(c)["CSP"] and not _drv(c)["CST"], "the drive switches with the next frame"
    assert m.cmd_pos[0] == 0.0
    c.step(1)  # E+1
    assert tc.Busy and tc.Active and not tc.InTorque
    assert _drv(c)["CST"] and not _drv(c)["CSP"] and _tx(c, "modes_display") == CST
    assert m.act_trq[0] == pytest.approx(0.1), "6077h: the torque the drive applied in this period"
    assert m.trq_cmd[0] == pytest.approx(0.2)
    for k in range(2, 99):  # E+2 … E+98
        c.step(1)
        assert not tc.InTorque, f"E+{k}"
        assert m.trq_cmd[0] == pytest.approx(0.1 * (k + 1))
        assert m.cmd_pos[0] == m.prev_act_pos[0], "Cmd.Pos: feedback of one period earlier"
        assert m.act_trq[0] == pytest.approx(0.1 * k)
    c.step(1)  # E+99: the command reaches 10 %
    assert m.trq_cmd[0] == 10.0 and not tc.InTorque
    c.step(1)  # E+100: the drive has received it
    assert tc.InTorque and tc.Busy and tc.Active and m.act_trq[0] == 10.0
    c.step(500)
    assert tc.InTorque and tc.Busy and m.axes[0].state == AxisState.Continuous, "never Done"
    assert m.act_vel[0] > 0


def test_torque_drives_the_inertia() -> None:
    """In CST the shaft follows J·dω/dt = T − b·ω − T_load (architecture.md "Mechanism"): without friction or load
    a constant 10 % of the rated torque accelerates the inertia uniformly; 6077h reports the applied torque."""
    c = _ctrl(ViscousFriction=0.0)
    m = c.mc
    _tc(c, Torque=10.0, Velocity=400.0)  # TorqueRamp 0: step change
    c.step(1)  # E: 10 % is sent; the drive applies it from E+1
    alpha = 0.1 * 1.27 / 2.7e-4 * MM_PER_RAD  # mm/s²
    done = 0
    for n in (1, 10, 100, 300):  # after n periods of torque (exchanges E+1 … E+n)
        c.step(n - done)
        done = n
        t = n * 0.001
        assert m.act_pos[0] == pytest.approx(alpha * t * t / 2, abs=1 / PPU), f"n={n}"
        assert m.act_trq[0] == 10.0 and not _drv(c)["ILA"]
    assert c.network.plant.velocity[0] / PPU == pytest.approx(alpha * 0.3, rel=1e-9)


def test_load_torque_and_velocity_zero_hold_still() -> None:
    """A constant load torque (LoadTorque, positive = acting in the negative direction) is balanced by an equal
    motor torque; Velocity 0 is a speed limit of 0: the drive holds the axis with the torque that takes (D24)."""
    c = _ctrl(LoadTorque=0.127)  # 10 % of the rated torque
    m = c.mc
    tc = _tc(c, Torque=10.0, Velocity=50.0)
    step_until(c, tc, "InTorque")
    c.step(200)
    assert m.act_pos[0] == 0.0 and m.act_vel[0] == 0.0 and m.act_trq[0] == 10.0
    assert not _drv(c)["ILA"]
    # no motor torque against the load: the axis runs negative until the velocity limit
    c2 = _ctrl(LoadTorque=0.127)
    tc2 = _tc(c2, Torque=0.0, Velocity=5.0)
    c2.step(400)
    assert tc2.InTorque and c2.mc.act_vel[0] == pytest.approx(-5.0, abs=0.01)
    assert _drv(c2)["ILA"], "the velocity limit acts (drive internal limit)"
    # Velocity 0: nothing moves although 50 % is commanded; the drive limits (ILA)
    c3 = _ctrl()
    tc3 = _tc(c3, Torque=50.0, Velocity=0.0)
    c3.step(300)
    assert tc3.InTorque and c3.mc.act_pos[0] == 0.0 and c3.mc.act_trq[0] == 0.0 and _drv(c3)["ILA"]
    assert _rx(c3, "max_profile_velocity") == 0


def test_velocity_limit_reduces_the_torque() -> None:
    """Velocity is the speed limit of torque control, sent as 607Fh [pulse/s]: at the limit the drive reduces the
    torque (seed 10597 "Velocity"); with viscous friction the torque at the limit is b·ω; DrvStatus.ILA (statusword
    bit 11) shows the drive's internal limit (omron-mc-basics.md §2.3)."""
    c = _ctrl(ViscousFriction=0.01)
    m = c.mc
    tc = _tc(c, Torque=50.0, Velocity=20.0)
    c.step(1)
    assert _rx(c, "max_profile_velocity") == round(20.0 * PPU)
    top = 0.0
    for _ in range(300):
        c.step(1)
        top = max(top, float(m.act_vel[0]))
        assert m.act_vel[0] <= 20.0 + 1.5 / PPU / 0.001, "never faster than the limit (± one pulse per period)"
    assert top >= 20.0 - 1.5 / PPU / 0.001
    assert tc.InTorque and m.trq_cmd[0] == 50.0, "the command torque stays the target"
    b_omega = 0.01 * 20.0 / MM_PER_RAD  # N·m at 20 mm/s
    assert m.act_trq[0] == pytest.approx(round(b_omega / 1.27 * 1000) / 10)  # 9.9 %
    assert _drv(c)["ILA"]


def test_torque_direction_and_clamping() -> None:
    """Direction _mcNegativeDirection outputs the torque negative; Torque above 1000.0 acts as 1000.0, negative as
    0.0, in 0.1 % steps rounded half up (seed 10597 input table, footnote *1). The drive limits what it applies to
    its torque limits 60E0h/60E1h, by default the axis parameters [Maximum Positive/Negative Torque Limit]."""
    c = _ctrl()
    m = c.mc
    _tc(c, Torque=1500.0, Velocity=400.0, Direction="_mcNegativeDirection")
    c.step(2)
    assert m.trq_cmd[0] == -1000.0 and _rx(c, "target_torque") == -10000
    assert _rx(c, "negative_torque_limit") == 3000 and m.act_trq[0] == -300.0 and _drv(c)["ILA"]
    for value, expect in ((-5.0, 0.0), (12.25, 12.3), (12.24, 12.2)):
        c2 = _ctrl()
        _tc(c2, Torque=value, Velocity=1.0)
        c2.step(1)
        assert c2.mc.trq_cmd[0] == expect, value


def test_in_torque_of_a_virtual_servo_axis() -> None:
    """A virtual servo axis always accepts the instruction without a mode switch (seed "usable axes"): the command
    torque ramps and InTorque rises; there is no drive, so the axis does not move and DrvStatus keeps CSP (D24)."""
    c = Controller(axis_project())
    power_on(c, "MC_Axis001")
    m = c.mc
    tc = c.fb("MC_TorqueControl", Axis="MC_Axis001", Execute=True, Torque=5.0, TorqueRamp=1000.0, Velocity=10.0)
    c.step(1)
    assert tc.Busy and m.trq_cmd[1] == pytest.approx(1.0) and m.axes[1].state == AxisState.Continuous
    c.step(4)
    assert m.trq_cmd[1] == 5.0 and not tc.InTorque
    c.step(1)
    assert tc.InTorque and m.act_trq[1] == 5.0 and m.act_pos[1] == 0.0
    assert _drv(c, 1)["CSP"] and not _drv(c, 1)["CST"]


def test_axis_variable_status_home_and_torque() -> None:
    """`_sAXIS_REF` during torque control: Status.Continuous, DrvStatus.CST, home stays defined (seed "home
    state"), Cmd.Trq = the command torque, Act.Trq = 6077h; outside torque control Cmd.Trq reads Act.Trq
    (omron-mc-basics.md §2.3)."""
    c = _ctrl(axis_project(encoder="absolute"))  # absolute encoder: home defined at servo ON
    tc = _tc(c, Torque=20.0, TorqueRamp=1000.0, Velocity=200.0)
    step_until(c, tc, "InTorque")
    studio = Studio(runner=Runner(c), project_dir=None, projects_root=None)
    v = dict(studio.axis_views(c.publish(), [AX]))[AX]
    assert v["Status"]["Continuous"] and not v["Status"]["Standstill"]
    assert v["DrvStatus"]["CST"] and not v["DrvStatus"]["CSP"] and v["DrvStatus"]["ServoOn"]
    assert v["Details"]["Homed"]
    assert v["Cmd"]["Trq"] == 20.0 and v["Act"]["Trq"] == 20.0
    stop = c.fb("MC_Stop", Axis=AX, Execute=True)
    step_until(c, stop, "Done")
    c.step(2)
    v = dict(studio.axis_views(c.publish(), [AX]))[AX]
    assert v["Details"]["Homed"] and v["DrvStatus"]["CSP"]
    assert v["Cmd"]["Trq"] == v["Act"]["Trq"] == c.mc.act_trq[0]


def test_override_does_not_apply() -> None:
    """MC_SetOverride applies to seven named instructions; MC_TorqueControl is not one of them: torque and velocity
    limit are unchanged by a 50 % override."""
    c = _ctrl()
    _tc(c, Torque=20.0, Velocity=10.0)
    c.step(2)
    before = (_rx(c, "target_torque"), _rx(c, "max_profile_velocity"))
    ov = c.fb("MC_SetOverride", Axis=AX, Enable=True, VelFactor=50.0)
    c.step(3)
    assert ov.Enabled and (_rx(c, "target_torque"), _rx(c, "max_profile_velocity")) == before


# ---------------------------------------------------------------------------------------------- back to CSP

def _running(c: Controller, **inputs: Any) -> FunctionBlock:
    tc = _tc(c, **{"Torque": 20.0, "Velocity": 30.0, **inputs})
    c.step(300)
    assert tc.InTorque and c.mc.act_vel[0] == pytest.approx(30.0, abs=0.01)
    return tc


def test_abort_by_move_velocity_switches_back_to_csp_without_a_jump() -> None:
    """Another instruction aborting torque control switches to position control at once (seed "control mode
    switching"): CommandAborted in that period, 6060h = 8 in its outputs, the drive in CSP one period later; the new
    profile starts from the feedback position and velocity, so the shaft moves on without a jump (D25)."""
    c = _ctrl()
    m = c.mc
    tc = _running(c)
    mv = c.fb("MC_MoveVelocity", Axis=AX, Execute=True, Velocity=10.0, Acceleration=100.0, Deceleration=100.0)
    c.step(1)  # period A
    p_a = float(m.act_pos[0])
    assert tc.CommandAborted and not tc.Busy and not tc.Active and not tc.InTorque
    assert mv.Busy and _rx(c, "modes_of_operation") == CSP and _rx(c, "target_torque") == 0
    # the first position command is one period ahead of the feedback, at the feedback velocity
    assert m.cmd_pos[0] - p_a == pytest.approx(30.0 * 0.001, abs=2e-4)
    c.step(1)  # A+1: the drive is in CSP at that command
    assert _drv(c)["CSP"] and not _drv(c)["CST"] and mv.Active
    assert m.act_pos[0] - p_a == pytest.approx(30.0 * 0.001, abs=2e-4)
    last = float(m.act_pos[0])
    for _ in range(300):
        c.step(1)
        step = float(m.act_pos[0]) - last
        last = float(m.act_pos[0])
        assert 0.0 <= step <= 30.0 * 0.001 + 1e-6, "decelerating at 100 mm/s² to 10 mm/s, no jump"
    assert mv.InVelocity and m.cmd_vel[0] == pytest.approx(10.0)


def test_stop_locks_the_servo_at_the_feedback_position() -> None:
    """MC_Stop during torque control stops immediately, its Deceleration not applied (seed "axis stop during torque
    control"); the drive is servo-locked at the feedback position when it switches to CSP (seed "control mode
    switching decision", other vendors' drives). Done one period later, Stopping while Execute is TRUE (D25)."""
    c = _ctrl()
    m = c.mc
    tc = _running(c)
    stop = c.fb("MC_Stop", Axis=AX, Execute=True, Deceleration=10.0)
    c.step(1)  # period S
    p_s = float(m.act_pos[0])
    assert tc.CommandAborted and stop.Busy and m.axes[0].state == AxisState.Stopping
    assert _rx(c, "modes_of_operation") == CSP and m.cmd_pos[0] == p_s
    c.step(1)
    assert stop.Done and _drv(c)["CSP"] and m.act_pos[0] == p_s and m.act_vel[0] == 0.0
    c.step(100)
    assert m.act_pos[0] == p_s and m.axes[0].state == AxisState.Stopping
    stop.Execute = False
    c.step(1)
    assert m.axes[0].state == AxisState.Standstill


def test_error_stop_and_servo_off_switch_back_to_csp() -> None:
    """An axis error during torque control stops the axis immediately (a deceleration stop is handled as an
    immediate stop, seed "axis stop during torque control"); servo OFF switches the drive back to CSP (seed "servo
    OFF")."""
    c = _ctrl()
    tc = _running(c)
    c.fb("MC_ImmediateStop", Axis=AX, Execute=True)
    c.step(1)
    p = float(c.mc.act_pos[0])
    assert tc.CommandAborted and c.mc.axes[0].state == AxisState.ErrorStop
    assert _rx(c, "modes_of_operation") == CSP
    c.step(5)
    assert _drv(c)["CSP"] and c.mc.act_pos[0] == p
    c2 = _ctrl()
    ax = c2.mc.axes[0]
    tc2 = _running(c2)
    power = next(e.fb for e in c2.program.values() if e.fb.DEF.name == "MC_Power")
    power.Enable = False
    c2.step(1)
    assert tc2.CommandAborted and _rx(c2, "modes_of_operation") == CSP
    c2.step(3)
    assert not ax.servo_on and ax.state == AxisState.Disabled and _tx(c2, "modes_display") == CSP


def test_following_error_is_not_checked_in_torque_control() -> None:
    """In torque control the position loop is off (Cmd.Pos is the feedback of one period earlier): a following
    error limit smaller than one period's travel does not stop the axis."""
    c = _ctrl(axis_project(Limit={"FollowingErrorOverVal": 0.001}))
    tc = _running(c)
    assert tc.Busy and not tc.Error and c.mc.axes[0].state == AxisState.Continuous


def test_software_limit_in_torque_control() -> None:
    """Software limits apply in torque control even when they are set for the command position with a
    deceleration stop (seed "software limits"): the axis stops at once at the feedback position (D25)."""
    c = _ctrl(axis_project(encoder="absolute", Limit={"SwLimitMode": "_mcCmdDecelerationStop",
                                                      "PosiSwLimit": 5.0, "NegaSwLimit": -5.0}))
    m = c.mc
    tc = _tc(c, Torque=20.0, Velocity=30.0)
    step_until(c, tc, "CommandAborted", limit=2000)
    assert m.axes[0].state == AxisState.ErrorStop and m.axes[0].error_code == 0x6450
    p = float(m.act_pos[0])
    assert 5.0 <= p <= 5.0 + 30.0 * 0.001 + 1e-6
    c.step(5)
    assert m.act_pos[0] == p and _drv(c)["CSP"]


# ---------------------------------------------------------------------------------------------- re-execution

def test_reexecution_changes_torque_ramp_and_velocity() -> None:
    """Re-execution may change Torque, TorqueRamp and Velocity; a new target torque drops InTorque until the drive
    has it (seed "re-execution"); the ramp continues from the current command torque. Velocity alone keeps
    InTorque."""
    c = _ctrl()
    m = c.mc
    tc = _tc(c, Torque=10.0, TorqueRamp=1000.0, Velocity=200.0)
    step_until(c, tc, "InTorque")
    tc.Execute = False
    c.step(1)
    tc.Velocity = 100.0
    tc.Execute = True
    c.step(1)
    assert tc.InTorque and _rx(c, "max_profile_velocity") == round(100.0 * PPU)
    tc.Execute = False
    c.step(1)
    tc.Torque, tc.TorqueRamp, tc.Execute = 4.0, 2000.0, True
    c.step(1)  # period R
    assert not tc.InTorque and tc.Busy and tc.Active and not tc.Error
    assert m.trq_cmd[0] == pytest.approx(8.0), "from 10 % down at 2 %/ms"
    c.step(2)
    assert m.trq_cmd[0] == 4.0 and not tc.InTorque
    c.step(1)
    assert tc.InTorque and m.act_trq[0] == 4.0


@pytest.mark.parametrize(("change", "code"), [({"Direction": "_mcNegativeDirection"}, 0x5455),
                                              ({"BufferMode": "_mcBuffered"}, 0x5454)])
def test_reexecution_of_direction_or_buffer_mode_is_an_error(change: dict, code: int) -> None:
    """Direction and BufferMode cannot change on re-execution (A-2.3: 5455, 5454); the axis stops (immediately in
    torque control) and returns to CSP."""
    c = _ctrl()
    tc = _tc(c, Torque=10.0, Velocity=20.0)
    c.step(5)
    tc.Execute = False
    c.step(1)
    tc.set_inputs({**change, "Execute": True})
    c.step(1)
    assert tc.Error and tc.ErrorID == code and not tc.Busy and not tc.InTorque
    assert c.mc.axes[0].state == AxisState.ErrorStop and _rx(c, "modes_of_operation") == CSP


# ---------------------------------------------------------------------------------------------- multi-execution

def test_torque_control_aborting_torque_control_reverses_with_the_ramp() -> None:
    """A second MC_TorqueControl (Aborting) takes over at once; a reversal of the torque follows the new
    TorqueRamp from the current command torque, whatever [Operation Selection at Reversing] (seed "reversal")."""
    c = _ctrl()
    m = c.mc
    first = _tc(c, Torque=10.0, Velocity=200.0)
    step_until(c, first, "InTorque")
    second = _tc(c, Torque=10.0, TorqueRamp=1000.0, Velocity=200.0, Direction="_mcNegativeDirection")
    c.step(1)
    assert first.CommandAborted and second.Busy and m.axes[0].state == AxisState.Continuous
    assert _rx(c, "modes_of_operation") == CST and m.trq_cmd[0] == pytest.approx(9.0)
    for expect in (8.0, 7.0, 6.0):
        c.step(1)
        assert m.trq_cmd[0] == pytest.approx(expect) and _drv(c)["CST"]
    step_until(c, second, "InTorque")
    assert m.trq_cmd[0] == -10.0


def test_buffered_torque_control_starts_when_the_positioning_is_done() -> None:
    """BufferMode _mcBuffered: MC_TorqueControl waits for the running positioning's Done, then switches to torque
    control (seed "control mode switching"); Active shows with the Done."""
    c = _ctrl()
    m = c.mc
    mv = c.fb("MC_MoveRelative", Axis=AX, Execute=True, Distance=2.0, Velocity=20.0, Acceleration=200.0,
              Deceleration=200.0)
    c.step(2)
    tc = _tc(c, Torque=5.0, Velocity=10.0, BufferMode="_mcBuffered")
    c.step(1)
    assert tc.Busy and not tc.Active and mv.Active and _rx(c, "modes_of_operation") == CSP
    step_until(c, mv, "Done")
    assert tc.Active and _rx(c, "modes_of_operation") == CST and m.cmd_pos[0] == pytest.approx(2.0)
    c.step(1)
    assert _drv(c)["CST"]
    step_until(c, tc, "InTorque")


def test_instruction_buffered_on_torque_control_starts_at_in_torque() -> None:
    """Others may multi-execute onto MC_TorqueControl with Aborting or Buffered; a buffered instruction starts when
    InTorque rises (the "Done or InVelocity" rule, omron-mc-basics.md §1.5, D24); Blending is 543C (D18)."""
    c = _ctrl()
    tc = _tc(c, Torque=2.0, TorqueRamp=100.0, Velocity=200.0)  # 2 % after 20 periods: InTorque at E+20
    c.step(1)  # E
    mv = c.fb("MC_MoveVelocity", Axis=AX, Execute=True, Velocity=5.0, Acceleration=1000.0, Deceleration=1000.0,
              BufferMode="_mcBuffered")
    c.step(1)
    assert mv.Busy and not mv.Active and tc.Active and not tc.InTorque
    assert step_until(c, tc, "CommandAborted") == 19, "taken over in the period InTorque would rise"
    assert mv.Busy and _rx(c, "modes_of_operation") == CSP
    step_until(c, mv, "InVelocity")
    assert c.publish().mc["cmd_trq"][0] == c.mc.act_trq[0], "Cmd.Trq reads Act.Trq outside torque control"
    c2 = _ctrl()
    _tc(c2, Torque=2.0, Velocity=20.0)
    c2.step(2)
    ma = c2.fb("MC_MoveAbsolute", Axis=AX, Execute=True, Position=5.0, Velocity=10.0, Acceleration=100.0,
               Deceleration=100.0, BufferMode="_mcBlendingLow")
    c2.step(1)
    assert ma.Error and ma.ErrorID == 0x543C


# ---------------------------------------------------------------------------------------------- errors

@pytest.mark.parametrize(("inputs", "code"), [
    ({"TorqueRamp": -1.0}, 0x5427),
    ({"Velocity": -0.001}, 0x5422),
    ({"Direction": "_mcShortestWay"}, 0x542E),
    ({"Direction": "_mcCurrentDirection"}, 0x542E),
    ({"Direction": "_mcNoDirection"}, 0x542E),
    ({"BufferMode": "_mcBlendingLow"}, 0x542B),
    ({"BufferMode": 6}, 0x542B),
])
def test_input_errors(inputs: dict, code: int) -> None:
    """Inputs out of their valid range (seed 10597 input table; A-1 5427 Torque Ramp, 5422 velocity, 542E
    direction, 542B buffer mode): Error at start, the axis error-stops (A-1 effect AX-D)."""
    c = _ctrl()
    tc = _tc(c, **{"Torque": 10.0, "Velocity": 10.0, **inputs})
    c.step(1)
    assert tc.Error and tc.ErrorID == code and not tc.Busy
    assert c.mc.axes[0].state == AxisState.ErrorStop and _rx(c, "modes_of_operation") == CSP
    assert any(e.code == f"{code:04X}0000" for e in c.events.list())


def test_servo_off_encoder_axis_and_homing() -> None:
    """Servo OFF: 5441 (A-1 #34); encoder axis: 543D (A-3.7); during homing: 543C (A-3.4 F → H, D6)."""
    c = Controller(axis_project())
    c.step(2)
    tc = _tc(c, Torque=10.0)
    c.step(1)
    assert tc.Error and tc.ErrorID == 0x5441
    p = axis_project(sensors={"HomeProximityStart": 500.0, "HomeProximityEnd": 510.0},
                     Homing={"Mode": "_mcHomeSwTurnHomeSwOff", "Vel": 10.0, "ApproachVel": 1.0})
    p.axes[1].type = "_mcEncdr"  # type: ignore[assignment]
    p.axes[1].node_address = 2
    c = Controller(p)
    power_on(c)
    enc = c.fb("MC_TorqueControl", Axis="MC_Axis001", Execute=True, Torque=10.0)
    c.step(1)
    assert enc.Error and enc.ErrorID == 0x543D and c.mc.axes[1].state == AxisState.ErrorStop
    home = c.fb("MC_Home", Axis=AX, Execute=True)
    c.step(5)
    assert home.Busy and c.mc.axes[0].state == AxisState.Homing
    tc = _tc(c, Torque=10.0)
    c.step(1)
    assert tc.Error and tc.ErrorID == 0x543C


def test_command_aborted_while_stopping() -> None:
    """Started while MC_Stop is executing: CommandAborted, no error (seed 10597 output table)."""
    c = _ctrl()
    stop = c.fb("MC_Stop", Axis=AX, Execute=True)
    c.step(2)
    tc = _tc(c, Torque=10.0)
    c.step(1)
    assert tc.CommandAborted and not tc.Error and not tc.Busy and stop.Done
    assert _rx(c, "modes_of_operation") == CSP


def test_missing_pdo_objects_give_3461() -> None:
    """6071h, 6060h, 6077h and 6061h must be mapped, else 3461 (seed "mapping of data objects"; omron-mc-basics.md
    §2.11). The fixed mapping has them; the axis's mapped objects stand in for a mapping without 6077h."""
    c = _ctrl()
    c.mc.pdo_objects[0] = c.mc.pdo_objects[0] - {0x6077}  # type: ignore[operator]
    tc = _tc(c, Torque=10.0)
    c.step(1)
    assert tc.Error and tc.ErrorID == 0x3461 and c.mc.axes[0].state == AxisState.ErrorStop


def test_drive_without_cst_gives_7439_after_one_second() -> None:
    """If the drive has not switched to CST 1 s after the command: 7439 (servo drive control mode switching
    error), servo OFF with a free-run stop (seed "control mode switching failure"; a drive without CST, D26). Until
    then position control is held: the command position does not move."""
    c = _ctrl(CyclicTorqueMode=False)
    tc = _tc(c, Torque=10.0, Velocity=10.0)
    c.step(1)  # the request is sent in this period's outputs
    assert tc.Busy and _rx(c, "modes_of_operation") == CST
    c.step(999)
    assert tc.Active and not tc.Error and not tc.InTorque and _drv(c)["CSP"] and c.mc.act_pos[0] == 0.0
    c.step(1)  # 1000 periods = 1 s after the request
    assert tc.Error and tc.ErrorID == 0x7439 and not tc.Busy
    assert c.mc.axes[0].state == AxisState.ErrorStop
    c.step(2)
    assert not c.mc.axes[0].servo_on


def test_limit_input_in_the_torque_direction_at_start() -> None:
    """An active limit input in the direction of the torque refuses the start (6443/6444, as for the other
    continuous instructions)."""
    c = _ctrl(axis_project(sensors={"PositiveLimit": -1.0}))
    tc = _tc(c, Torque=10.0)
    c.step(1)
    assert tc.Error and tc.ErrorID == 0x6443


def test_set_position_during_torque_control_is_an_error() -> None:
    """MC_SetPosition on an axis executing MC_TorqueControl: multi-execution error (A-3.4 footnote *5, seed 000
    line 6287) — 543C (D6); the axis error-stops and torque control is aborted."""
    c = _ctrl()
    tc = _tc(c, Torque=10.0, Velocity=10.0)
    c.step(3)
    sp = c.fb("MC_SetPosition", Axis=AX, Execute=True, Position=100.0)
    c.step(1)
    assert sp.Error and sp.ErrorID == 0x543C
    assert tc.CommandAborted and c.mc.axes[0].state == AxisState.ErrorStop
    assert c.mc.act_pos[0] < 1.0, "the position was not changed"


# ---------------------------------------------------------------------------------------------- MC_SetTorqueLimit

def _limit(c: Controller, axis: str = AX, **inputs: Any) -> FunctionBlock:
    return c.fb("MC_SetTorqueLimit", Axis=axis, Enable=True, **inputs)


def test_set_torque_limit_limits_the_applied_torque() -> None:
    """While Enable is TRUE, PositiveEnable limits the positive torque at PositiveValue (60E0h), NegativeEnable the
    negative torque at NegativeValue (60E1h); a direction enable FALSE sends the axis parameter [Maximum ... Torque
    Limit] (seed 10917 functional rules, D27). The drive applies it in CST: 6077h at the limit, DrvStatus.ILA."""
    c = _ctrl()
    m = c.mc
    assert (_rx(c, "positive_torque_limit"), _rx(c, "negative_torque_limit")) == (3000, 3000)
    lim = _limit(c, PositiveEnable=True, PositiveValue=20.0, NegativeValue=5.0)
    c.step(1)  # period L: written in this period's outputs
    assert lim.Enabled and lim.Busy and not lim.Error
    assert (_rx(c, "positive_torque_limit"), _rx(c, "negative_torque_limit")) == (200, 3000)
    tc = _tc(c, Torque=50.0, Velocity=400.0)
    step_until(c, tc, "InTorque")
    for _ in range(20):
        c.step(1)
        assert m.trq_cmd[0] == 50.0 and m.act_trq[0] == 20.0 and _drv(c)["ILA"]
    # the negative side: enabled at 5 %, changed while Enable stays TRUE (inputs applied every period)
    lim.NegativeEnable = True
    c.step(1)
    assert _rx(c, "negative_torque_limit") == 50
    rev = _tc(c, Torque=50.0, Velocity=400.0, Direction="_mcNegativeDirection")  # aborts the first one
    step_until(c, rev, "InTorque")
    assert tc.CommandAborted
    c.step(1)
    assert m.act_trq[0] == -5.0 and _drv(c)["ILA"]
    lim.Enable = False  # Enable FALSE: both parameter values, Busy/Enabled FALSE
    c.step(1)
    assert not lim.Enabled and not lim.Busy
    assert (_rx(c, "positive_torque_limit"), _rx(c, "negative_torque_limit")) == (3000, 3000)
    c.step(1)
    assert m.act_trq[0] == -50.0 and not _drv(c)["ILA"]


@pytest.mark.parametrize(("value", "sent"), [(500.0, 2500), (0.0, 0), (-3.0, 0), (12.25, 123), (0.04, 0)])
def test_set_torque_limit_values(value: float, sent: int) -> None:
    """PositiveValue above the axis parameter [Maximum Positive Torque Limit] acts as that parameter; 0 or negative
    act as 0; 0.1 % resolution, rounded half up (seed 10917 input table)."""
    c = _ctrl(axis_project(OtherOperation={"MaxPosiTrqLimit": 250.0}))
    _limit(c, PositiveEnable=True, PositiveValue=value)
    c.step(1)
    assert _rx(c, "positive_torque_limit") == sent


def test_set_torque_limit_zero_holds_the_positive_torque_at_zero() -> None:
    """A positive limit of 0: the drive outputs no positive torque; the axis does not move."""
    c = _ctrl()
    _limit(c, PositiveEnable=True, PositiveValue=0.0)
    tc = _tc(c, Torque=30.0, Velocity=100.0)
    step_until(c, tc, "InTorque")
    c.step(50)
    assert c.mc.act_trq[0] == 0.0 and c.mc.act_pos[0] == 0.0


def test_set_torque_limit_enabled_follows_the_servo() -> None:
    """Enabled is TRUE only with the servo ON; with the servo OFF the limit is not applied (the parameter values are
    sent); Busy follows Enable (seed 10917 output table and "usable axes")."""
    c = Controller(axis_project())
    lim = _limit(c, PositiveEnable=True, PositiveValue=10.0)
    c.step(2)
    assert lim.Busy and not lim.Enabled and _rx(c, "positive_torque_limit") == 3000
    pw = power_on(c)
    c.step(1)
    assert lim.Busy and lim.Enabled and _rx(c, "positive_torque_limit") == 100
    pw.Enable = False
    c.step(3)
    assert lim.Busy and not lim.Enabled and _rx(c, "positive_torque_limit") == 3000


def test_set_torque_limit_later_instance_has_priority() -> None:
    """Two instances on one axis: the later one's values apply, both show Enabled; the later one's Enable FALSE
    disables the torque limit (seed 10917 "multi-execution")."""
    c = _ctrl()
    a = _limit(c, PositiveEnable=True, PositiveValue=40.0)
    c.step(1)
    b = _limit(c, PositiveEnable=True, PositiveValue=10.0)
    c.step(1)
    assert a.Enabled and b.Enabled and _rx(c, "positive_torque_limit") == 100
    a.PositiveValue = 30.0  # the earlier instance no longer controls the limit
    c.step(1)
    assert _rx(c, "positive_torque_limit") == 100
    b.Enable = False
    c.step(1)
    assert a.Enabled and not b.Enabled and _rx(c, "positive_torque_limit") == 3000


def test_set_torque_limit_axis_types_and_pdo() -> None:
    """Encoder axes: error at start, 543D (A-3.7); virtual servo axes accept it and do nothing; 60E0h/60E1h must be
    mapped, else 3461 (seed 10917 "mapping of data objects")."""
    p = axis_project()
    p.axes[1].type = "_mcEncdr"  # type: ignore[assignment]
    p.axes[1].node_address = 2
    c = Controller(p)
    enc = _limit(c, "MC_Axis001", PositiveEnable=True, PositiveValue=10.0)
    c.step(1)
    assert enc.Error and enc.ErrorID == 0x543D and c.mc.axes[1].state == AxisState.ErrorStop
    c = Controller(axis_project())
    power_on(c, "MC_Axis001")
    virt = _limit(c, "MC_Axis001", PositiveEnable=True, PositiveValue=10.0)
    c.step(1)
    assert virt.Enabled and not virt.Error and c.mc.trq_lim_pos[1] == 300.0
    c = _ctrl()
    c.mc.pdo_objects[0] = c.mc.pdo_objects[0] - {0x60E1}  # type: ignore[operator]
    lim = _limit(c, NegativeEnable=True, NegativeValue=10.0)
    c.step(1)
    assert lim.Error and lim.ErrorID == 0x3461 and not lim.Enabled and _rx(c, "negative_torque_limit") == 3000


def test_touch_probe_immediate_stop_needs_csp() -> None:
    """MC_TouchProbe with StopMode _mcImmediateStop works only in CSP: started in torque control → 5492; armed
    before and the axis switched to torque control → CommandAborted (omron-axis-instructions.md MC_TouchProbe,
    StopMode)."""
    ext1 = {"Mode": "_mcDrive", "LatchID": "_mcLatch1", "InputDrive": "_mcEXT"}
    c = _ctrl()
    tp = c.fb("MC_TouchProbe", Axis=AX, Execute=True, TriggerInput=ext1, StopMode="_mcImmediateStop")
    c.step(2)
    assert tp.Busy and not tp.Error
    tc = _tc(c, Torque=5.0, Velocity=10.0)
    c.step(1)
    assert tc.Busy and tp.CommandAborted and not tp.Busy
    late = c.fb("MC_TouchProbe", Axis=AX, Execute=True, TriggerInput=ext1, StopMode="_mcImmediateStop")
    c.step(1)
    assert late.Error and late.ErrorID == 0x5492
    nonstop = _ctrl()
    _tc(nonstop, Torque=5.0, Velocity=10.0)
    nonstop.step(2)
    ok = nonstop.fb("MC_TouchProbe", Axis=AX, Execute=True, TriggerInput=ext1)  # StopMode _mcNonStop
    nonstop.step(1)
    assert ok.Busy and not ok.Error
