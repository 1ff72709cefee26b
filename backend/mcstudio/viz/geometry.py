"""Pure geometry of the 3-D view: meshes, transforms and the Delta3's pose from three joint angles.

No viser here — everything is numpy in, numpy out, so the pose is testable against the kinematics
(`controller/mc/kinematics`, `omron-robot-delta3.md` §12.8). Lengths are **mm** (the kinematics' unit) unless a
name says `_m`; the scene converts to metres (viser) with `MM`.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..controller.mc.kinematics import Delta3Params, Delta3Workspace, Status, forward_point

F64 = NDArray[np.float64]
MM = 1e-3  # metres per millimetre: the kinematics work in mm, viser in m


# ----------------------------------------------------------------------------------------------- transforms
def quat_z_to(d: ArrayLike) -> F64:
    """Unit quaternions (w, x, y, z) turning +Z onto the directions `d` (..., 3) (any length > 0).

    q = (1 + ẑ·d̂, ẑ × d̂) normalised; for d̂ = −ẑ (antiparallel) a half turn about X."""
    v = np.asarray(d, dtype=np.float64)
    n = np.linalg.norm(v, axis=-1, keepdims=True)
    u = np.divide(v, n, out=np.zeros_like(v), where=n > 0)
    q = np.stack([1.0 + u[..., 2], -u[..., 1], u[..., 0], np.zeros(u.shape[:-1])], axis=-1)
    qn = np.linalg.norm(q, axis=-1, keepdims=True)
    flip = qn[..., 0] < 1e-9
    q = np.divide(q, qn, out=np.zeros_like(q), where=qn > 1e-9)
    q[flip] = (0.0, 1.0, 0.0, 0.0)
    return q


def quat_from_matrix(R: ArrayLike) -> F64:
    """Unit quaternion (w, x, y, z) of a rotation matrix (3, 3) (Shepperd's method)."""
    m = np.asarray(R, dtype=np.float64)
    tr = m[0, 0] + m[1, 1] + m[2, 2]
    if tr > 0:
        s = 2.0 * math.sqrt(tr + 1.0)
        q = (0.25 * s, (m[2, 1] - m[1, 2]) / s, (m[0, 2] - m[2, 0]) / s, (m[1, 0] - m[0, 1]) / s)
    elif m[0, 0] > m[1, 1] and m[0, 0] > m[2, 2]:
        s = 2.0 * math.sqrt(1.0 + m[0, 0] - m[1, 1] - m[2, 2])
        q = ((m[2, 1] - m[1, 2]) / s, 0.25 * s, (m[0, 1] + m[1, 0]) / s, (m[0, 2] + m[2, 0]) / s)
    elif m[1, 1] > m[2, 2]:
        s = 2.0 * math.sqrt(1.0 + m[1, 1] - m[0, 0] - m[2, 2])
        q = ((m[0, 2] - m[2, 0]) / s, (m[0, 1] + m[1, 0]) / s, 0.25 * s, (m[1, 2] + m[2, 1]) / s)
    else:
        s = 2.0 * math.sqrt(1.0 + m[2, 2] - m[0, 0] - m[1, 1])
        q = ((m[1, 0] - m[0, 1]) / s, (m[0, 2] + m[2, 0]) / s, (m[1, 2] + m[2, 1]) / s, 0.25 * s)
    out = np.array(q)
    return out / np.linalg.norm(out)


def rotate_by_quat(q: ArrayLike, v: ArrayLike) -> F64:
    """Rotate vectors v (..., 3) by unit quaternions q (..., 4) (w, x, y, z)."""
    qa = np.asarray(q, dtype=np.float64)
    va = np.asarray(v, dtype=np.float64)
    w, xyz = qa[..., :1], qa[..., 1:]
    t = 2.0 * np.cross(xyz, va)
    return va + w * t + np.cross(xyz, t)


@dataclass(frozen=True, slots=True)
class SegmentTransforms:
    """Instance transforms that stretch the unit cylinder of `unit_cylinder()` (radius 1, z 0…1) over segments:
    `positions` (N, 3) = start points, `wxyzs` (N, 4), `scales` (N, 3) = (radius, radius, length)."""

    positions: F64
    wxyzs: F64
    scales: F64


def segment_transforms(segments: ArrayLike, radii: ArrayLike) -> SegmentTransforms:
    """Transforms of cylinders from segments (N, 2, 3) with radii (N,) or a scalar (same unit as the points)."""
    s = np.asarray(segments, dtype=np.float64)
    a, b = s[:, 0], s[:, 1]
    d = b - a
    length = np.linalg.norm(d, axis=-1)
    r = np.broadcast_to(np.asarray(radii, dtype=np.float64), length.shape)
    return SegmentTransforms(positions=a.copy(), wxyzs=quat_z_to(d), scales=np.stack([r, r, length], axis=-1))


# ----------------------------------------------------------------------------------------------- meshes
@dataclass(frozen=True, slots=True)
class Mesh:
    vertices: F64  # (V, 3)
    faces: NDArray[np.uint32]  # (F, 3), counter-clockwise seen from outside

    def scaled(self, k: float) -> Mesh:
        return Mesh(self.vertices * k, self.faces)

    def translated(self, offset: ArrayLike) -> Mesh:
        return Mesh(self.vertices + np.asarray(offset, dtype=np.float64), self.faces)

    @property
    def bounds(self) -> tuple[F64, F64]:
        return self.vertices.min(axis=0), self.vertices.max(axis=0)


def unit_cylinder(segments: int = 16) -> Mesh:
    """Radius 1 around +Z from z = 0 to z = 1, with caps (for `segment_transforms`)."""
    return revolve([(0.0, 1.0), (1.0, 1.0), (1.0, 0.0), (0.0, 0.0)], segments=segments)


def revolve(profile: Sequence[tuple[float, float]], *, segments: int = 64) -> Mesh:
    """Body of revolution about Z from a profile polyline of (r, z), e.g. `Delta3Workspace.profile()` (top centre →
    round → bottom centre). Each profile segment gets its own two rings so edges stay sharp; a ring of radius 0
    is one vertex."""
    ang = np.linspace(0.0, 2.0 * np.pi, segments, endpoint=False)
    c, s = np.cos(ang), np.sin(ang)
    verts: list[F64] = []
    faces: list[NDArray[np.int64]] = []
    base = 0

    def ring(r: float, z: float) -> tuple[F64, bool]:
        if r == 0.0:
            return np.array([[0.0, 0.0, z]]), True
        return np.stack([r * c, r * s, np.full(segments, z)], axis=-1), False

    k = np.arange(segments)
    k1 = (k + 1) % segments
    for (ra, za), (rb, zb) in itertools.pairwise(profile):
        va, pa = ring(ra, za)
        vb, pb = ring(rb, zb)
        if pa and pb:
            continue
        ia, ib = base, base + len(va)
        verts += [va, vb]
        base += len(va) + len(vb)
        # the profile runs top → bottom on the outside: faces (a_k, b_k, b_k+1) wind counter-clockwise outward
        if pa:
            faces.append(np.stack([np.full(segments, ia), ib + k, ib + k1], axis=-1))
        elif pb:
            faces.append(np.stack([ia + k, np.full(segments, ib), ia + k1], axis=-1))
        else:
            faces.append(np.stack([ia + k, ib + k, ib + k1], axis=-1))
            faces.append(np.stack([ia + k, ib + k1, ia + k1], axis=-1))
    return Mesh(np.concatenate(verts), np.concatenate(faces).astype(np.uint32))


def polygon_from_halfplanes(normals_deg: Sequence[float], offsets: Sequence[float]) -> F64:
    """Convex polygon (N, 2), counter-clockwise, bounded by the lines n_k·p = d_k with normals at increasing
    angles (degrees)."""
    n = np.radians(np.asarray(normals_deg, dtype=np.float64))
    d = np.asarray(offsets, dtype=np.float64)
    pts = []
    for k in range(len(n)):
        j = (k + 1) % len(n)
        A = np.array([[math.cos(n[k]), math.sin(n[k])], [math.cos(n[j]), math.sin(n[j])]])
        pts.append(np.linalg.solve(A, [d[k], d[j]]))
    return np.array(pts)


def prism(polygon: ArrayLike, z0: float, z1: float) -> Mesh:
    """Extrude a convex counter-clockwise polygon (N, 2) from z0 up to z1 (flat-shaded look: sides have their own
    vertices)."""
    p = np.asarray(polygon, dtype=np.float64)
    n = len(p)
    bottom = np.column_stack([p, np.full(n, z0)])
    top = np.column_stack([p, np.full(n, z1)])
    verts = [top, bottom]
    faces = [np.array([[0, k, k + 1] for k in range(1, n - 1)]),  # top, counter-clockwise seen from +Z
             np.array([[n, n + k + 1, n + k] for k in range(1, n - 1)])]  # bottom, seen from −Z
    base = 2 * n
    for k in range(n):
        j = (k + 1) % n
        verts.append(np.array([bottom[k], bottom[j], top[j], top[k]]))
        faces.append(np.array([[base, base + 1, base + 2], [base, base + 2, base + 3]]))
        base += 4
    return Mesh(np.concatenate(verts), np.concatenate(faces).astype(np.uint32))


def box(size: ArrayLike, center: ArrayLike = (0.0, 0.0, 0.0)) -> Mesh:
    sx, sy, sz = (0.5 * float(v) for v in np.asarray(size, dtype=np.float64))
    cx, cy, cz = (float(v) for v in np.asarray(center, dtype=np.float64))
    poly = np.array([[cx - sx, cy - sy], [cx + sx, cy - sy], [cx + sx, cy + sy], [cx - sx, cy + sy]])
    return prism(poly, cz - sz, cz + sz)


def merge(*meshes: Mesh) -> Mesh:
    verts, faces, base = [], [], 0
    for m in meshes:
        verts.append(m.vertices)
        faces.append(m.faces.astype(np.int64) + base)
        base += len(m.vertices)
    return Mesh(np.concatenate(verts), np.concatenate(faces).astype(np.uint32))


def workspace_mesh(ws: Delta3Workspace, *, segments: int = 96) -> Mesh:
    """The configured workspace solid (cylinder on a truncated cone, §3.2) in mm: the same outline as
    `Delta3Workspace.profile()`, so its bounds are exactly the configured ones."""
    return revolve(ws.profile(), segments=segments)


def workspace_outline(ws: Delta3Workspace, *, segments: int = 96) -> F64:
    """Line segments (N, 2, 3) mm of the workspace's edges: the top, cylinder/cone and bottom circles and four
    meridians — drawn over the translucent solid so its shape reads at a glance."""
    ang = np.linspace(0.0, 2.0 * np.pi, segments + 1)
    segs = []
    for r, z in ws.profile()[1:-1]:
        if r <= 0.0:
            continue
        ring = np.stack([r * np.cos(ang), r * np.sin(ang), np.full_like(ang, z)], axis=-1)
        segs.append(np.stack([ring[:-1], ring[1:]], axis=1))
    prof = ws.profile()[1:-1]
    for a in np.radians([45.0, 135.0, 225.0, 315.0]):
        pts = np.array([[r * math.cos(a), r * math.sin(a), z] for r, z in prof])
        segs.append(np.stack([pts[:-1], pts[1:]], axis=1))
    return np.concatenate(segs)


# ----------------------------------------------------------------------------------------------- the Delta3
@dataclass(frozen=True, slots=True)
class RobotStyle:
    """Cosmetic sizes (mm) derived from the robot's parameters, so any configured robot looks proportionate."""

    arm_radius: float
    rod_radius: float
    rod_spacing: float  # w of §12.8: the two rods of a forearm parallelogram, along the motor axis tᵢ
    joint_radius: float
    platform_thickness: float
    base_thickness: float
    motor_radius: float
    motor_length: float

    @classmethod
    def for_params(cls, p: Delta3Params) -> RobotStyle:
        size = max(p.Lf, 1e-6)
        rod_spacing = min(0.25 * size, 1.6 * p.Rm)
        rod_radius = 0.012 * p.Lm
        return cls(arm_radius=0.055 * size, rod_radius=rod_radius, rod_spacing=rod_spacing,
                   joint_radius=1.6 * rod_radius, platform_thickness=0.06 * size, base_thickness=0.08 * p.Rf,
                   motor_radius=0.14 * p.Rf, motor_length=0.5 * p.Rf)


# Instances of the link cylinder: upper arms 0–2, forearm rods 3–8 (arm i: 3 + 2i, 4 + 2i), elbow bars 9–11.
N_LINKS = 12
UPPER_ARMS = slice(0, 3)
RODS = slice(3, 9)
ELBOW_BARS = slice(9, 12)


@dataclass(frozen=True, slots=True)
class RobotPose:
    """Where every moving part of a Delta3 is, in the MCS (mm), for one set of joint angles (deg).

    `links` (12, 2, 3): the cylinders' end points (upper arm Mᵢ → Eᵢ, two forearm rods Eᵢ ± w/2·tᵢ → Wᵢ ± w/2·tᵢ,
    the elbow bar between the rods); `link_radii` (12,); `joints` (12, 3): the rods' ball joints; `tcp` (3,) —
    the moving platform's centre; `ok`: forward kinematics solved (else `tcp`, the rods and joints are NaN)."""

    angles: F64
    shoulders: F64
    elbows: F64
    wrists: F64
    tcp: F64
    links: F64
    link_radii: F64
    joints: F64
    status: Status

    @property
    def ok(self) -> bool:
        return self.status == Status.OK


def robot_pose(params: Delta3Params, angles: ArrayLike, style: RobotStyle | None = None) -> RobotPose:
    """The pose of every moving part for ACS angles (A0, A1, A2) in degrees (§12.2, §12.8).

    The same points as `arm_geometry` (tested), computed for one pose with the one-point forward kinematics
    (`forward_point`, ~4 µs) instead of the vectorised one (~250 µs of numpy call overhead for a single point):
    this runs for every frame of the view."""
    st = style or RobotStyle.for_params(params)
    a = np.asarray(angles, dtype=np.float64).reshape(3)
    u, t = params.radial, params.tangential
    q = np.radians(a)[:, None]
    base = np.array([0.0, 0.0, params.motor_plane_z])
    shoulders = base + params.Rf * u
    elbows = shoulders + params.Lf * (np.cos(q) * u - np.sin(q) * _Z)
    status, p = forward_point(params, float(a[0]), float(a[1]), float(a[2]))
    tcp = np.array(p)
    wrists = tcp + params.Rm * u
    half = 0.5 * st.rod_spacing * t  # (3, 3)
    links = np.empty((N_LINKS, 2, 3))
    links[UPPER_ARMS, 0] = shoulders
    links[UPPER_ARMS, 1] = elbows
    rods = links[RODS].reshape(3, 2, 2, 3)  # (3 arms, 2 rods (+w/2, −w/2), 2 ends (elbow, wrist), 3), a view
    rods[:, 0, 0] = elbows + half
    rods[:, 0, 1] = wrists + half
    rods[:, 1, 0] = elbows - half
    rods[:, 1, 1] = wrists - half
    links[ELBOW_BARS, 0] = elbows - half
    links[ELBOW_BARS, 1] = elbows + half
    radii = np.empty(N_LINKS)
    radii[UPPER_ARMS] = st.arm_radius
    radii[RODS] = st.rod_radius
    radii[ELBOW_BARS] = 0.8 * st.arm_radius
    joints = links[RODS].reshape(12, 3)  # both ends of each rod
    return RobotPose(angles=a, shoulders=shoulders, elbows=elbows, wrists=wrists, tcp=tcp, links=links,
                     link_radii=radii, joints=joints, status=Status(int(status)))


_Z = np.array([0.0, 0.0, 1.0])


def base_polygon(params: Delta3Params, margin: float) -> F64:
    """Fixed-frame outline (N, 2) mm: a triangle whose edges carry the motor axes (apothem Rf + margin, edge
    normals uᵢ) with its corners cut, so the motors sit on its edges as on a real Delta."""
    phi = np.degrees(params.azimuths_rad)
    normals, offsets = [], []
    for p in phi:
        normals += [p, p + 60.0]
        offsets += [params.Rf + margin, 1.25 * params.Rf]
    order = np.argsort(np.mod(normals, 360.0))
    return polygon_from_halfplanes(np.mod(normals, 360.0)[order], np.asarray(offsets)[order])


def platform_polygon(params: Delta3Params, style: RobotStyle) -> F64:
    """Moving-frame outline (N, 2) mm around its centre: a cut triangle whose edges hold the wrist joints Wᵢ."""
    phi = np.degrees(params.azimuths_rad)
    half_edge = 0.5 * style.rod_spacing + 1.2 * style.joint_radius
    # the corner cut (normal at φᵢ + 60°) keeps the outer joints inside: n·(Rm·uᵢ + h·tᵢ) = Rm/2 + h·√3/2; it must
    # stay below the triangle's corner (2·Rm) to cut anything
    cut = min(0.5 * params.Rm + 0.5 * math.sqrt(3.0) * half_edge + style.joint_radius, 1.9 * params.Rm)
    normals, offsets = [], []
    for p in phi:
        normals += [p, p + 60.0]
        offsets += [params.Rm, cut]
    order = np.argsort(np.mod(normals, 360.0))
    return polygon_from_halfplanes(np.mod(normals, 360.0)[order], np.asarray(offsets)[order])
