"""Rotary Mode (ring counter) and the Direction input of MC_MoveAbsolute.

Spec: omron-axis-instructions.md MC_MoveAbsolute "Direction" (seed 000 lines 3575–3615: examples 50 → −20 and
−20 → 290 with _mcNoDirection), usage notes on 5478 (seed 000 line 3618); MC_MoveZeroPosition (line 4899).
"""

from __future__ import annotations

import pytest

from mcstudio.controller.kernel import Controller
from tests.conftest import axis_project, power_on, step_until

RING = (-180.0, 180.0)


def _ctrl(**kw) -> Controller:
    return Controller(axis_project(count_mode="_mcCountModeRotary", modulo=RING, **kw))


def _move(c: Controller, position: float, direction: str, **kw) -> tuple[float, object]:
    """Move and return (net travel in continuous coordinates, instance)."""
    start = float(c.mc.cmd_pos[0])
    mv = c.fb("MC_MoveAbsolute", Axis="MC_Axis000", Execute=True, Position=position, Velocity=500.0,
              Acceleration=10000.0, Deceleration=10000.0, Direction=direction, **kw)
    step_until(c, mv, "Done")
    return float(c.mc.cmd_pos[0]) - start, mv


@pytest.mark.parametrize(
    ("direction", "travel"),
    [
        ("_mcPositiveDirection", 290.0),  # 50 → 180 ≡ −180 → −20
        ("_mcNegativeDirection", -70.0),
        ("_mcShortestWay", -70.0),
        ("_mcNoDirection", -70.0),  # numeric comparison inside the ring
    ],
)
def test_direction_from_50_to_minus_20(direction: str, travel: float) -> None:
    c = _ctrl()
    power_on(c)
    _move(c, 50.0, "_mcNoDirection")
    got, _ = _move(c, -20.0, direction)
    assert got == pytest.approx(travel, abs=1e-9)
    assert c.mc.axes[0].cmd_pos == pytest.approx(-20.0, abs=1e-9)
    assert c.publish().mc["cmd_pos"][0] == pytest.approx(-20.0, abs=1e-9), "Cmd.Pos is reported on the ring"


def test_current_direction_follows_the_last_motion() -> None:
    c = _ctrl()
    power_on(c)
    _move(c, 50.0, "_mcPositiveDirection")  # last motion positive
    got, _ = _move(c, -20.0, "_mcCurrentDirection")
    assert got == pytest.approx(290.0)
    _move(c, -30.0, "_mcNegativeDirection")  # last motion negative
    got, _ = _move(c, -20.0, "_mcCurrentDirection")
    assert got == pytest.approx(-350.0)


def test_shortest_way_tie_uses_current_direction() -> None:
    """Equal distances both ways: as _mcCurrentDirection (seed 000 line 3609)."""
    c = _ctrl()
    power_on(c)
    _move(c, 0.0, "_mcNoDirection")
    _move(c, 10.0, "_mcNegativeDirection")  # travels −350: last direction negative
    got, _ = _move(c, -170.0, "_mcShortestWay")  # 180 either way
    assert got == pytest.approx(-180.0)


def test_no_direction_beyond_the_ring_is_multi_turn() -> None:
    """Current −20, Position 290 with _mcNoDirection: the part beyond the upper limit is extra relative travel
    (seed 000 lines 3598–3602): travel 310, final −70 on the ring."""
    c = _ctrl()
    power_on(c)
    _move(c, -20.0, "_mcNoDirection")
    got, _ = _move(c, 290.0, "_mcNoDirection")
    assert got == pytest.approx(310.0)
    assert c.mc.axes[0].cmd_pos == pytest.approx(-70.0)


@pytest.mark.parametrize("position", [180.5, -181.0])
def test_target_outside_the_ring_is_5478(position: float) -> None:
    c = _ctrl()
    power_on(c)
    mv = c.fb("MC_MoveAbsolute", Axis="MC_Axis000", Execute=True, Position=position, Velocity=10.0,
              Direction="_mcShortestWay")
    c.step(1)
    assert mv.Error and mv.ErrorID == 0x5478


def test_ring_limits_themselves_are_valid_targets() -> None:
    """5478 only above the upper or below the lower limit (decision D14/seed line 3618)."""
    c = _ctrl()
    power_on(c)
    got, mv = _move(c, 180.0, "_mcPositiveDirection")
    assert not mv.Error and got == pytest.approx(180.0)
    assert c.mc.axes[0].cmd_pos == pytest.approx(-180.0), "180 ≡ −180 on the ring"


def test_relative_move_is_multi_turn_in_rotary_mode() -> None:
    c = _ctrl()
    power_on(c)
    mr = c.fb("MC_MoveRelative", Axis="MC_Axis000", Execute=True, Distance=1000.0, Velocity=2000.0,
              Acceleration=20000.0, Deceleration=20000.0)
    step_until(c, mr, "Done")
    assert c.mc.axes[0].cmd_pos == pytest.approx(1000.0 - 1080.0)
    assert c.mc.axes[0].act_pos == pytest.approx(-80.0, abs=1e-6)


def test_move_zero_position_shortest_way_and_home_rules() -> None:
    """MC_MoveZeroPosition: home must be defined (5466), rotary: shortest way to 0 (seed 000 line 4899)."""
    c = _ctrl()
    power_on(c)
    z = c.fb("MC_MoveZeroPosition", Axis="MC_Axis000", Execute=True, Velocity=100.0)
    c.step(1)
    assert z.Error and z.ErrorID == 0x5466
    c2 = _ctrl(encoder="absolute")  # absolute encoder: home defined at servo ON
    power_on(c2)
    _move(c2, 150.0, "_mcPositiveDirection")
    z = c2.fb("MC_MoveZeroPosition", Axis="MC_Axis000", Execute=True, Velocity=100.0, Acceleration=1000.0,
              Deceleration=1000.0)
    start = float(c2.mc.cmd_pos[0])
    step_until(c2, z, "Done")
    assert float(c2.mc.cmd_pos[0]) - start == pytest.approx(-150.0)


def test_move_zero_position_ring_without_zero_is_549c() -> None:
    c = Controller(axis_project(count_mode="_mcCountModeRotary", modulo=(10.0, 370.0), encoder="absolute"))
    power_on(c)
    z = c.fb("MC_MoveZeroPosition", Axis="MC_Axis000", Execute=True, Velocity=100.0)
    c.step(1)
    assert z.Error and z.ErrorID == 0x549C
