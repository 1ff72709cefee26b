"""Group monitoring and the rules of the interpolation instructions completed in issue 7 (`group_monitor.py`,
`group_planning.py`): in-position check at the end of group moves (D103), interpolation warning values (D104), the
Deceleration = 0 rule with a blending successor (D105), 5444 and rapid acc/dec (D106), `Details.VelLimit` under
MC_GroupSyncMoveAbsolute (D107) and the drive error reset of MC_GroupReset (D108).

Spec: omron-group-and-cam.md §0.4 (Moving includes in-position waiting), §4.3 MC_MoveLinear (seed 000 line 14568:
velocity profile, Deceleration = 0, BufferMode, 5444), §4.7 (line 16497: no in-position check on stop), §4.12
MC_GroupSyncMoveAbsolute (line 17041: VelLimit), §4.13 MC_GroupReset (line 17219: drive error reset, monitoring
time), §5.3 (interpolation warning values, line 17672); A-1 5444 (line 19902); omron-mc-basics.md §2.4 L378
(group Details.InPosWaiting = any composition axis waiting).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import pytest

from mcstudio.controller.kernel import Controller
from mcstudio.controller.mc.axis import axis_variables
from mcstudio.controller.mc.enums import AxisState
from mcstudio.controller.mc.group import AxesGroup, GroupState
from mcstudio.project.models import Project
from tests.conftest import step_until
from tests.controller.mc.group_helpers import group_project, positions, ready

G0 = "MC_Group000"
PPU = 104857.6  # pulses per mm of the fixtures (2^20 pulses per 10 mm)
LINE = {"Velocity": 100.0, "Acceleration": 1000.0, "Deceleration": 1000.0}


def _project(check_ms: int = 0, in_range: float = 0.01, **operation: Any) -> Project:
    p = group_project(**operation)
    for a in p.axes:
        a.parameters.Operation.InPosCheckTime = check_ms
        a.parameters.Operation.InPosRange = in_range
    return p


def _group(c: Controller, name: str = G0) -> AxesGroup:
    return c.mc.groups_by_name[name]


def _block(c: Controller, at_mm: float) -> Callable[[], None]:
    """A mechanical stop: the motor of MC_Axis000 (node 1) cannot pass `at_mm`. Returns the function that removes
    it. The drive's own following-error window is opened (these tests are about the MC module's reaction)."""
    plant = c.network.plant
    advance = plant.advance
    stop = int(at_mm * PPU)

    def blocked(position: Any, *args: Any, **kwargs: Any) -> Any:
        result = advance(position, *args, **kwargs)
        position[0] = min(int(position[0]), stop)
        return result

    def release() -> None:
        plant.advance = advance  # type: ignore[method-assign]

    plant.advance = blocked  # type: ignore[method-assign]
    c.network.drive_rx["following_error_window"][0] = 0xFFFFFFFF
    return release


def _until(c: Controller, cond: Callable[[], bool], limit: int = 1000) -> int:
    """Step one period at a time until `cond` holds (at most `limit` periods); returns the periods run."""
    for n in range(1, limit + 1):
        c.step(1)
        if cond():
            return n
    raise AssertionError(f"condition not met within {limit} periods")


def _events(c: Controller, code: int) -> list[Any]:
    return [e for e in c.events.list() if e.code == f"{code:04X}0000"]


# ------------------------------------------------------------------------------------------- in-position (D103)
def test_done_waits_for_in_position_of_every_composition_axis() -> None:
    """In-position Check Time 50 ms, range 0.01 mm: the command reaches (30, 40) but A0 is held 0.5 mm short. From the
    period after the final command value the group shows Details.InPosWaiting (Idle FALSE), stays Moving (§0.4 c),
    and A0 — only A0 — shows InPosWaiting; Done comes in the period the actual position is back in range."""
    c = Controller(_project(check_ms=50))
    ready(c)
    g = _group(c)
    release = _block(c, 29.5)
    mv = c.fb("MC_MoveLinearAbsolute", AxesGroup=G0, Execute=True, Position=[30.0, 40.0], **LINE)
    _until(c, lambda: g.in_pos_waiting)
    assert positions(c) == (30.0, 40.0) and mv.Busy and mv.Active and not mv.Done
    cap = g.capture()
    assert cap["Details"] == {"Idle": False, "InPosWaiting": True} and cap["Status"]["Moving"]
    assert [a.in_pos_waiting for a in g.axes] == [True, False]
    c.step(30)  # within the 50 ms: still waiting, no error
    assert g.in_pos_waiting and mv.Busy and g.error_code == 0
    release()
    n = step_until(c, mv, "Done", limit=20)
    assert n <= 3  # the drive follows within the next exchanges
    assert abs(float(c.mc.act_pos[0]) - 30.0) <= 0.01
    assert not g.in_pos_waiting and not any(a.in_pos_waiting for a in g.axes)
    assert g.state == GroupState.Standby and g.capture()["Details"] == {"Idle": True, "InPosWaiting": False}


def test_in_position_check_time_exceeded_is_6455_on_the_group() -> None:
    """The check time (50 ms from the period of the final command value) runs out with A0 still 0.5 mm short: the
    group error-stops with 6455 (D103/D19), the move is CommandAborted (aborted by the error), the composition axes
    keep no error (§4.1) and stay Coordinated; MC_GroupReset clears it."""
    c = Controller(_project(check_ms=50))
    ready(c)
    g = _group(c)
    _block(c, 29.5)
    mv = c.fb("MC_MoveLinearAbsolute", AxesGroup=G0, Execute=True, Position=[30.0, 40.0], **LINE)
    _until(c, lambda: g.in_pos_waiting)
    waiting_from = c.cycle
    step_until(c, mv, "CommandAborted", limit=100)
    assert 49 <= c.cycle - waiting_from <= 50, "the error comes when the 50 ms have run, not before"
    assert not mv.Error and not mv.Done
    assert g.state == GroupState.ErrorStop and g.error_code == 0x6455
    assert not g.in_pos_waiting and not any(a.in_pos_waiting for a in g.axes)
    assert all(a.error_code == 0 and a.state == AxisState.Coordinated for a in g.axes)
    ev = _events(c, 0x6455)
    assert ev and ev[-1].level == "minor fault" and "MC_Axis000" in ev[-1].detail
    rs = c.fb("MC_GroupReset", AxesGroup=G0, Execute=True)
    step_until(c, rs, "Done", limit=5)
    assert g.state == GroupState.Standby and g.error_code == 0


def test_no_in_position_wait_with_check_time_0() -> None:
    """In-position Check Time 0 (§5.5.3 L1487, D9): no in-position check — Done 600 periods after the start as with
    an ideal drive, although A0 is held 0.5 mm short."""
    c = Controller(_project(check_ms=0))
    ready(c)
    _block(c, 29.5)
    mv = c.fb("MC_MoveLinearAbsolute", AxesGroup=G0, Execute=True, Position=[30.0, 40.0], **LINE)
    assert step_until(c, mv, "Done", limit=700) == 601
    assert not _group(c).in_pos_waiting and float(c.mc.act_pos[0]) < 29.6


def test_buffered_successor_starts_after_the_in_position_check() -> None:
    """A Buffered successor starts when the move is Done (§4.3 BufferMode), i.e. after the in-position check."""
    c = Controller(_project(check_ms=50))
    ready(c)
    g = _group(c)
    release = _block(c, 29.5)
    mv1 = c.fb("MC_MoveLinearAbsolute", AxesGroup=G0, Execute=True, Position=[30.0, 40.0], **LINE)
    c.step(2)
    mv2 = c.fb("MC_MoveLinearAbsolute", AxesGroup=G0, Execute=True, Position=[0.0, 40.0], BufferMode=1, **LINE)
    _until(c, lambda: g.in_pos_waiting)
    c.step(10)
    assert positions(c) == (30.0, 40.0) and not mv2.Active
    release()
    step_until(c, mv1, "Done", limit=20)
    c.step(2)
    assert mv2.Active and positions(c)[0] < 30.0


def test_group_stop_while_waiting_for_in_position_needs_no_in_position() -> None:
    """MC_GroupStop during the in-position wait: the move is CommandAborted, the stop is Done without an in-position
    check (§4.7, seed 000 line 16497) and InPosWaiting clears."""
    c = Controller(_project(check_ms=500))
    ready(c)
    g = _group(c)
    _block(c, 29.5)
    mv = c.fb("MC_MoveLinearAbsolute", AxesGroup=G0, Execute=True, Position=[30.0, 40.0], **LINE)
    _until(c, lambda: g.in_pos_waiting)
    st = c.fb("MC_GroupStop", AxesGroup=G0, Execute=True, Deceleration=1000.0)
    c.step(1)
    assert mv.CommandAborted and not g.in_pos_waiting and not g.axes[0].in_pos_waiting
    step_until(c, st, "Done", limit=5)
    assert g.error_code == 0


# ------------------------------------------------------------------------------------------- warnings (D104)
def test_interpolation_velocity_warning_is_a_group_observation() -> None:
    """InterpolationVelWarningVal 5 % of MaxInterpolationVel 1000 → 50 mm/s: a 100 mm/s move sets the observation
    6464 (Obsr of the group, one event) while Cmd.Vel > 50; it clears when Cmd.Vel is back under it; the group keeps
    moving and no error is set."""
    c = Controller(_project(InterpolationVelWarningVal=5))
    ready(c)
    g = _group(c)
    mv = c.fb("MC_MoveLinearAbsolute", AxesGroup=G0, Execute=True, Position=[30.0, 40.0], **LINE)
    _until(c, lambda: g.cmd_vel > 40.0)
    assert g.capture()["Obsr"] == {"Active": False, "Code": "0000"}
    _until(c, lambda: g.cmd_vel > 50.0 or bool(g.observations), limit=20)
    assert g.cmd_vel > 50.0, "set in the period Cmd.Vel passes 50, not before"
    assert g.capture()["Obsr"] == {"Active": True, "Code": "6464"} and g.state == GroupState.Moving
    c.step(300)
    assert len(_events(c, 0x6464)) == 1 and _events(c, 0x6464)[0].level == "observation"
    _until(c, lambda: g.cmd_vel <= 50.0 and g.cmd_accdec < 0)
    assert g.capture()["Obsr"]["Active"] is False
    step_until(c, mv, "Done", limit=200)
    assert g.error_code == 0 and not mv.Error


def test_interpolation_acceleration_and_deceleration_warnings() -> None:
    """Acc/Dec warning values 50 % of MaxInterpolationAcc/Dec 1500 → 750 mm/s²: the 1000 mm/s² ramps set 6465 while
    accelerating and 6466 while decelerating; neither is set while cruising. MC_GroupReset clears an observation
    (§4.13)."""
    c = Controller(_project(MaxInterpolationAcc=1500.0, MaxInterpolationDec=1500.0, InterpolationAccWarningVal=50,
                            InterpolationDecWarningVal=50))
    ready(c)
    g = _group(c)
    c.fb("MC_MoveLinearAbsolute", AxesGroup=G0, Execute=True, Position=[30.0, 40.0], **LINE)
    c.step(20)
    assert g.observations == {0x6465: True}
    _until(c, lambda: g.cmd_accdec == 0.0)
    assert g.observations == {}
    _until(c, lambda: g.cmd_accdec < 0)
    c.step(1)
    assert g.observations == {0x6466: True}
    assert len(_events(c, 0x6466)) == 1
    rs = c.fb("MC_GroupReset", AxesGroup=G0, Execute=True)
    c.step(2)
    # the reset clears the observation; the deceleration goes on, so it is detected again as a new event (only the
    # errors present at the rising edge are cleared, §4.13)
    assert rs.Done and len(_events(c, 0x6466)) == 2
    _until(c, lambda: g.cmd_vel == 0.0)
    assert g.observations == {}


def test_no_acceleration_warning_without_a_maximum_interpolation_acceleration() -> None:
    """MaxInterpolationAcc 0 = no limit: a percentage of it gives no threshold, so no warning (D104)."""
    c = Controller(_project(InterpolationAccWarningVal=1))
    ready(c)
    mv = c.fb("MC_MoveLinearAbsolute", AxesGroup=G0, Execute=True, Position=[30.0, 40.0], **LINE)
    step_until(c, mv, "Done", limit=700)
    assert not _events(c, 0x6465) and not _group(c).observations


# ------------------------------------------------------------------------------------------- Dec = 0 (D105)
def _vel_trace(c: Controller, g: AxesGroup, n: int) -> list[float]:
    out = []
    for _ in range(n):
        c.step(1)
        out.append(g.cmd_vel)
    return out


@pytest.mark.parametrize(("v1", "v2"), [(50.0, 100.0), (100.0, 50.0)])
def test_deceleration_0_with_a_blending_successor_changes_instantly_to_its_velocity(v1: float, v2: float) -> None:
    """§4.3 velocity profile: "Deceleration = 0 … when the next instruction is buffered with a blending mode: no stop,
    the velocity changes instantly to the next instruction's target velocity" — whatever the BufferMode's transit
    velocity (here _mcBlendingLow = min(v1, v2)). The first move keeps v1 to its end (no deceleration); in the next
    period the path velocity is v2 (no ramp, D105); the first move is Done at the corner, the second Active."""
    c = Controller(_project())
    ready(c)
    g = _group(c)
    mv1 = c.fb("MC_MoveLinearAbsolute", AxesGroup=G0, Execute=True, Position=[20.0, 0.0], Velocity=v1,
               Acceleration=1000.0, Deceleration=0.0)
    c.step(1)
    mv2 = c.fb("MC_MoveLinearAbsolute", AxesGroup=G0, Execute=True, Position=[20.0, 20.0], Velocity=v2,
               Acceleration=1000.0, Deceleration=1000.0, BufferMode=2)
    trace: list[float] = []
    while not mv2.Active:  # up to the period of the hand-over
        c.step(1)
        trace.append(g.cmd_vel)
        assert len(trace) < 1000
    after = _vel_trace(c, g, 3)
    assert mv1.Done and positions(c)[1] > 0.0
    assert all(abs(v - v1) < 1e-9 for v in trace[-40:-1]), "v1 up to the corner: no deceleration"
    assert abs(trace[-1] - v2) < 1e-9 and all(abs(v - v2) < 1e-9 for v in after), "v2 at once, no ramp"


def test_deceleration_above_0_keeps_the_transit_velocity_of_the_buffer_mode() -> None:
    """The contrast: with Deceleration > 0 the first move ends at the _mcBlendingLow transit velocity min(100, 50)
    = 50 and the path velocity is 50 across the corner (§4.3 BufferMode)."""
    c = Controller(_project())
    ready(c)
    g = _group(c)
    c.fb("MC_MoveLinearAbsolute", AxesGroup=G0, Execute=True, Position=[20.0, 0.0], Velocity=100.0,
         Acceleration=1000.0, Deceleration=1000.0)
    c.step(1)
    c.fb("MC_MoveLinearAbsolute", AxesGroup=G0, Execute=True, Position=[20.0, 20.0], Velocity=200.0,
         Acceleration=1000.0, Deceleration=1000.0, BufferMode=2)
    _until(c, lambda: positions(c)[1] > 0.0)
    assert g.cmd_vel == pytest.approx(100.0, abs=1.0)  # min(100, 200): the transit velocity, then accelerating


# ------------------------------------------------------------------------------------------- 5444 (D106)
def _moving_at_100(c: Controller) -> Any:
    mv = c.fb("MC_MoveLinearAbsolute", AxesGroup=G0, Execute=True, Position=[100.0, 0.0], **LINE)
    c.step(200)  # cruising at 100 mm/s along A0 (x ≈ 15 mm)
    assert _group(c).cmd_vel == pytest.approx(100.0)
    return mv


def test_aborting_onto_a_moving_group_that_cannot_stop_is_5444_with_error_stop() -> None:
    """InterpolationAccDecOver = error stop: an Aborting MC_MoveLinearAbsolute 1 mm ahead on the same line with
    Deceleration 1000 mm/s² needs 5 mm to stop from 100 mm/s → 5444 (A-1, seed 000 line 19902): the new instruction
    Errors, the running one is CommandAborted, the group error-stops (MFaultLvl 5444)."""
    c = Controller(_project(InterpolationAccDecOver="_mcAccDecOverErrorStop"))
    ready(c)
    mv1 = _moving_at_100(c)
    x = positions(c)[0]
    mv2 = c.fb("MC_MoveLinearAbsolute", AxesGroup=G0, Execute=True, Position=[x + 1.0, 0.0], **LINE)
    c.step(1)
    assert mv2.Error and mv2.ErrorID == 0x5444 and mv1.CommandAborted
    g = _group(c)
    assert g.state == GroupState.ErrorStop and g.error_code == 0x5444


def test_aborting_onto_a_moving_group_uses_rapid_deceleration_otherwise() -> None:
    """InterpolationAccDecOver = rapid (default _mcAccDecOverBuffer, CPU ≥ 1.10 semantics as for axes): the same
    Aborting move arrives on its target with the deceleration it takes — never past it — and is Done."""
    c = Controller(_project())
    ready(c)
    _moving_at_100(c)
    x = positions(c)[0]
    mv2 = c.fb("MC_MoveLinearAbsolute", AxesGroup=G0, Execute=True, Position=[x + 1.0, 0.0], **LINE)
    peak = 0.0
    for _ in range(200):
        c.step(1)
        peak = max(peak, positions(c)[0])
        if mv2.Done:
            break
    assert mv2.Done and not mv2.Error
    assert positions(c) == (x + 1.0, 0.0) and peak <= x + 1.0 + 1e-9


# ------------------------------------------------------------------------------------------- VelLimit (D107)
def test_group_sync_move_sets_vel_limit_on_the_saturated_axis() -> None:
    """§4.12 (seed 000 line 17041): a target step above Maximum Velocity (500 mm/s → 0.5 mm per period) is output over
    several periods and Details.VelLimit of that axis is TRUE meanwhile (A1, with a small step, is not); it clears
    when the axis has caught up, and with MC_GroupStop."""
    c = Controller(_project())
    ready(c)
    g = _group(c)
    sm = c.fb("MC_GroupSyncMoveAbsolute", AxesGroup=G0, Execute=True, Position=[2.0, 0.1])
    c.step(2)
    a0, a1 = g.axes
    assert a0.vel_limit and not a1.vel_limit
    snap = c.publish().mc
    row = {"cmd_pos": 0.0, "cmd_vel": 0.0, "cmd_accdec": 0.0, "cmd_jerk": 0.0, "act_pos": 0.0, "act_vel": 0.0,
           "drv": {}}
    assert axis_variables(a0, snap["discrete"][a0.i], row)["Details"]["VelLimit"] is True
    assert axis_variables(a1, snap["discrete"][a1.i], row)["Details"]["VelLimit"] is False
    c.step(5)  # 2 mm at 0.5 mm per period: reached
    assert float(c.mc.cmd_pos[a0.i]) == 2.0 and not a0.vel_limit
    sm.set_inputs({"Position": [10.0, 0.1]})
    c.step(2)
    assert a0.vel_limit
    c.fb("MC_GroupStop", AxesGroup=G0, Execute=True)
    c.step(1)
    assert sm.CommandAborted and not a0.vel_limit


# ------------------------------------------------------------------------------------------- MC_GroupReset (D108)
def test_group_reset_resets_the_drive_error_of_a_composition_axis() -> None:
    """§4.13: a member's drive alarm (3002); MC_GroupReset sends the CiA402 fault reset first, then clears the axis
    error: Done, the axis leaves ErrorStop and its drive leaves Fault (Switch on disabled)."""
    c = Controller(_project())
    ready(c)
    g = _group(c)
    c.network.drives.inject_fault(0, 0x2310)
    c.step(3)
    a0 = g.axes[0]
    assert a0.error_code == 0x3002
    rs = c.fb("MC_GroupReset", AxesGroup=G0, Execute=True)
    c.step(1)
    assert rs.Busy and not rs.Done  # the drive reset takes periods
    step_until(c, rs, "Done", limit=300)
    assert a0.error_code == 0 and a0.state != AxisState.ErrorStop and int(c.network.drives.state[0]) == 1


def test_group_reset_fails_after_the_monitoring_time_when_the_drive_keeps_its_fault() -> None:
    """The cause persists: MC_GroupReset stays Busy for the member's Drive Error Reset Monitoring Time (200 ms), then
    Failure and the axis error stays; with the cause removed a new Execute is Done."""
    c = Controller(_project())
    ready(c)
    g = _group(c)
    c.network.drives.inject_fault(0, 0x7305, persistent=True)
    c.step(3)
    rs = c.fb("MC_GroupReset", AxesGroup=G0, Execute=True)
    c.step(100)
    assert rs.Busy and not rs.Failure
    n = step_until(c, rs, "Failure", limit=300)
    assert 90 <= n <= 110
    assert g.axes[0].error_code == 0x3002 and not c.mc.fault_reset_req[g.axes[0].i]
    c.network.drives.clear_fault_cause(0)
    rs.set_inputs({"Execute": False})
    c.step(1)
    rs.set_inputs({"Execute": True})
    step_until(c, rs, "Done", limit=300)
    assert g.axes[0].error_code == 0
