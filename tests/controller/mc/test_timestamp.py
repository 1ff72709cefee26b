"""MC_TimeStampToPos and MC_DigitalCamSwitch on the emulated bus (DC time stamps, decision D48).

Spec: omron-axis-instructions.md MC_DigitalCamSwitch (seed 000 line 12897: switches, tracks, directions,
position-/time-based modes, compensation, EnableMask), MC_TimeStampToPos (line 13539: position at a time stamp from
the feedback position, velocity and the axis time stamp).
"""

from __future__ import annotations

import pytest

from mcstudio.controller.kernel import Controller
from mcstudio.controller.mc.fb.timestamp import axis_time_stamp
from tests.conftest import axis_project, power_on, step_until

AX = "MC_Axis000"


def _moving(velocity: float = 100.0, rotary: bool = True) -> Controller:
    kw = {"count_mode": "_mcCountModeRotary", "modulo": (0.0, 360.0)} if rotary else {}
    c = Controller(axis_project(**kw))
    power_on(c)
    mv = c.fb("MC_MoveVelocity", Axis=AX, Execute=True, Velocity=velocity, Acceleration=0.0, Deceleration=0.0)
    step_until(c, mv, "InVelocity")
    c.step(20)
    return c


def test_time_stamp_to_pos_extrapolates_the_feedback() -> None:
    """At constant velocity the position at a time stamp 2 ms after the axis's own is Act.Pos + 2 ms × Act.Vel;
    a later period's feedback agrees."""
    c = _moving(velocity=100.0, rotary=False)
    ax = c.mc.axes[0]
    ts = axis_time_stamp(ax)
    assert ts == round(c.mc.cycle * 1e6), "DC time of this period's position sample"
    fb = c.fb("MC_TimeStampToPos", Axis=AX, Enable=True, TimeStamp=ts + 2_000_000)
    c.step(1)  # the instance is called with this period's time stamp (1 ms later): 1 ms ahead of it
    assert fb.Enabled and fb.Busy and not fb.Error
    predicted = fb.CalcPosition
    c.step(1)
    assert float(c.mc.act_pos[0]) == pytest.approx(predicted, abs=1e-6)


def test_time_stamp_to_pos_on_a_virtual_axis_is_543d() -> None:
    c = Controller(axis_project())
    fb = c.fb("MC_TimeStampToPos", Axis="MC_Axis001", Enable=True, TimeStamp=0)
    c.step(1)
    assert fb.Error and fb.ErrorID == 0x543D


SWITCHES = [
    # the manual's example, scaled to a 0–360° ring: track 0 = switch 0 (ON 144→216 positive direction),
    # switch 2 (288→72 across the ring, both directions); track 1 = switch 3 (ON at 216 for 100 ms, time based)
    {"TrackNumber": 0, "FirstOnPosition": 144.0, "LastOnPosition": 216.0, "AxisDirection": "_mcPositiveDirection",
     "CamSwitchMode": "_mcPositionBased"},
    {"TrackNumber": 0, "FirstOnPosition": 180.0, "LastOnPosition": 216.0, "AxisDirection": "_mcNegativeDirection",
     "CamSwitchMode": "_mcPositionBased"},
    {"TrackNumber": 0, "FirstOnPosition": 288.0, "LastOnPosition": 72.0, "AxisDirection": "_mcNoDirection",
     "CamSwitchMode": "_mcPositionBased"},
    {"TrackNumber": 1, "FirstOnPosition": 216.0, "AxisDirection": "_mcNoDirection", "CamSwitchMode": "_mcTimeBased",
     "Duration": 100.0},
]


def test_digital_cam_switch_time_stamps_and_states() -> None:
    """Positive motion at 360°/s: the ON edge of switch 0 is output as a time stamp in the period before the axis
    reaches 144°, at the time the feedback crosses it; track 0 is ON between 144° and 216° (switch 1 acts only in
    the negative direction) and across the ring between 288° and 72°; track 1 time based (216° for 100 ms)."""
    c = _moving(velocity=360.0)
    fb = c.fb("MC_DigitalCamSwitch", Axis=AX, Enable=True, EnableMask=0x0003, Switches=SWITCHES,
              TrackOptions=[{}, {}])
    seen_on: list[int] = []
    for _ in range(1000):
        c.step(1, publish=False)
        assert fb.InOperation and not fb.Error
        pos = float(c.mc.act_pos[0]) % 360.0
        state = fb.TrackState
        in0 = 144.0 <= pos <= 216.0 or pos >= 288.0 or pos <= 72.0
        assert bool(state & 1) == in0, f"track 0 at {pos}"
        ts = axis_time_stamp(c.mc.axes[0])
        assert ts is not None
        for t in (t for t in fb.Outputs[0]["OnTime"] if t):
            # the feedback reaches an ON position (144° positive, 288° both ways) at that time stamp
            at = (float(c.mc.act_pos[0]) + 360.0 * (t - ts) * 1e-9) % 360.0
            assert min(abs(at - 144.0), abs(at - 288.0)) < 1e-4, at  # ns rounding, encoder quantization
            assert ts <= t < ts + 2_000_000, "a switching of the coming period"
            seen_on.append(t)
    assert len(set(seen_on)) >= 4, "two ON edges per turn over almost three turns"


def test_digital_cam_switch_enable_mask_and_compensation() -> None:
    c = _moving(velocity=360.0)
    fb = c.fb("MC_DigitalCamSwitch", Axis=AX, Enable=True, EnableMask=0x0001, Switches=SWITCHES,
              TrackOptions=[{"OnCompensation": 5.0}, {}])
    c.step(1)
    assert fb.Outputs[0]["EnableOut"] and not fb.Outputs[1]["EnableOut"]
    assert all(t == 0 for t in fb.Outputs[1]["OnTime"]), "a masked track has no switchings"
    # compensation beyond half a revolution (0.5 s at 360°/s) disables the track and InOperation
    c.set_inputs(fb.id, {"TrackOptions": [{"OnCompensation": 600.0}, {}]})
    c.step(1)
    assert not fb.InOperation and not fb.Outputs[0]["EnableOut"]


def test_digital_cam_switch_bad_structure_member_is_refused() -> None:
    c = Controller(axis_project())
    with pytest.raises(ValueError, match="Switches\\[0\\]"):
        c.fb("MC_DigitalCamSwitch", Axis=AX, Enable=True, Switches=[{"Track": 1}])
