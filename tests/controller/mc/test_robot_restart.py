"""The robot's restart table, cell by cell: what happens when a robot instruction starts while another one drives the
robot (multi-execution, `omron-robot-delta3.md` §10.1, seed 003 L4935–5003) and when a running one is re-executed
(§10.2: L3622–3624 MC_MoveTimeAbsolute, L4381–4383 MC_SyncLinearConveyor, L4675–4677 MC_SyncOut).

The table (rows: the instruction started now, seed line of the row; columns: the instruction executing):

| started now ↓ (line)      | MoveTimeAbs | SyncLinConv Ph≠6 | SyncLinConv Ph=6 | SyncOut type 0 | GroupSyncMoveAbs |
|---------------------------|-------------|------------------|------------------|----------------|------------------|
| MoveTimeAbsolute (L4974)  | OK1         | OK1              | OK1              | OK1            | OK1              |
| SyncLinearConv. (L4979)   | OK1         | OK1              | OK1              | OK1            | OK1              |
| SyncOut type 0 (L4984)    | Error       | Error            | OK               | Error          | Error            |
| SyncOut type 1 (L4989)    | Error       | OK               | OK               | Error          | Error            |
| GroupSyncMoveAbs (L4995)  | OK          | OK               | OK               | OK             | OK               |

Legend (L4997–5003): Error — an error is detected when the instruction is executed and the axes stop immediately;
OK — the instruction runs and aborts the executing one; OK1 — as OK, but the command velocity starts from 0. The
"Error" code is not named: 571C (D84; the MC_SyncOut rows are the only ones with Error cells). Every cell runs on the
demo Delta3 tracking workpieces on the conveyor moving at 100 mm/s (UCS 0 = the belt), period 1 ms.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import pytest

from mcstudio.controller.kernel import Controller
from mcstudio.controller.mc.fb.base import FunctionBlock
from mcstudio.controller.mc.group import AxesGroup, GroupState
from mcstudio.controller.mc.robot import cubic
from tests.controller.mc.test_robot_conveyor import OUT, TD, sync, tracking_rig
from tests.controller.mc.test_robot_motion import GRP, TRAJ, move, tcp

INIT = [-100.0, 20.0, 0.0]  # workpiece on the belt (UCS 0)
TARGET = [0.0, 0.0, -200.0]  # MC_MoveTimeAbsolute target (MCS)
TABLE: dict[str, tuple[int, dict[str, str]]] = {
    "MoveTimeAbsolute": (4974, {"MoveTimeAbsolute": "OK1", "SyncLinearConveyor<6": "OK1",
                                "SyncLinearConveyor=6": "OK1", "SyncOut0": "OK1", "GroupSyncMoveAbsolute": "OK1"}),
    "SyncLinearConveyor": (4979, {"MoveTimeAbsolute": "OK1", "SyncLinearConveyor<6": "OK1",
                                  "SyncLinearConveyor=6": "OK1", "SyncOut0": "OK1", "GroupSyncMoveAbsolute": "OK1"}),
    "SyncOut0": (4984, {"MoveTimeAbsolute": "Error", "SyncLinearConveyor<6": "Error", "SyncLinearConveyor=6": "OK",
                        "SyncOut0": "Error", "GroupSyncMoveAbsolute": "Error"}),
    "SyncOut1": (4989, {"MoveTimeAbsolute": "Error", "SyncLinearConveyor<6": "OK", "SyncLinearConveyor=6": "OK",
                        "SyncOut0": "Error", "GroupSyncMoveAbsolute": "Error"}),
    "GroupSyncMoveAbsolute": (4995, {"MoveTimeAbsolute": "OK", "SyncLinearConveyor<6": "OK",
                                     "SyncLinearConveyor=6": "OK", "SyncOut0": "OK", "GroupSyncMoveAbsolute": "OK"}),
}


def angles(c: Controller, g: AxesGroup) -> list[float]:
    return [float(c.mc.cmd_pos[i]) for i in g.idx]


def gsma(c: Controller, g: AxesGroup) -> FunctionBlock:
    return c.fb("MC_GroupSyncMoveAbsolute", AxesGroup=GRP, Execute=True, Position=[*angles(c, g), 0.0])


def sync_out(c: Controller, stop_type: int) -> FunctionBlock:
    return c.fb("MC_SyncOut", AxesGroup=GRP, Execute=True, TrajData={**OUT, "SyncStopType": stop_type})


def executing(column: str) -> tuple[Controller, AxesGroup, FunctionBlock]:
    """The rig with the column's instruction driving the robot (its instance returned)."""
    c, g, _ = tracking_rig()
    if column == "MoveTimeAbsolute":
        fb = move(c, [100.0, 0.0, -150.0])
        c.step(100)
    elif column == "SyncLinearConveyor<6":
        fb = sync(c, INIT)
        c.step(200)
        assert fb.TrajStatus["Phase"] == 3
    elif column == "SyncLinearConveyor=6":
        fb = sync(c, INIT)
        c.step(600)
        assert fb.TrajStatus["Phase"] == 6
    elif column == "SyncOut0":
        tracking = sync(c, INIT)
        c.step(600)
        fb = sync_out(c, 0)
        c.step(50)
        assert tracking.CommandAborted
    else:
        fb = gsma(c, g)
        c.step(5)
    assert fb.Busy and not fb.Error and g.state == GroupState.Moving, column
    return c, g, fb


STARTERS: dict[str, Callable[[Controller, AxesGroup], FunctionBlock]] = {
    "MoveTimeAbsolute": lambda c, g: move(c, TARGET),
    "SyncLinearConveyor": lambda c, g: sync(c, INIT),
    "SyncOut0": lambda c, g: sync_out(c, 0),
    "SyncOut1": lambda c, g: sync_out(c, 1),
    "GroupSyncMoveAbsolute": gsma,
}
CELLS = [(row, col, line, cell) for row, (line, cols) in TABLE.items() for col, cell in cols.items()]


@pytest.mark.parametrize(("row", "column", "line", "cell"), CELLS,
                         ids=[f"L{line}-{row}-onto-{col}-{cell}" for row, col, line, cell in CELLS])
def test_multi_execution_cell(row: str, column: str, line: int, cell: str) -> None:
    c, g, running = executing(column)
    p_before = tcp(c, g)
    q_before = angles(c, g)
    new = STARTERS[row](c, g)
    c.step(1)
    if cell == "Error":
        # L4997: the error is detected at the start and the axes stop immediately (571C, D84; group ErrorStop)
        assert new.Error and new.ErrorID == 0x571C, f"{new.ErrorID:04X}"
        assert running.CommandAborted and not running.Busy
        assert g.state == GroupState.ErrorStop
        assert angles(c, g) == q_before, "no command moved in the start period"
        c.step(3)
        assert angles(c, g) == q_before, "held"
        return
    # OK / OK1 (L4999–5003): the new instruction runs, the executing one is aborted
    assert not new.Error, f"{new.ErrorID:04X}"
    assert running.CommandAborted and not running.Busy
    assert new.Busy and g.state == GroupState.Moving
    p = tcp(c, g)
    if cell == "OK1":
        # the command velocity starts from 0: the first command is the new instruction's first step from rest
        if row == "MoveTimeAbsolute":
            s = cubic(1 / TRAJ["TrajTime"])
            expected = [a + (b - a) * s for a, b in zip(p_before, TARGET, strict=True)]
        else:  # the flat trajectory's first period: only the rise H1·s(T/T1), X/Y stay (catch-up from Ttrans1·T1)
            expected = [p_before[0], p_before[1], p_before[2] + TD["TrajDistance"][0] * cubic(1 / TD["TrajTime"][0])]
        assert p == pytest.approx(expected, abs=1e-6)
    elif row == "GroupSyncMoveAbsolute":
        assert angles(c, g) == pytest.approx(q_before, abs=1e-12), "the synchronous target is where the robot was"
    elif row == "SyncOut1":
        assert p == pytest.approx(p_before, abs=1e-12), "_mcRBT_ImmediateStop: no further command (§9.6)"
        c.step(1)
        assert new.Done and g.state == GroupState.Standby
    else:  # SyncOut type 0 in phase 6: velocity-continuous release (§9.6), the TCP keeps the conveyor's speed
        assert (p[0] - p_before[0]) * 1000.0 == pytest.approx(100.0, rel=0.02)
    c.step(3)
    assert not new.Error and g.state in (GroupState.Moving, GroupState.Standby)


REEXEC: list[tuple[str, int, Callable[[Controller], Any]]] = [
    ("MoveTimeAbsolute", 3622, lambda c: move(c, [100.0, 0.0, -150.0])),
    ("SyncLinearConveyor", 4381, lambda c: sync(c, INIT)),
    ("SyncOut", 4675, lambda c: None),
]


@pytest.mark.parametrize(("name", "line", "starter"), REEXEC, ids=[f"L{line}-{n}" for n, line, _ in REEXEC])
def test_reexecution_is_543b_and_stops_the_axes(name: str, line: int, starter: Callable[[Controller], Any]) -> None:
    """§10.2: a new Execute edge on the running instance → 543B ("motion instruction cannot be re-executed") and every
    axis the instruction drives stops (immediately, group ErrorStop)."""
    c, g, _ = tracking_rig()
    fb = starter(c)
    if fb is None:  # MC_SyncOut type 0 needs MC_SyncLinearConveyor in phase 6
        sync(c, INIT)
        c.step(600)
        fb = sync_out(c, 0)
    c.step(20)
    assert fb.Busy
    c.set_inputs(fb.id, {"Execute": False})
    c.step(1)
    assert fb.Busy
    held = angles(c, g)
    c.set_inputs(fb.id, {"Execute": True})
    c.step(1)
    assert fb.Error and fb.ErrorID == 0x543B and not fb.Busy
    assert g.state == GroupState.ErrorStop
    assert angles(c, g) == held
    c.step(3)
    assert angles(c, g) == held
