"""MC_SetOverride and the blending buffer modes.

Spec: omron-axis-instructions.md MC_SetOverride (seed 000 line 6331; VelFactor rules omron-mc-basics.md §2.6),
BufferMode and transit velocity (omron-mc-basics.md §1.5, seed 000 lines 989–1017, MC_MoveAbsolute lines 3460–3469),
_eMC_ACCDECOVER (§2.7, errors 5444/5445).
"""

from __future__ import annotations

import pytest

from mcstudio.controller.kernel import Controller
from mcstudio.controller.mc.enums import AxisState
from tests.conftest import axis_project, power_on, step_until


@pytest.fixture
def c() -> Controller:
    ctrl = Controller(axis_project())
    power_on(ctrl)
    return ctrl


def _velocity_at(c: Controller, cycles: int) -> float:
    c.step(cycles)
    return float(c.mc.cmd_vel[0])


def test_override_scales_the_target_velocity(c: Controller) -> None:
    mv = c.fb("MC_MoveVelocity", Axis="MC_Axis000", Execute=True, Velocity=100.0, Acceleration=1000.0,
              Deceleration=1000.0)
    step_until(c, mv, "InVelocity")
    ov = c.fb("MC_SetOverride", Axis="MC_Axis000", Enable=True, VelFactor=50.0)
    c.step(1)
    assert ov.Enabled and ov.Busy
    assert _velocity_at(c, 200) == pytest.approx(50.0)
    assert mv.InVelocity, "InVelocity stays TRUE when the override changes (MC_SetOverride rules)"
    ov.VelFactor = 150.0
    assert _velocity_at(c, 200) == pytest.approx(150.0)
    ov.Enable = False
    c.step(1)
    assert not ov.Enabled and not ov.Busy
    assert _velocity_at(c, 200) == pytest.approx(100.0), "Enable FALSE: back to 100 %"


def test_override_zero_pauses_a_positioning(c: Controller) -> None:
    """VelFactor exactly 0: the axis decelerates to 0 and waits, still Discrete; the instruction stays Busy."""
    mv = c.fb("MC_MoveAbsolute", Axis="MC_Axis000", Execute=True, Position=200.0, Velocity=100.0,
              Acceleration=1000.0, Deceleration=1000.0)
    c.step(300)
    ov = c.fb("MC_SetOverride", Axis="MC_Axis000", Enable=True, VelFactor=0.0)
    c.step(500)
    assert c.mc.cmd_vel[0] == 0.0
    assert c.mc.axes[0].state == AxisState.Discrete and mv.Busy and mv.Active and not mv.Done
    ov.VelFactor = 100.0
    step_until(c, mv, "Done")
    assert c.mc.act_pos[0] == pytest.approx(200.0, abs=1e-9)


@pytest.mark.parametrize(("factor", "effective"), [(0.001, 0.01), (-5.0, 0.01), (800.0, 500.0), (0.0, 0.0)])
def test_vel_factor_clamping(factor: float, effective: float) -> None:
    """§2.6: below 0.01 (incl. negative) → 0.01, above 500 → 500, only exactly 0 → 0."""
    from mcstudio.controller.mc.fb.admin import MC_SetOverride

    assert MC_SetOverride.effective(factor) == effective


def test_override_is_clamped_to_maximum_velocity(c: Controller) -> None:
    mv = c.fb("MC_MoveVelocity", Axis="MC_Axis000", Execute=True, Velocity=400.0, Acceleration=10000.0,
              Deceleration=10000.0)
    step_until(c, mv, "InVelocity")
    c.fb("MC_SetOverride", Axis="MC_Axis000", Enable=True, VelFactor=200.0)
    assert _velocity_at(c, 300) == pytest.approx(500.0), "MaxVel is 500"


def test_later_override_instance_has_priority(c: Controller) -> None:
    mv = c.fb("MC_MoveVelocity", Axis="MC_Axis000", Execute=True, Velocity=100.0, Acceleration=10000.0,
              Deceleration=10000.0)
    step_until(c, mv, "InVelocity")
    a = c.fb("MC_SetOverride", Axis="MC_Axis000", Enable=True, VelFactor=50.0)
    c.step(10)
    b = c.fb("MC_SetOverride", Axis="MC_Axis000", Enable=True, VelFactor=20.0)
    assert _velocity_at(c, 100) == pytest.approx(20.0)
    assert a.Enabled and b.Enabled
    b.Enable = False
    assert _velocity_at(c, 100) == pytest.approx(100.0), "the later instance's Enable FALSE disables the override"


def test_override_does_not_apply_to_mc_stop(c: Controller) -> None:
    mv = c.fb("MC_MoveVelocity", Axis="MC_Axis000", Execute=True, Velocity=100.0, Acceleration=10000.0,
              Deceleration=10000.0)
    step_until(c, mv, "InVelocity")
    st = c.fb("MC_Stop", Axis="MC_Axis000", Execute=True, Deceleration=100.0)
    c.step(10)
    c.fb("MC_SetOverride", Axis="MC_Axis000", Enable=True, VelFactor=10.0)
    n = step_until(c, st, "Done")
    assert abs((n + 10) * 0.001 - 1.0) <= 0.005, "the stop keeps its deceleration (100 → 0 at 100 mm/s² = 1 s)"


@pytest.mark.parametrize(
    ("mode", "transit"),
    [("_mcBlendingLow", 40.0), ("_mcBlendingPrevious", 100.0), ("_mcBlendingNext", 40.0),
     ("_mcBlendingHigh", 100.0)],
)
def test_blending_transit_velocity(c: Controller, mode: str, transit: float) -> None:
    """Positioning A (100 mm/s to 50) blended with B (40 mm/s to 120): the axis passes A's target at the transit
    velocity without stopping; A is Done at that moment and B takes over (§1.5)."""
    a = c.fb("MC_MoveAbsolute", Axis="MC_Axis000", Execute=True, Position=50.0, Velocity=100.0,
             Acceleration=1000.0, Deceleration=1000.0)
    c.step(5)
    b = c.fb("MC_MoveAbsolute", Axis="MC_Axis000", Execute=True, Position=120.0, Velocity=40.0,
             Acceleration=1000.0, Deceleration=1000.0, BufferMode=mode)
    velocity_at_done = None
    min_velocity = 1e9
    for _ in range(10000):
        c.step(1)
        if 20 < c.mc.cmd_pos[0] < 100:
            min_velocity = min(min_velocity, float(c.mc.cmd_vel[0]))
        if a.Done and velocity_at_done is None:
            velocity_at_done = float(c.mc.cmd_vel[0])
            pos_at_done = float(c.mc.cmd_pos[0])
        if b.Done:
            break
    assert velocity_at_done == pytest.approx(transit, rel=0.02)
    assert pos_at_done == pytest.approx(50.0, abs=transit * 0.001 + 1e-9)
    assert min_velocity >= min(40.0, transit) - 1.0, "no stop at the junction"
    assert b.Done and c.mc.act_pos[0] == pytest.approx(120.0, abs=1e-9)


def test_blending_with_reversal_passes_at_zero_velocity(c: Controller) -> None:
    a = c.fb("MC_MoveAbsolute", Axis="MC_Axis000", Execute=True, Position=50.0, Velocity=100.0,
             Acceleration=1000.0, Deceleration=1000.0)
    c.step(5)
    b = c.fb("MC_MoveAbsolute", Axis="MC_Axis000", Execute=True, Position=10.0, Velocity=40.0,
             Acceleration=1000.0, Deceleration=1000.0, BufferMode="_mcBlendingHigh")
    step_until(c, a, "Done")
    assert abs(c.mc.cmd_vel[0]) < 1.0
    step_until(c, b, "Done")
    assert c.mc.act_pos[0] == pytest.approx(10.0, abs=1e-9)


def test_blending_onto_move_velocity_is_543c(c: Controller) -> None:
    mv = c.fb("MC_MoveVelocity", Axis="MC_Axis000", Execute=True, Velocity=10.0, Acceleration=100.0)
    c.step(5)
    b = c.fb("MC_MoveAbsolute", Axis="MC_Axis000", Execute=True, Position=100.0, Velocity=40.0,
             BufferMode="_mcBlendingLow")
    c.step(1)
    assert b.Error and b.ErrorID == 0x543C
    assert mv.CommandAborted


def test_acc_dec_over_error_stop_on_blending_is_5445() -> None:
    """Not enough distance to reach the transit velocity with the instruction's deceleration and [Acc/Dec Over]
    = error stop → 5445 (A-1 #38)."""
    c = Controller(axis_project(Operation={"AccDecOver": "_mcAccDecOverErrorStop"}))
    power_on(c)
    a = c.fb("MC_MoveAbsolute", Axis="MC_Axis000", Execute=True, Position=100.0, Velocity=100.0,
             Acceleration=100.0, Deceleration=100.0)
    c.step(1900)  # 2 s triangle: 0.5 mm left at 10 mm/s; reaching 300 mm/s there needs 450 mm at 100 mm/s²
    b = c.fb("MC_MoveAbsolute", Axis="MC_Axis000", Execute=True, Position=300.0, Velocity=300.0,
             Acceleration=100.0, Deceleration=100.0, BufferMode="_mcBlendingNext")
    c.step(2)
    assert c.mc.axes[0].error_code == 0x5445
    assert c.mc.axes[0].state == AxisState.ErrorStop
    assert a.Error and a.ErrorID == 0x5445
    assert b.CommandAborted


def test_acc_dec_over_on_aborting_multi_execution() -> None:
    """A new target too close to stop with the instruction's deceleration: 5444 with error stop, rapid
    deceleration onto the target otherwise (decision D8, _eMC_ACCDECOVER)."""
    c = Controller(axis_project(Operation={"AccDecOver": "_mcAccDecOverErrorStop"}))
    power_on(c)
    c.fb("MC_MoveVelocity", Axis="MC_Axis000", Execute=True, Velocity=200.0, Acceleration=10000.0)
    c.step(200)
    target = float(c.mc.cmd_pos[0]) + 5.0  # 200²/(2·100) = 200 mm needed
    b = c.fb("MC_MoveAbsolute", Axis="MC_Axis000", Execute=True, Position=target, Velocity=200.0,
             Acceleration=100.0, Deceleration=100.0)
    c.step(2)
    assert b.Error and b.ErrorID == 0x5444
    c2 = Controller(axis_project(Operation={"AccDecOver": "_mcAccDecOverRapid"}))
    power_on(c2)
    c2.fb("MC_MoveVelocity", Axis="MC_Axis000", Execute=True, Velocity=200.0, Acceleration=10000.0)
    c2.step(200)
    target = float(c2.mc.cmd_pos[0]) + 5.0
    b = c2.fb("MC_MoveAbsolute", Axis="MC_Axis000", Execute=True, Position=target, Velocity=200.0,
              Acceleration=100.0, Deceleration=100.0)
    step_until(c2, b, "Done")
    assert float(c2.mc.act_pos[0]) == pytest.approx(target, abs=0.5 / 104857.6), "rapid: no overshoot (±½ pulse)"
