"""MC_SyncLinearConveyor and MC_SyncOut as timing charts: the demo Delta3 tracking workpieces of the plant's
WorkpieceSource on the conveyor axis MC_Axis007 (rotary, mm) moving at 100 mm/s.

Spec: omron-robot-delta3.md §9.5 (seed 003 L3637–4394: flat trajectory T1/T2/T3, Ttrans1/2, H1, phases 1–6,
RemainTime, InSync after T1 + T2 + T3·(1 − Ttrans2) within 0.1 mm per 1 ms, 6702, 571A, 5719, 5714–5717, conveyor
direction = X of the CS, UCS Rx/Ry ignored), §9.6 (L4395–4703: _mcSyncStop only in phase 6, velocity-continuous
release over T4 with the H4 lift, _mcRBT_ImmediateStop, 571C), §10.1 (multi-execution). Decision D84.
"""

from __future__ import annotations

import math
from typing import Any

import pytest

from mcstudio.controller.kernel import Controller
from mcstudio.controller.mc.fb.base import FunctionBlock
from mcstudio.controller.mc.group import AxesGroup, GroupState
from mcstudio.plant.workpieces import WorkpieceSource
from tests.conftest import step_until
from tests.controller.mc.test_robot_motion import GRP, move, robot, tcp

CONV = "MC_Axis007"
BELT_Z = -280.0  # belt surface in the MCS (UCS 0: the conveyor's coordinate system)
SRC = WorkpieceSource(pitch=200.0, entry_x=-250.0, exit_x=250.0, y=20.0, z=0.0)
TD = {"SyncTrajType": 0, "TrajTime": [100, 300, 100], "TrajTransition": [50, 50], "TrajDistance": [30.0],
      "MaxVelocity": 5000.0, "MaxAcceleration": 1e6}
OUT = {"SyncStopType": 0, "TrajTime": [200], "TrajDistance": [50.0], "MaxVelocity": 5000.0, "MaxAcceleration": 1e6}


def tracking_rig(speed: float = 100.0) -> tuple[Controller, AxesGroup, FunctionBlock]:
    """Robot at (0, 0, −150), UCS 0 = the belt (origin at z = −280), conveyor moving at `speed` mm/s."""
    c, g = robot()
    d = c.fb("MC_DefineCoordSystem", AxesGroup=GRP, Execute=True,
             CoordTransform={"CSID": 0, "Pose": [0.0, 0.0, BELT_Z, 0.0, 0.0, 0.0]})
    step_until(c, d, "Done")
    c.fb("MC_Power", Axis=CONV, Enable=True)
    c.step(20)
    mv = c.fb("MC_MoveVelocity", Axis=CONV, Execute=True, Velocity=speed, Acceleration=1000.0, Deceleration=1000.0)
    if speed:
        step_until(c, mv, "InVelocity", limit=2000)
    return c, g, mv


def conveyor_mm(c: Controller) -> float:
    return float(c.mc.act_pos[c.mc.by_name[CONV].i])


def sync(c: Controller, init: list[float], **inputs: Any) -> FunctionBlock:
    args: dict[str, Any] = {"AxesGroup": GRP, "ConveyorAxis": CONV, "Execute": True, "InitWorkpiecePosition": init,
                            "TrajData": TD, "CoordSystem": "_mcRBT_UCS", "CSID": 0, **inputs}
    return c.fb("MC_SyncLinearConveyor", **args)


def test_catch_up_insync_and_follow_the_workpiece() -> None:
    """§9.5 timing chart (T1 100, T2 300, T3 100 ms, Ttrans 50 %, H1 30 mm): cycle 0 Busy, group Moving; phases
    1 (≤ 50 ms) 2 (≤ 100) 3 (≤ 400) 4 (≤ 450) 5 (≤ 500) 6; the rise reaches P0.z + H1 at T1; InSync in the first period
    after T1 + T2 + T3·(1 − Ttrans2) = 450 ms (phase 5: "InSync is TRUE in phases 5 and 6"), and from then on X/Y
    are exactly the workpiece's (the plant's WorkpieceSource position, moving with the conveyor feedback) and Z
    reaches the belt at 500 ms; RemainTime counts
    down T1 + T2 + T3; no Done."""
    c, g, _ = tracking_rig()
    c_now = conveyor_mm(c)
    k = math.floor(c_now / SRC.pitch)  # the latest workpiece on the belt
    init = list(SRC.workpiece(k, c_now))
    assert -250.0 <= init[0] <= 250.0
    p0 = tcp(c, g)
    fb = sync(c, init)
    c.step(1)
    assert fb.Busy and not fb.Active and not fb.InSync and g.state == GroupState.Moving
    c0 = conveyor_mm(c)  # InitWorkpiecePosition is where the workpiece is in the Execute period
    phases = {}
    for n in range(1, 700):
        c.step(1)
        t_ms = n + 1  # the command of period n is for t = (n + 1)·T
        # TrajStatus and InSync are pushed in the period of the command they describe (D84)
        phases.setdefault(fb.TrajStatus["Phase"], t_ms)
        assert fb.TrajStatus["RemainTime"] == max(0, 500 - t_ms)
        assert fb.Busy and fb.Active and not fb.Error
        if t_ms == 100:
            assert tcp(c, g)[2] == pytest.approx(p0[2] + 30.0, abs=1e-9)  # rise H1 after T1
        assert fb.InSync == (t_ms > 450), f"t = {t_ms} ms"
        if t_ms > 450:
            wx, wy, wz = SRC.workpiece(k, conveyor_mm(c) - (c0 - c_now))
            p = tcp(c, g)
            assert (p[0], p[1]) == pytest.approx((wx, wy), abs=1e-9)
            if t_ms >= 500:
                assert p[2] == pytest.approx(BELT_Z + wz, abs=1e-9)
    assert phases == {1: 2, 2: 51, 3: 101, 4: 401, 5: 451, 6: 501}
    assert "Done" not in fb.out


def test_sync_out_leaves_velocity_continuously_and_lifts() -> None:
    """§9.6 _mcSyncStop in phase 6: the running MC_SyncLinearConveyor is CommandAborted, the TCP leaves with the
    conveyor velocity (no velocity jump), decelerates to 0 over T4 = 200 ms travelling v·T4/2 = 10 mm in X and rises
    H4 = 50 mm; Done in the period after T4; group Standby."""
    c, g, _ = tracking_rig()
    c_now = conveyor_mm(c)
    k = math.floor(c_now / SRC.pitch)
    fb = sync(c, list(SRC.workpiece(k, c_now)))
    c.step(600)
    assert fb.TrajStatus["Phase"] == 6
    before = tcp(c, g)
    c.step(1)
    p_last = tcp(c, g)
    v_in = (p_last[0] - before[0]) * 1000.0
    out = c.fb("MC_SyncOut", AxesGroup=GRP, Execute=True, TrajData=OUT)
    c.step(1)
    assert fb.CommandAborted and not fb.InSync and out.Busy
    p1 = tcp(c, g)
    assert (p1[0] - p_last[0]) * 1000.0 == pytest.approx(v_in, rel=0.01)  # velocity continuous
    for _ in range(198):
        c.step(1)
        assert out.Busy and not out.Done
    c.step(1)  # t = T4: the last command
    end = tcp(c, g)
    assert end[0] - p_last[0] == pytest.approx(v_in * 0.2 / 2, abs=0.05)
    assert end[2] == pytest.approx(p_last[2] + 50.0, abs=1e-9)
    c.step(1)
    assert out.Done and g.state == GroupState.Standby
    c.step(5)
    assert tcp(c, g) == pytest.approx(end, abs=1e-12)


def test_sync_out_immediate_stop_in_any_phase() -> None:
    """§9.6 _mcRBT_ImmediateStop while catching up (phase 3): MC_SyncLinearConveyor CommandAborted, no further
    command (the TCP stops at once), Done in the next period."""
    c, g, _ = tracking_rig()
    fb = sync(c, [-100.0, 20.0, 0.0])
    c.step(200)
    assert fb.TrajStatus["Phase"] == 3
    held = tcp(c, g)
    out = c.fb("MC_SyncOut", AxesGroup=GRP, Execute=True, TrajData={**OUT, "SyncStopType": 1})
    c.step(1)
    assert fb.CommandAborted and out.Busy
    assert tcp(c, g) == pytest.approx(held, abs=1e-12)
    c.step(1)
    assert out.Done and g.state == GroupState.Standby


def test_sync_out_errors_571c() -> None:
    """§9.6 / §10.1: _mcSyncStop before InSync (phase ≠ 6) → 571C; without MC_SyncLinearConveyor (nothing or
    MC_MoveTimeAbsolute running) → 571C; the robot stops immediately."""
    c, g, _ = tracking_rig()
    fb = sync(c, [-100.0, 20.0, 0.0])
    c.step(100)
    out = c.fb("MC_SyncOut", AxesGroup=GRP, Execute=True, TrajData=OUT)
    c.step(1)
    assert out.ErrorID == 0x571C and fb.CommandAborted and g.state == GroupState.ErrorStop
    c, g, _ = tracking_rig()
    out = c.fb("MC_SyncOut", AxesGroup=GRP, Execute=True, TrajData={**OUT, "SyncStopType": 1})
    c.step(1)
    assert out.ErrorID == 0x571C
    c, g, _ = tracking_rig()
    mv = move(c, [50.0, 0.0, -150.0])
    c.step(10)
    out = c.fb("MC_SyncOut", AxesGroup=GRP, Execute=True, TrajData={**OUT, "SyncStopType": 1})
    c.step(1)
    assert out.ErrorID == 0x571C and mv.CommandAborted


def test_conveyor_speed_change_before_catch_up_is_6702() -> None:
    """§9.5: the conveyor accelerates before the robot caught up → at T1 + T2 + T3·(1 − Ttrans2) the command is off
    the workpiece by more than 0.1 mm → 6702, immediate stop, group ErrorStop."""
    c, g, _ = tracking_rig()
    fb = sync(c, [-100.0, 20.0, 0.0])
    c.step(100)
    c.fb("MC_MoveVelocity", Axis=CONV, Execute=True, Velocity=150.0, Acceleration=1000.0, Deceleration=1000.0)
    step_until(c, fb, "Error", limit=1000)
    assert fb.ErrorID == 0x6702 and not fb.InSync and g.state == GroupState.ErrorStop
    assert any(e.code == "67020000" for e in c.events.list())


@pytest.mark.parametrize(("inputs", "code"), [
    ({"ConveyorAxis": "MC_Axis004"}, 0x571A),  # a robot axis (group member, degrees)
    ({"InitWorkpiecePosition": [-100.0, 20.0, -200.0]}, 0x5719),  # 480 mm below the belt: outside the workspace
    ({"TrajData": {**TD, "TrajTime": [100, 0, 100]}}, 0x5714),
    ({"TrajData": {**TD, "TrajTransition": [40, 50]}}, 0x5716),
    ({"TrajData": {**TD, "TrajDistance": [30.0, 1.0]}}, 0x5717),
    ({"TrajData": {**TD, "SyncTrajType": 1}}, 0x5715),
    ({"TrajData": {**TD, "MaxAcceleration": 0.0}}, 0x5713),
    ({"CSID": 9}, 0x570B),
])
def test_sync_linear_conveyor_input_errors(inputs: dict[str, Any], code: int) -> None:
    c, g, _ = tracking_rig()
    fb = sync(c, [-100.0, 20.0, 0.0], **inputs)
    c.step(1)
    assert fb.Error and fb.ErrorID == code, f"{fb.ErrorID:04X}"
    assert g.state == GroupState.ErrorStop


def test_move_time_absolute_aborts_the_tracking_ok1() -> None:
    """§10.1 OK1: MC_MoveTimeAbsolute onto MC_SyncLinearConveyor (any phase) aborts it and starts from velocity 0."""
    c, _, _ = tracking_rig()
    fb = sync(c, [-100.0, 20.0, 0.0])
    c.step(600)
    mv = move(c, [0.0, 0.0, -150.0])
    c.step(1)
    assert fb.CommandAborted and mv.Busy
    step_until(c, mv, "Done", limit=1000)
