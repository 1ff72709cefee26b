"""MC_RobotJog (MC Studio extension, `fb/robot_jog.py`, decision D90) as timing charts on the paused controller.

Spec: omron-robot-delta3.md §12.8 [Emulator] — "a Cartesian jog for the test run is not an NJ feature; implement it
as … InverseKin + GroupSyncMoveAbsolute"; §3.2/§12.6 workspace (0.1 mm margin), §11 codes 6700 (command outside),
6701 (current outside at the start), 571B (target outside), 5710 (kinematics not set). The demo robot MC_Group000
(Rf 200, Lf 350, Rm 50, Lm 800 mm; workspace Zu −50, Rcy 300, Hcy 250, Rco 150, Hco 150) on MC_Axis004–006.
"""

from __future__ import annotations

import itertools
import math

import pytest

from mcstudio.controller.kernel import Controller
from mcstudio.controller.mc.fb.base import FunctionBlock
from mcstudio.controller.mc.group import GroupState
from mcstudio.controller.mc.kinematics import forward_point, inverse_point
from mcstudio.project.io import load_project
from tests.conftest import DEMO, step_until

GRP = "MC_Group000"
READY = (0.0, 0.0, -300.0)  # MCS [mm], inside the workspace


def _tcp(c: Controller, *, actual: bool = False) -> tuple[float, float, float]:
    g = c.mc.groups_by_name[GRP]
    src = c.mc.act_pos if actual else c.mc.cmd_pos
    status, p = forward_point(g.kinematics.params(), *(float(src[a.i]) for a in g.axes))  # type: ignore[union-attr]
    assert status.name == "OK"
    return p


def _robot_at(point: tuple[float, float, float] = READY, *, enable: bool = True) -> Controller:
    """Servo ON (absolute encoders: homed), the arms moved to the IK of `point` axis by axis, MC_GroupEnable."""
    c = Controller(load_project(DEMO))
    g = c.mc.groups_by_name[GRP]
    for a in g.axes:
        c.fb("MC_Power", Axis=a.name, Enable=True)
    c.step(20)
    _, angles = inverse_point(g.kinematics.params(), *point)  # type: ignore[union-attr]
    moves = [c.fb("MC_MoveAbsolute", Axis=a.name, Position=v, Velocity=180.0, Acceleration=1800.0,
                  Deceleration=1800.0, Execute=True) for a, v in zip(g.axes, angles, strict=True)]
    for mv in moves:
        step_until(c, mv, "Done", limit=5000)
    c.step(200)  # settle
    if enable:
        en = c.fb("MC_GroupEnable", AxesGroup=GRP, Execute=True)
        step_until(c, en, "Done")
    return c


def _jog(c: Controller, **inputs: object) -> FunctionBlock:
    return c.fb("MC_RobotJog", AxesGroup=GRP, **{"Velocity": 100.0, "Acceleration": 1000.0, **inputs})


def test_jog_plus_x_moves_the_tcp_along_x_only() -> None:
    """cycle 0 Enable↑ → Busy/Enabled, group Moving; Active from the next call; the command TCP moves along +X at
    100 mm/s after the ramp, Y and Z unchanged within 1e-6 mm every period; Enable↓ decelerates, the group is
    Standby again and the outputs drop."""
    c = _robot_at()
    g = c.mc.groups_by_name[GRP]
    p0 = _tcp(c)
    jog = _jog(c, Direction=[1.0, 0.0, 0.0], Enable=True)
    c.step(1)
    assert jog.Busy and jog.Enabled and not jog.Active and not jog.Error
    assert g.state == GroupState.Moving
    xs = []
    for _ in range(300):
        c.step(1)
        p = _tcp(c)
        assert abs(p[1] - p0[1]) < 1e-6 and abs(p[2] - p0[2]) < 1e-6, p
        xs.append(p[0])
    assert jog.Active
    assert all(b >= a for a, b in itertools.pairwise(xs))  # monotonic +X
    assert xs[-1] - xs[-2] == pytest.approx(0.1, abs=1e-6)  # 100 mm/s × 1 ms after the 0.1 s ramp
    assert jog.CommandVelocity == pytest.approx(100.0)
    assert list(jog.CommandPosition) == pytest.approx(list(_tcp(c)), abs=1e-9)
    jog.Enable = False
    step_until(c, jog, "Busy", False, limit=500)
    p_end = _tcp(c)
    assert abs(p_end[1] - p0[1]) < 1e-6 and abs(p_end[2] - p0[2]) < 1e-6
    c.step(2)
    assert g.state == GroupState.Standby and not jog.Active and not jog.Enabled
    c.step(300)
    pa = _tcp(c, actual=True)  # the axes followed: the feedback TCP is there too
    assert pa == pytest.approx(p_end, abs=0.01)


def test_jog_stops_inside_at_the_workspace_boundary() -> None:
    """Jog −Z from z = −300 towards the bottom of the cone (Zu − Hcy − Hco = −450): the point stops inside the
    0.1 mm margin, AtBoundary and WarningID 6700 (a warning, no error); the group stays Moving under control, and a
    jog back up moves again."""
    c = _robot_at((0.0, 0.0, -420.0))
    g = c.mc.groups_by_name[GRP]
    ws = g.kinematics.workspace_obj()  # type: ignore[union-attr]
    jog = _jog(c, Direction=[0.0, 0.0, -1.0], Velocity=200.0, Enable=True)
    step_until(c, jog, "AtBoundary", limit=2000)
    p = _tcp(c)
    assert ws.z_bottom + 0.1 - 1e-6 <= p[2] < ws.z_bottom + 0.1 + 0.01  # at the boundary, inside the margin
    assert jog.out["WarningID"] == 0x6700
    assert not jog.Error and g.error_code == 0
    for _ in range(50):  # pushing on: never leaves
        c.step(1)
        assert _tcp(c)[2] >= ws.z_bottom + 0.1 - 1e-6
    assert any(e.code == "67000000" for e in c.mc.events.list())
    jog.Direction = [0.0, 0.0, 1.0]
    c.step(100)
    assert _tcp(c)[2] > p[2] + 1.0 and not jog.AtBoundary and jog.out["WarningID"] == 0


def test_jog_refuses_a_start_outside_the_workspace() -> None:
    """The zero pose (TCP at the MCS origin) is above Zu = −50: Enable↑ → 6701, the group in ErrorStop."""
    c = Controller(load_project(DEMO))
    g = c.mc.groups_by_name[GRP]
    for a in g.axes:
        c.fb("MC_Power", Axis=a.name, Enable=True)
    c.step(20)
    en = c.fb("MC_GroupEnable", AxesGroup=GRP, Execute=True)
    step_until(c, en, "Done")
    jog = _jog(c, Enable=True)
    c.step(1)
    assert jog.Error and jog.out["ErrorID"] == 0x6701 and g.state == GroupState.ErrorStop


def test_jog_needs_an_enabled_group_and_valid_inputs() -> None:
    c = _robot_at(enable=False)
    jog = _jog(c, Enable=True)
    c.step(1)
    assert jog.Error and jog.out["ErrorID"] == 0x543F  # group disabled
    c2 = _robot_at()
    bad = _jog(c2, Velocity=0.0, Enable=True)
    c2.step(1)
    assert bad.Error and bad.out["ErrorID"] == 0x5422


def test_go_to_moves_on_a_straight_line_and_reports_in_position() -> None:
    """Mode 1: to (100, 50, −350) on the straight line from the start, InPosition at the target; a target outside
    the workspace → WarningID 571B and no motion."""
    c = _robot_at()
    a = _tcp(c)
    goal = (100.0, 50.0, -350.0)
    jog = _jog(c, Mode=1, TargetPosition=list(goal), Velocity=250.0, Acceleration=2500.0, Enable=True)
    d = [y - x for x, y in zip(a, goal, strict=True)]
    n = math.sqrt(sum(x * x for x in d))
    for _ in range(200):
        c.step(1)
        p = _tcp(c)
        w = [y - x for x, y in zip(a, p, strict=True)]
        t = sum(x * y for x, y in zip(w, d, strict=True)) / n
        assert math.sqrt(max(sum(x * x for x in w) - t * t, 0.0)) < 1e-6
    step_until(c, jog, "InPosition", limit=3000)
    assert _tcp(c) == pytest.approx(goal, abs=1e-6)
    jog.TargetPosition = [0.0, 0.0, 0.0]  # above Zu
    c.step(5)
    assert jog.out["WarningID"] == 0x571B and _tcp(c) == pytest.approx(goal, abs=1e-6)


def test_group_stop_aborts_the_jog() -> None:
    c = _robot_at()
    g = c.mc.groups_by_name[GRP]
    jog = _jog(c, Direction=[0.0, 1.0, 0.0], Enable=True)
    c.step(50)
    stop = c.fb("MC_GroupStop", AxesGroup=GRP, Execute=True)
    c.step(3)
    assert jog.CommandAborted and not jog.Busy and g.state == GroupState.Stopping
    stop.Execute = False
    jog.Enable = False
    c.step(3)
    assert g.state == GroupState.Standby and not jog.CommandAborted


def test_jog_in_a_ucs_follows_its_axes() -> None:
    """CoordSystem 3 (UCS): with MC_DefineCoordSystem CSID 2 turned by Rz = 90° and moved to (0, 0, −300), +X of
    the UCS is +Y of the MCS; CommandPosition is in the UCS. CSID 5 (not defined) → 570B."""
    c = _robot_at()
    d = c.fb("MC_DefineCoordSystem", AxesGroup=GRP, Execute=True,
             CoordTransform={"CSID": 2, "Pose": [0.0, 0.0, -300.0, 0.0, 0.0, 90.0]})
    step_until(c, d, "Done")
    p0 = _tcp(c)
    jog = _jog(c, Direction=[1.0, 0.0, 0.0], CoordSystem=3, CSID=2, Enable=True)
    c.step(200)
    p = _tcp(c)
    assert p[1] > p0[1] + 5.0 and abs(p[0] - p0[0]) < 1e-6 and abs(p[2] - p0[2]) < 1e-6
    assert list(jog.CommandPosition) == pytest.approx([p[1], -p[0], p[2] + 300.0], abs=1e-6)
    jog.Enable = False
    step_until(c, jog, "Busy", False, limit=500)
    bad = _jog(c, CoordSystem=3, CSID=5, Enable=True)
    c.step(1)
    assert bad.Error and bad.out["ErrorID"] == 0x570B


def test_deleting_a_running_jog_ends_its_job_and_holds_the_robot() -> None:
    """D90: deleting the instance while it moves (the studio's lease expiring on a crashed page ends up here, too)
    ends the group's synchronous job through the group's public `end_sync`: the command holds where it is, the group
    is Standby at once and takes the next instruction."""
    c = _robot_at()
    g = c.mc.groups_by_name[GRP]
    jog = _jog(c, Direction=[1.0, 0.0, 0.0], Enable=True)
    c.step(100)
    assert g.state == GroupState.Moving and jog.CommandVelocity > 0
    c.delete_fb(jog.id)
    held = [float(c.mc.cmd_pos[i]) for i in g.idx]
    assert g.state == GroupState.Standby and g.current is None
    c.step(5)
    assert [float(c.mc.cmd_pos[i]) for i in g.idx] == held
    again = _jog(c, Direction=[0.0, 1.0, 0.0], Enable=True)
    c.step(50)
    assert again.Active and not again.Error and g.state == GroupState.Moving


def test_step_mode_moves_exactly_the_distance_in_a_ucs_then_stops() -> None:
    """Mode 2 (D93, inching): at Enable↑ a step of Distance along Direction of the chosen CS — here +X of a UCS
    turned by Rz = 90° (= +Y of the MCS) — on a straight line, ending exactly Distance further and InPosition; the
    group stays Moving under control until Enable↓, then Standby; the next step needs a new Enable↑."""
    c = _robot_at()
    g = c.mc.groups_by_name[GRP]
    d = c.fb("MC_DefineCoordSystem", AxesGroup=GRP, Execute=True,
             CoordTransform={"CSID": 1, "Pose": [0.0, 0.0, -300.0, 0.0, 0.0, 90.0]})
    step_until(c, d, "Done")
    p0 = _tcp(c)
    jog = _jog(c, Mode=2, Distance=10.0, Direction=[1.0, 0.0, 0.0], CoordSystem=3, CSID=1, Enable=True)
    step_until(c, jog, "InPosition", limit=2000)
    p = _tcp(c)
    assert p == pytest.approx((p0[0], p0[1] + 10.0, p0[2]), abs=1e-9)
    assert list(jog.CommandPosition) == pytest.approx([p[1], -p[0], p[2] + 300.0], abs=1e-9)
    c.step(50)
    assert _tcp(c) == p and jog.InPosition and g.state == GroupState.Moving
    jog.Enable = False
    step_until(c, jog, "Busy", False, limit=10)
    assert g.state == GroupState.Standby
    jog.Direction = [0.0, -1.0, 0.0]  # −Y of the UCS = +X of the MCS
    jog.Enable = True
    c.step(1)
    step_until(c, jog, "InPosition", limit=2000)
    assert _tcp(c) == pytest.approx((p0[0] + 10.0, p0[1] + 10.0, p0[2]), abs=1e-9)


def test_step_mode_stops_at_the_boundary_and_needs_a_positive_distance() -> None:
    """Mode 2: a step past the workspace's bottom face stops inside the 0.1 mm margin (AtBoundary, WarningID 6700,
    not InPosition) like the jog; Distance ≤ 0 → 5479 (Travel Distance Out of Range)."""
    c = _robot_at((0.0, 0.0, -440.0))
    g = c.mc.groups_by_name[GRP]
    ws = g.kinematics.workspace_obj()  # type: ignore[union-attr]
    jog = _jog(c, Mode=2, Distance=20.0, Direction=[0.0, 0.0, -1.0], Enable=True)
    step_until(c, jog, "AtBoundary", limit=2000)
    assert ws.z_bottom + 0.1 - 1e-6 <= _tcp(c)[2] < ws.z_bottom + 0.1 + 0.01
    assert jog.out["WarningID"] == 0x6700 and not jog.InPosition and not jog.Error
    c2 = _robot_at()
    bad = _jog(c2, Mode=2, Distance=0.0, Enable=True)
    c2.step(1)
    assert bad.Error and bad.out["ErrorID"] == 0x5479
