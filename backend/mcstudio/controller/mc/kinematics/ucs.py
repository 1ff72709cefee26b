"""User coordinate systems (UCS) of a robot: pose (Tx, Ty, Tz, Rx, Ry, Rz) relative to the MCS, with the rotation
order of manual 3.3.4 (`omron-robot-delta3.md` §4, §8.2 `_sMC_COORD_REF`, §9.2; seed 003 L2187–2234).

Rz about Z first, then Ry about the new Y, then Rx about the newest X (intrinsic Z-Y′-X″), i.e.
R = Rz(Rz)·Ry(Ry)·Rx(Rx); p_MCS = T + R·p_UCS and p_UCS = Rᵀ·(p_MCS − T). Vectorised over (..., 3) arrays."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .codes import E_CSID, E_NONE, E_POSE

CSID_MAX = 15  # 16 user coordinate systems per robot, CSID 0–15
# Pose angle ranges (deg), `_sMC_COORD_REF.Pose[3..5]` (§8.2): Rx −180…180, Ry −90…90, Rz −180…180.
POSE_RANGES: tuple[tuple[str, float, float], ...] = (("Rx", -180.0, 180.0), ("Ry", -90.0, 90.0), ("Rz", -180.0, 180.0))


def rotation(Rx: float, Ry: float, Rz: float) -> NDArray[np.float64]:
    """R = Rz(Rz)·Ry(Ry)·Rx(Rx) (angles in degrees): columns are the UCS axes Xu, Yu, Zu seen in the MCS."""
    a, b, c = math.radians(Rz), math.radians(Ry), math.radians(Rx)
    ca, sa, cb, sb, cc, sc = math.cos(a), math.sin(a), math.cos(b), math.sin(b), math.cos(c), math.sin(c)
    rz = np.array([[ca, -sa, 0.0], [sa, ca, 0.0], [0.0, 0.0, 1.0]])
    ry = np.array([[cb, 0.0, sb], [0.0, 1.0, 0.0], [-sb, 0.0, cb]])
    rx = np.array([[1.0, 0.0, 0.0], [0.0, cc, -sc], [0.0, sc, cc]])
    return rz @ ry @ rx


@dataclass(frozen=True, kw_only=True)
class UserCoordSystem:
    """A UCS pose: origin (Tx, Ty, Tz) mm from the MCS origin, rotations Rx, Ry, Rz in degrees (§4)."""

    Tx: float = 0.0
    Ty: float = 0.0
    Tz: float = 0.0
    Rx: float = 0.0
    Ry: float = 0.0
    Rz: float = 0.0

    @classmethod
    def from_pose(cls, Pose: Sequence[float]) -> UserCoordSystem:
        """From `_sMC_COORD_REF.Pose[0..5]` = Tx, Ty, Tz, Rx, Ry, Rz (missing elements count as 0)."""
        v = [float(x) for x in Pose] + [0.0] * max(0, 6 - len(Pose))
        return cls(Tx=v[0], Ty=v[1], Tz=v[2], Rx=v[3], Ry=v[4], Rz=v[5])

    def pose(self) -> list[float]:
        return [self.Tx, self.Ty, self.Tz, self.Rx, self.Ry, self.Rz]

    def planar(self) -> UserCoordSystem:
        """The pose MC_SyncLinearConveyor uses: Rx and Ry ignored (§9.5 [Emulator]: "disabled, set them to 0")."""
        return UserCoordSystem(Tx=self.Tx, Ty=self.Ty, Tz=self.Tz, Rz=self.Rz)

    @cached_property
    def R(self) -> NDArray[np.float64]:
        """Rotation matrix UCS → MCS (3, 3)."""
        return rotation(self.Rx, self.Ry, self.Rz)

    @cached_property
    def T(self) -> NDArray[np.float64]:
        """Origin of the UCS in the MCS (3,)."""
        return np.array([self.Tx, self.Ty, self.Tz])

    def to_mcs(self, p_ucs: ArrayLike) -> NDArray[np.float64]:
        """Positions (..., 3) in this UCS → MCS: T + R·p."""
        return np.asarray(p_ucs, dtype=np.float64) @ self.R.T + self.T

    def from_mcs(self, p_mcs: ArrayLike) -> NDArray[np.float64]:
        """Positions (..., 3) in the MCS → this UCS: Rᵀ·(p − T)."""
        return (np.asarray(p_mcs, dtype=np.float64) - self.T) @ self.R

    def vector_to_mcs(self, v_ucs: ArrayLike) -> NDArray[np.float64]:
        """Directions/velocities (..., 3): R·v (no translation)."""
        return np.asarray(v_ucs, dtype=np.float64) @ self.R.T

    def vector_from_mcs(self, v_mcs: ArrayLike) -> NDArray[np.float64]:
        """Directions/velocities (..., 3): Rᵀ·v — MC_GroupMon's ActualVelocity in a UCS (§9.3)."""
        return np.asarray(v_mcs, dtype=np.float64) @ self.R


def check_pose(Pose: Sequence[float]) -> tuple[int, str]:
    """`_sMC_COORD_REF.Pose` range check of MC_DefineCoordSystem: (0, "") or (570C, reason). Tx, Ty, Tz may be any
    finite value; a NaN/inf element is out of range as well (D30.8)."""
    if len(Pose) > 6:
        return E_POSE, f"Pose has {len(Pose)} elements; ARRAY[0..5] holds 6"
    v = [float(x) for x in Pose] + [0.0] * (6 - len(Pose))
    for k, x in enumerate(v):
        if not math.isfinite(x):
            return E_POSE, f"Pose[{k}] = {x} is not a number"
    for k, (name, lo, hi) in enumerate(POSE_RANGES, start=3):
        if not lo <= v[k] <= hi:
            return E_POSE, f"{name} = Pose[{k}] = {v[k]}° must be within {lo:g}…{hi:g}°"
    return E_NONE, ""


def check_csid(CSID: int, defined: Sequence[int] | None = None) -> tuple[int, str]:
    """CSID 0–15 and, when `defined` is given, registered by MC_DefineCoordSystem: (0, "") or (570B, reason)."""
    if not 0 <= CSID <= CSID_MAX:
        return E_CSID, f"CSID {CSID} must be within 0–{CSID_MAX}"
    if defined is not None and CSID not in defined:
        return E_CSID, f"user coordinate system {CSID} is not defined (MC_DefineCoordSystem)"
    return E_NONE, ""
