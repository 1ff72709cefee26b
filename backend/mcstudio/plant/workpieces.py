"""Workpieces on a conveyor: the plant side of conveyor tracking (MC_SyncLinearConveyor, `omron-robot-delta3.md` §9.5).

A workpiece appears at the belt's entry every `pitch` mm of conveyor travel and then moves with the belt, i.e. with
the conveyor axis's **feedback** position (unwrapped, mm); it leaves at the exit. The source holds no state: the
workpieces are a pure function of the conveyor position, so the same position always gives the same workpieces
(deterministic, and the 3-D view can compute them from a published snapshot: `SceneServer.set_conveyor(position,
source.positions(position))`). Positions are (x, y, z) mm in the conveyor's coordinate system: x along the belt
(the X axis of the coordinate system the robot tracks in, §9.5), z = 0 on the belt surface.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

MAX_WORKPIECES = 64  # the 3-D view draws at most 64


@dataclass(frozen=True, kw_only=True)
class WorkpieceSource:
    """Workpieces every `pitch` mm of travel, entering at `entry_x` and leaving after `exit_x` (mm, belt x);
    `offset` shifts the spawn phase: workpiece k = 0, 1, … enters when the conveyor position is offset + k·pitch
    (the belt is empty before offset)."""

    pitch: float = 200.0
    entry_x: float = -500.0
    exit_x: float = 500.0
    y: float = 0.0
    z: float = 0.0
    offset: float = 0.0

    def __post_init__(self) -> None:
        if not (math.isfinite(self.pitch) and self.pitch > 0):
            raise ValueError(f"pitch must be a positive number of mm, got {self.pitch!r}")
        if not (math.isfinite(self.entry_x) and math.isfinite(self.exit_x) and self.exit_x > self.entry_x):
            raise ValueError("exit_x must be downstream of entry_x (finite mm)")

    def positions(self, conveyor_mm: float) -> list[tuple[float, float, float]]:
        """The workpieces on the belt at conveyor feedback position `conveyor_mm` (unwrapped), downstream first.
        Workpiece k entered when the conveyor was at offset + k·pitch; it is now at entry_x + (c − offset − k·pitch)."""
        if not math.isfinite(conveyor_mm):
            return []
        travel = conveyor_mm - self.offset
        length = self.exit_x - self.entry_x
        k_new = math.floor(travel / self.pitch)  # the latest workpiece to enter
        k_old = math.floor((travel - length) / self.pitch) + 1  # the oldest still on the belt
        k_old = max(k_old, k_new - MAX_WORKPIECES + 1, 0)  # the first workpiece enters at c = offset
        return [(self.entry_x + travel - k * self.pitch, self.y, self.z) for k in range(k_old, k_new + 1)]

    def workpiece(self, k: int, conveyor_mm: float) -> tuple[float, float, float]:
        """Where workpiece k is at conveyor position `conveyor_mm` (it may be off the belt)."""
        return (self.entry_x + conveyor_mm - self.offset - k * self.pitch, self.y, self.z)
