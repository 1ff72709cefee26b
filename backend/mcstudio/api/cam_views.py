"""What POST /cams/generate answers: the generated profile's kinematics (at the cam data or sampled for a plot), the
characteristic values per segment and for the whole table, and the continuity warnings (docs/cams.md
"Characteristics and continuity"). Models and their computation; the routes are in `routers/cams.py`."""

from __future__ import annotations

import math

import numpy as np
from pydantic import BaseModel, Field

from ..controller.mc.cam.analysis import continuity, kinematics, profile_characteristics
from ..controller.mc.cam.generate import CamProfile, GenerateResult, sample_segments
from ..controller.mc.cam.table import MAX_POINTS, REAL
from ..project.cam_models import CamSource

__all__ = ["CamGenerateIn", "CamGenerateOut", "generate_view", "real_list"]


class CamGenerateIn(CamSource):
    """MC_GenerateCamTable's inputs and how to answer: nothing is saved."""

    phase_pitch: float | None = Field(
        None, ge=0.001, le=3.4e38, description="If given, the PhasePitch of every node (a convenience for scripts)")
    size: int | None = Field(
        None, ge=2, le=MAX_POINTS + 1, description="Table size (MaxDataNumber) the data must fit (5741 otherwise); "
        "null = up to 65,535 points")
    max_points: int = Field(
        MAX_POINTS, ge=16, le=MAX_POINTS, description="Most points to return: a table with more cam data is answered "
        "with this many points sampled along the laws (at least two per segment, both sides of each segment boundary, "
        "so jumps show), `sampled` = true")


class CamSegmentOut(BaseModel):
    node: int = Field(description="Index of the node whose segment this is (it ends at that node)")
    curve: str = Field(description="_eMC_CAM_CURVE of the segment")
    phase_start: float
    phase_end: float
    distance_start: float
    distance_end: float
    points: int = Field(description="Cam data the segment adds (N of §5.4.4)")
    time_s: float = Field(description="Duration at the master velocity [s]")
    Vm: float | None = Field(description="Dimensionless maximum velocity of the law (null where the rise is 0)")
    Am: float | None = Field(description="Dimensionless maximum acceleration")
    Jm: float | None = Field(description="Dimensionless maximum jerk inside the smooth pieces")
    v_max: float = Field(description="Maximum |velocity| [command units/s] at the master velocity")
    a_max: float = Field(description="Maximum |acceleration| [command units/s²]")
    j_max: float = Field(description="Maximum |jerk| inside the smooth pieces [command units/s³]")
    accel_jump_inside: bool = Field(description="The acceleration jumps inside the segment (the jerk is unbounded)")
    v_init: float = Field(description="Cubic/quintic: velocity at the start [command units/s] (else 0)")
    v_fin: float = Field(description="Cubic/quintic: velocity at the end")
    a_init: float = Field(description="Quintic: acceleration at the start [command units/s²] (else 0)")
    a_fin: float = Field(description="Quintic: acceleration at the end")


class CamTableCharacteristicsOut(BaseModel):
    master_velocity: float = Field(description="Master velocity the values are for [master units/s]")
    cycle_time: float = Field(description="CamProperty.CycleTime as rounded [s]")
    point_count: int = Field(description="Cam data generated, start point included (Tcd)")
    end_point_index: int
    phase_end: float
    distance_end: float
    distance_min: float
    distance_max: float
    v_max: float
    a_max: float
    j_max: float
    v_node: int = Field(description="Node whose segment reaches v_max")
    a_node: int
    j_node: int
    Vm: float = Field(description="Largest dimensionless Vm among the segments")
    Am: float
    Jm: float


class CamCharacteristicsOut(BaseModel):
    table: CamTableCharacteristicsOut
    segments: list[CamSegmentOut]


class CamJumpOut(BaseModel):
    node: int = Field(description="The node whose segment ends at the boundary")
    point: int = Field(description="Cam data index of the boundary")
    phase: float
    quantity: str = Field(description="position, velocity or acceleration")
    left: float = Field(description="Value at the end of the segment")
    right: float = Field(description="Value at the start of the next segment (with periodic: the next cycle's start)")
    size: float = Field(description="right − left")
    message: str


class CamGenerateOut(BaseModel):
    phase: list[float] = Field(description="Master phase of each returned point")
    distance: list[float] = Field(description="Slave distance [command units]")
    velocity: list[float] = Field(description="Slave velocity [command units/s] at the master velocity")
    acceleration: list[float] = Field(description="[command units/s²]")
    jerk: list[float] = Field(description="[command units/s³]")
    sampled: bool = Field(description="The points are sampled along the laws (more cam data than max_points)")
    characteristics: CamCharacteristicsOut
    continuity: list[CamJumpOut] = Field(description="Jumps at segment boundaries (warnings)")


def real_list(a: np.ndarray) -> list[float]:
    """REAL values as the shortest decimals that read back as the same REAL (0.1, not 0.10000000149)."""
    return [float(x) for x in np.asarray(a, dtype=REAL).astype(str)]


def _finite_list(a: np.ndarray) -> list[float]:
    if not bool(np.all(np.isfinite(a))):
        raise ValueError("a value is beyond the range of LREAL")
    return [float(x) for x in a]


def _sampled(profile: CamProfile, speed: float, budget: int) -> list[np.ndarray]:
    """[phase, d, v, a, j] at points spread over the segments by span, both ends of each segment included."""
    arr = profile.arrays
    span = arr["p1"] - arr["p0"]
    n = len(profile.segments)
    extra = max(budget - 2 * n, 0)
    counts = 2 + np.floor(extra * span / profile.p_max).astype(np.int64)
    seg = np.repeat(np.arange(n), counts)
    starts = np.concatenate([[0], np.cumsum(counts)[:-1]])
    k = np.arange(seg.size) - starts[seg]
    x = k / (counts[seg] - 1)
    rate = speed / span[seg]
    phase = arr["p0"][seg] + x * span[seg]
    out = [phase, arr["d0"][seg] + sample_segments(profile, seg, x, 0)]
    out.extend(sample_segments(profile, seg, x, order) * rate**order for order in (1, 2, 3))
    return out


def _jump_message(quantity: str, size: float, phase: float) -> str:
    unit = {"position": "", "velocity": "/s", "acceleration": "/s²"}[quantity]
    return f"{quantity} jumps by {size:.6g} units{unit} at phase {phase:g}"


def generate_view(result: GenerateResult, source: CamSource, max_points: int) -> CamGenerateOut:
    """The answer for a successful generation (`result.ok`, `result.profile` set)."""
    profile = result.profile
    assert profile is not None
    speed = source.master_velocity if source.master_velocity is not None else profile.master_velocity
    tcd = profile.point_count
    if tcd <= max_points:
        k = kinematics(profile, master_velocity=speed)
        cols = [k.phase, k.distance, k.velocity, k.acceleration, k.jerk]
    else:
        cols = _sampled(profile, speed, max_points)
    chars = profile_characteristics(profile, master_velocity=speed)
    segs = []
    for s, c in zip(profile.segments, chars.segments, strict=True):
        dim = c.dimensionless
        segs.append(CamSegmentOut(
            node=s.node, curve=s.curve.name, phase_start=s.p0, phase_end=s.p1, distance_start=s.d0,
            distance_end=s.d1, points=s.count, time_s=s.span / speed, Vm=None if dim is None else dim.Vm,
            Am=None if dim is None else dim.Am, Jm=None if dim is None else _finite(dim.Jm), v_max=c.v_max,
            a_max=c.a_max, j_max=c.j_max, accel_jump_inside=c.accel_jump_inside, v_init=s.v_init, v_fin=s.v_fin,
            a_init=s.a_init, a_fin=s.a_fin))
    d = result.distance.astype(float)
    table = CamTableCharacteristicsOut(
        master_velocity=speed, cycle_time=profile.cycle_time, point_count=tcd, end_point_index=result.end_point_index,
        phase_end=profile.p_max, distance_end=profile.segments[-1].d1, distance_min=float(d.min()),
        distance_max=float(d.max()), v_max=chars.v_max, a_max=chars.a_max, j_max=chars.j_max, v_node=chars.v_node,
        a_node=chars.a_node, j_node=chars.j_node, Vm=chars.Vm, Am=chars.Am, Jm=_finite(chars.Jm) or 0.0)
    jumps = [CamJumpOut(node=j.node, point=j.point, phase=j.phase, quantity=j.quantity, left=j.left, right=j.right,
                        size=j.size, message=_jump_message(j.quantity, j.size, j.phase))
             for j in continuity(profile, master_velocity=speed, periodic=source.periodic)]
    return CamGenerateOut(
        phase=_finite_list(cols[0]), distance=_finite_list(cols[1]), velocity=_finite_list(cols[2]),
        acceleration=_finite_list(cols[3]), jerk=_finite_list(cols[4]), sampled=tcd > max_points,
        characteristics=CamCharacteristicsOut(table=table, segments=segs), continuity=jumps)


def _finite(v: float) -> float | None:
    return v if math.isfinite(v) else None
