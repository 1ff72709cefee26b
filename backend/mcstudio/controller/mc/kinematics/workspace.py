"""The Delta3 workspace: a cylinder on top of a truncated cone, coaxial with the MCS Z axis, and the region 0.1 mm
inside it in which the robot may move (`omron-robot-delta3.md` §3.2, §12.6; seed 003 L1968–2073).

Membership is "inside the configured solid and at least `margin` (0.1 mm) from every point of its surface" —
the solid eroded by a 0.1 mm ball (decision D30.4). The solid is a body of revolution, so the distance of a point to
its surface is the distance, in the point's meridian half-plane (r = √(x² + y²), z), to the profile polyline
top → cylinder wall → cone wall → bottom. All functions are vectorised over (..., 3) arrays."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import ArrayLike, NDArray

MARGIN_MM = 0.1  # manual 3.3.2 (3): the drivable region is 0.1 mm inside the configured workspace
# Round-off allowance: a target placed exactly 0.1 mm inside (e.g. z = Zu − 0.1) computes its distance as
# 0.09999999999999 mm; the manual tells users to place targets "0.1 mm inside", so that must count as inside.
TOLERANCE_MM = 1e-9


@dataclass(frozen=True, kw_only=True)
class Delta3Workspace:
    """Zu (top face z, ≤ 0), Rcy (cylinder radius), Hcy (cylinder height), Rco (radius of the cone's lower face),
    Hco (cone height), all in mm, as `_sMC_WORKSPACE_REF.WorkspaceParam[0..4]`. The cone's top radius is Rcy (§3.2,
    figure labels). `margin` is the manual's 0.1 mm."""

    Zu: float
    Rcy: float
    Hcy: float
    Rco: float
    Hco: float
    margin: float = MARGIN_MM

    @classmethod
    def from_workspace_param(cls, WorkspaceParam: Sequence[float]) -> Delta3Workspace:
        """From `WorkspaceParam[0..7]` (Zu, Rcy, Hcy, Rco, Hco, reserved…); missing elements count as 0."""
        wp = [float(v) for v in WorkspaceParam] + [0.0] * max(0, 5 - len(WorkspaceParam))
        return cls(Zu=wp[0], Rcy=wp[1], Hcy=wp[2], Rco=wp[3], Hco=wp[4])

    def workspace_param(self) -> list[float]:
        return [self.Zu, self.Rcy, self.Hcy, self.Rco, self.Hco, 0.0, 0.0, 0.0]

    @property
    def z_cylinder_bottom(self) -> float:
        """z where the cylinder ends and the cone begins (mm)."""
        return self.Zu - self.Hcy

    @property
    def z_bottom(self) -> float:
        """z of the cone's lower face, the bottom of the workspace (mm)."""
        return self.Zu - self.Hcy - self.Hco

    def profile(self) -> list[tuple[float, float]]:
        """The outline (r, z) from the top centre round to the bottom centre, for drawing the solid."""
        return [(0.0, self.Zu), (self.Rcy, self.Zu), (self.Rcy, self.z_cylinder_bottom), (self.Rco, self.z_bottom),
                (0.0, self.z_bottom)]

    @cached_property
    def _segments(self) -> NDArray[np.float64]:
        """The four surface segments of the profile, shape (4, 2 ends, 2 coords (r, z))."""
        p = self.profile()
        return np.array([[p[k], p[k + 1]] for k in range(4)], dtype=np.float64)

    @np.errstate(all="ignore")  # NaN/inf points give NaN/outside, not warnings
    def signed_distance(self, xyz: ArrayLike) -> NDArray[np.float64]:
        """Distance (mm) of each point to the configured surface: positive inside, negative outside, NaN for
        non-finite points. Shape (...) for input (..., 3)."""
        p = np.asarray(xyz, dtype=np.float64)
        r = np.hypot(p[..., 0], p[..., 1])
        z = p[..., 2]
        dist2 = np.full(r.shape, np.inf)
        for (ra, za), (rb, zb) in self._segments:
            dr, dz = rb - ra, zb - za
            length2 = dr * dr + dz * dz
            if length2 == 0.0:  # Rco = 0 makes the bottom face a point on the axis
                t: NDArray[np.float64] | float = 0.0
            else:
                t = np.clip(((r - ra) * dr + (z - za) * dz) / length2, 0.0, 1.0)
            er = r - (ra + t * dr)
            ez = z - (za + t * dz)
            np.minimum(dist2, er * er + ez * ez, out=dist2)
        dist = np.sqrt(dist2)
        return np.where(self._inside_solid(r, z), dist, -dist)

    def _inside_solid(self, r: NDArray[np.float64], z: NDArray[np.float64]) -> NDArray[np.bool_]:
        zc = self.z_cylinder_bottom
        with np.errstate(invalid="ignore", divide="ignore"):
            # Only used below zc, where z ≥ z_bottom implies Hco > 0 (no division by zero there).
            r_cone = self.Rcy + (self.Rco - self.Rcy) * (zc - z) / self.Hco if self.Hco > 0 else np.zeros_like(z)
            r_max = np.where(z >= zc, self.Rcy, r_cone)
            return (z <= self.Zu) & (z >= self.z_bottom) & (r <= r_max)

    @np.errstate(all="ignore")
    def contains(self, xyz: ArrayLike) -> NDArray[np.bool_]:
        """True where the point lies in the drivable region: inside and ≥ margin from the surface (± 1e-9 mm).
        Non-finite points are outside. Shape (...) for input (..., 3)."""
        d = self.signed_distance(xyz)
        with np.errstate(invalid="ignore"):
            return d >= self.margin - TOLERANCE_MM


def describe_distance(distance: float) -> str:
    """A short text for an event detail: how far inside/outside the configured surface a point is."""
    if not math.isfinite(distance):
        return "position not finite"
    if distance < 0:
        return f"{-distance:.4f} mm outside the configured workspace"
    return f"{distance:.4f} mm inside the configured surface (must be ≥ {MARGIN_MM} mm)"
