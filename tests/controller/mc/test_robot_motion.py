"""MC_MoveTimeAbsolute as timing charts on the paused controller (the demo's Delta3 MC_Group000, period 1 ms).

Spec: omron-robot-delta3.md §9.4 (seed 003 L3338–3636: cubic time law on X, Y, Z, Done when the target time is
reached, no in-position check, 6703/6704 at start, workspace checks 6701/571B/6700, 6705, input errors, 543B on
re-execution), §10.1 (OK1: aborting, the new command starts from velocity 0), §10.3 (Standby → Moving → Standby,
MC_GroupStop → Stopping), §7.2 (MC_GroupStop stops a robot immediately), §7.4 (group Cmd.Vel stays 0), §11 (every
robot error: group ErrorStop, immediate stop). Decisions D80–D82.
"""

from __future__ import annotations

import math
from typing import Any

import pytest

from mcstudio.controller.kernel import Controller
from mcstudio.controller.mc.fb.base import FunctionBlock
from mcstudio.controller.mc.group import AxesGroup, GroupState
from mcstudio.controller.mc.kinematics import forward_point, inverse_point
from mcstudio.project.io import load_project
from tests.conftest import DEMO, step_until

GRP = "MC_Group000"
HOME = (0.0, 0.0, -150.0)  # a TCP position inside the demo workspace (Zu −50, Rcy 300, Hcy 250, Rco 150, Hco 150)
TRAJ = {"MoveTrajType": 0, "TrajTime": 500, "MaxVelocity": 2000.0, "MaxAcceleration": 50000.0}


def robot(*, at: tuple[float, float, float] | None = HOME, enable: bool = True, power: bool = True
          ) -> tuple[Controller, AxesGroup]:
    """The demo robot (project kinematics in force from cycle 0, D71): servo ON, the TCP moved to `at` with
    single-axis moves while the group is disabled, then MC_GroupEnable."""
    c = Controller(load_project(DEMO))
    c.step(2)
    g = c.mc.groups_by_name[GRP]
    if power:
        for a in g.axes:
            c.fb("MC_Power", Axis=a.name, Enable=True)
        c.step(20)
    if at is not None:
        assert g.kinematics is not None
        _, q = inverse_point(g.kinematics.params(), *at)
        moves = [c.fb("MC_MoveAbsolute", Axis=a.name, Execute=True, Position=q[k], Velocity=100.0,
                      Acceleration=1000.0, Deceleration=1000.0) for k, a in enumerate(g.axes)]
        for mv in moves:
            step_until(c, mv, "Done", limit=5000)
    if enable:
        en = c.fb("MC_GroupEnable", AxesGroup=GRP, Execute=True)
        step_until(c, en, "Done")
    return c, g


def tcp(c: Controller, g: AxesGroup) -> tuple[float, float, float]:
    assert g.kinematics is not None
    st, p = forward_point(g.kinematics.params(), *[float(c.mc.cmd_pos[i]) for i in g.idx])
    assert st == 0
    return p


def move(c: Controller, target: list[float], **inputs: Any) -> FunctionBlock:
    args: dict[str, Any] = {"AxesGroup": GRP, "Execute": True, "Position": target, "TrajData": TRAJ, **inputs}
    return c.fb("MC_MoveTimeAbsolute", **args)


def distance_to_segment(p: tuple[float, ...], a: tuple[float, ...], b: tuple[float, ...]) -> float:
    d = [y - x for x, y in zip(a, b, strict=True)]
    w = [y - x for x, y in zip(a, p, strict=True)]
    n2 = sum(x * x for x in d)
    t = min(1.0, max(0.0, sum(x * y for x, y in zip(w, d, strict=True)) / n2))
    return math.dist(p, [x + t * y for x, y in zip(a, d, strict=True)])


def test_straight_line_in_the_target_time() -> None:
    """§9.4 timing chart: cycle 0 Execute↑ → Busy, group Moving; cycle 1 Active; every period the forward kinematics
    of the command angles lies within 1e-6 mm of the segment P0–P1 and follows P0 + (P1 − P0)·(3τ² − 2τ³);
    cycle 500 (TrajTime 500 ms) Done, Busy/Active ↓, group Standby; the last command is P1. Group Cmd.Vel stays 0
    (§7.4)."""
    c, g = robot()
    p0 = tcp(c, g)
    p1 = (60.0, -40.0, -260.0)
    fb = move(c, list(p1))
    c.step(1)
    assert fb.Busy and not fb.Active and g.state == GroupState.Moving
    worst = 0.0
    for k in range(1, 500):
        p = tcp(c, g)
        worst = max(worst, distance_to_segment(p, p0, p1))
        tau = k / 500
        s = 3 * tau**2 - 2 * tau**3
        assert p == pytest.approx([a + (b - a) * s for a, b in zip(p0, p1, strict=True)], abs=1e-6)
        c.step(1)
        assert fb.Busy and fb.Active and not fb.Done, f"cycle {k}"
        assert g.capture()["Cmd"]["Vel"] == 0.0
    assert worst < 1e-6
    assert tcp(c, g) == pytest.approx(p1, abs=1e-9)  # cycle 499: τ = 1
    c.step(1)  # cycle 500
    assert fb.Done and not fb.Busy and not fb.Active and not fb.Error
    assert g.state == GroupState.Standby
    c.set_inputs(fb.id, {"Execute": False})
    c.step(1)
    assert not fb.Done


def test_target_outside_the_workspace_is_571b_and_stops_the_robot_immediately() -> None:
    """§9.4 / §3.2 check 2: a target outside the workspace → 571B at start; the group goes to ErrorStop, the running
    MC_MoveTimeAbsolute is CommandAborted and the command positions hold where they are (immediate stop, §11 B)."""
    c, g = robot()
    first = move(c, [100.0, 0.0, -250.0])
    c.step(100)
    assert first.Active
    held = [float(c.mc.cmd_pos[i]) for i in g.idx]
    bad = move(c, [0.0, 0.0, -10.0])  # above Zu = −50 mm
    c.step(1)
    assert bad.Error and bad.ErrorID == 0x571B and not bad.Busy
    assert first.CommandAborted and not first.Busy
    assert g.state == GroupState.ErrorStop and g.error_code == 0x571B
    assert any(e.code == "571B0000" for e in c.events.list())
    # the start error is detected in the program stage, before this period's command: the command holds
    assert [float(c.mc.cmd_pos[i]) for i in g.idx] == held
    c.step(5)
    assert [float(c.mc.cmd_pos[i]) for i in g.idx] == held
    assert all(float(c.mc.cmd_vel[i]) == 0.0 for i in g.idx)
    reset = c.fb("MC_GroupReset", AxesGroup=GRP, Execute=True)
    step_until(c, reset, "Done")
    assert g.state == GroupState.Standby and not bad.Error


def test_current_position_outside_is_6701() -> None:
    """§3.2 check 1: the zero pose (TCP at the MCS origin) is above the demo workspace → 6701 at start."""
    c, g = robot(at=None)
    fb = move(c, [0.0, 0.0, -150.0])
    c.step(1)
    assert fb.Error and fb.ErrorID == 0x6701 and g.state == GroupState.ErrorStop


def test_workspace_check_off_allows_a_start_outside() -> None:
    """MC_SetKinTransform EnableWorkspace = FALSE: no workspace checks (§9.1, §3.2)."""
    c, g = robot(at=None)
    g.workspace_check = False
    fb = move(c, [0.0, 0.0, -150.0])
    step_until(c, fb, "Done", limit=1000)
    assert tcp(c, g) == pytest.approx((0.0, 0.0, -150.0), abs=1e-9)


def test_velocity_and_acceleration_errors_at_start() -> None:
    """§9.4: 1.5·D/T > MaxVelocity → 6703; 6·D/T² > MaxAcceleration → 6704 (TCP vector magnitudes, D81)."""
    c, g = robot()
    fb = move(c, [0.0, 0.0, -250.0], TrajData={**TRAJ, "MaxVelocity": 299.0})  # 1.5·100/0.5 = 300 mm/s
    c.step(1)
    assert fb.ErrorID == 0x6703 and g.state == GroupState.ErrorStop
    c, g = robot()
    fb = move(c, [0.0, 0.0, -250.0], TrajData={**TRAJ, "MaxVelocity": 300.0, "MaxAcceleration": 2399.0})
    c.step(1)
    assert fb.ErrorID == 0x6704  # 6·100/0.25 = 2400 mm/s²
    c, g = robot()
    fb = move(c, [0.0, 0.0, -250.0], TrajData={**TRAJ, "MaxVelociy": 300.0, "MaxAcceleration": 2400.0})
    del fb.inp["TrajData"]["MaxVelocity"]
    step_until(c, fb, "Done", limit=1000)  # exactly at the thresholds; the manual's spelling MaxVelociy accepted


def test_axis_maximum_velocity_is_6705_during_execution() -> None:
    """§9.4: an axis' command velocity above its Maximum Velocity (360°/s in the demo) → 6705 during execution,
    the robot stops immediately with the last command that passed."""
    c, g = robot()
    fb = move(c, [0.0, 0.0, -380.0], TrajData={**TRAJ, "TrajTime": 60, "MaxVelocity": 1e6,
                                                 "MaxAcceleration": 1e9})
    c.step(1)
    assert fb.Busy
    step_until(c, fb, "Error", limit=100)
    assert fb.ErrorID == 0x6705 and g.state == GroupState.ErrorStop
    held = [float(c.mc.cmd_pos[i]) for i in g.idx]
    c.step(3)
    assert [float(c.mc.cmd_pos[i]) for i in g.idx] == held
    ev = [e for e in c.events.list() if e.code == "67050000"]
    assert ev and "logical axis" in ev[-1].detail


@pytest.mark.parametrize(("inputs", "code"), [
    ({"BufferMode": 1}, 0x542B),
    ({"TransitionMode": 10}, 0x5432),
    ({"CoordSystem": 2}, 0x542C),
    ({"TrajData": {**TRAJ, "MoveTrajType": 1}}, 0x5715),
    ({"TrajData": {**TRAJ, "TrajTime": 0}}, 0x5714),
    ({"TrajData": {**TRAJ, "MaxVelocity": 0.0}}, 0x5712),
    ({"TrajData": {**TRAJ, "MaxAcceleration": -1.0}}, 0x5713),
    ({"CoordSystem": "_mcRBT_UCS", "CSID": 3}, 0x570B),  # not defined by MC_DefineCoordSystem
    ({"Position": [400.0, 0.0, -150.0]}, 0x571B),
])
def test_input_errors(inputs: dict[str, Any], code: int) -> None:
    """§9.4 input errors (checked in the order of D80); each is a group error with an immediate stop (§11)."""
    c, g = robot()
    fb = move(c, [0.0, 0.0, -200.0], **inputs)
    c.step(1)
    assert fb.Error and fb.ErrorID == code, f"{fb.ErrorID:04X}"
    assert g.state == GroupState.ErrorStop


def test_start_conditions() -> None:
    """§9.4 conditions: group disabled → 543F; servo OFF → 5441 (group not enabled: 543F first, D80); no
    kinematics → 5710; home undefined → 5466."""
    c, g = robot(enable=False)
    fb = move(c, [0.0, 0.0, -200.0])
    c.step(1)
    assert fb.ErrorID == 0x543F
    c, g = robot()
    g.kinematics = None
    fb = move(c, [0.0, 0.0, -200.0])
    c.step(1)
    assert fb.ErrorID == 0x5710
    c, g = robot()
    g.axes[1].homed = False
    fb = move(c, [0.0, 0.0, -200.0])
    c.step(1)
    assert fb.ErrorID == 0x5466


def test_reexecution_is_543b_and_stops_the_robot() -> None:
    """§10.2: a new Execute edge while Busy → 543B, the robot stops immediately."""
    c, g = robot()
    fb = move(c, [50.0, 0.0, -200.0])
    c.step(50)
    c.set_inputs(fb.id, {"Execute": False})
    c.step(1)
    c.set_inputs(fb.id, {"Execute": True})
    c.step(1)
    assert fb.Error and fb.ErrorID == 0x543B and not fb.CommandAborted
    assert g.state == GroupState.ErrorStop
    held = [float(c.mc.cmd_pos[i]) for i in g.idx]
    c.step(2)
    assert [float(c.mc.cmd_pos[i]) for i in g.idx] == held


def test_multi_execution_ok1_restarts_from_velocity_zero() -> None:
    """§10.1 OK1: a second MC_MoveTimeAbsolute aborts the first (CommandAborted) and starts from the present command
    position with velocity 0 — its first period moves only 3τ² of the new distance."""
    c, g = robot()
    first = move(c, [100.0, 0.0, -150.0])
    c.step(250)  # half way, at full speed
    p_mid = tcp(c, g)
    second = move(c, [100.0, 0.0, -250.0])
    c.step(1)
    assert first.CommandAborted and not first.Busy
    assert second.Busy and g.state == GroupState.Moving
    p = tcp(c, g)
    tau = 1 / 500
    expected = [a + (b - a) * (3 * tau**2 - 2 * tau**3) for a, b in zip(p_mid, (100.0, 0.0, -250.0), strict=True)]
    assert p == pytest.approx(expected, abs=1e-6)
    step_until(c, second, "Done", limit=1000)
    assert tcp(c, g) == pytest.approx((100.0, 0.0, -250.0), abs=1e-9)


def test_group_stop_stops_a_robot_immediately() -> None:
    """§7.2 / §9.9: MC_GroupStop stops a robot immediately whatever its Deceleration; the motion is CommandAborted;
    Stopping while Execute is held, then Standby (§10.3 *2)."""
    c, g = robot()
    fb = move(c, [100.0, 0.0, -150.0])
    c.step(200)
    stop = c.fb("MC_GroupStop", AxesGroup=GRP, Execute=True, Deceleration=10.0)
    c.step(1)
    assert fb.CommandAborted and g.state == GroupState.Stopping
    held = [float(c.mc.cmd_pos[i]) for i in g.idx]
    c.step(3)
    assert [float(c.mc.cmd_pos[i]) for i in g.idx] == held
    assert stop.Done
    late = move(c, [0.0, 0.0, -150.0])
    c.step(1)
    assert late.CommandAborted  # started while MC_GroupStop is executing (§9.4 CommandAborted)
    c.set_inputs(stop.id, {"Execute": False})
    c.step(1)
    assert g.state == GroupState.Standby


def test_group_sync_move_absolute_aborts_it() -> None:
    """§10.1: MC_GroupSyncMoveAbsolute onto MC_MoveTimeAbsolute is OK (CommandAborted); MC_MoveTimeAbsolute onto
    MC_GroupSyncMoveAbsolute is OK1."""
    c, g = robot()
    fb = move(c, [100.0, 0.0, -150.0])
    c.step(10)
    q = [float(c.mc.cmd_pos[i]) for i in g.idx]
    sync = c.fb("MC_GroupSyncMoveAbsolute", AxesGroup=GRP, Execute=True, Position=q)
    c.step(1)
    assert fb.CommandAborted and sync.Busy
    again = move(c, [0.0, 0.0, -150.0])
    c.step(1)
    assert sync.CommandAborted and again.Busy


def test_set_kin_transform_replaces_the_startup_kinematics() -> None:
    """D82: the project's kinematics are in force from cycle 0 (MC_MoveTimeAbsolute runs without a program);
    MC_SetKinTransform on the disabled group replaces them at run time (θ 30°), usable from the period after Done."""
    c, g = robot(enable=False)
    assert g.kinematics is not None and g.kinematics.theta == 0.0 and g.kin_from_cycle == 0
    fb = c.fb("MC_SetKinTransform", AxesGroup=GRP, Execute=True,
              KinTransform={"KinType": 100, "KinParam": [200.0, 350.0, 50.0, 800.0], "ExpansionParam": [30.0]},
              Workspace={"WorkspaceType": 100, "WorkspaceParam": [-50.0, 300.0, 250.0, 150.0, 150.0]})
    step_until(c, fb, "Done")
    assert g.kinematics.theta == 30.0
    en = c.fb("MC_GroupEnable", AxesGroup=GRP, Execute=True)
    step_until(c, en, "Done")
    mv = move(c, [0.0, 0.0, -200.0])
    step_until(c, mv, "Done", limit=1000)
    assert tcp(c, g) == pytest.approx((0.0, 0.0, -200.0), abs=1e-9)


def push(c: Controller, g: AxesGroup, degrees: float) -> None:
    """An external push on the stopped robot: every arm's shaft is turned by `degrees` behind the drive's back (the
    mechanism takes a position changed from outside as it is, `plant/mechanism.py`); the command stays where it
    was, so only the TCP **feedback** moves (the position loops pull it back over the next periods)."""
    drives = c.network.drives
    for a in g.axes:
        slave = next(s for s in c.network.slaves if s.node_address == a.config.node_address)
        drives.position[slave.row] += round(degrees * a.ppu)


def feedback_tcp(c: Controller, g: AxesGroup) -> tuple[float, float, float]:
    assert g.kinematics is not None
    st, p = forward_point(g.kinematics.params(), *[float(c.mc.act_pos[i]) for i in g.idx])
    assert st == 0
    return p


TOP = (0.0, 0.0, -55.0)  # 4.9 mm below the usable top face of the demo workspace (Zu −50 mm, 0.1 mm margin)


def test_workspace_check_4_feedback_of_a_robot_at_rest() -> None:
    """§3.2 check 4 (seed 003 L1982 "while the robot is stopped, is the TCP feedback inside?", L2028 "TCP target or
    TCP feedback beyond the drivable range → error, the robot stops immediately"), decision D92: a robot at rest
    (Standby) pushed 2° up on every arm has its command inside but its feedback above the workspace → the next
    MC_MoveTimeAbsolute is 6701 (L7072: "current position … when starting the next instruction") with the robot
    held and the group ErrorStop; after MC_GroupReset and the position loops settling, the same start runs."""
    c, g = robot(at=TOP)
    c.step(200)  # settled
    assert g.state == GroupState.Standby
    push(c, g, -2.0)  # negative = arm up (§2.2)
    c.step(1)
    assert tcp(c, g) == pytest.approx(TOP, abs=1e-6), "the command is inside"
    assert feedback_tcp(c, g)[2] > -50.1, "the feedback is above the usable top face"
    fb = move(c, [0.0, 0.0, -150.0])
    held = [float(c.mc.cmd_pos[i]) for i in g.idx]
    c.step(1)
    assert fb.Error and fb.ErrorID == 0x6701 and g.state == GroupState.ErrorStop
    c.step(5)
    assert [float(c.mc.cmd_pos[i]) for i in g.idx] == held
    assert any(e.code == "67010000" for e in c.events.list())
    c.step(300)  # the position loops bring the arms back to the command
    assert feedback_tcp(c, g) == pytest.approx(TOP, abs=1e-3)
    reset = c.fb("MC_GroupReset", AxesGroup=GRP, Execute=True)
    step_until(c, reset, "Done")
    again = move(c, [0.0, 0.0, -150.0])
    step_until(c, again, "Done", limit=1000)
    assert not again.Error


def test_workspace_check_4_is_not_made_on_a_moving_robot_nor_with_the_check_off() -> None:
    """D92: check 4 watches a robot at rest. Multi-execution onto a moving robot (group Moving; the feedback lags the
    command) checks the command only (check 1); with EnableWorkspace FALSE there is no check 4 either."""
    c, g = robot(at=TOP)
    c.step(200)
    first = move(c, [0.0, 0.0, -60.0], TrajData={**TRAJ, "TrajTime": 1000})
    c.step(5)
    assert g.state == GroupState.Moving
    push(c, g, -2.0)
    c.step(1)
    assert feedback_tcp(c, g)[2] > -50.1
    second = move(c, [0.0, 0.0, -150.0])
    c.step(1)
    assert first.CommandAborted and second.Busy and not second.Error
    step_until(c, second, "Done", limit=1000)
    c, g = robot(at=TOP)
    c.step(200)
    g.workspace_check = False
    push(c, g, -2.0)
    c.step(1)
    fb = move(c, [0.0, 0.0, -150.0])
    c.step(1)
    assert fb.Busy and not fb.Error
