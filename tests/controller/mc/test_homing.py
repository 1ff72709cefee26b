"""MC_Home / MC_HomeWithParameter against the simulated sensors (limit switches, home proximity dog, Z phase,
external home input) reached through the drive's 60FDh bits and touch-probe latch.

Spec: omron-axis-instructions.md MC_Home (seed 000 lines 2713–3228: the ten modes and the common tail T1–T4),
MC_HomeWithParameter (3229), A-2.4 detail codes of 5700. The fixture: 10 mm/rev, Z phase every 10 mm at
0.0095 mm (1000 pulses), dog 20–30 mm, external home input 15–16 mm, limits ±60 mm; homing velocity 100 mm/s,
approach velocity 10 mm/s, acceleration/deceleration 2000 mm/s².
"""

from __future__ import annotations

from typing import Any

import pytest

from mcstudio.controller.kernel import Controller, Until
from mcstudio.controller.mc.enums import AxisState
from tests.conftest import axis_project, power_on, step_until

PPU = 104857.6
Z0 = 1000 / PPU  # first Z pulse [mm]
SENSORS = {"PositiveLimit": 60.0, "NegativeLimit": -60.0, "HomeProximityStart": 20.0, "HomeProximityEnd": 30.0,
           "ZPhaseOffset": 1000, "ExternalHomeStart": 15.0, "ExternalHomeEnd": 16.0}
BASE = {"Vel": 100.0, "ApproachVel": 10.0, "Acc": 2000.0, "Dec": 2000.0, "PosiLimitInputMode": "_mcRevImmediateStop",
        "NegaLimitInputMode": "_mcRevImmediateStop"}
DECEL = (100.0**2 - 10.0**2) / (2 * 2000.0)  # travel from homing to approach velocity
HALF_PULSE = 0.5 / PPU


def _home(mode: str, start_at: float = 0.0, **homing: Any) -> tuple[Controller, object]:
    c = Controller(axis_project(sensors=SENSORS, Homing={**BASE, "Mode": mode, **homing}))
    power_on(c)
    if start_at:
        mv = c.fb("MC_MoveAbsolute", Axis="MC_Axis000", Execute=True, Position=start_at, Velocity=200.0,
                  Acceleration=2000.0, Deceleration=2000.0)
        step_until(c, mv, "Done")
    h = c.fb("MC_Home", Axis="MC_Axis000", Execute=True)
    c.step(1)
    c.step(200_000, Until(h.id, "Busy", False))  # Busy falls with Done, Error or CommandAborted
    return c, h


def _physical(c: Controller) -> float:
    """Where the mechanism really is [mm] (motor pulses / pulses per mm)."""
    return float(c.network.drives.position[0]) / PPU


def _z_after(x: float) -> float:
    import math

    return Z0 + math.floor((x - Z0) / 10.0 + 1) * 10.0


@pytest.mark.parametrize(
    ("mode", "expected"),
    [
        ("_mcHomeSwTurnHomeSwOff", _z_after(30.0)),  # first Z after the dog goes OFF
        ("_mcHomeSwTurnHomeSwOn", _z_after(20.0 + DECEL)),  # first Z after the approach velocity is reached
        ("_mcHomeSwOff", _z_after(30.0)),
        ("_mcHomeSwOn", _z_after(20.0 + DECEL)),
        ("_mcNoHomeSwHoldingHomeInput", Z0),  # approach velocity from 0: the first Z
    ],
)
def test_home_input_modes_latch_the_z_phase(mode: str, expected: float) -> None:
    """T1–T4: latch at the Z edge, immediate stop, return to the latched position, home offset 0 there."""
    c, h = _home(mode)
    assert h.Done and not h.Error
    ax = c.mc.axes[0]
    assert ax.homed and ax.state == AxisState.Standstill
    assert ax.cmd_pos == pytest.approx(0.0, abs=1e-9)
    assert _physical(c) == pytest.approx(expected, abs=1.5 / PPU)


def test_mode_9_mask_distance() -> None:
    c, h = _home("_mcHomeSwTurnHomeMask", HomeInputMaskDistance=12.0)
    assert h.Done
    assert _physical(c) == pytest.approx(_z_after(32.0), abs=1.5 / PPU)


def test_mode_9_mask_shorter_than_deceleration_is_742b() -> None:
    c, h = _home("_mcHomeSwTurnHomeMask", HomeInputMaskDistance=0.2, Dec=200.0)
    assert h.Error and h.ErrorID == 0x742B
    assert c.mc.axes[0].state == AxisState.ErrorStop


def test_mode_8_limit_input_off() -> None:
    """Toward the limit opposite the detection direction, out of it at the approach velocity, first Z after it
    turned OFF."""
    c, h = _home("_mcLimitInputOff")
    assert h.Done
    assert _physical(c) == pytest.approx(_z_after(-60.0), abs=1.5 / PPU)


def test_mode_11_limit_inputs_only() -> None:
    """Home = the OFF edge of the limit opposite the detection direction at the approach velocity; immediate stop
    without return: final position = home offset + overshoot D (here one period of the approach velocity)."""
    c, h = _home("_mcLimitInputOnly", HomeOffset=5.0)
    assert h.Done
    assert c.mc.axes[0].cmd_pos == pytest.approx(5.0, abs=10.0 * 0.001 + 1e-6)
    assert _physical(c) == pytest.approx(-60.0, abs=0.02)


def test_mode_12_holding_time() -> None:
    c, h = _home("_mcHomeSwTurnHoldingTime", HoldingTime=400)
    assert h.Done
    # the timer starts with the deceleration at the dog (20 mm): 100 → 10 mm/s at 2000 mm/s² (45 ms),
    # then 10 mm/s for the rest of 0.4 s
    assert _physical(c) == pytest.approx(20.0 + DECEL + 10.0 * 0.355, abs=0.02)


def test_mode_14_preset_keeps_the_following_error() -> None:
    c, h = _home("_mcHomePreset", start_at=42.0, HomeOffset=-7.0)
    assert h.Done and c.mc.axes[0].homed
    assert c.mc.axes[0].cmd_pos == -7.0
    assert _physical(c) == pytest.approx(42.0, abs=HALF_PULSE), "no motion"


def test_home_offset_and_compensation() -> None:
    """T3: 500 ms wait, then the compensation move; T4: that position becomes the home offset."""
    c, h = _home("_mcHomeSwTurnHomeSwOff", CompensationVal=-3.0, CompensationVel=10.0, HomeOffset=100.0)
    assert h.Done
    assert c.mc.axes[0].cmd_pos == pytest.approx(100.0, abs=1e-9)
    assert _physical(c) == pytest.approx(_z_after(30.0) - 3.0, abs=1.5 / PPU)


def test_retreat_when_started_on_the_dog() -> None:
    """Modes 0/1/9/12 started with the proximity input ON retreat against the detection direction first."""
    c, h = _home("_mcHomeSwTurnHomeSwOff", start_at=25.0)
    assert h.Done
    assert _physical(c) == pytest.approx(_z_after(30.0), abs=1.5 / PPU)


def test_start_direction_opposite_reverses_at_the_limit() -> None:
    c, h = _home("_mcHomeSwTurnHomeSwOff", StartDirection="_mcNegativeDirection",
                 NegaLimitInputMode="_mcRevDecelerationStop")
    assert h.Done
    assert _physical(c) == pytest.approx(_z_after(30.0), abs=1.5 / PPU)


def test_limit_with_error_stop_operation_is_an_error() -> None:
    c, h = _home("_mcHomeSwTurnHomeSwOff", StartDirection="_mcNegativeDirection", NegaLimitInputMode="_mcErrorStop")
    assert h.Error and h.ErrorID == 0x6456
    assert c.mc.axes[0].state == AxisState.ErrorStop and not c.mc.axes[0].homed


def test_no_home_input_between_the_limits() -> None:
    """Both limits 'reverse', no dog: travelling from the opposite limit to the other one → error."""
    c = Controller(axis_project(sensors={"PositiveLimit": 20.0, "NegativeLimit": -20.0},
                                Homing={**BASE, "Mode": "_mcHomeSwTurnHomeSwOff"}))
    power_on(c)
    h = c.fb("MC_Home", Axis="MC_Axis000", Execute=True)
    c.step(100_000, Until(h.id, "Error", True))
    assert h.Error and h.ErrorID == 0x6457


def test_external_home_input() -> None:
    c, h = _home("_mcNoHomeSwHoldingHomeInput", HomeInputSignal="_mcExternalSignal")
    assert h.Done
    assert _physical(c) == pytest.approx(15.0, abs=1.5 / PPU)


def test_home_only_from_standstill_and_not_reexecutable() -> None:
    c = Controller(axis_project(sensors=SENSORS, Homing={**BASE}))
    power_on(c)
    c.fb("MC_MoveVelocity", Axis="MC_Axis000", Execute=True, Velocity=10.0)
    c.step(5)
    h = c.fb("MC_Home", Axis="MC_Axis000", Execute=True)
    c.step(1)
    assert h.Error and h.ErrorID == 0x543C
    c2 = Controller(axis_project(sensors=SENSORS, Homing={**BASE}))
    power_on(c2)
    h2 = c2.fb("MC_Home", Axis="MC_Axis000", Execute=True)
    c2.step(20)
    assert c2.mc.axes[0].state == AxisState.Homing
    h2.Execute = False
    c2.step(1)
    h2.Execute = True
    c2.step(1)
    assert h2.Error and h2.ErrorID == 0x543B


def test_virtual_axis_is_preset() -> None:
    c = Controller(axis_project())
    power_on(c, "MC_Axis001")
    h = c.fb("MC_Home", Axis="MC_Axis001", Execute=True)
    step_until(c, h, "Done", limit=10)
    assert c.mc.axes[1].homed


def _ref(**kw: Any) -> dict[str, Any]:
    base = {"HomingMode": "_mcHomeSwTurnHomeSwOff", "HomeInput": "_mcZPhase", "StartDir": "_mcPositiveDirection",
            "HomeDir": "_mcPositiveDirection", "PosiLmtMode": "_mcRevImmediateStop",
            "NegaLmtMode": "_mcRevImmediateStop", "Vel": 100.0, "ApproachVel": 10.0, "Acc": 2000.0, "Dec": 2000.0,
            "Jerk": 0.0, "Mask": 0.0, "Offset": 3.0, "PushTime": 0, "Compensation": 0.0, "CompensationVel": 5.0}
    base.update(kw)
    return base


def test_home_with_parameter_uses_its_own_parameters() -> None:
    c = Controller(axis_project(sensors=SENSORS, Homing={**BASE, "Mode": "_mcHomePreset"}))
    power_on(c)
    h = c.fb("MC_HomeWithParameter", Axis="MC_Axis000", Execute=True, HomingParameter=_ref())
    step_until(c, h, "Done")
    assert c.mc.axes[0].cmd_pos == pytest.approx(3.0)
    assert _physical(c) == pytest.approx(_z_after(30.0), abs=1.5 / PPU)
    assert int(c.mc.axes[0].params.Homing.Mode) == 14, "the axis parameters are not changed"


@pytest.mark.parametrize(
    ("member", "value", "detail"),
    [("HomingMode", 3, 1), ("Vel", 0.0, 7), ("ApproachVel", 160.0, 108), ("Vel", 900.0, 106),
     ("Acc", -1.0, 9)],
)
def test_home_with_parameter_out_of_range_is_5700(member: str, value: Any, detail: int) -> None:
    c = Controller(axis_project(sensors=SENSORS))
    power_on(c)
    h = c.fb("MC_HomeWithParameter", Axis="MC_Axis000", Execute=True, HomingParameter=_ref(**{member: value}))
    c.step(1)
    assert h.Error and h.ErrorID == 0x5700
    assert any(e.code == "57000000" and f"attached information {detail}:" in e.detail for e in c.events.list())


@pytest.mark.parametrize("mode", ["_mcHomeSwTurnHomeSwOff", "_mcHomeSwOff", "_mcHomeSwTurnHomeMask"])
def test_limit_reversal_turns_back_after_passing_the_dog(mode: str) -> None:
    """Started between the dog and the limit in the detection direction: the axis reverses at that limit, passes
    the dog against the detection direction, turns back once the dog is OFF and homes on it — it does not travel
    on to the far limit (D20)."""
    c = Controller(axis_project(sensors=SENSORS, Homing={**BASE, "Mode": mode, "HomeInputMaskDistance": 12.0}))
    power_on(c)
    mv = c.fb("MC_MoveAbsolute", Axis="MC_Axis000", Execute=True, Position=45.0, Velocity=200.0,
              Acceleration=2000.0, Deceleration=2000.0)
    step_until(c, mv, "Done")
    h = c.fb("MC_Home", Axis="MC_Axis000", Execute=True)
    lowest = 45.0
    for _ in range(2000):  # 20 s of 10-period chunks
        c.step(10, Until(h.id, "Busy", False))
        lowest = min(lowest, _physical(c))
        if not h.Busy:
            break
    assert h.Done and not h.Error
    # turned back within a deceleration distance (100 mm/s at 2000 mm/s²: 2.5 mm) of the dog's lower edge
    assert 20.0 - 2.5 - 0.2 < lowest < 20.0
    expected = _z_after(32.0) if mode == "_mcHomeSwTurnHomeMask" else _z_after(30.0)
    assert _physical(c) == pytest.approx(expected, abs=1.5 / PPU)


def test_struct_member_names_match_the_instruction_tables() -> None:
    """The member names the input check accepts are the ones the instructions read."""
    from mcstudio.controller.mc.fb.base import STRUCT_MEMBERS
    from mcstudio.controller.mc.fb.homing_fb import HOMING_REF_MEMBERS
    from mcstudio.project.models import AxisParameters

    assert {m[0] for m in HOMING_REF_MEMBERS} == STRUCT_MEMBERS["_sHOMING_REF"]
    assert set(AxisParameters.model_fields) == STRUCT_MEMBERS["_sAXIS_PARAM"]
