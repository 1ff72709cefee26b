"""MC_GenerateCamTable: cam property + cam nodes → cam data, or the manual's error (`omron-group-and-cam.md` §5.4).

`plan()` checks and rounds the inputs and resolves the connecting conditions into a `CamProfile` (one `CamSegment`
per valid node); `generate()` samples it into REAL cam data for a table of a given size; `generate_into()` writes
the result into a `CamTable` as the instruction does (element 0 := (0, 0), the points, Phase 0 after the end point
when there is room, EndPointIndex; on error the table keeps its data, except after 5742). All sampling is vectorised
over every point of every segment at once (one pass per curve type present), so 65,535 points take a few
milliseconds.

Rules as implemented (decisions D34, D37):
* check order: 573E (node array longer than 359 elements), 573C (InitVel, InitAcc, CycleTime), 573F, then node by
  node in index order: 573D (Phase, Distance, Curve, ConnectingVel, ConnectingAcc, PhasePitch) and 5740, then 5741
  (at the node whose points overflow the table), then 5742 while sampling;
* a REAL input is out of range when it is not finite, or non-zero with |x| < 0.001 (CycleTime, PhasePitch: < 0.001);
  values that pass are rounded half up to 3 decimals, and Phase/Distance then truncated to 7 significant digits
  (on the decimal the REAL stands for, its shortest repr: 359.9 stays 359.9);
* members the instruction ignores are not checked: Distance of `_mcConstantLine`, ConnectingVel/ConnectingAcc whose
  enable flag is FALSE;
* the quintic's A_init from a previous quintic follows ConnectingAccEnable (the source prints ConnectingVelEnable,
  taken as a typo, D34).
"""

from __future__ import annotations

import decimal
import functools
import math
from collections.abc import Sequence
from dataclasses import dataclass
from decimal import ROUND_DOWN, ROUND_HALF_UP, Decimal

import numpy as np

from .curves import LAWS, POLYNOMIAL_CURVES, _eMC_CAM_CURVE, poly3_coefficients, poly5_coefficients
from .table import MAX_POINTS, REAL, CamTable

__all__ = [
    "MAX_NODE_ELEMENTS",
    "CamProfile",
    "CamSegment",
    "GenerateError",
    "GenerateResult",
    "_sMC_CAM_NODE",
    "_sMC_CAM_PROPERTY",
    "generate",
    "generate_into",
    "plan",
    "sample_segments",
    "table_points",
]

MAX_NODE_ELEMENTS = 359  # user-defined CamNodes: ARRAY[0..N] with N ≤ 358 (§5.4, seed 000 line 17821)
_C = _eMC_CAM_CURVE
_REAL_MAX = float(np.finfo(REAL).max)
_CTX = decimal.Context(prec=80)  # REAL spans 1e±38: quantizing to 0.001 needs ~42 digits

# ErrorParameterCode values (appendix A-2, seed 000 lines 21082–21110)
PROPERTY_CODES = {"InitVel": 0x0000, "InitAcc": 0x0001, "CycleTime": 0x0002}
NODE_CODES = {"Phase": 0x0000, "Distance": 0x0001, "Curve": 0x0002, "ConnectingVel": 0x0003,
              "ConnectingAcc": 0x0004, "PhasePitch": 0x0005}


@dataclass
class _sMC_CAM_PROPERTY:
    """Cam property (§5.4.1): initial velocity [units/s] and acceleration [units/s²], cycle time [s]."""

    InitVel: float = 0.0
    InitAcc: float = 0.0
    CycleTime: float = 0.0


@dataclass
class _sMC_CAM_NODE:
    """One cam node (§5.4.2): the end point of one curve segment. `Curve` is an int so that out-of-range values can
    be passed (they give 573D with ErrorParameterCode 16#0002)."""

    Phase: float = 0.0
    Distance: float = 0.0
    Curve: int = 0
    ConnectingVelEnable: bool = False
    ConnectingVel: float = 0.0
    ConnectingAccEnable: bool = False
    ConnectingAcc: float = 0.0
    PhasePitch: float = 0.0


@dataclass(frozen=True)
class GenerateError:
    """ErrorID with its ErrorParameterCode and ErrorNodePointIndex (0 where the error has none)."""

    ErrorID: int
    ErrorParameterCode: int = 0
    ErrorNodePointIndex: int = 0
    message: str = ""


@dataclass(frozen=True)
class CamSegment:
    """One valid node m turned into a segment from (p0, d0) to (p1, d1), after rounding and truncation.

    `count` is the number of cam data it adds (N of §5.4.4), `first` the table index of its first one; T its
    duration [s] at the profile's master velocity. Polynomials carry `coeffs` b_i = h·a_i (i = 1…3 or 1…5) and the
    boundary values used [units/s, units/s²]."""

    node: int
    curve: _eMC_CAM_CURVE
    p0: float
    p1: float
    d0: float
    d1: float
    pitch: float
    count: int
    first: int
    T: float
    coeffs: np.ndarray | None = None
    v_init: float = 0.0
    v_fin: float = 0.0
    a_init: float = 0.0
    a_fin: float = 0.0

    @property
    def h(self) -> float:
        return self.d1 - self.d0

    @property
    def span(self) -> float:
        return self.p1 - self.p0


@dataclass(frozen=True)
class CamProfile:
    """The validated nodes as segments; `master_velocity` = P_max / CycleTime [master units/s] (§5.4.4)."""

    segments: tuple[CamSegment, ...]
    cycle_time: float
    p_max: float

    @property
    def master_velocity(self) -> float:
        return self.p_max / self.cycle_time

    @property
    def point_count(self) -> int:
        """Tcd: cam data the profile generates, the start point included."""
        return 1 + sum(s.count for s in self.segments)

    @functools.cached_property
    def arrays(self) -> dict[str, np.ndarray]:
        """The segments' values as arrays (one entry per segment), for vectorised sampling."""
        s = self.segments
        coeffs = np.zeros((len(s), 5))
        for k, seg in enumerate(s):
            if seg.coeffs is not None:
                coeffs[k, : seg.coeffs.size] = seg.coeffs
        return {
            "p0": np.array([g.p0 for g in s]), "p1": np.array([g.p1 for g in s]),
            "d0": np.array([g.d0 for g in s]), "d1": np.array([g.d1 for g in s]),
            "pitch": np.array([g.pitch for g in s]), "count": np.array([g.count for g in s], dtype=np.int64),
            "first": np.array([g.first for g in s], dtype=np.int64), "curve": np.array([int(g.curve) for g in s]),
            "coeffs": coeffs,
        }


@dataclass
class GenerateResult:
    """Outcome of a generation: REAL points (start point included) and EndPointIndex, or `error`.

    After 5742, `phase`/`distance` hold the points computed before the overflowing one (what the aborted instruction
    had written)."""

    phase: np.ndarray
    distance: np.ndarray
    end_point_index: int = 0
    error: GenerateError | None = None
    profile: CamProfile | None = None

    @property
    def ok(self) -> bool:
        return self.error is None


# --- REAL inputs: range, rounding, truncation -----------------------------------------------------------------

def _real(x: float) -> float | None:
    """The REAL a value becomes, or None when it is not a finite REAL."""
    try:
        v = float(x)
    except (TypeError, ValueError):
        return None
    if not math.isfinite(v) or abs(v) > _REAL_MAX:
        return None
    return float(np.float32(v))


def _decimal(v: float) -> Decimal:
    """The decimal a REAL stands for: its shortest round-trip representation (0.1f → 0.1)."""
    return Decimal(np.format_float_scientific(np.float32(v), unique=True))


def _round3(v: float) -> Decimal:
    """Rounded half up at the 4th decimal place (§5.4.1 *1)."""
    return _decimal(v).quantize(Decimal("0.001"), rounding=ROUND_HALF_UP, context=_CTX)


def _trunc7(d: Decimal) -> Decimal:
    """7 significant digits, the 8th and later dropped (§5.4.2 *2)."""
    if d == 0:
        return d
    return d.quantize(Decimal(1).scaleb(d.adjusted() - 6), rounding=ROUND_DOWN, context=_CTX)


def _in_range(v: float | None, *, positive: bool) -> bool:
    """abs ≥ 0.001 or 0 (positive: ≥ 0.001 only) on the REAL value, before rounding (D37)."""
    if v is None:
        return False
    if positive:
        return v >= 0.001
    return v == 0 or abs(v) >= 0.001


def _node_error(m: int, member: str, value: object, why: str) -> GenerateError:
    return GenerateError(0x573D, NODE_CODES[member], m, f"CamNodes[{m}].{member} = {value!r}: {why}")


def plan(nodes: Sequence[_sMC_CAM_NODE], prop: _sMC_CAM_PROPERTY) -> CamProfile | GenerateError:
    """Check and round the inputs, resolve the connecting conditions (§5.4.4): a `CamProfile`, or the error."""
    if len(nodes) > MAX_NODE_ELEMENTS:
        return GenerateError(0x573E, message=f"CamNodes has {len(nodes)} elements, at most {MAX_NODE_ELEMENTS}")
    pv: dict[str, float] = {}
    for name in ("InitVel", "InitAcc", "CycleTime"):
        raw = getattr(prop, name)
        v = _real(raw)
        if not _in_range(v, positive=name == "CycleTime"):
            return GenerateError(0x573C, PROPERTY_CODES[name], 0, f"CamProperty.{name} = {raw!r} is out of range")
        pv[name] = float(_round3(v))  # type: ignore[arg-type]
    if not nodes or _real(nodes[0].Phase) == 0:
        return GenerateError(0x573F, message="CamNodes[0].Phase is 0: no node to generate")

    # Node by node, in index order: range of each member, then ascending phases (after truncation).
    rows: list[tuple[int, _eMC_CAM_CURVE, Decimal, Decimal, Decimal, float, float]] = []
    prev_phase, prev_dist = Decimal(0), Decimal(0)
    for m, node in enumerate(nodes):
        phase = _real(node.Phase)
        if phase == 0:
            break  # the first Phase 0 ends the list; later elements are not looked at
        if not _in_range(phase, positive=True):
            return _node_error(m, "Phase", node.Phase, "must be 0 or ≥ 0.001")
        try:
            curve = _eMC_CAM_CURVE(int(node.Curve))
        except (TypeError, ValueError):
            curve = None
        dist = _real(node.Distance)
        if curve != _C._mcConstantLine and not _in_range(dist, positive=False):
            return _node_error(m, "Distance", node.Distance, "must be 0 or |x| ≥ 0.001")
        if curve is None:
            return _node_error(m, "Curve", node.Curve, "is not an _eMC_CAM_CURVE value (0–14)")
        vel = _real(node.ConnectingVel) if node.ConnectingVelEnable else 0.0
        if not _in_range(vel, positive=False):
            return _node_error(m, "ConnectingVel", node.ConnectingVel, "must be 0 or |x| ≥ 0.001")
        acc = _real(node.ConnectingAcc) if node.ConnectingAccEnable else 0.0
        if not _in_range(acc, positive=False):
            return _node_error(m, "ConnectingAcc", node.ConnectingAcc, "must be 0 or |x| ≥ 0.001")
        pitch = _real(node.PhasePitch)
        if not _in_range(pitch, positive=True):
            return _node_error(m, "PhasePitch", node.PhasePitch, "must be ≥ 0.001")
        p = _trunc7(_round3(phase))  # type: ignore[arg-type]
        if p <= prev_phase:
            return GenerateError(0x5740, 0, m, f"CamNodes[{m}].Phase = {node.Phase!r} (taken as {p}) is not "
                                               f"above the previous phase {prev_phase}")
        d = prev_dist if curve == _C._mcConstantLine else _trunc7(_round3(dist))  # type: ignore[arg-type]
        rows.append((m, curve, p, d, _round3(pitch), float(_round3(vel)), float(_round3(acc))))  # type: ignore
        prev_phase, prev_dist = p, d

    p_max = float(rows[-1][2])
    cycle = pv["CycleTime"]
    speed = p_max / cycle  # master velocity [units/s]
    segs: list[CamSegment] = []
    first = 1
    p0 = d0 = Decimal(0)
    spans = [(r[2] - (rows[i - 1][2] if i else Decimal(0)), r[3] - (rows[i - 1][3] if i else Decimal(0)))
             for i, r in enumerate(rows)]

    def line_velocity(i: int) -> float:
        """Slope of straight-line node i converted to time: Δd/ΔP · P_max/CycleTime."""
        return float(spans[i][1]) / float(spans[i][0]) * speed

    for i, (m, curve, p, d, pitch, vel, acc) in enumerate(rows):
        q = _CTX.divide(p - p0, pitch)
        count = int(q) if q == q.to_integral_value() else int(q) + 1
        span = float(p - p0)
        T = cycle * span / p_max
        coeffs = None
        vi = vf = ai = af = 0.0
        if curve in POLYNOMIAL_CURVES:
            prev = rows[i - 1] if i else None
            nxt = rows[i + 1] if i + 1 < len(rows) else None
            if prev is None:
                vi = pv["InitVel"]
            elif prev[1] == _C._mcStraightLine:
                vi = line_velocity(i - 1)
            elif prev[1] in POLYNOMIAL_CURVES and nodes[prev[0]].ConnectingVelEnable:
                vi = prev[5]
            if nodes[m].ConnectingVelEnable:
                vf = vel
            elif nxt is not None and nxt[1] == _C._mcStraightLine:
                vf = line_velocity(i + 1)
            if curve == _C._mcPolynomic5:
                if prev is None:
                    ai = pv["InitAcc"]
                elif prev[1] == _C._mcPolynomic5 and nodes[prev[0]].ConnectingAccEnable:
                    ai = prev[6]
                af = acc if nodes[m].ConnectingAccEnable else 0.0
            h = float(d - d0)
            coeffs = (poly3_coefficients(h, vi * T, vf * T) if curve == _C._mcPolynomic3
                      else poly5_coefficients(h, vi * T, vf * T, ai * T * T, af * T * T))
        segs.append(CamSegment(node=m, curve=curve, p0=float(p0), p1=float(p), d0=float(d0), d1=float(d),
                               pitch=float(pitch), count=count, first=first, T=T, coeffs=coeffs,
                               v_init=vi, v_fin=vf, a_init=ai, a_fin=af))
        first += count
        p0, d0 = p, d
    return CamProfile(segments=tuple(segs), cycle_time=cycle, p_max=p_max)


# --- sampling -------------------------------------------------------------------------------------------------

def sample_segments(profile: CamProfile, seg: np.ndarray, x: np.ndarray, order: int = 0) -> np.ndarray:
    """h·f^(order)(x) of each point's segment [command units per unit x^order] (order 0: distance − d0).

    `seg` indexes `profile.segments`, x ∈ [0, 1] is the position inside it; vectorised over all points, one pass
    per curve type present."""
    arr = profile.arrays
    h = (arr["d1"] - arr["d0"])[seg]
    curve = arr["curve"][seg]
    out = np.zeros(x.shape)
    for c in np.unique(curve):
        mask = curve == c
        cc = _eMC_CAM_CURVE(int(c))
        if cc == _C._mcConstantLine:
            continue
        if cc in POLYNOMIAL_CURVES:
            b = arr["coeffs"][seg[mask]]
            xm = x[mask]
            acc = np.zeros(xm.shape)
            for i in range(5, order - 1, -1):  # Horner on the order-th derivative of Σ b_i x^i
                acc = acc * xm + (b[:, i - 1] * math.perm(i, order) if i >= 1 else 0.0)
            out[mask] = acc
        elif cc == _C._mcStraightLine:
            out[mask] = h[mask] * (x[mask] if order == 0 else (1.0 if order == 1 else 0.0))
        else:
            out[mask] = h[mask] * LAWS[cc](x[mask], order)
    return out


def table_points(profile: CamProfile) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Per generated point (table index 1 … Tcd−1): its segment, its phase (float64) and its x."""
    arr = profile.arrays
    total = profile.point_count - 1
    seg = np.repeat(np.arange(len(profile.segments)), arr["count"])
    n = np.arange(1, total + 1) - arr["first"][seg] + 1  # 1 … N within the segment
    last = n == arr["count"][seg]
    phase = np.where(last, arr["p1"][seg], arr["p0"][seg] + n * arr["pitch"][seg])
    x = np.where(last, 1.0, n * arr["pitch"][seg] / (arr["p1"] - arr["p0"])[seg])
    return seg, phase, x


def generate(nodes: Sequence[_sMC_CAM_NODE], prop: _sMC_CAM_PROPERTY, *, table_size: int) -> GenerateResult:
    """Cam data for a table of `table_size` elements (§5.4.4): REAL phase/distance of Tcd points, or the error."""
    empty = np.zeros(0, dtype=REAL)
    profile = plan(nodes, prop)
    if isinstance(profile, GenerateError):
        return GenerateResult(empty, empty, error=profile)
    limit = min(table_size, MAX_POINTS)
    total = 1
    for s in profile.segments:
        total += s.count
        if total > limit:
            return GenerateResult(empty, empty, profile=profile, error=GenerateError(
                0x5741, 0, s.node, f"CamNodes[{s.node}] brings the cam data to {total}: the table holds "
                                   f"{table_size} (at most {MAX_POINTS})"))
    seg, phase, x = table_points(profile)
    arr = profile.arrays
    dist = arr["d0"][seg] + sample_segments(profile, seg, x)
    dist[x == 1.0] = arr["d1"][seg][x == 1.0]  # Distance(N) = d_final exactly
    with np.errstate(over="ignore", invalid="ignore"):
        dist32 = dist.astype(REAL)
    phase32 = np.concatenate([[0.0], phase]).astype(REAL)
    dist32 = np.concatenate([np.zeros(1, dtype=REAL), dist32])
    bad = np.flatnonzero(~np.isfinite(dist32))
    if bad.size:
        k = int(bad[0])
        node = profile.segments[int(seg[k - 1])].node
        return GenerateResult(phase32[:k], dist32[:k], profile=profile, error=GenerateError(
            0x5742, 0, node, f"Distance of cam data {k} (CamNodes[{node}]) exceeds REAL"))
    return GenerateResult(phase32, dist32, end_point_index=total - 1, profile=profile)


def generate_into(table: CamTable, nodes: Sequence[_sMC_CAM_NODE], prop: _sMC_CAM_PROPERTY) -> GenerateResult:
    """MC_GenerateCamTable on a cam data variable (§5.4.4, §5.4.5).

    Success: elements 0 … Tcd−1 are overwritten, the next element's Phase (only) is set to 0 when the table has one,
    EndPointIndex = Tcd − 1 is put in force and the error state is cleared. Error: the table keeps its data, except
    after 5742, where the points computed before the overflow are written and the table enters the error state in
    which MC_CamIn, MC_SaveCamTable and MC_SetCamTableProperty give 5743."""
    result = generate(nodes, prop, table_size=table.max_data_number)
    n = result.phase.size
    if result.ok:
        table.phase[:n] = result.phase
        table.distance[:n] = result.distance
        if n < table.max_data_number:
            table.phase[n] = 0.0
        table.end_point_index = result.end_point_index
        table.generation_aborted = False
    elif result.error is not None and result.error.ErrorID == 0x5742:
        table.phase[:n] = result.phase
        table.distance[:n] = result.distance
        table.generation_aborted = True
    return result
