"""Kernel determinism (architecture.md): the same project and the same commands at the same cycles give
bit-identical variables, independent of wall-clock time."""

from __future__ import annotations

import numpy as np

from mcstudio.controller.kernel import Controller
from tests.conftest import small_project


def _script(c: Controller) -> tuple[np.ndarray, np.ndarray, list[tuple]]:
    """A scripted session: commands at fixed cycles, positions recorded every cycle."""
    cmd, act, outs = [], [], []
    schedule = {
        0: lambda: c.fb("MC_Power", Axis="MC_Axis000", Enable=True),
        1: lambda: c.fb("MC_Power", Axis="MC_Axis001", Enable=True),
        10: lambda: c.fb("MC_MoveAbsolute", Axis="MC_Axis000", Execute=True, Position=37.5, Velocity=80.0,
                         Acceleration=900.0, Deceleration=700.0, Jerk=20000.0),
        15: lambda: c.fb("MC_MoveVelocity", Axis="MC_Axis001", Execute=True, Velocity=33.3, Acceleration=250.0,
                         Deceleration=250.0),
        400: lambda: c.fb("MC_MoveRelative", Axis="MC_Axis000", Execute=True, Distance=-12.25, Velocity=40.0,
                          Acceleration=400.0, Deceleration=400.0, BufferMode="_mcBuffered"),
        900: lambda: c.fb("MC_Stop", Axis="MC_Axis001", Execute=True, Deceleration=120.0),
    }
    for k in range(1500):
        if k in schedule:
            schedule[k]()
        c.step(1, publish=False)
        cmd.append(c.mc.cmd_pos.copy())
        act.append(c.mc.act_pos.copy())
        outs.append(tuple(tuple(e.fb.out.values()) for e in c.program.values()))
    return np.array(cmd), np.array(act), outs


def test_identical_runs_give_identical_traces() -> None:
    cmd1, act1, out1 = _script(Controller(small_project()))
    cmd2, act2, out2 = _script(Controller(small_project()))
    assert cmd1.tobytes() == cmd2.tobytes()
    assert act1.tobytes() == act2.tobytes()
    assert out1 == out2
    assert np.ptp(cmd1[:, 0]) > 10 and np.ptp(cmd1[:, 1]) > 10, "the script really moved both axes"
