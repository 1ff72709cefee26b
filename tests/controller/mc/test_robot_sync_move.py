"""MC_GroupSyncMoveAbsolute on a robot group: targets within each axis's Maximum Velocity are followed; a step above
it is 6705 with an immediate stop (omron-robot-delta3.md §9.8 [Emulator], §6.3 "exceeding it is an error with
immediate stop"; decision D49). On a group without kinematics the command saturates instead (§4.12,
test_group_states.py)."""

from __future__ import annotations

import pytest

from mcstudio.controller.mc.group import GroupState
from tests.controller.mc.test_robot_motion import GRP, robot


def test_robot_follows_targets_within_maximum_velocity() -> None:
    c, g = robot()
    start = [float(c.mc.cmd_pos[i]) for i in g.idx]
    fb = c.fb("MC_GroupSyncMoveAbsolute", AxesGroup=GRP, Execute=True, Position=[*start, 0.0])
    c.step(2)
    for k in range(1, 200):  # 0.1° per period = 100 °/s, below the demo's 360 °/s
        c.set_inputs(fb.id, {"Position": [q + 0.1 * k for q in start] + [0.0]})
        c.step(1, publish=False)
        assert [float(c.mc.cmd_pos[i]) for i in g.idx] == pytest.approx([q + 0.1 * k for q in start])
    assert not fb.Error and g.state == GroupState.Moving


def test_a_step_above_maximum_velocity_is_6705_and_an_immediate_stop() -> None:
    c, g = robot()
    start = [float(c.mc.cmd_pos[i]) for i in g.idx]
    fb = c.fb("MC_GroupSyncMoveAbsolute", AxesGroup=GRP, Execute=True, Position=[*start, 0.0])
    c.step(2)
    c.set_inputs(fb.id, {"Position": [start[0] + 1.0, start[1], start[2], 0.0]})  # 1° in 1 ms = 1000 °/s
    c.step(1)
    assert fb.Error and fb.ErrorID == 0x6705
    assert g.state == GroupState.ErrorStop
    assert [float(c.mc.cmd_pos[i]) for i in g.idx] == pytest.approx(start), "stopped where it was"
    assert any(e.code == "67050000" for e in c.events.list())
