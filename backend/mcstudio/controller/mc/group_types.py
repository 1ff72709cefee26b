"""Axes groups: the shared types — group states, the ErrorIDs of the group instructions, a path being followed
(`Motion`) and the evaluation of its 1-D profile.

Used by `group.py` (state machine), `group_planning.py` (planning, buffering, blending, override) and
`group_motion.py` (the period: profile evaluation, stops, MC_GroupSyncMoveAbsolute).
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass, field

from .enums import _eMC_TRANSITION_MODE
from .group_path import Path
from .jobs import Job
from .profile import Segments

E_GROUP_CANNOT_ENABLE = 0x5440
E_GROUP_DISABLED = 0x543F
E_ILLEGAL_GROUP = 0x5461
E_MEMBER_STOPPING = 0x5442
E_COUNT_MODE = 0x544A
E_GROUP_IMMEDIATE_STOP = 0x5486
E_MEMBER_ERROR = 0x7430
E_CHANGE_AXES = 0x549D
MAX_BUFFERED = 7  # A-3 note: a group buffers up to 7 instructions (executing + buffered ≤ 8)


class GroupState(enum.IntEnum):
    """The five exclusive flags of `_sGROUP_REF.Status` (A-3 letters a–e)."""

    Disabled = 0
    Standby = 1
    Moving = 2
    Stopping = 3
    ErrorStop = 4


G = GroupState


@dataclass(slots=True)
class Motion:
    """A path being followed: its 1-D profile `seg` starts at kernel time `t0` (s); `s`, `sd`, `sdd` are the last
    evaluated path position, velocity and acceleration."""

    job: Job
    path: Path
    seg: Segments
    t0: float
    velocity: float  # planned path velocity (clamped, before override)
    v_end: float = 0.0  # path velocity at the end (blending transit velocity)
    k: int = 0  # segment index of the last evaluation
    s: float = 0.0
    sd: float = 0.0
    sdd: float = 0.0
    end_cycle: int = -1  # period in which the final command value was output
    stopping: bool = False  # an MC_GroupStop / error deceleration along the path
    paused: bool = False  # override 0: decelerated to velocity 0 and waiting
    t_dec: float = math.inf  # profile time where the final deceleration begins (corner superimposition)
    instant: bool = False  # Deceleration 0 before a blending successor: it starts at its target velocity (D105)


@dataclass(slots=True)
class _Pos:
    """Start data of a move: the path start and the per-axis velocity there (for the start velocity of Aborting)."""

    point: tuple[float, ...]
    velocity: tuple[float, ...] = field(default_factory=tuple)


def sample(seg: Segments, t: float, k: int) -> tuple[float, float, float, int]:
    """s, ṡ, s̈ of a profile at time t (seconds from its start), from segment k on (times only increase)."""
    ts = seg.t
    n = len(ts)
    while k + 1 < n and t >= ts[k + 1]:
        k += 1
    tau = t - ts[k]
    j, a, v = seg.j[k], seg.a[k], seg.v[k]
    return (seg.p[k] + tau * (v + tau * (a / 2 + tau * j / 6)), v + tau * (a + tau * j / 2), a + tau * j, k)


def decel_start(seg: Segments) -> float:
    """Time at which the final deceleration of a profile begins (its velocity no longer increases)."""
    k = len(seg.t) - 2  # the last segment is the tail
    while k >= 0:
        if seg.a[k] > 1e-9 or (seg.j[k] > 0 and seg.a[k] >= -1e-9):
            return seg.t[k + 1]
        if seg.a[k] >= -1e-9 and seg.j[k] == 0 and (k == 0 or seg.a[k - 1] >= -1e-9):
            return seg.t[k + 1]  # a cruise phase
        k -= 1
    return 0.0


def transition_error(buffer_mode: int, transition_mode: int) -> int:
    """5432: TransitionMode out of range, or corner superimposition without a Blending BufferMode (§4.3)."""
    if transition_mode not in (0, 10):
        return 0x5432
    if transition_mode == _eMC_TRANSITION_MODE._mcTMCornerSuperimposed and buffer_mode < 2:
        return 0x5432
    return 0
