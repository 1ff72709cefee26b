"""Paths of the interpolation instructions: a straight line in 2–4 axes, a circular arc in two of them.

A path is parametrised by its arc length s ∈ [0, length] (command units); the group plans a 1-D profile s(t) once
per move (`profile.Planner`) and maps it to the axes every period with `point`. The mapping is exact geometry, so a
line stays on its straight line and an arc on its circle to round-off (< 1e-9 of the coordinates), whatever the
profile does. Geometry of MC_MoveCircular2D (`omron-group-and-cam.md` §4.6, seed 000 lines 15700–15800): border
(via) point, centre and radius modes, full circles, and the degenerate cases that become straight lines.

All functions are plain float math on tuples (n ≤ 4): one period costs a few µs per group, no numpy temporaries.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

TWO_PI = 2.0 * math.pi


@dataclass(slots=True)
class LinePath:
    """Straight line from `start` to `end` (all logical axes)."""

    start: tuple[float, ...]
    end: tuple[float, ...]
    length: float
    u: tuple[float, ...]  # unit direction (zeros for a zero-length move)

    @classmethod
    def between(cls, start: tuple[float, ...], end: tuple[float, ...]) -> LinePath:
        d = [e - s for s, e in zip(start, end, strict=True)]
        length = math.sqrt(sum(x * x for x in d))
        u = tuple(x / length for x in d) if length > 0 else tuple(0.0 for _ in d)
        return cls(tuple(start), tuple(end), length, u)

    def point(self, s: float) -> tuple[float, ...]:
        if s >= self.length:
            return self.end
        return tuple(p + k * s for p, k in zip(self.start, self.u, strict=True))

    def velocity(self, s: float, sd: float, sdd: float) -> tuple[tuple[float, ...], tuple[float, ...]]:
        """Per-axis velocity and acceleration at s for path velocity sd and acceleration sdd."""
        return tuple(k * sd for k in self.u), tuple(k * sdd for k in self.u)

    def direction_in(self) -> tuple[float, ...]:
        return self.u

    def direction_out(self) -> tuple[float, ...]:
        return self.u


@dataclass(slots=True)
class ArcPath:
    """Arc in the plane of logical axes (ix, iy) around (cx, cy) with `radius`, from angle `theta0` through the
    signed `sweep` (rad; positive = counter-clockwise, _mcCCW). The other axes stay where they are."""

    start: tuple[float, ...]
    end: tuple[float, ...]
    ix: int
    iy: int
    cx: float
    cy: float
    radius: float
    theta0: float
    sweep: float
    length: float

    @classmethod
    def make(cls, start: tuple[float, ...], end: tuple[float, ...], ix: int, iy: int, cx: float, cy: float,
             radius: float, sweep: float) -> ArcPath:
        # the given end point lies on the circle (up to round-off): the move ends exactly on it
        theta0 = math.atan2(start[iy] - cy, start[ix] - cx)
        return cls(tuple(start), tuple(end), ix, iy, cx, cy, radius, theta0, sweep, radius * abs(sweep))

    def point(self, s: float) -> tuple[float, ...]:
        if s >= self.length:
            return self.end
        th = self.theta0 + math.copysign(s / self.radius, self.sweep)
        p = list(self.start)
        p[self.ix] = self.cx + self.radius * math.cos(th)
        p[self.iy] = self.cy + self.radius * math.sin(th)
        return tuple(p)

    def velocity(self, s: float, sd: float, sdd: float) -> tuple[tuple[float, ...], tuple[float, ...]]:
        sign = 1.0 if self.sweep >= 0 else -1.0
        th = self.theta0 + sign * min(s, self.length) / self.radius
        c, sn = math.cos(th), math.sin(th)
        v = [0.0] * len(self.start)
        a = [0.0] * len(self.start)
        v[self.ix], v[self.iy] = -sn * sign * sd, c * sign * sd
        cent = sd * sd / self.radius  # centripetal acceleration toward the centre
        a[self.ix] = -sn * sign * sdd - c * cent
        a[self.iy] = c * sign * sdd - sn * cent
        return tuple(v), tuple(a)

    def _tangent(self, th: float) -> tuple[float, ...]:
        sign = 1.0 if self.sweep >= 0 else -1.0
        t = [0.0] * len(self.start)
        t[self.ix], t[self.iy] = -math.sin(th) * sign, math.cos(th) * sign
        return tuple(t)

    def direction_in(self) -> tuple[float, ...]:
        return self._tangent(self.theta0)

    def direction_out(self) -> tuple[float, ...]:
        return self._tangent(self.theta0 + self.sweep)


Path = LinePath | ArcPath


# ---------------------------------------------------------------------------------------------------------- circles
def _ccw_sweep(a_from: float, a_to: float) -> float:
    """Counter-clockwise angle from a_from to a_to in (0, 2π] (0 only for identical angles: then 2π)."""
    d = (a_to - a_from) % TWO_PI
    return d if d > 0 else TWO_PI


def _sweep(a_from: float, a_to: float, ccw: bool) -> float:
    d = _ccw_sweep(a_from, a_to)
    return d if ccw else -(TWO_PI - d if d < TWO_PI else TWO_PI)


def border_arc(start: tuple[float, ...], via: tuple[float, float], end: tuple[float, float], ix: int, iy: int,
               ccw: bool, pulse: tuple[float, float]) -> Path | int:
    """_mcBorder: the arc from the start through `via` to `end`. `pulse` = one pulse in command units of X and Y
    (the collinearity tolerance). Returns a path or 5448 (start = via = end)."""
    sx, sy = start[ix], start[iy]
    (ax, ay), (ex, ey) = via, end
    same_se = sx == ex and sy == ey
    if same_se and ax == sx and ay == sy:
        return 0x5448
    target = list(start)
    target[ix], target[iy] = ex, ey
    if same_se:
        # full circle whose diameter is start–via, direction from PathChoice
        cx, cy = (sx + ax) / 2.0, (sy + ay) / 2.0
        r = math.hypot(ax - sx, ay - sy) / 2.0
        return ArcPath.make(start, tuple(target), ix, iy, cx, cy, r, TWO_PI if ccw else -TWO_PI)
    if (ax == ex and ay == ey) or (ax == sx and ay == sy):
        return LinePath.between(start, tuple(target))
    # collinear: the via point is less than 1 pulse (in X and in Y) from the start–end line
    dx, dy = ex - sx, ey - sy
    chord2 = dx * dx + dy * dy
    t = ((ax - sx) * dx + (ay - sy) * dy) / chord2
    px, py = sx + t * dx, sy + t * dy
    if abs(ax - px) < pulse[0] and abs(ay - py) < pulse[1]:
        return LinePath.between(start, tuple(target))
    # circumcentre of start, via, end
    bx, by = ax - sx, ay - sy
    d = 2.0 * (bx * dy - by * dx)
    b2, c2 = bx * bx + by * by, chord2
    ux = (dy * b2 - by * c2) / d
    uy = (bx * c2 - dx * b2) / d
    cx, cy = sx + ux, sy + uy
    r = math.hypot(ux, uy)
    a_s = math.atan2(sy - cy, sx - cx)
    a_v = math.atan2(ay - cy, ax - cx)
    a_e = math.atan2(ey - cy, ex - cx)
    ccw_path = _ccw_sweep(a_s, a_v) < _ccw_sweep(a_s, a_e)  # the via point comes first counter-clockwise
    return ArcPath.make(start, tuple(target), ix, iy, cx, cy, r, _sweep(a_s, a_e, ccw_path))


def _centre_from_radius(sx: float, sy: float, ex: float, ey: float, r: float, left: bool) -> tuple[float, float]:
    dx, dy = ex - sx, ey - sy
    c = math.hypot(dx, dy)
    h = math.sqrt(max(r * r - c * c / 4.0, 0.0))
    mx, my = (sx + ex) / 2.0, (sy + ey) / 2.0
    nx, ny = -dy / c, dx / c  # unit normal to the left of start → end
    return (mx + h * nx, my + h * ny) if left else (mx - h * nx, my - h * ny)


def radius_arc(start: tuple[float, ...], radius: float, end: tuple[float, float], ix: int, iy: int,
               ccw: bool) -> Path | int:
    """_mcRadius: positive radius = the shorter arc (≤ 180°), negative = the longer one; 5448 when start = end,
    547C when |radius| is less than half the chord."""
    sx, sy = start[ix], start[iy]
    ex, ey = end
    if sx == ex and sy == ey:
        return 0x5448
    r = abs(radius)
    c = math.hypot(ex - sx, ey - sy)
    if r == 0.0 or r < c / 2.0 * (1.0 - 1e-12):
        return 0x547C
    # counter-clockwise with the centre on the left of the chord is the shorter arc (and so on by symmetry)
    short = radius > 0
    cx, cy = _centre_from_radius(sx, sy, ex, ey, r, left=(ccw == short))
    target = list(start)
    target[ix], target[iy] = ex, ey
    a_s = math.atan2(sy - cy, sx - cx)
    a_e = math.atan2(ey - cy, ex - cx)
    return ArcPath.make(start, tuple(target), ix, iy, cx, cy, r, _sweep(a_s, a_e, ccw))


def centre_arc(start: tuple[float, ...], centre: tuple[float, float], end: tuple[float, float], ix: int, iy: int,
               ccw: bool, allowance_pct: float) -> Path | int:
    """_mcCenter: around `centre`; start = end is a full circle. Unequal radii: the mean radius with the centre
    corrected as in radius mode; with a non-zero [Correction Allowance Ratio] the given centre must lie within
    radius × ratio / 100 of the corrected one (5449)."""
    sx, sy = start[ix], start[iy]
    ex, ey = end
    cx, cy = centre
    r1 = math.hypot(sx - cx, sy - cy)
    r2 = math.hypot(ex - cx, ey - cy)
    target = list(start)
    target[ix], target[iy] = ex, ey
    if r1 == 0.0 or r2 == 0.0:
        return 0x5449
    if sx == ex and sy == ey:
        return ArcPath.make(start, tuple(target), ix, iy, cx, cy, r1, TWO_PI if ccw else -TWO_PI)
    r = r1
    if r1 != r2:
        r = (r1 + r2) / 2.0
        c = math.hypot(ex - sx, ey - sy)
        if r < c / 2.0:
            return 0x5449
        cand = [_centre_from_radius(sx, sy, ex, ey, r, left=side) for side in (True, False)]
        ncx, ncy = min(cand, key=lambda p: math.hypot(p[0] - cx, p[1] - cy))
        if allowance_pct > 0 and math.hypot(ncx - cx, ncy - cy) > r * allowance_pct / 100.0:
            return 0x5449
        cx, cy = ncx, ncy
    a_s = math.atan2(sy - cy, sx - cx)
    a_e = math.atan2(ey - cy, ex - cx)
    return ArcPath.make(start, tuple(target), ix, iy, cx, cy, r, _sweep(a_s, a_e, ccw))
