"""MC_DefineCoordSystem, MC_GroupMon and MC_MoveTimeAbsolute in a user coordinate system, as timing charts.

Spec: omron-robot-delta3.md §9.2 (seed 003 L2978–3101: CSID 0–15, Pose ranges, 570B, 570C with source MC common,
5710), §4 (R = Rz·Ry·Rx, p_MCS = T + R·p_UCS), §9.3 (L3102–3337: Valid/Busy, command position updated only while
the group is enabled, feedback position and velocity always, 5710/5466/542C/570B/570F), §9.4 (Position in the
chosen CS), §12.5 (TCP velocity). Decisions D83.
"""

from __future__ import annotations

import math

import pytest

from mcstudio.controller.mc.group import GroupState
from mcstudio.controller.mc.kinematics import forward_point, tcp_velocity_point
from tests.conftest import step_until
from tests.controller.mc.test_robot_motion import GRP, distance_to_segment, move, robot, tcp


def define(c, csid, pose):  # type: ignore[no-untyped-def]
    return c.fb("MC_DefineCoordSystem", AxesGroup=GRP, Execute=True, CoordTransform={"CSID": csid, "Pose": pose})


def test_define_coord_system_registers_a_ucs() -> None:
    """§9.2: cycle 0 Execute↑ → Busy; cycle 1 Done; CSID 5 holds the pose (works with the group disabled too)."""
    c, g = robot(enable=False)
    fb = define(c, 5, [10.0, -20.0, -200.0, 0.0, 0.0, 30.0])
    c.step(1)
    assert fb.Busy and not fb.Done
    c.step(1)
    assert fb.Done and not fb.Busy and not fb.Error
    assert g.coord_systems[5].pose() == [10.0, -20.0, -200.0, 0.0, 0.0, 30.0]


@pytest.mark.parametrize(("csid", "pose", "code", "group_error"), [
    (16, [0.0] * 6, 0x570B, True),
    (0, [0.0, 0.0, 0.0, 0.0, 91.0, 0.0], 0x570C, False),  # Ry −90…90
    (0, [0.0, 0.0, 0.0, -181.0, 0.0, 0.0], 0x570C, False),  # Rx −180…180
])
def test_define_coord_system_errors(csid: int, pose: list[float], code: int, group_error: bool) -> None:
    """§9.2/§11: 570B is a group error (ErrorStop); 570C has source MC common and no effect on the group."""
    c, g = robot()
    fb = define(c, csid, pose)
    c.step(1)
    assert fb.Error and fb.ErrorID == code
    assert (g.state == GroupState.ErrorStop) is group_error
    assert any(e.code == f"{code:04X}0000" for e in c.events.list())
    assert not g.coord_systems


def test_define_coord_system_without_kinematics_is_5710() -> None:
    c, g = robot()
    g.kinematics = None
    fb = define(c, 0, [0.0] * 6)
    c.step(1)
    assert fb.ErrorID == 0x5710


def test_move_time_absolute_in_a_ucs() -> None:
    """§9.4 + §4: Position in UCS 2 (T = (20, 10, −200), Rz = 90°) → the MCS target T + R·p; the TCP still moves on a
    straight line (1e-6 mm every period)."""
    c, g = robot()
    d = define(c, 2, [20.0, 10.0, -200.0, 0.0, 0.0, 90.0])
    step_until(c, d, "Done")
    p0 = tcp(c, g)
    fb = move(c, [30.0, 0.0, -20.0], CoordSystem="_mcRBT_UCS", CSID=2)
    target = (20.0, 40.0, -220.0)  # Xu = Ym
    worst = 0.0
    for _ in range(500):
        c.step(1)
        worst = max(worst, distance_to_segment(tcp(c, g), p0, target))
    assert worst < 1e-6
    c.step(1)
    assert fb.Done
    assert tcp(c, g) == pytest.approx(target, abs=1e-9)


def test_group_mon_positions_and_velocity_in_mcs_and_ucs() -> None:
    """§9.3: Valid and Busy with Enable; CommandPosition = FK(command angles of the last period), ActualPosition =
    FK(feedback angles), ActualVelocity = J(q)·q̇ of the feedback (§12.5), |ActualVelocity| = ActualVelocityTCP;
    in a UCS the same quantities transformed (p_UCS = Rᵀ·(p − T), v_UCS = Rᵀ·v)."""
    c, g = robot()
    d = define(c, 1, [0.0, 0.0, -200.0, 0.0, 0.0, 90.0])
    step_until(c, d, "Done")
    mon = c.fb("MC_GroupMon", AxesGroup=GRP, Enable=True)
    mon_u = c.fb("MC_GroupMon", AxesGroup=GRP, Enable=True, CoordSystem="_mcRBT_UCS", CSID=1)
    fb = move(c, [100.0, 0.0, -150.0])
    c.step(249)
    before = tcp(c, g)  # the instance reads the command of the previous period (program stage before motion)
    c.step(1)
    assert mon.Valid and mon.Busy and mon_u.Valid
    params = g.kinematics.params()  # type: ignore[union-attr]
    m = c.mc
    q_act = tuple(float(m.act_pos[i]) for i in g.idx)
    v_q = tuple(float(m.act_vel[i]) for i in g.idx)
    _, p_act = forward_point(params, *q_act)
    _, v_act = tcp_velocity_point(params, q_act, v_q)
    pos, vel = mon.Position, mon.Velocity
    assert pos["CommandPosition"][:3] == pytest.approx(before, abs=1e-9)
    assert pos["ActualPosition"][:3] == pytest.approx(p_act, abs=1e-9)
    assert vel["ActualVelocity"][:3] == pytest.approx(v_act, abs=1e-9)
    assert vel["ActualVelocityTCP"] == pytest.approx(math.hypot(*v_act), abs=1e-9)
    # half way through a 100 mm move along X in 0.5 s: about the peak speed 1.5·D/T = 300 mm/s, along +X
    assert vel["ActualVelocity"][0] == pytest.approx(300.0, rel=0.02) and abs(vel["ActualVelocity"][1]) < 1.0
    upos, uvel = mon_u.Position, mon_u.Velocity
    x, y, z = pos["ActualPosition"][:3]
    assert upos["ActualPosition"][:3] == pytest.approx([y, -x, z + 200.0], abs=1e-9)
    vx, vy, vz = vel["ActualVelocity"][:3]
    assert uvel["ActualVelocity"][:3] == pytest.approx([vy, -vx, vz], abs=1e-9)
    assert uvel["ActualVelocityTCP"] == pytest.approx(vel["ActualVelocityTCP"], abs=1e-9)
    assert fb.Active
    c.set_inputs(mon.id, {"Enable": False})
    c.step(1)
    assert not mon.Valid and not mon.Busy
    assert mon.Position["ActualPosition"] == pos["ActualPosition"]  # held after Enable↓


def test_group_mon_command_position_holds_while_disabled() -> None:
    """§9.3: with the group disabled the command position keeps its last enabled value; the feedback follows."""
    c, g = robot()
    mon = c.fb("MC_GroupMon", AxesGroup=GRP, Enable=True)
    c.step(1)
    cmd = list(mon.Position["CommandPosition"])
    dis = c.fb("MC_GroupDisable", AxesGroup=GRP, Execute=True)
    step_until(c, dis, "Done")
    a0 = g.axes[0]
    mv = c.fb("MC_MoveRelative", Axis=a0.name, Execute=True, Distance=5.0, Velocity=50.0, Acceleration=500.0,
              Deceleration=500.0)
    step_until(c, mv, "Done", limit=2000)
    assert mon.Valid
    assert mon.Position["CommandPosition"] == cmd
    assert mon.Position["ActualPosition"][:3] != pytest.approx(cmd[:3], abs=1e-3)


@pytest.mark.parametrize(("inputs", "code"), [({"CoordSystem": 2}, 0x542C),
                                               ({"CoordSystem": "_mcRBT_UCS", "CSID": 4}, 0x570B)])
def test_group_mon_errors(inputs: dict[str, object], code: int) -> None:
    c, g = robot()
    mon = c.fb("MC_GroupMon", AxesGroup=GRP, Enable=True, **inputs)
    c.step(1)
    assert mon.Error and mon.ErrorID == code and not mon.Valid and not mon.Busy
    assert g.state == GroupState.ErrorStop


def test_group_mon_without_home_is_5466() -> None:
    c, g = robot()
    g.axes[2].homed = False
    mon = c.fb("MC_GroupMon", AxesGroup=GRP, Enable=True)
    c.step(1)
    assert mon.ErrorID == 0x5466
