"""MC_TouchProbe, MC_AbortTrigger and MC_MoveFeed with the drive's touch probe and in controller mode.

Spec: omron-axis-instructions.md MC_TouchProbe (seed 000 line 11271), MC_AbortTrigger (11881), MC_MoveFeed (5064).
The fixture's external latch input 1 is ON between 40 and 42 mm, input 2 between 60 and 61 mm.
"""

from __future__ import annotations

import pytest

from mcstudio.controller.kernel import Controller
from mcstudio.controller.mc.enums import AxisState
from tests.conftest import axis_project, power_on, step_until

SENSORS = {"ExternalHomeStart": 40.0, "ExternalHomeEnd": 42.0, "Latch2Start": 60.0, "Latch2End": 61.0,
           "ZPhaseOffset": 1000}
EXT1 = {"Mode": "_mcDrive", "LatchID": "_mcLatch1", "InputDrive": "_mcEXT"}
EXT2 = {"Mode": "_mcDrive", "LatchID": "_mcLatch2", "InputDrive": "_mcEXT"}


@pytest.fixture
def c() -> Controller:
    ctrl = Controller(axis_project(sensors=SENSORS))
    power_on(ctrl)
    return ctrl


def _run(c: Controller, v: float = 20.0) -> object:
    return c.fb("MC_MoveVelocity", Axis="MC_Axis000", Execute=True, Velocity=v, Acceleration=200.0,
                Deceleration=200.0)


def test_touch_probe_records_the_exact_edge_position(c: Controller) -> None:
    tp = c.fb("MC_TouchProbe", Axis="MC_Axis000", Execute=True, TriggerInput=EXT1)
    _run(c)
    c.step(1)
    assert tp.Busy and not tp.Done
    step_until(c, tp, "Done")
    assert tp.RecordedPosition == pytest.approx(40.0, abs=0.5 / 104857.6), "the drive latch, not the period sample"
    assert not tp.Busy and c.mc.axes[0].state == AxisState.Continuous, "StopMode _mcNonStop: keeps moving"


def test_touch_probe_z_phase(c: Controller) -> None:
    tp = c.fb("MC_TouchProbe", Axis="MC_Axis000", Execute=True,
              TriggerInput={**EXT1, "InputDrive": "_mcEncoderMark"})
    _run(c)
    step_until(c, tp, "Done")
    assert tp.RecordedPosition == pytest.approx(1000 / 104857.6, abs=1e-9)


def test_touch_probe_window(c: Controller) -> None:
    """WindowOnly: triggers outside [First, Last] are ignored — the Z pulses at 0.0095 … 40.0095 are skipped."""
    tp = c.fb("MC_TouchProbe", Axis="MC_Axis000", Execute=True, WindowOnly=True, FirstPosition=45.0,
              LastPosition=55.0, TriggerInput={**EXT1, "InputDrive": "_mcEncoderMark"})
    _run(c, 50.0)
    step_until(c, tp, "Done")
    assert tp.RecordedPosition == pytest.approx(50.0 + 1000 / 104857.6, abs=1e-9)


def test_touch_probe_immediate_stop(c: Controller) -> None:
    """StopMode _mcImmediateStop: the running instruction is aborted, the axis returns to the latched position
    (Stopping meanwhile), Done when stopped there."""
    tp = c.fb("MC_TouchProbe", Axis="MC_Axis000", Execute=True, TriggerInput=EXT2, StopMode="_mcImmediateStop")
    mv = _run(c)
    step_until(c, mv, "CommandAborted")
    assert c.mc.axes[0].state == AxisState.Stopping
    step_until(c, tp, "Done")
    assert c.mc.act_pos[0] == pytest.approx(60.0, abs=0.5 / 104857.6)
    c.step(1)
    assert c.mc.axes[0].state == AxisState.Standstill


def test_new_touch_probe_on_the_same_latch_aborts_the_old(c: Controller) -> None:
    a = c.fb("MC_TouchProbe", Axis="MC_Axis000", Execute=True, TriggerInput=EXT1)
    c.step(2)
    b = c.fb("MC_TouchProbe", Axis="MC_Axis000", Execute=True, TriggerInput=EXT1)
    c.step(1)
    assert a.CommandAborted and b.Busy


def test_abort_trigger(c: Controller) -> None:
    tp = c.fb("MC_TouchProbe", Axis="MC_Axis000", Execute=True, TriggerInput=EXT1)
    c.step(2)
    ab = c.fb("MC_AbortTrigger", Axis="MC_Axis000", Execute=True, TriggerInput=EXT1)
    c.step(1)
    assert tp.CommandAborted
    c.step(1)
    assert ab.Done, "Done one period after Execute"
    _run(c)
    c.step(3000)
    assert not tp.Done


def test_controller_mode_trigger_variable(c: Controller) -> None:
    tp = c.fb("MC_TouchProbe", Axis="MC_Axis000", Execute=True, TriggerInput={"Mode": "_mcController"})
    _run(c)
    c.step(500)
    tp.TriggerVariable = True
    c.step(1)
    assert tp.Done and tp.RecordedPosition == pytest.approx(float(c.mc.act_pos[0]))


def test_touch_probe_input_errors(c: Controller) -> None:
    bad = c.fb("MC_TouchProbe", Axis="MC_Axis000", Execute=True, TriggerInput={"LatchID": 7})
    c.step(1)
    assert bad.Error and bad.ErrorID == 0x544E


def test_move_feed_relative_then_feed(c: Controller) -> None:
    """Relative move of 100; the interrupt at 40 mm (external input 1) feeds 5 mm from the latched position:
    InFeed, then Done at 45."""
    mf = c.fb("MC_MoveFeed", Axis="MC_Axis000", Execute=True, TriggerInput=EXT1, MoveMode="_mcRelative",
              Position=100.0, Velocity=20.0, Acceleration=200.0, Deceleration=200.0, FeedDistance=5.0,
              FeedVelocity=10.0)
    step_until(c, mf, "InFeed")
    step_until(c, mf, "Done")
    assert c.mc.act_pos[0] == pytest.approx(45.0, abs=0.5 / 104857.6)


def test_move_feed_without_interrupt(c: Controller) -> None:
    """No interrupt before the target: Done normally; with ErrorDetect the instruction ends CommandAborted."""
    mf = c.fb("MC_MoveFeed", Axis="MC_Axis000", Execute=True, TriggerInput=EXT1, MoveMode="_mcAbsolute",
              Position=20.0, Velocity=20.0, Acceleration=200.0, Deceleration=200.0, FeedDistance=5.0,
              FeedVelocity=10.0)
    step_until(c, mf, "Done")
    mf2 = c.fb("MC_MoveFeed", Axis="MC_Axis000", Execute=True, TriggerInput=EXT1, MoveMode="_mcAbsolute",
               Position=30.0, Velocity=20.0, Acceleration=200.0, Deceleration=200.0, FeedDistance=5.0,
               FeedVelocity=10.0, ErrorDetect=True)
    step_until(c, mf2, "CommandAborted")


def test_buffered_onto_move_feed_is_543c(c: Controller) -> None:
    mf = c.fb("MC_MoveFeed", Axis="MC_Axis000", Execute=True, TriggerInput=EXT1, MoveMode="_mcVelocity",
              Velocity=20.0, Acceleration=200.0, Deceleration=200.0, FeedDistance=5.0, FeedVelocity=10.0)
    c.step(10)
    nxt = c.fb("MC_MoveAbsolute", Axis="MC_Axis000", Execute=True, Position=0.0, Velocity=10.0,
               BufferMode="_mcBuffered")
    c.step(1)
    assert nxt.Error and nxt.ErrorID == 0x543C and mf.CommandAborted


@pytest.mark.parametrize(("inputs", "code"), [({"FeedVelocity": 0.0}, 0x542A), ({"MoveMode": 3}, 0x5431),
                                               ({"MoveMode": 2, "Direction": 1}, 0x542E)])
def test_move_feed_input_errors(c: Controller, inputs: dict, code: int) -> None:
    base = {"TriggerInput": EXT1, "MoveMode": 1, "Position": 10.0, "Velocity": 10.0, "FeedDistance": 1.0,
            "FeedVelocity": 5.0}
    mf = c.fb("MC_MoveFeed", Axis="MC_Axis000", Execute=True, **{**base, **inputs})
    c.step(1)
    assert mf.Error and mf.ErrorID == code
