"""What the cam editor shows about a generated profile: velocity, acceleration and jerk of the slave in user units,
maxima per segment and for the whole table, and jumps at segment boundaries.

Units: the master runs at `master_velocity` [master units/s] (default P_max / CycleTime, the speed §5.4.4 assumes).
With ΔP the master span and h the slave rise of a segment, x = (P − P0)/ΔP and V the master velocity:

    v = h·f'(x)·V/ΔP,   a = h·f''(x)·(V/ΔP)²,   j = h·f'''(x)·(V/ΔP)³       (A.2 of the spec)

All values come from the analytic derivatives of each segment's law, not from differences of the REAL table.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .curves import (
    POLYNOMIAL_CURVES,
    CurveCharacteristics,
    _eMC_CAM_CURVE,
    characteristics,
    polynomial_characteristics,
)
from .generate import CamProfile, CamSegment, sample_segments, table_points

__all__ = ["Jump", "Kinematics", "ProfileCharacteristics", "SegmentCharacteristics", "continuity",
           "kinematics", "profile_characteristics", "segment_characteristics"]


@dataclass(frozen=True)
class Kinematics:
    """Slave distance [units], velocity [units/s], acceleration [units/s²], jerk [units/s³] at master phases.

    At a segment boundary a generated point belongs to the segment that ends there (its left-hand values); the
    continuity report gives both sides."""

    phase: np.ndarray
    distance: np.ndarray
    velocity: np.ndarray
    acceleration: np.ndarray
    jerk: np.ndarray
    master_velocity: float


def _speed(profile: CamProfile, master_velocity: float | None) -> float:
    v = profile.master_velocity if master_velocity is None else float(master_velocity)
    if not v > 0 or not math.isfinite(v):
        raise ValueError(f"master velocity must be positive, not {master_velocity!r}")
    return v


def _scaled(profile: CamProfile, seg: np.ndarray, x: np.ndarray, speed: float) -> list[np.ndarray]:
    """[distance, v, a, j] of points given by segment and x."""
    arr = profile.arrays
    rate = speed / (arr["p1"] - arr["p0"])[seg]  # dx/dt [1/s]
    out = [arr["d0"][seg] + sample_segments(profile, seg, x, 0)]
    for order in (1, 2, 3):
        out.append(sample_segments(profile, seg, x, order) * rate**order)
    return out


def kinematics(profile: CamProfile, *, master_velocity: float | None = None,
               phase: np.ndarray | None = None) -> Kinematics:
    """Distance, v, a, j at the generated points (start point included) or at given master phases (vectorised).

    Given phases are clamped to [0, P_max]; a phase exactly on a boundary belongs to the segment ending there."""
    speed = _speed(profile, master_velocity)
    arr = profile.arrays
    if phase is None:
        seg, ph, x = table_points(profile)
        seg, ph, x = np.concatenate([[0], seg]), np.concatenate([[0.0], ph]), np.concatenate([[0.0], x])
    else:
        ph = np.clip(np.asarray(phase, dtype=float), 0.0, profile.p_max)
        seg = np.clip(np.searchsorted(arr["p1"], ph, side="left"), 0, len(profile.segments) - 1)
        x = (ph - arr["p0"][seg]) / (arr["p1"] - arr["p0"])[seg]
    d, v, a, j = _scaled(profile, seg, x, speed)
    return Kinematics(phase=ph, distance=d, velocity=v, acceleration=a, jerk=j, master_velocity=speed)


@dataclass(frozen=True)
class SegmentCharacteristics:
    """Maxima of one segment: dimensionless (None where the law has no rise, h = 0) and in user units.

    `j_max` is the largest |jerk| inside the smooth pieces; `accel_jump_inside` tells that the acceleration jumps
    inside the segment (parabolic), where the jerk is unbounded."""

    node: int
    curve: _eMC_CAM_CURVE
    dimensionless: CurveCharacteristics | None
    v_max: float
    a_max: float
    j_max: float
    accel_jump_inside: bool


@dataclass(frozen=True)
class ProfileCharacteristics:
    """Whole-table maxima [user units] and the node whose segment reaches each one; `Vm`, `Am`, `Jm` are the
    largest dimensionless values among the segments (each relative to its own rise and span)."""

    segments: tuple[SegmentCharacteristics, ...]
    v_max: float
    a_max: float
    j_max: float
    v_node: int
    a_node: int
    j_node: int
    master_velocity: float
    Vm: float
    Am: float
    Jm: float


def segment_characteristics(s: CamSegment, master_velocity: float) -> SegmentCharacteristics:
    """Vm, Am, Jm of the segment's law and |v|, |a|, |j| maxima at a master velocity [master units/s]."""
    rate = master_velocity / s.span
    h = abs(s.h)
    if s.curve in POLYNOMIAL_CURVES and s.coeffs is not None:
        pc = polynomial_characteristics(s.coeffs)  # maxima of h·f^(k): already in units of the slave
        dim = None if h == 0 else CurveCharacteristics(
            Vm=pc.Vm / h, Am=pc.Am / h, Jm=pc.Jm / h, Jm_dwell=pc.Jm_dwell / h, V0=pc.V0 / s.h, V1=pc.V1 / s.h,
            A0=pc.A0 / s.h, A1=pc.A1 / s.h, accel_jump_inside=False)
        return SegmentCharacteristics(s.node, s.curve, dim, pc.Vm * rate, pc.Am * rate**2, pc.Jm * rate**3, False)
    c = characteristics(s.curve)
    return SegmentCharacteristics(s.node, s.curve, None if h == 0 else c, h * c.Vm * rate, h * c.Am * rate**2,
                                  h * c.Jm * rate**3, c.accel_jump_inside and h > 0)


def profile_characteristics(profile: CamProfile, *, master_velocity: float | None = None) -> ProfileCharacteristics:
    """Per-segment and whole-table maxima of |v|, |a|, |j| at a master velocity (default P_max / CycleTime)."""
    speed = _speed(profile, master_velocity)
    segs = tuple(segment_characteristics(s, speed) for s in profile.segments)

    def top(attr: str) -> tuple[float, int]:
        best = max(segs, key=lambda c: getattr(c, attr))
        return getattr(best, attr), best.node

    (v, vn), (a, an), (j, jn) = top("v_max"), top("a_max"), top("j_max")
    dims = [c.dimensionless for c in segs if c.dimensionless is not None]
    return ProfileCharacteristics(segs, v, a, j, vn, an, jn, speed, Vm=max((d.Vm for d in dims), default=0.0),
                                  Am=max((d.Am for d in dims), default=0.0), Jm=max((d.Jm for d in dims), default=0.0))


@dataclass(frozen=True)
class Jump:
    """A discontinuity at the end of node `node`'s segment (cam data index `point`, master `phase`): the value of
    `quantity` ("position", "velocity" or "acceleration") left and right of the boundary, and `size` = right − left.
    With `periodic`, node = last node and point = EndPointIndex: the wrap from the end back to the start."""

    node: int
    point: int
    phase: float
    quantity: str
    left: float
    right: float

    @property
    def size(self) -> float:
        return self.right - self.left


def continuity(profile: CamProfile, *, master_velocity: float | None = None, periodic: bool = False,
               rel_tol: float = 1e-6) -> list[Jump]:
    """Jumps of position, velocity or acceleration at segment boundaries (and, with `periodic`, at the wrap from
    the end point to the start of the next cycle, where the slave continues from its end distance).

    A difference counts when it exceeds `rel_tol` × the largest |value| of that quantity in the profile (plus 1e-9),
    so round-off of the rounded node values is not reported."""
    speed = _speed(profile, master_velocity)
    n = len(profile.segments)
    segs_left = np.arange(n - 1 + (1 if periodic else 0))
    segs_right = (segs_left + 1) % n
    if segs_left.size == 0:
        return []
    left = _scaled(profile, segs_left, np.ones(segs_left.size), speed)
    right = _scaled(profile, segs_right, np.zeros(segs_left.size), speed)
    if periodic:  # next cycle starts where this one ended: shift its positions by the end distance
        right[0][-1] += profile.segments[-1].d1
    chars = profile_characteristics(profile, master_velocity=speed)
    scale = {"position": max(max(abs(s.d1) for s in profile.segments), 1.0), "velocity": chars.v_max,
             "acceleration": chars.a_max}
    jumps: list[Jump] = []
    for k in range(segs_left.size):
        s = profile.segments[int(segs_left[k])]
        point = s.first + s.count - 1
        for q, name in enumerate(("position", "velocity", "acceleration")):
            lv, rv = float(left[q][k]), float(right[q][k])
            if abs(rv - lv) > rel_tol * scale[name] + 1e-9:
                jumps.append(Jump(node=s.node, point=point, phase=s.p1, quantity=name, left=lv, right=rv))
    return jumps
