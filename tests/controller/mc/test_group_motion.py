"""Interpolation instructions: timing, path accuracy every period, circles, buffering/blending, override.

Spec: omron-group-and-cam.md §4.3 MC_MoveLinear (seed 000 line 14568: velocity decomposition, profiles, BufferMode,
TransitionMode), §4.4/§4.5, §4.6 MC_MoveCircular2D (line 15581: border/centre/radius modes, full circles, errors),
§4.9 MC_GroupSetOverride (line 16694), §0.4 buffer limit (5443); sample programs of §4.3 (lines ~14880–15430) and
§4.6 (lines ~15945–16380). Path tolerances: a line within 1e-6 mm of its straight line, an arc within 1e-6 mm of its
radius, checked in every period.
"""

from __future__ import annotations

import math

import pytest

from mcstudio.controller.kernel import Controller
from mcstudio.controller.mc.group import GroupState
from tests.conftest import step_until
from tests.controller.mc.group_helpers import group_project, line_distance, positions, ready

TOL = 1e-6


@pytest.fixture
def c() -> Controller:
    ctrl = Controller(group_project())
    ready(ctrl)
    return ctrl


def test_linear_timing_chart_and_straight_path(c: Controller) -> None:
    """Execute↑ → Busy; Active one period later; the 50 mm move at 100 mm/s, 1000 mm/s² lasts 0.6 s: Done at cycle
    600 after Execute, on target; every period on the straight line; per-axis velocities F·Lai/L (§4.3)."""
    mv = c.fb("MC_MoveLinearAbsolute", AxesGroup="MC_Group000", Execute=True, Position=[30.0, 40.0],
              Velocity=100.0, Acceleration=1000.0, Deceleration=1000.0)
    c.step(1)
    assert (mv.Busy, mv.Active) == (True, False)
    c.step(1)
    assert (mv.Busy, mv.Active) == (True, True)
    assert c.mc.groups_by_name["MC_Group000"].state == GroupState.Moving
    worst = 0.0
    for _ in range(597):
        c.step(1, publish=False)
        worst = max(worst, line_distance(positions(c), (0.0, 0.0), (30.0, 40.0)))
        if c.mc.cmd_vel[0] > 59.99:
            assert c.mc.cmd_vel[0] == pytest.approx(60.0) and c.mc.cmd_vel[1] == pytest.approx(80.0)
    assert worst < TOL
    assert not mv.Done
    c.step(1)  # cycle 599: the final command value goes out
    assert positions(c) == (30.0, 40.0) and not mv.Done
    c.step(1)  # cycle 600: positioning complete
    assert (mv.Done, mv.Busy, mv.Active) == (True, False, False)
    assert c.mc.groups_by_name["MC_Group000"].state == GroupState.Standby


def test_velocity_is_reduced_so_no_axis_exceeds_its_maximum_velocity() -> None:
    """§4.3: Fai = F·Lai/L must stay ≤ the axis Maximum Velocity (500 mm/s): F is reduced."""
    c = Controller(group_project())
    ready(c)
    c.fb("MC_MoveLinearRelative", AxesGroup="MC_Group000", Execute=True, Distance=[1000.0, 10.0], Velocity=800.0)
    c.step(100)
    assert abs(c.mc.cmd_vel[0]) <= 500.0 + 1e-6 and c.mc.cmd_vel[0] == pytest.approx(500.0)


def test_three_axis_relative_line(c: Controller) -> None:
    en = c.fb("MC_GroupEnable", AxesGroup="MC_Group001", Execute=True)
    step_until(c, en, "Done")
    mv = c.fb("MC_MoveLinear", AxesGroup="MC_Group001", Execute=True, Position=[10.0, -20.0, 5.0], Velocity=50.0,
              Acceleration=200.0, Deceleration=200.0, Jerk=5000.0, MoveMode="_mcRelative")
    worst = 0.0
    while not mv.Done:
        c.step(1, publish=False)
        worst = max(worst, line_distance(positions(c, "MC_Group001"), (0.0, 0.0, 0.0), (10.0, -20.0, 5.0)))
        assert not mv.Error
    assert worst < TOL and positions(c, "MC_Group001") == (10.0, -20.0, 5.0)


def _run_arc(c: Controller, centre: tuple[float, float], radius: float, **inputs: object) -> list[tuple[float, ...]]:
    mv = c.fb("MC_MoveCircular2D", AxesGroup="MC_Group000", Execute=True, CircAxes=[0, 1], Velocity=20.0,
              Acceleration=200.0, Deceleration=200.0, **inputs)
    pts = []
    for _ in range(100_000):
        c.step(1, publish=False)
        p = positions(c)
        pts.append(p)
        assert abs(math.hypot(p[0] - centre[0], p[1] - centre[1]) - radius) < TOL
        assert not mv.Error, hex(mv.ErrorID)
        if mv.Done:
            break
    assert mv.Done
    return pts


def test_sample_program_radius_and_centre_arcs(c: Controller) -> None:
    """Sample of §4.6: to (10, 5); radius mode R = 5 to (15, 10) CCW (centre (10, 10), a quarter circle); line to
    (15, 15); centre mode around (15, 20) to (20, 20) CW (three quarters). The radius holds every period."""
    ln = c.fb("MC_MoveLinearAbsolute", AxesGroup="MC_Group000", Execute=True, Position=[10.0, 5.0], Velocity=20.0,
              Acceleration=200.0, Deceleration=200.0)
    step_until(c, ln, "Done")
    pts = _run_arc(c, (10.0, 10.0), 5.0, CircMode="_mcRadius", AuxPoint=[5.0, 0.0], EndPoint=[15.0, 10.0],
                   PathChoice="_mcCCW")
    assert pts[-1] == (15.0, 10.0) and all(p[0] >= 10.0 - TOL and p[1] <= 10.0 + TOL for p in pts)
    ln2 = c.fb("MC_MoveLinearAbsolute", AxesGroup="MC_Group000", Execute=True, Position=[15.0, 15.0],
               Velocity=20.0, Acceleration=200.0, Deceleration=200.0)
    step_until(c, ln2, "Done")
    pts = _run_arc(c, (15.0, 20.0), 5.0, CircMode="_mcCenter", AuxPoint=[15.0, 20.0], EndPoint=[20.0, 20.0],
                   PathChoice="_mcCW")
    assert min(p[0] for p in pts) == pytest.approx(10.0, abs=1e-3)  # CW from the bottom through the left side
    arc_time = len(pts) * 0.001
    assert arc_time == pytest.approx(5.0 * 1.5 * math.pi / 20.0 + 0.1, abs=0.005)


def test_border_mode_and_full_circle(c: Controller) -> None:
    """_mcBorder: through the via point; start = end → full circle on the diameter start–via, PathChoice direction."""
    pts = _run_arc(c, (5.0, 0.0), 5.0, CircMode="_mcBorder", AuxPoint=[5.0, 5.0], EndPoint=[10.0, 0.0])
    assert max(p[1] for p in pts) == pytest.approx(5.0, abs=1e-3)
    pts = _run_arc(c, (15.0, 0.0), 5.0, CircMode="_mcBorder", AuxPoint=[20.0, 0.0], EndPoint=[10.0, 0.0],
                   PathChoice="_mcCCW")
    assert min(p[1] for p in pts) == pytest.approx(-5.0, abs=1e-3)  # CCW from the left: down first
    assert pts[-1] == (10.0, 0.0)


@pytest.mark.parametrize(("inputs", "code"), [
    ({"CircMode": "_mcRadius", "AuxPoint": [5.0, 0.0], "EndPoint": [0.0, 0.0]}, 0x5448),
    ({"CircMode": "_mcBorder", "AuxPoint": [0.0, 0.0], "EndPoint": [0.0, 0.0]}, 0x5448),
    ({"CircMode": "_mcRadius", "AuxPoint": [1.0, 0.0], "EndPoint": [10.0, 0.0]}, 0x547C),
    ({"CircMode": "_mcRadius", "AuxPoint": [5.0, 0.0], "EndPoint": [10.0, 0.0], "CircAxes": [1, 1]}, 0x547E),
    ({"CircMode": "_mcCenter", "AuxPoint": [5.5, 0.0], "EndPoint": [10.0, 0.0]}, 0x5449),
    ({"CircMode": 3}, 0x542D),
    ({"CircMode": "_mcRadius", "AuxPoint": [5.0, 0.0], "EndPoint": [10.0, 0.0], "TransitionMode": 10}, 0x5432),
])
def test_circular_errors(c: Controller, inputs: dict[str, object], code: int) -> None:
    """§4.6 errors (A-1): 5448 identical points, 547C radius too small, 547E CircAxes, 5449 centre beyond the
    Correction Allowance Ratio (0.1 %), 542D CircMode, 5432 corner superimposition with Aborting."""
    mv = c.fb("MC_MoveCircular2D", AxesGroup="MC_Group000", Execute=True, Velocity=10.0, **inputs)
    c.step(1)
    assert mv.Error and mv.ErrorID == code


def test_sample_program_zigzag_buffers_seven_and_refuses_the_eighth(c: Controller) -> None:
    """Sample of §4.3: MV_LIN1 then MV_LIN2…7 Buffered while it is Active (six buffered); a seventh buffered
    instruction still fits, the eighth buffered one is 5443 (A-3 note: executing + buffered ≤ 8)."""
    common = {"AxesGroup": "MC_Group000", "Velocity": 100.0, "Acceleration": 100.0, "Deceleration": 100.0}
    pts = [(50.0, 5.0), (0.0, 10.0), (50.0, 15.0), (0.0, 20.0), (50.0, 25.0), (50.0, 0.0), (0.0, 0.0)]
    first = c.fb("MC_MoveLinearAbsolute", Execute=True, Position=list(pts[0]), **common)
    step_until(c, first, "Active")
    rest = [c.fb("MC_MoveLinearAbsolute", Execute=True, Position=list(p), BufferMode="_mcBuffered", **common)
            for p in [*pts[1:], (5.0, 5.0)]]
    c.step(1)
    assert all(r.Busy and not r.Active for r in rest)
    eighth = c.fb("MC_MoveLinearAbsolute", Execute=True, Position=[1.0, 1.0], BufferMode="_mcBuffered", **common)
    c.step(1)
    assert eighth.Error and eighth.ErrorID == 0x5443
    # the 5443 group error stops the group and aborts everything
    assert first.CommandAborted and all(r.CommandAborted for r in rest)


def test_buffered_chain_runs_in_order(c: Controller) -> None:
    common = {"AxesGroup": "MC_Group000", "Velocity": 100.0, "Acceleration": 1000.0, "Deceleration": 1000.0}
    pts = [(50.0, 5.0), (0.0, 10.0), (50.0, 15.0)]
    fbs = [c.fb("MC_MoveLinearAbsolute", Execute=True, Position=list(p), BufferMode="_mcBuffered", **common)
           for p in pts]
    prev = (0.0, 0.0)
    for fb, p in zip(fbs, pts, strict=True):
        worst = 0.0
        while not fb.Done:
            c.step(1, publish=False)
            worst = max(worst, line_distance(positions(c), prev, p))
        assert worst < TOL and positions(c) == p
        prev = p


def test_blending_next_keeps_the_path_velocity_through_the_corner(c: Controller) -> None:
    """§4.3 _mcBlendingNext with _mcTMNone: the path goes through P2 at the transit velocity (no stop); the first
    instruction is Done in the period the second becomes Active; each segment stays on its line."""
    common = {"AxesGroup": "MC_Group000", "Velocity": 50.0, "Acceleration": 500.0, "Deceleration": 500.0}
    a = c.fb("MC_MoveLinearAbsolute", Execute=True, Position=[20.0, 0.0], **common)
    b = c.fb("MC_MoveLinearAbsolute", Execute=True, Position=[20.0, 20.0], BufferMode="_mcBlendingNext", **common)
    g = c.mc.groups_by_name["MC_Group000"]
    slowest = math.inf
    handover = False
    for _ in range(3000):
        c.step(1, publish=False)
        p = positions(c)
        if not a.Done:
            assert line_distance(p, (0.0, 0.0), (20.0, 0.0)) < TOL
        elif not handover:
            handover = True
            assert b.Active
        else:
            assert line_distance(p, (20.0, 0.0), (20.0, 20.0)) < TOL
        if (a.Active or b.Active) and p[0] > 5.0 and p[1] < 10.0:
            slowest = min(slowest, g.cmd_vel)
        if b.Done:
            break
    assert b.Done and positions(c) == (20.0, 20.0)
    assert slowest == pytest.approx(50.0, abs=1e-6)  # no slow-down at the corner


def test_corner_superimposed_keeps_axis_velocities_continuous(c: Controller) -> None:
    """§4.3 _mcTMCornerSuperimposed: the deceleration of the first move overlaps the acceleration of the second
    (same duration): each axis's velocity changes continuously and the path cuts the corner near P2."""
    common = {"AxesGroup": "MC_Group000", "Velocity": 50.0, "Acceleration": 500.0, "Deceleration": 500.0}
    c.fb("MC_MoveLinearAbsolute", Execute=True, Position=[20.0, 0.0], **common)
    b = c.fb("MC_MoveLinearAbsolute", Execute=True, Position=[20.0, 20.0], BufferMode="_mcBlendingNext",
             TransitionMode="_mcTMCornerSuperimposed", **common)
    prev = (0.0, 0.0)
    nearest = math.inf
    while not b.Done:
        c.step(1, publish=False)
        v = (float(c.mc.cmd_vel[0]), float(c.mc.cmd_vel[1]))
        assert abs(v[0] - prev[0]) <= 500.0 * 0.001 + 1e-6 and abs(v[1] - prev[1]) <= 500.0 * 0.001 + 1e-6
        prev = v
        p = positions(c)
        nearest = min(nearest, math.hypot(p[0] - 20.0, p[1]))
    assert positions(c) == (20.0, 20.0)
    assert 0.5 < nearest < 5.0  # passes near P2, not through it


def test_override_scales_and_zero_pauses_in_moving(c: Controller) -> None:
    """§4.9: new velocity = Velocity × override; 0 → decelerates to 0 and stays Moving; Enable↓ → 100 %."""
    g = c.mc.groups_by_name["MC_Group000"]
    mv = c.fb("MC_MoveLinearAbsolute", AxesGroup="MC_Group000", Execute=True, Position=[300.0, 400.0],
              Velocity=100.0, Acceleration=1000.0, Deceleration=1000.0)
    c.step(200)
    ov = c.fb("MC_GroupSetOverride", AxesGroup="MC_Group000", Enable=True, VelFactor=50.0)
    c.step(200)
    assert ov.Enabled and g.cmd_vel == pytest.approx(50.0)
    ov.VelFactor = 0.0
    c.step(200)
    assert g.cmd_vel == 0.0 and g.state == GroupState.Moving and mv.Active
    here = positions(c)
    assert line_distance(here, (0.0, 0.0), (300.0, 400.0)) < TOL
    ov.Enable = False
    c.step(200)
    assert g.cmd_vel == pytest.approx(100.0)
    step_until(c, mv, "Done")
    assert positions(c) == (300.0, 400.0)
