"""The MC layer on the second-order drive model: following error visible in Act vs Cmd, Done waiting for
in-position, the torque limit making the axis lag, the drive's following-error window, an encoder axis on an encoder
input slave.

Spec: omron-axis-instructions.md MC_MoveAbsolute timing (Done "when the target is reached and positioning is complete
(in-position check per [In-position Range] / [In-position Check Time])", digest line 468), omron-group-and-cam.md
§5.5 In-position Check Time (L1487), omron-mc-basics.md §2.3 (Cmd/Act, Details.InPosWaiting, DrvStatus.ILA ← 6041h
bit 11). Drive and mechanism: docs/ethercat.md "Drives and mechanism"; decisions D9, D29.
"""

from __future__ import annotations

import math

import pytest

from mcstudio.controller.kernel import Controller
from mcstudio.controller.mc.module import drv_status
from mcstudio.project.models import AxisConfig, EtherCATSlaveConfig, Project
from tests.conftest import MM_AXIS, axis_project, power_on, step_until

AX = "MC_Axis000"


def _second_order(bandwidth: float = 30.0, damping: float = 1.0, ff: float = 0.0, **groups: dict) -> Controller:
    p = axis_project(**groups)
    d = p.axes[0].drive
    d.PositionLoop, d.PositionLoopBandwidth, d.PositionLoopDamping, d.VelocityFeedForward = \
        "SecondOrder", bandwidth, damping, ff
    c = Controller(p)
    power_on(c)
    return c


def test_following_error_is_visible_at_constant_velocity() -> None:
    """At constant velocity v the loop lags by 2ζ·v/ωn (no feed-forward): 100 mm/s, ζ = 1, 30 Hz → 1.061 mm, plus one
    period of travel (0.1 mm): Act.Pos is read in the period after the command went out (D1)."""
    c = _second_order()
    c.fb("MC_MoveVelocity", Axis=AX, Execute=True, Velocity=100.0, Acceleration=1000.0, Deceleration=1000.0)
    c.step(600)  # 0.1 s ramp, then 0.5 s at speed: the transient has died out
    lag = float(c.mc.cmd_pos[0] - c.mc.act_pos[0])
    assert lag == pytest.approx(100.0 * 0.001 + 2 * 1.0 * 100.0 / (2 * math.pi * 30.0), rel=0.01)
    assert float(c.mc.act_vel[0]) == pytest.approx(100.0, rel=1e-3)


def test_feed_forward_removes_the_lag() -> None:
    c = _second_order(ff=100.0)
    c.fb("MC_MoveVelocity", Axis=AX, Execute=True, Velocity=100.0, Acceleration=1000.0, Deceleration=1000.0)
    c.step(600)
    assert float(c.mc.cmd_pos[0] - c.mc.act_pos[0]) == pytest.approx(0.1, abs=1e-4)  # only the period of transport


def test_done_waits_for_in_position() -> None:
    """In-position Check Time 100 ms, range 0.01 mm: the command reaches 10 mm at the end of the profile, InPosWaiting
    is TRUE while the shaft settles, Done comes once |Act − 10| ≤ 0.01 — several periods later."""
    c = _second_order(Operation={"InPosCheckTime": 100, "InPosRange": 0.01})
    mv = c.fb("MC_MoveAbsolute", Axis=AX, Execute=True, Position=10.0, Velocity=100.0, Acceleration=1000.0,
              Deceleration=1000.0)
    ax = c.mc.axes[0]
    n = 0
    while not ax.in_pos_waiting and n < 1000:
        c.step(1)
        n += 1
    assert ax.in_pos_waiting and not mv.Done and float(c.mc.cmd_pos[0]) == 10.0
    assert abs(float(c.mc.act_pos[0]) - 10.0) > 0.01, "the shaft lags when the command arrives"
    waited = step_until(c, mv, "Done")
    assert waited > 3
    assert abs(float(c.mc.act_pos[0]) - 10.0) <= 0.01 and not ax.in_pos_waiting


def test_without_check_time_done_does_not_wait() -> None:
    """In-position Check Time 0 (D9): Done when the command reaches the target, the shaft still lagging."""
    c = _second_order()
    mv = c.fb("MC_MoveAbsolute", Axis=AX, Execute=True, Position=10.0, Velocity=100.0, Acceleration=1000.0,
              Deceleration=1000.0)
    step_until(c, mv, "Done")
    assert abs(float(c.mc.act_pos[0]) - 10.0) > 0.01


def test_torque_limit_makes_the_axis_lag_and_sets_ila() -> None:
    """MC_SetTorqueLimit 5 %: the acceleration needs more torque, the drive saturates (6041h bit 11 → DrvStatus.ILA)
    and the following error grows far beyond the unlimited loop's."""
    c = _second_order(bandwidth=50.0)
    c.fb("MC_SetTorqueLimit", Axis=AX, Enable=True, PositiveEnable=True, PositiveValue=5.0, NegativeEnable=True,
         NegativeValue=5.0)
    c.step(2)
    c.fb("MC_MoveVelocity", Axis=AX, Execute=True, Velocity=500.0, Acceleration=10000.0, Deceleration=10000.0)
    ila = False
    for _ in range(60):
        c.step(1)
        ila |= drv_status(int(c.mc.drv[0]))["ILA"]
    assert ila
    assert float(c.mc.cmd_pos[0] - c.mc.act_pos[0]) > 5.0


def test_drive_following_error_window_faults_the_drive() -> None:
    """6065h = 1000 pulses (start-up SDO): a lag beyond it for longer than 6066h = 0 ms → drive fault 8611h → axis
    3002 with the code in the event."""
    p = axis_project()
    p.axes[0].drive.PositionLoop = "SecondOrder"
    p.ethercat.slaves = [EtherCATSlaveConfig(node_address=1, startup_sdos=[
        {"index": 0x6065, "value": 1000, "bit_len": 32}])]
    c = Controller(p)
    power_on(c)
    c.fb("MC_MoveVelocity", Axis=AX, Execute=True, Velocity=100.0, Acceleration=1000.0, Deceleration=1000.0)
    c.step(200)
    assert c.mc.axes[0].error_code == 0x3002
    assert any(e.code == "30020000" and "8611h" in e.detail for e in c.events.list())


def test_encoder_axis_on_an_encoder_input_slave() -> None:
    """An encoder axis on the built-in encoder input (4010h aliased to the position): the encoder turns at
    104857.6 pulses/s = 1 mm/s; Act.Pos follows."""
    p = Project(name="enc", axes=[
        AxisConfig(name="MC_Axis000", number=0, type="_mcEncdr", node_address=5, parameters=MM_AXIS)])
    p.ethercat.slaves = [EtherCATSlaveConfig(node_address=5, device="builtin:encoder-input",
                                             emulation={"encoder_velocity": 104857.6})]
    c = Controller(p)
    assert c.mc.axes[0].error_code == 0
    c.step(1000)
    assert float(c.mc.act_pos[0]) == pytest.approx(1.0, abs=2e-3)
    assert 0x6064 in c.network.mapped_objects(0)


def test_degenerate_drive_parameters_are_rejected_at_load() -> None:
    from mcstudio.project.io import ProjectError, parse_project

    doc = axis_project().model_dump(mode="json")
    doc["axes"][0]["drive"].update(PositionLoop="SecondOrder", PositionLoopBandwidth=400.0)
    with pytest.raises(ProjectError) as err:
        parse_project(doc)
    assert err.value.issues[0].path == "axes[0].drive.PositionLoopBandwidth"
    doc["axes"][0]["drive"].update(PositionLoopBandwidth=0.0)
    with pytest.raises(ProjectError) as err:
        parse_project(doc)
    assert err.value.issues[0].path == "axes[0].drive.PositionLoopBandwidth"
    doc["axes"][0]["drive"].update(PositionLoopBandwidth=50.0, PositionLoopDamping=0.0)
    with pytest.raises(ProjectError) as err:
        parse_project(doc)
    assert err.value.issues[0].path == "axes[0].drive.PositionLoopDamping"
