"""Cam tables: `ARRAY[0..N] OF _sMC_CAM_REF`, the end-point rule and MC_SetCamTableProperty, evaluation.

Data model (`omron-group-and-cam.md` §5.0.1, seed 000 lines ~6774 and 17346–17470):

* a cam data variable is an array of (Phase, Distance) REAL pairs; its size N+1 is `MaxDataNumber`;
* element 0 is the start point; the **end point** is the element just before the first element (searching from
  index 1) whose Phase is 0, or the last element when there is none; everything after it is ignored;
* phases must be strictly ascending from the start point to the end point, otherwise (or with no valid data)
  MC_SetCamTableProperty ends with 5480;
* the controller interpolates linearly between two cam data points (seed 000 line 6736).

REAL semantics (D35): phases and distances are stored as float32, exactly as the controller's REAL, so an imported
or generated table holds the values the controller would hold (two phases 0.001 apart at 100000 collapse into one,
as they would there); arithmetic on them is done in float64.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

__all__ = ["MAX_POINTS", "REAL", "CamTable", "CamTableSet", "EndPoint", "find_end_point"]

REAL = np.float32
MAX_POINTS = 65535  # most cam data MC_GenerateCamTable writes, and the largest EndPointIndex (UINT) + 1
ERR_ASCENDING = 0x5480  # "ascending-order error in cam table property update"


@dataclass(frozen=True)
class EndPoint:
    """Outputs of MC_SetCamTableProperty: ErrorID (0 or 16#5480), EndPointIndex, MaxDataNumber."""

    error_id: int
    end_point_index: int
    max_data_number: int

    @property
    def ok(self) -> bool:
        return self.error_id == 0


def find_end_point(phase: ArrayLike) -> EndPoint:
    """The end-point search of MC_SetCamTableProperty (§5.1), vectorised.

    End point = the element before the first Phase 0 found from index 1 (the last element when there is none).
    5480 when a phase up to the end point is not greater than the one before it (NaN counts as not ascending) or
    when no data follow the start point (end point = element 0). On error EndPointIndex is 0."""
    p = np.asarray(phase, dtype=REAL)
    size = int(p.size)
    if size == 0:
        return EndPoint(ERR_ASCENDING, 0, 0)
    zeros = np.flatnonzero(p[1:] == 0)
    end = int(zeros[0]) if zeros.size else size - 1
    if end == 0 or not bool(np.all(p[1:end + 1] > p[:end])):
        return EndPoint(ERR_ASCENDING, 0, size)
    return EndPoint(0, end, size)


class CamTable:
    """One cam data variable: REAL phase/distance arrays of size MaxDataNumber and the end point in force.

    `end_point_index` is what the cam motion uses; like the controller, it changes only when MC_SetCamTableProperty
    (`set_cam_table_property`) or MC_GenerateCamTable succeeds, or when the table is downloaded (`from_points`) —
    writing data alone does not move it (§5.1, "same rewrite but instruction not executed"). `generation_aborted`
    is the error state after a 5742 (using the table then gives 5743, §5.4.5)."""

    def __init__(self, size: int) -> None:
        if not 1 <= size <= MAX_POINTS + 1:
            raise ValueError(f"a cam table has 1 … {MAX_POINTS + 1} elements, not {size}")
        self.phase = np.zeros(size, dtype=REAL)
        self.distance = np.zeros(size, dtype=REAL)
        self.end_point_index: int | None = None
        self.generation_aborted = False

    @classmethod
    def from_points(cls, phase: ArrayLike, distance: ArrayLike, *, size: int | None = None) -> CamTable:
        """A table holding these points from element 0 (a download from the cam editor): the elements after them
        are zero, so the element after the last point is the Phase-0 terminator; the end point is computed.

        Raises ValueError when the arrays differ in length or do not fit `size` (default: the number of points)."""
        p = np.asarray(phase, dtype=REAL).ravel()
        d = np.asarray(distance, dtype=REAL).ravel()
        if p.shape != d.shape:
            raise ValueError(f"{p.size} phases but {d.size} distances")
        table = cls(size if size is not None else max(p.size, 1))
        if p.size > table.max_data_number:
            raise ValueError(f"{p.size} points do not fit a table of {table.max_data_number} elements")
        table.phase[: p.size] = p
        table.distance[: d.size] = d
        ep = find_end_point(table.phase)
        table.end_point_index = ep.end_point_index if ep.ok else None
        return table

    @property
    def max_data_number(self) -> int:
        return int(self.phase.size)

    def copy(self) -> CamTable:
        other = CamTable(self.max_data_number)
        other.phase[:] = self.phase
        other.distance[:] = self.distance
        other.end_point_index = self.end_point_index
        other.generation_aborted = self.generation_aborted
        return other

    def set_cam_table_property(self) -> EndPoint:
        """MC_SetCamTableProperty: search the end point; on success it becomes the one in force (§5.1)."""
        ep = find_end_point(self.phase)
        if ep.ok:
            self.end_point_index = ep.end_point_index
        return ep

    def valid(self) -> tuple[np.ndarray, np.ndarray]:
        """(phase, distance) from the start point to the end point in force (views, REAL); empty if none."""
        if self.end_point_index is None:
            return self.phase[:0], self.distance[:0]
        n = self.end_point_index + 1
        return self.phase[:n], self.distance[:n]

    def evaluate(self, phase: ArrayLike) -> np.ndarray:
        """Slave distance at master phase(s), interpolated linearly between cam data (float64, vectorised).

        Phases outside [Phase[0], Phase[end]] give the distance at the nearer end (the cam layer wraps periodic
        cams before asking)."""
        p, d = self.valid()
        if p.size == 0:
            raise ValueError("the cam table has no valid end point")
        return np.interp(np.asarray(phase, dtype=float), p.astype(float), d.astype(float))


class CamTableSet:
    """Several cam tables flattened into one array, evaluated for many axes at once.

    Each table's phases are shifted by an offset so that the concatenation ascends strictly (table k starts above
    the end of table k−1); one `searchsorted` of every axis's shifted phase then finds its cam data interval,
    whatever the number of axes and tables, and the distance is interpolated with the table's own REAL values."""

    def __init__(self, tables: Sequence[CamTable]) -> None:
        phases, dists, starts, ends, offsets = [], [], [], [], []
        offset = 0.0
        n = 0
        for t in tables:
            p, d = t.valid()
            if p.size < 2:
                raise ValueError("every table needs a valid end point")
            p64 = p.astype(float)
            phases.append(p64)
            dists.append(d.astype(float))
            starts.append(n)
            ends.append(n + p.size - 1)
            offsets.append(offset - p64[0])
            offset += p64[-1] - p64[0] + 1.0  # a gap of 1 keeps neighbouring tables apart
            n += p.size
        self.P = np.concatenate(phases)
        self.D = np.concatenate(dists)
        self.start = np.array(starts, dtype=np.int64)
        self.end = np.array(ends, dtype=np.int64)
        self.offset = np.array(offsets)
        self.key = self.P + np.repeat(self.offset, self.end - self.start + 1)
        dp = np.diff(self.P, append=self.P[-1])
        dd = np.diff(self.D, append=self.D[-1])
        # Slope of each interval; the last element of a table starts no interval (its slope is never used).
        self.slope = np.divide(dd, dp, out=np.zeros_like(dd), where=dp > 0)
        self.slope[self.end] = 0.0

    def evaluate(self, table: ArrayLike, phase: ArrayLike) -> np.ndarray:
        """Distance of each axis at its master phase, on its table (index into the set); phases outside a
        table's range give the distance at the nearer end. Vectorised over the axes."""
        table = np.asarray(table, dtype=np.int64)
        lo, hi = self.start[table], self.end[table]
        x = np.clip(np.asarray(phase, dtype=float), self.P[lo], self.P[hi])
        i = np.searchsorted(self.key, x + self.offset[table], side="right") - 1
        i = np.clip(i, lo, hi - 1)
        return self.D[i] + self.slope[i] * (x - self.P[i])
