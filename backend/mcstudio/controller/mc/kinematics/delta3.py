"""Delta3 kinematics, vectorised over arrays of points (`omron-robot-delta3.md` §12; the manual gives no formulas).

Conventions (§12.1, decisions D30.1–D30.3): MCS with Z up, origin at the TCP when A0 = A1 = A2 = 0 (zero pose);
arm i at azimuth φᵢ = (0°, 120°, 240°)ᵢ + θ counter-clockwise from +Xm; Aᵢ = 0° with the upper arm horizontal and
pointing outward, positive = arm swings down; inverse kinematics takes the elbow-out root, forward kinematics the
lower of the two sphere intersections. Angles in degrees, lengths in mm, the ACS range is [−180°, 180°).

Every function takes (..., 3) arrays and returns arrays of the same leading shape plus a per-point `Status`
(`codes.py`); bad input (NaN, ±inf, unreachable points) is a status, never an exception."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .codes import E_KIN_CALC, E_NONE, Status, WorkspaceCheck
from .params import Delta3Params
from .workspace import Delta3Workspace

F64 = NDArray[np.float64]
# A point the inverse solves must lie on the robot's branch: FK picks the lower sphere intersection, so the TCP
# may be at most this far (mm) above the plane of the three sphere centres (round-off only; §12.4, D30.3).
BRANCH_TOLERANCE_MM = 1e-9
# Forward kinematics: two sphere centres closer than this (mm), or three nearly collinear, have no unique solution.
DEGENERATE_MM = 1e-9
# Bad input must come out as a status, never as a FloatingPointError/RuntimeWarning (whatever np.seterr says).
_QUIET = np.errstate(all="ignore")
CHUNK = 8192  # points per vectorised block (temporaries of 64 KB stay in the L2 cache)


@dataclass(frozen=True, slots=True)
class InverseResult:
    """`angles` (..., 3) in degrees, NaN where not reachable; `reachable` and `inside` (...) bool (`inside` is
    True where no workspace was given); `status` (...) int8 `Status`; `error_id` (...) uint16 — the ErrorID the
    caller raises (0, 570F, or the code of the workspace check it asked for)."""

    angles: F64
    reachable: NDArray[np.bool_]
    inside: NDArray[np.bool_]
    status: NDArray[np.int8]
    error_id: NDArray[np.uint16]

    @property
    def ok(self) -> bool:
        return bool(np.all(self.status == Status.OK))


@dataclass(frozen=True, slots=True)
class ForwardResult:
    """`position` (..., 3) TCP in the MCS (mm), NaN where not solvable; `status` (...) int8; `error_id` (...)
    uint16 (0 or 570F; the MC layer uses 571F instead when MC_SetKinTransform finds the axes there)."""

    position: F64
    status: NDArray[np.int8]
    error_id: NDArray[np.uint16]

    @property
    def ok(self) -> bool:
        return bool(np.all(self.status == Status.OK))


def _as_points(a: ArrayLike) -> F64:
    p = np.asarray(a, dtype=np.float64)
    if p.ndim == 0 or p.shape[-1] != 3:
        raise ValueError(f"expected an array of shape (..., 3), got {p.shape}")  # a programming error, not input
    return p


@_QUIET
def inverse(params: Delta3Params, xyz: ArrayLike, *, workspace: Delta3Workspace | None = None,
            check: WorkspaceCheck | None = None) -> InverseResult:
    """MCS TCP positions (..., 3) mm → ACS angles A0, A1, A2 (..., 3) deg (§12.3, elbow-out root).

    With `workspace`, points outside its 0.1 mm-shrunk region get `Status.OUTSIDE_WORKSPACE` (their angles are
    still computed if reachable: MC_InverseKin outputs them with OutWorkspace, §9.7) and `error_id` = the code of
    `check` (0 without a check: OutWorkspace is no error). Order per point (§9.4's per-period algorithm):
    non-finite → 570F; outside the workspace → the check's code; unreachable → 570F."""
    p = _as_points(xyz)
    shape = p.shape[:-1]
    flat = p.reshape(-1, 3)
    n = flat.shape[0]
    q = np.empty((3, n))
    reachable = np.empty(n, dtype=bool)
    # Chunks keep every temporary in the cache (and avoid page faults on fresh 24 MB arrays): about 3× faster.
    for k in range(0, n, CHUNK):
        sl = slice(k, min(n, k + CHUNK))
        reachable[sl] = _inverse_chunk(params, flat[sl, 0], flat[sl, 1], flat[sl, 2], q[:, sl])
    angles = np.degrees(q.T).reshape(*shape, 3)
    reachable = reachable.reshape(shape)
    finite = np.all(np.isfinite(p), axis=-1)
    reachable &= finite
    angles[~reachable] = np.nan
    inside = workspace.contains(p) if workspace is not None else np.ones(shape, dtype=bool)
    status = np.where(reachable, Status.OK, Status.UNREACHABLE).astype(np.int8)
    status[~inside] = Status.OUTSIDE_WORKSPACE
    status[~finite] = Status.NOT_FINITE
    error_id = np.where(status == Status.OK, E_NONE, E_KIN_CALC).astype(np.uint16)
    error_id[status == Status.OUTSIDE_WORKSPACE] = check.error_id if check is not None else E_NONE
    return InverseResult(angles=angles, reachable=reachable, inside=inside, status=status, error_id=error_id)


def _inverse_chunk(params: Delta3Params, x: F64, y: F64, z: F64, q_out: F64) -> NDArray[np.bool_]:
    """Elbow-out angles (rad) of 1-D point arrays into q_out (3, n); returns which points are reachable.

    Per arm: A·cos q + zb·sin q = C (§12.3) with A = R·cos γ, zb = R·sin γ; the root q = γ + α, cos α = C/R, gives
    cos q = (A·C − zb·D)/R² and sin q = (zb·C + A·D)/R², D = √(R² − C²) — one atan2 instead of atan2 + acos, and
    cos q / sin q for the branch check without further trigonometry."""
    Rf, Lf, Rm, Lm = params.Rf, params.Lf, params.Rm, params.Lm
    zb = z + params.Z0  # motor-plane frame (§12.2)
    zb2 = zb * zb
    k0 = Lm * Lm - Lf * Lf
    reachable = zb < 0.0  # elbow-out is the outer root only below the motor plane; the robot hangs there
    cq = np.empty((3, x.shape[0]))
    sq = np.empty((3, x.shape[0]))
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        for i, (c, s) in enumerate(zip(params.cos_phi, params.sin_phi, strict=True)):
            A = (Rf - Rm) - (x * c + y * s)  # Rf − Rm − radial coordinate of the TCP in arm i's plane
            yi = y * c - x * s  # out-of-plane coordinate
            R2 = A * A + zb2
            C = (k0 - R2 - yi * yi) * (0.5 / Lf)
            D2 = R2 - C * C
            reachable &= (R2 > 0.0) & (D2 >= 0.0)
            D = np.sqrt(np.maximum(D2, 0.0))
            cq[i] = (A * C - zb * D) / R2
            sq[i] = (zb * C + A * D) / R2
            q_out[i] = np.arctan2(sq[i], cq[i])
        np.copyto(q_out, -np.pi, where=q_out >= np.pi)  # ACS range [−180°, 180°)
        reachable &= _on_lower_branch(params, cq, sq, x, y, zb)
    return reachable


def _sphere_centres(params: Delta3Params, q_rad: F64) -> tuple[F64, F64, F64]:
    """Sᵢ = (Rf − Rm + Lf·cos qᵢ)·uᵢ − Lf·sin qᵢ·ẑ in the motor-plane frame, as x, y, z arrays (..., 3 arms)."""
    rho = (params.Rf - params.Rm) + params.Lf * np.cos(q_rad)
    phi = params.azimuths_rad
    return rho * np.cos(phi), rho * np.sin(phi), -params.Lf * np.sin(q_rad)


def _on_lower_branch(params: Delta3Params, cq: F64, sq: F64, x: F64, y: F64, zb: F64) -> NDArray[np.bool_]:
    """True where the TCP (motor-plane frame) is the lower intersection of the three spheres for arm angles with
    cosines/sines cq, sq (3, n), i.e. what `forward` returns for them: not above the plane through the sphere
    centres oriented by its upward normal."""
    rho = (params.Rf - params.Rm) + params.Lf * cq
    sx = rho * params.cos_phi[:, None]
    sy = rho * params.sin_phi[:, None]
    sz = -params.Lf * sq
    ax, ay, az = sx[1] - sx[0], sy[1] - sy[0], sz[1] - sz[0]
    bx, by, bz = sx[2] - sx[0], sy[2] - sy[0], sz[2] - sz[0]
    nx, ny, nz = ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx
    norm = np.sqrt(nx * nx + ny * ny + nz * nz)
    height = ((x - sx[0]) * nx + (y - sy[0]) * ny + (zb - sz[0]) * nz) / norm
    # forward() takes base − h·ez when ez points up (or is horizontal), base + h·ez when it points down.
    return np.where(nz >= 0.0, height, -height) <= BRANCH_TOLERANCE_MM


@_QUIET
def forward(params: Delta3Params, angles: ArrayLike) -> ForwardResult:
    """ACS angles (..., 3) deg → MCS TCP positions (..., 3) mm: intersection of the three spheres of radius Lm
    around the shifted elbows, lower solution (§12.4)."""
    a = _as_points(angles)
    shape = a.shape[:-1]
    flat = a.reshape(-1, 3)
    n = flat.shape[0]
    pos = np.empty((n, 3))
    solvable = np.empty(n, dtype=bool)
    for k in range(0, n, CHUNK):
        sl = slice(k, min(n, k + CHUNK))
        solvable[sl] = _forward_chunk(params, np.radians(flat[sl].T), pos[sl])
    pos = pos.reshape(*shape, 3)
    solvable = solvable.reshape(shape)
    finite = np.all(np.isfinite(a), axis=-1)
    solvable &= finite & np.all(np.isfinite(pos), axis=-1)
    pos[~solvable] = np.nan
    status = np.where(solvable, Status.OK, Status.UNREACHABLE).astype(np.int8)
    status[~finite] = Status.NOT_FINITE
    error_id = np.where(solvable, E_NONE, E_KIN_CALC).astype(np.uint16)
    return ForwardResult(position=pos, status=status, error_id=error_id)


def _forward_chunk(params: Delta3Params, q: F64, out: F64) -> NDArray[np.bool_]:
    """Trilateration (§12.4) of angles q (3, n) rad into out (n, 3) MCS mm; returns where it has a solution."""
    Lm = params.Lm
    rho = (params.Rf - params.Rm) + params.Lf * np.cos(q)
    sx = rho * params.cos_phi[:, None]
    sy = rho * params.sin_phi[:, None]
    sz = -params.Lf * np.sin(q)
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        ux, uy, uz = sx[1] - sx[0], sy[1] - sy[0], sz[1] - sz[0]  # S2 − S1
        vx, vy, vz = sx[2] - sx[0], sy[2] - sy[0], sz[2] - sz[0]  # S3 − S1
        d = np.sqrt(ux * ux + uy * uy + uz * uz)
        exx, exy, exz = ux / d, uy / d, uz / d
        i = exx * vx + exy * vy + exz * vz
        wx, wy, wz = vx - i * exx, vy - i * exy, vz - i * exz
        j = np.sqrt(wx * wx + wy * wy + wz * wz)
        eyx, eyy, eyz = wx / j, wy / j, wz / j
        ezx, ezy, ezz = exy * eyz - exz * eyy, exz * eyx - exx * eyz, exx * eyy - exy * eyx
        X = 0.5 * d  # equal radii
        Y = (i * i + j * j) / (2.0 * j) - (i / j) * X
        Z2 = Lm * Lm - X * X - Y * Y
        # Z² a hair below 0 is a tangency lost to round-off (forearms coplanar); clearly below 0: no solution.
        solvable = (d > DEGENERATE_MM) & (j > DEGENERATE_MM) & (Z2 + 1e-12 * Lm * Lm >= 0.0)
        h = np.sqrt(np.maximum(Z2, 0.0))
        h = np.where(ezz >= 0.0, -h, h)  # the lower intersection
        out[:, 0] = sx[0] + X * exx + Y * eyx + h * ezx
        out[:, 1] = sy[0] + X * exy + Y * eyy + h * ezy
        out[:, 2] = sz[0] + X * exz + Y * eyz + h * ezz - params.Z0
    return solvable


@dataclass(frozen=True, slots=True)
class ArmGeometry:
    """Points of the mechanism in the MCS (mm), for the 3-D view (§12.8). Arm axis = A0, A1, A2.

    `shoulders` (..., 3, 3): motor joints Mᵢ; `elbows` (..., 3, 3): Eᵢ; `wrists` (..., 3, 3): forearm joints on the
    moving frame Wᵢ = TCP + Rm·uᵢ; `tcp` (..., 3); `rods` (..., 3 arms, 2 rods, 2 ends (elbow, wrist), 3): the two
    parallel rods of each forearm parallelogram, `rod_spacing` apart along the motor axis tᵢ (cosmetic; the
    kinematics only use Lm). Shoulders and elbows follow from the angles alone and are finite even where the TCP
    cannot be solved (then `tcp`, `wrists`, `rods` are NaN and `status` says why)."""

    shoulders: F64
    elbows: F64
    wrists: F64
    tcp: F64
    rods: F64
    status: NDArray[np.int8]
    motor_plane_z: float


@_QUIET
def arm_geometry(params: Delta3Params, angles: ArrayLike, *, rod_spacing: float = 0.0) -> ArmGeometry:
    """Shoulder, elbow, wrist and forearm-rod end points for ACS angles (..., 3) deg, in the MCS (§12.2, §12.8)."""
    a = _as_points(angles)
    q = np.radians(a)[..., None]  # (..., 3 arms, 1)
    u = params.radial  # (3, 3)
    t = params.tangential
    z_hat = np.array([0.0, 0.0, 1.0])
    base = np.array([0.0, 0.0, params.motor_plane_z])  # motor-plane centre in the MCS
    shoulders = np.broadcast_to(base + params.Rf * u, (*a.shape[:-1], 3, 3)).copy()
    elbows = base + (params.Rf + params.Lf * np.cos(q)) * u - (params.Lf * np.sin(q)) * z_hat
    fk = forward(params, a)
    tcp = fk.position
    wrists = tcp[..., None, :] + params.Rm * u
    half = 0.5 * rod_spacing * t  # (3 arms, 3)
    ends = np.stack([elbows, wrists], axis=-2)  # (..., 3 arms, 2 ends, 3)
    rods = np.stack([ends + half[:, None, :], ends - half[:, None, :]], axis=-3)  # (..., 3, 2 rods, 2 ends, 3)
    return ArmGeometry(shoulders=shoulders, elbows=elbows, wrists=wrists, tcp=tcp, rods=rods, status=fk.status,
                       motor_plane_z=params.motor_plane_z)


@_QUIET
def jacobian(params: Delta3Params, angles: ArrayLike) -> tuple[F64, NDArray[np.int8]]:
    """J (..., 3, 3) with ṗ = J·q̇, ṗ in mm/s and q̇ in deg/s, at ACS angles (..., 3) deg (§12.5).

    From |p − Sᵢ(qᵢ)|² = Lm²: Jx·ṗ = diag(Jq)·q̇ with Jx rows (p − Sᵢ)ᵀ and Jq,i = (p − Sᵢ)·∂Sᵢ/∂qᵢ. Where Jx is
    singular (forearms coplanar) J is NaN and the status `SINGULAR`; where FK fails, its status."""
    a = _as_points(angles)
    rows, jq, status = _velocity_terms(params, a)
    with np.errstate(invalid="ignore", over="ignore"):
        det = np.linalg.det(rows)
        scale = np.prod(np.linalg.norm(rows, axis=-1), axis=-1)
        regular = np.abs(det) > 1e-9 * scale
    status[(status == Status.OK) & ~regular] = Status.SINGULAR
    good = status == Status.OK
    # Solve Jx·J = diag(Jq) for every point at once; points that are not OK get an identity stand-in (then NaN).
    Jx = np.where(good[..., None, None], rows, np.eye(3))
    J = np.linalg.solve(Jx, np.where(good[..., None], jq, 0.0)[..., None] * np.eye(3))
    J[~good] = np.nan
    return J, status


def _velocity_terms(params: Delta3Params, a: F64) -> tuple[F64, F64, NDArray[np.int8]]:
    """Rows p − Sᵢ (..., 3 arms, 3) and Jq (..., 3) per degree, with the FK status."""
    fk = forward(params, a)
    q = np.radians(a)
    sx, sy, sz = _sphere_centres(params, q)
    pb = fk.position + np.array([0.0, 0.0, params.Z0])  # motor-plane frame, as the centres
    rows = pb[..., None, :] - np.stack([sx, sy, sz], axis=-1)
    jq = np.sum(rows * _dS(params, q), axis=-1) * (math.pi / 180.0)
    return rows, jq, fk.status.copy()


def _dS(params: Delta3Params, q_rad: F64) -> F64:
    """∂Sᵢ/∂qᵢ per radian, (..., 3 arms, 3): (−Lf·sin qᵢ·cos φᵢ, −Lf·sin qᵢ·sin φᵢ, −Lf·cos qᵢ)."""
    phi = params.azimuths_rad
    sq = np.sin(q_rad)
    return np.stack([-params.Lf * sq * np.cos(phi), -params.Lf * sq * np.sin(phi), -params.Lf * np.cos(q_rad)],
                    axis=-1)


@_QUIET
def tcp_velocity(params: Delta3Params, angles: ArrayLike, joint_velocity: ArrayLike) -> tuple[F64, NDArray[np.int8]]:
    """TCP velocity (..., 3) mm/s in the MCS from ACS angles (deg) and their velocities (deg/s), for MC_GroupMon's
    ActualVelocity (§9.3, §12.5). NaN where the status is not OK."""
    J, status = jacobian(params, angles)
    qd = np.asarray(joint_velocity, dtype=np.float64)
    v = np.einsum("...ij,...j->...i", J, qd)
    bad = ~np.all(np.isfinite(qd), axis=-1)
    status = np.where(bad & (status == Status.OK), np.int8(Status.NOT_FINITE), status).astype(np.int8)
    v[status != Status.OK] = np.nan
    return v, status


@_QUIET
def joint_velocity(params: Delta3Params, angles: ArrayLike, tcp_vel: ArrayLike) -> tuple[F64, NDArray[np.int8]]:
    """ACS velocities (..., 3) deg/s that move the TCP at `tcp_vel` (mm/s, MCS) from the given angles:
    q̇ᵢ = (p − Sᵢ)·ṗ / Jq,i (§12.5). NaN (status SINGULAR) where an arm cannot move the TCP (Jq,i = 0)."""
    a = _as_points(angles)
    rows, jq, status = _velocity_terms(params, a)
    v = np.asarray(tcp_vel, dtype=np.float64)
    with np.errstate(invalid="ignore", divide="ignore"):
        qd = np.sum(rows * v[..., None, :], axis=-1) / jq
    scale = params.Lf * params.Lm * (math.pi / 180.0)
    singular = (status == Status.OK) & np.any(np.abs(jq) <= 1e-12 * scale, axis=-1)
    status[singular] = Status.SINGULAR
    status[(status == Status.OK) & ~np.all(np.isfinite(v), axis=-1)] = Status.NOT_FINITE
    qd[status != Status.OK] = np.nan
    return qd, status
