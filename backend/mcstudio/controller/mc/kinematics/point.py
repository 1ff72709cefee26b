"""One-point Delta3 kinematics in plain `math`, for the MC layer's per-period work (one TCP per robot per period).

The same formulas as the vectorised `delta3.py` (§12.3–§12.5) and `workspace.py` (§12.6, D30.4), written for
scalars because numpy's per-call overhead makes a one-point array call ~20× slower (~100 µs vs ~5 µs).
`tests/controller/mc/kinematics/test_point.py` checks that both give the same numbers on random points."""

from __future__ import annotations

import itertools
import math

from .codes import Status
from .delta3 import BRANCH_TOLERANCE_MM, DEGENERATE_MM
from .params import Delta3Params
from .workspace import TOLERANCE_MM, Delta3Workspace

Vec3 = tuple[float, float, float]
_NAN3: Vec3 = (math.nan, math.nan, math.nan)


def inverse_point(params: Delta3Params, x: float, y: float, z: float) -> tuple[Status, Vec3]:
    """MCS TCP (mm) → (status, (A0, A1, A2) deg). Status OK, UNREACHABLE or NOT_FINITE (angles NaN then)."""
    if not (math.isfinite(x) and math.isfinite(y) and math.isfinite(z)):
        return Status.NOT_FINITE, _NAN3
    Rf, Lf, Rm, Lm = params.Rf, params.Lf, params.Rm, params.Lm
    zb = z + params.Z0
    if not zb < 0.0:  # also NaN Z0
        return Status.UNREACHABLE, _NAN3
    k0 = Lm * Lm - Lf * Lf
    cq: list[float] = []
    sq: list[float] = []
    q: list[float] = []
    for c, s in params.cs_phi:
        A = (Rf - Rm) - (x * c + y * s)
        yi = y * c - x * s
        R2 = A * A + zb * zb
        C = (k0 - R2 - yi * yi) * (0.5 / Lf)
        D2 = R2 - C * C
        if not (R2 > 0.0 and D2 >= 0.0):
            return Status.UNREACHABLE, _NAN3
        D = math.sqrt(D2)
        cqi = (A * C - zb * D) / R2
        sqi = (zb * C + A * D) / R2
        qi = math.atan2(sqi, cqi)
        cq.append(cqi)
        sq.append(sqi)
        q.append(-math.pi if qi >= math.pi else qi)
    if not _on_lower_branch(params, cq, sq, x, y, zb):
        return Status.UNREACHABLE, _NAN3
    return Status.OK, (math.degrees(q[0]), math.degrees(q[1]), math.degrees(q[2]))


def _centres(params: Delta3Params, cq: list[float], sq: list[float]) -> list[Vec3]:
    out = []
    for (c, s), cqi, sqi in zip(params.cs_phi, cq, sq, strict=True):
        rho = (params.Rf - params.Rm) + params.Lf * cqi
        out.append((rho * c, rho * s, -params.Lf * sqi))
    return out


def _on_lower_branch(params: Delta3Params, cq: list[float], sq: list[float], x: float, y: float, zb: float) -> bool:
    (s0x, s0y, s0z), (s1x, s1y, s1z), (s2x, s2y, s2z) = _centres(params, cq, sq)
    ax, ay, az = s1x - s0x, s1y - s0y, s1z - s0z
    bx, by, bz = s2x - s0x, s2y - s0y, s2z - s0z
    nx, ny, nz = ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx
    norm = math.sqrt(nx * nx + ny * ny + nz * nz)
    if norm == 0.0:
        return False
    height = ((x - s0x) * nx + (y - s0y) * ny + (zb - s0z) * nz) / norm
    return (height if nz >= 0.0 else -height) <= BRANCH_TOLERANCE_MM


def forward_point(params: Delta3Params, a0: float, a1: float, a2: float) -> tuple[Status, Vec3]:
    """ACS angles (deg) → (status, MCS TCP (mm)), lower solution. Status OK, UNREACHABLE or NOT_FINITE."""
    if not (math.isfinite(a0) and math.isfinite(a1) and math.isfinite(a2)):
        return Status.NOT_FINITE, _NAN3
    q = (math.radians(a0), math.radians(a1), math.radians(a2))
    (s0x, s0y, s0z), (s1x, s1y, s1z), (s2x, s2y, s2z) = _centres(
        params, [math.cos(v) for v in q], [math.sin(v) for v in q])
    Lm = params.Lm
    ux, uy, uz = s1x - s0x, s1y - s0y, s1z - s0z
    vx, vy, vz = s2x - s0x, s2y - s0y, s2z - s0z
    d = math.sqrt(ux * ux + uy * uy + uz * uz)
    if not d > DEGENERATE_MM:
        return Status.UNREACHABLE, _NAN3
    exx, exy, exz = ux / d, uy / d, uz / d
    i = exx * vx + exy * vy + exz * vz
    wx, wy, wz = vx - i * exx, vy - i * exy, vz - i * exz
    j = math.sqrt(wx * wx + wy * wy + wz * wz)
    if not j > DEGENERATE_MM:
        return Status.UNREACHABLE, _NAN3
    eyx, eyy, eyz = wx / j, wy / j, wz / j
    ezx, ezy, ezz = exy * eyz - exz * eyy, exz * eyx - exx * eyz, exx * eyy - exy * eyx
    X = 0.5 * d
    Y = (i * i + j * j) / (2.0 * j) - (i / j) * X
    Z2 = Lm * Lm - X * X - Y * Y
    if not Z2 + 1e-12 * Lm * Lm >= 0.0:
        return Status.UNREACHABLE, _NAN3
    h = math.sqrt(max(Z2, 0.0))
    if ezz >= 0.0:
        h = -h
    p = (s0x + X * exx + Y * eyx + h * ezx, s0y + X * exy + Y * eyy + h * ezy,
         s0z + X * exz + Y * eyz + h * ezz - params.Z0)
    if not all(math.isfinite(v) for v in p):
        return Status.UNREACHABLE, _NAN3
    return Status.OK, p


def tcp_velocity_point(params: Delta3Params, angles: Vec3, joint_velocity: Vec3) -> tuple[Status, Vec3]:
    """TCP velocity (mm/s, MCS) from ACS angles (deg) and velocities (deg/s): Jx·ṗ = diag(Jq)·q̇ solved by
    Cramer's rule (§12.5). Status OK, UNREACHABLE, NOT_FINITE or SINGULAR."""
    st, p = forward_point(params, *angles)
    if st != Status.OK:
        return st, _NAN3
    if not all(math.isfinite(v) for v in joint_velocity):
        return Status.NOT_FINITE, _NAN3
    rows, jq = _velocity_terms(params, angles, p)
    rhs = [jq[k] * joint_velocity[k] for k in range(3)]
    (a, b, c), (d, e, f), (g, h, i) = rows
    det = a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g)
    scale = math.prod(math.sqrt(r[0] ** 2 + r[1] ** 2 + r[2] ** 2) for r in rows)
    if not abs(det) > 1e-9 * scale:
        return Status.SINGULAR, _NAN3
    r0, r1, r2 = rhs
    vx = (r0 * (e * i - f * h) - b * (r1 * i - f * r2) + c * (r1 * h - e * r2)) / det
    vy = (a * (r1 * i - f * r2) - r0 * (d * i - f * g) + c * (d * r2 - r1 * g)) / det
    vz = (a * (e * r2 - r1 * h) - b * (d * r2 - r1 * g) + r0 * (d * h - e * g)) / det
    return Status.OK, (vx, vy, vz)


def joint_velocity_point(params: Delta3Params, angles: Vec3, tcp_vel: Vec3) -> tuple[Status, Vec3]:
    """ACS velocities (deg/s) that move the TCP at `tcp_vel` (mm/s): q̇ᵢ = (p − Sᵢ)·ṗ / Jq,i (§12.5)."""
    st, p = forward_point(params, *angles)
    if st != Status.OK:
        return st, _NAN3
    if not all(math.isfinite(v) for v in tcp_vel):
        return Status.NOT_FINITE, _NAN3
    rows, jq = _velocity_terms(params, angles, p)
    scale = params.Lf * params.Lm * (math.pi / 180.0)
    if any(abs(v) <= 1e-12 * scale for v in jq):
        return Status.SINGULAR, _NAN3
    out = [(r[0] * tcp_vel[0] + r[1] * tcp_vel[1] + r[2] * tcp_vel[2]) / jq[k] for k, r in enumerate(rows)]
    return Status.OK, (out[0], out[1], out[2])


def _velocity_terms(params: Delta3Params, angles: Vec3, p: Vec3) -> tuple[list[Vec3], list[float]]:
    """Rows p − Sᵢ and Jq,i = (p − Sᵢ)·∂Sᵢ/∂qᵢ per degree, in the motor-plane frame."""
    pbx, pby, pbz = p[0], p[1], p[2] + params.Z0
    rows: list[Vec3] = []
    jq: list[float] = []
    Lf = params.Lf
    for (c, s), a in zip(params.cs_phi, angles, strict=True):
        qi = math.radians(a)
        cqi, sqi = math.cos(qi), math.sin(qi)
        rho = (params.Rf - params.Rm) + Lf * cqi
        row = (pbx - rho * c, pby - rho * s, pbz + Lf * sqi)
        rows.append(row)
        jq.append((row[0] * (-Lf * sqi * c) + row[1] * (-Lf * sqi * s) + row[2] * (-Lf * cqi)) * (math.pi / 180.0))
    return rows, jq


def signed_distance_point(ws: Delta3Workspace, x: float, y: float, z: float) -> float:
    """`Delta3Workspace.signed_distance` for one point (mm; positive inside, NaN if not finite)."""
    if not (math.isfinite(x) and math.isfinite(y) and math.isfinite(z)):
        return math.nan
    r = math.hypot(x, y)
    best = math.inf
    prof = ws.profile()
    for (ra, za), (rb, zb) in itertools.pairwise(prof):
        dr, dz = rb - ra, zb - za
        length2 = dr * dr + dz * dz
        t = 0.0 if length2 == 0.0 else min(1.0, max(0.0, ((r - ra) * dr + (z - za) * dz) / length2))
        er, ez = r - (ra + t * dr), z - (za + t * dz)
        best = min(best, er * er + ez * ez)
    dist = math.sqrt(best)
    zc = ws.z_cylinder_bottom
    r_max = ws.Rcy  # cylinder part
    if z < zc:  # cone part (below zc only when Hco > 0, else z < z_bottom fails anyway)
        r_max = ws.Rcy + (ws.Rco - ws.Rcy) * (zc - z) / ws.Hco if ws.Hco > 0 else -math.inf
    inside = ws.z_bottom <= z <= ws.Zu and r <= r_max
    return dist if inside else -dist


def contains_point(ws: Delta3Workspace, x: float, y: float, z: float) -> bool:
    """`Delta3Workspace.contains` for one point: inside and ≥ margin (0.1 mm) from the surface."""
    d = signed_distance_point(ws, x, y, z)
    return d >= ws.margin - TOLERANCE_MM  # False for NaN
