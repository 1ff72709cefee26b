"""The plant's workpiece source for conveyor tracking (omron-robot-delta3.md §9.5): pitch, entry, exit, movement
with the conveyor feedback, determinism."""

from __future__ import annotations

import pytest

from mcstudio.plant.workpieces import WorkpieceSource


def test_workpieces_appear_at_the_pitch_and_move_with_the_conveyor() -> None:
    src = WorkpieceSource(pitch=200.0, entry_x=-500.0, exit_x=500.0, y=20.0, z=5.0)
    assert src.positions(0.0) == [(-500.0, 20.0, 5.0)]  # workpiece 0 enters at c = 0
    assert src.positions(150.0) == [(-350.0, 20.0, 5.0)]
    assert src.positions(200.0) == [(-300.0, 20.0, 5.0), (-500.0, 20.0, 5.0)]
    xs = [p[0] for p in src.positions(1234.5)]
    assert xs == pytest.approx([334.5, 134.5, -65.5, -265.5, -465.5])  # 1000 mm belt → 5 workpieces, 200 mm apart
    assert all(-500.0 <= x <= 500.0 for x in xs)
    # a workpiece moves exactly as far as the conveyor
    assert src.workpiece(3, 1300.0)[0] - src.workpiece(3, 1234.5)[0] == pytest.approx(65.5)


def test_invalid_pitch_is_refused() -> None:
    with pytest.raises(ValueError, match="pitch"):
        WorkpieceSource(pitch=0.0)
    with pytest.raises(ValueError, match="exit_x"):
        WorkpieceSource(entry_x=10.0, exit_x=0.0)
