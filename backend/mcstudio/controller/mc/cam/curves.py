"""Normalised cam motion laws of `_eMC_CAM_CURVE`: f(x), f'(x), f''(x), f'''(x) on x ∈ [0, 1], vectorised.

A segment of a cam profile runs from (P_init, d_init) to (P_final, d_final); with x = (P − P_init)/(P_final −
P_init) its distance is d_init + (d_final − d_init)·f(x), f(0) = 0, f(1) = 1 (`omron-group-and-cam.md` §5.4.4).
The manual defines only the straight line, the dwell and the two polynomials (§5.4.4); every other shape is the
standard law of cam-design literature (Makino's standard curves, as tabulated by Japanese cam makers), chosen and
cited in docs/cams.md and decisions D31–D33.

Every fixed law is stored as pieces of "harmonic acceleration": on piece k (u = x − x_k)

    A(u) = c_k + Σ_t s_kt·sin(ω_kt·u + φ_kt)

which covers constant, sine, cosine and sums of harmonics, and integrates in closed form; the integration
constants (V and F at each piece start) and the scale that makes f(1) = 1 are computed once at import. Evaluation
is one `searchsorted` plus a handful of vector operations, so a 65,535-point segment costs well under a millisecond.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from ..enums import _eMC_CAM_CURVE

__all__ = [
    "LAWS",
    "POLYNOMIAL_CURVES",
    "CurveCharacteristics",
    "HarmonicLaw",
    "MirroredLaw",
    "_eMC_CAM_CURVE",
    "characteristics",
    "evaluate",
    "poly3_coefficients",
    "poly5_coefficients",
    "polynomial_characteristics",
    "polynomial_derivatives",
]

PI = math.pi
POLYNOMIAL_CURVES = frozenset({_eMC_CAM_CURVE._mcPolynomic3, _eMC_CAM_CURVE._mcPolynomic5})

# A piece term: (amplitude s, angular frequency ω, phase φ) of s·sin(ω·u + φ).
Term = tuple[float, float, float]


@dataclass(frozen=True)
class Piece:
    """One piece of an acceleration law: starts at x0, constant part c, harmonic terms (s, ω, φ)."""

    x0: float
    c: float = 0.0
    terms: tuple[Term, ...] = ()


class HarmonicLaw:
    """A normalised law given by its acceleration pieces (see the module docstring); scaled so that f(1) = 1."""

    def __init__(self, name: str, pieces: Sequence[Piece], *, v0: float = 0.0, normalise: bool = True) -> None:
        self.name = name
        k = len(pieces)
        t = max(1, max(len(p.terms) for p in pieces))
        self.breaks = np.array([p.x0 for p in pieces] + [1.0])
        self.c = np.array([p.c for p in pieces], dtype=float)
        # Unused term slots get s = 0 and ω = 1 so the closed forms need no special case (no division by 0).
        self.s = np.zeros((k, t))
        self.w = np.ones((k, t))
        self.ph = np.zeros((k, t))
        for i, p in enumerate(pieces):
            for j, (s, w, ph) in enumerate(p.terms):
                self.s[i, j], self.w[i, j], self.ph[i, j] = s, w, ph
        self.V0 = np.zeros(k)
        self.F0 = np.zeros(k)
        self._integrate(v0)
        if normalise:
            scale = 1.0 / float(self._raw(np.array([1.0]), 0)[0])
            self.c *= scale
            self.s *= scale
            self._integrate(v0 * scale)

    def _integrate(self, v0: float) -> None:
        """Velocity and displacement at each piece start, by integrating the previous pieces exactly."""
        v, f = v0, 0.0
        for k in range(len(self.c)):
            self.V0[k], self.F0[k] = v, f
            self._prepare()
            width = np.array([self.breaks[k + 1] - self.breaks[k]])
            v, f = float(self._piece(k, width, 1)[0]), float(self._piece(k, width, 0)[0])
        self._prepare()

    def _prepare(self) -> None:
        """Per-piece constants of the closed forms, so an evaluation is a few gathers and one sin/cos per term:
        F = F0' + V0'·u + c·u²/2 − Σ (s/ω²)·sin(ωu + φ),  V = V0' + c·u − Σ (s/ω)·cos(ωu + φ)."""
        sw = self.s / self.w
        self.f_const = self.F0 + (sw / self.w * np.sin(self.ph)).sum(axis=1)
        self.v_const = self.V0 + (sw * np.cos(self.ph)).sum(axis=1)
        self.s_w = sw
        self.s_w2 = sw / self.w
        self.s_x_w = self.s * self.w

    def _piece(self, k: int | np.ndarray, u: np.ndarray, order: int) -> np.ndarray:
        """Derivative `order` (0 = f … 3 = f''') of piece(s) k at local abscissa u (k broadcast against u)."""
        if order == 0:
            out = self.f_const[k] + (self.v_const[k] + 0.5 * self.c[k] * u) * u
        elif order == 1:
            out = self.v_const[k] + self.c[k] * u
        elif order == 2:
            out = self.c[k] + 0.0 * u
        else:
            out = np.zeros(np.shape(u))
        for t in range(self.s.shape[1]):
            arg = self.w[k, t] * u + self.ph[k, t]
            if order == 0:
                out = out - self.s_w2[k, t] * np.sin(arg)
            elif order == 1:
                out = out - self.s_w[k, t] * np.cos(arg)
            elif order == 2:
                out = out + self.s[k, t] * np.sin(arg)
            else:
                out = out + self.s_x_w[k, t] * np.cos(arg)
        return out

    def _raw(self, x: np.ndarray, order: int) -> np.ndarray:
        k = np.searchsorted(self.breaks[1:-1], x, side="right")
        return self._piece(k, x - self.breaks[k], order)

    def __call__(self, x: np.ndarray, order: int = 0) -> np.ndarray:
        """f (order 0), f' (1), f'' (2) or f''' (3) at x ∈ [0, 1]; at a piece border the right piece is used."""
        return self._raw(np.asarray(x, dtype=float), order)

    def piece_samples(self, per_piece: int) -> list[tuple[np.ndarray, list[np.ndarray]]]:
        """(x, [f, f', f'', f''']) sampled on each closed piece — both one-sided limits at the borders."""
        out = []
        for k in range(len(self.c)):
            u = np.linspace(0.0, self.breaks[k + 1] - self.breaks[k], per_piece)
            ks = np.full(u.shape, k)
            out.append((self.breaks[k] + u, [self._piece(ks, u, o) for o in range(4)]))
        return out


class MirroredLaw:
    """The reverse of a law: f_r(x) = 1 − f(1 − x) (what "reverse" means for trapecloid and double harmonic)."""

    def __init__(self, name: str, law: HarmonicLaw) -> None:
        self.name = name
        self.law = law

    def __call__(self, x: np.ndarray, order: int = 0) -> np.ndarray:
        y = self.law(1.0 - np.asarray(x, dtype=float), order)
        # d^n/dx^n of −f(1−x) is −(−1)^n f^(n)(1−x): sign + for odd orders, − for even ones.
        return 1.0 - y if order == 0 else (y if order % 2 else -y)

    def piece_samples(self, per_piece: int) -> list[tuple[np.ndarray, list[np.ndarray]]]:
        out = []
        for x, vals in reversed(self.law.piece_samples(per_piece)):
            xr = (1.0 - x)[::-1]
            f, v, a, j = (arr[::-1] for arr in vals)
            out.append((xr, [1.0 - f, v, -a, j]))
        return out


def _sin_ramp(x0: float, width: float, amp: float) -> Piece:
    """Quarter sine from 0 to amp over width (acceleration ramp of MT, MS, MCV)."""
    return Piece(x0, terms=((amp, PI / (2 * width), 0.0),))


def _cos_fall(x0: float, width: float, amp: float, quarters: int = 1) -> Piece:
    """amp·cos from amp down over width: one quarter (to 0) or two quarters (to −amp)."""
    return Piece(x0, terms=((amp, quarters * PI / (2 * width), PI / 2),))


_MT_AM = 8 * PI / (PI + 2)  # modified trapezoid peak acceleration, 4.8881
_C = _eMC_CAM_CURVE

_MT = HarmonicLaw("modified trapezoid", [
    _sin_ramp(0.0, 1 / 8, 1.0), Piece(1 / 8, c=1.0), _cos_fall(3 / 8, 1 / 4, 1.0, quarters=2),
    Piece(5 / 8, c=-1.0), _cos_fall(7 / 8, 1 / 8, -1.0)])
# Trapecloid (D32): the modified trapezoid's first half (acceleration) followed by the cycloid's second half
# (deceleration); both reach V = 2 and f = ½ at x = ½ with zero acceleration, so the halves join in V and A.
_TRAPECLOID = HarmonicLaw("trapecloid", [
    _sin_ramp(0.0, 1 / 8, _MT_AM), Piece(1 / 8, c=_MT_AM), _cos_fall(3 / 8, 1 / 8, _MT_AM),
    Piece(0.5, terms=((-2 * PI, 2 * PI, 0.0),))])
_DOUBLE_HARMONIC = HarmonicLaw("double harmonic", [Piece(0.0, terms=((1.0, PI, PI / 2), (-1.0, 2 * PI, PI / 2)))])

LAWS: dict[_eMC_CAM_CURVE, HarmonicLaw | MirroredLaw] = {
    _C._mcStraightLine: HarmonicLaw("straight line", [Piece(0.0)], v0=1.0),
    _C._mcParabolic: HarmonicLaw("parabolic", [Piece(0.0, c=1.0), Piece(0.5, c=-1.0)]),
    # MCV50 (D31): modified-sine-shaped acceleration compressed into the first quarter (ramp 1/16, fall 3/16),
    # constant velocity over the middle half, mirrored deceleration.
    _C._mcModifiedConstantVel: HarmonicLaw("modified constant velocity", [
        _sin_ramp(0.0, 1 / 16, 1.0), _cos_fall(1 / 16, 3 / 16, 1.0), Piece(1 / 4),
        _sin_ramp(3 / 4, 3 / 16, -1.0), _cos_fall(15 / 16, 1 / 16, -1.0)]),
    _C._mcModifiedTrapezoid: _MT,
    _C._mcModifiedSine: HarmonicLaw("modified sine", [
        _sin_ramp(0.0, 1 / 8, 1.0), _cos_fall(1 / 8, 3 / 4, 1.0, quarters=2), _cos_fall(7 / 8, 1 / 8, -1.0)]),
    _C._mcCycloidal: HarmonicLaw("cycloidal", [Piece(0.0, terms=((1.0, 2 * PI, 0.0),))]),
    _C._mcTrapeclloid: _TRAPECLOID,
    _C._mcReverseTrapeclloid: MirroredLaw("reverse trapecloid", _TRAPECLOID),
    _C._mcSimpleHarmonic: HarmonicLaw("simple harmonic", [Piece(0.0, terms=((1.0, PI, PI / 2),))]),
    # Double harmonic (D32): smooth (A = 0) at the start, A = −π² at the end; the reverse is its mirror.
    _C._mcDoubleHarmonic: _DOUBLE_HARMONIC,
    _C._mcReverseDoubleHarmonic: MirroredLaw("reverse double harmonic", _DOUBLE_HARMONIC),
    # NC2 (D33, unverified): a no-dwell law — constant ±A over the outer quarters joined by a half cosine.
    _C._mcNC2Curve: HarmonicLaw("NC2", [Piece(0.0, c=1.0), _cos_fall(0.25, 0.5, 1.0, quarters=2),
                                        Piece(0.75, c=-1.0)]),
}


# --- polynomials (§5.4.4): coefficients of h·f(x) = Σ b_i x^i, kept finite when h = 0 -------------------------

def poly3_coefficients(h: float, v_init_t: float, v_fin_t: float) -> np.ndarray:
    """b1..b3 of the cubic with b_i = h·a_i (§5.4.4): v_init_t = Vinit·T, v_fin_t = Vfin·T [command units].

    Written as the products h·a_i so that h = d_final − d_init = 0 needs no division (D34)."""
    return np.array([v_init_t, 3 * h - (2 * v_init_t + v_fin_t), (v_init_t + v_fin_t) - 2 * h])


def poly5_coefficients(h: float, v_init_t: float, v_fin_t: float, a_init_t2: float, a_fin_t2: float) -> np.ndarray:
    """b1..b5 of the quintic, b_i = h·a_i of §5.4.4 with Vinit·T, Vfin·T, Ainit·T², Afin·T² [command units]."""
    vi, vf, ai, af = v_init_t, v_fin_t, a_init_t2, a_fin_t2
    return np.array([
        vi,
        ai / 2,
        -((3 * ai - af) + (8 * vf + 12 * vi) - 20 * h) / 2,
        (1.5 * ai - af) + (7 * vf + 8 * vi) - 15 * h,
        -((ai - af) + (6 * vf + 6 * vi) - 12 * h) / 2,
    ])


def polynomial_derivatives(b: np.ndarray, x: np.ndarray, order: int) -> np.ndarray:
    """Derivative `order` of Σ b[..., i-1]·x^i (no constant term) by Horner; b is (…, degree) or (degree,)."""
    b = np.asarray(b, dtype=float)
    deg = b.shape[-1]
    # Coefficients of the order-th derivative: i!/(i-order)! · b_i for i ≥ order.
    out = np.zeros(np.broadcast_shapes(np.shape(x), b.shape[:-1]))
    for i in range(deg, order - 1, -1):
        out = out * x + (b[..., i - 1] * math.perm(i, order) if i >= 1 else 0.0)
    return out


# --- characteristic values -----------------------------------------------------------------------------------

@dataclass(frozen=True)
class CurveCharacteristics:
    """Dimensionless characteristic values of a normalised law (cam-design tables' Vm, Am, Jm).

    `Jm` is the largest |f'''| inside the smooth pieces (the finite value tables print); `Jm_dwell` is ∞ when the
    acceleration jumps — inside the law, or against a dwell at either end (A(0) or A(1) ≠ 0) — as tables print
    "∞" for such curves. `V0`/`V1`, `A0`/`A1` are the velocity and acceleration at the ends."""

    Vm: float
    Am: float
    Jm: float
    Jm_dwell: float
    V0: float
    V1: float
    A0: float
    A1: float
    accel_jump_inside: bool


def _from_samples(pieces: list[tuple[np.ndarray, list[np.ndarray]]], tol: float = 1e-9) -> CurveCharacteristics:
    vm = max(float(np.max(np.abs(v[1]))) for _, v in pieces)
    am = max(float(np.max(np.abs(v[2]))) for _, v in pieces)
    jm = max(float(np.max(np.abs(v[3]))) for _, v in pieces)
    jump = any(abs(pieces[i][1][2][-1] - pieces[i + 1][1][2][0]) > tol for i in range(len(pieces) - 1))
    first, last = pieces[0][1], pieces[-1][1]
    a0, a1 = float(first[2][0]), float(last[2][-1])
    jm_dwell = math.inf if jump or abs(a0) > tol or abs(a1) > tol else jm
    return CurveCharacteristics(Vm=vm, Am=am, Jm=jm, Jm_dwell=jm_dwell, V0=float(first[1][0]),
                                V1=float(last[1][-1]), A0=a0, A1=a1, accel_jump_inside=jump)


@functools.cache
def characteristics(curve: _eMC_CAM_CURVE | int) -> CurveCharacteristics:
    """Vm, Am, Jm of a curve type, computed from the law (sampled densely on every piece, both border limits).

    The polynomials are given with zero boundary values (3x² − 2x³ and 10x³ − 15x⁴ + 6x⁵); `_mcConstantLine` has
    no rise, so all its values are 0."""
    curve = _eMC_CAM_CURVE(curve)
    if curve == _C._mcConstantLine:
        return CurveCharacteristics(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, False)
    if curve == _C._mcPolynomic3:
        return polynomial_characteristics(poly3_coefficients(1.0, 0.0, 0.0))
    if curve == _C._mcPolynomic5:
        return polynomial_characteristics(poly5_coefficients(1.0, 0.0, 0.0, 0.0, 0.0))
    return _from_samples(LAWS[curve].piece_samples(20001))


def _abs_max_on_unit(p: np.polynomial.Polynomial) -> float:
    """max |p(x)| on [0, 1]: at the ends or where p' = 0 (exact, no sampling)."""
    cands = [0.0, 1.0]
    if p.degree() >= 2:
        cands += [float(r.real) for r in p.deriv().roots() if abs(r.imag) < 1e-12 and 0.0 < r.real < 1.0]
    return float(np.max(np.abs(p(np.array(cands)))))


def polynomial_characteristics(b: np.ndarray) -> CurveCharacteristics:
    """Characteristics of h·f(x) = Σ b_i x^i (b from `poly3_coefficients` / `poly5_coefficients`), exactly."""
    p = np.polynomial.Polynomial(np.concatenate([[0.0], np.asarray(b, dtype=float)]))
    v, a, j = p.deriv(1), p.deriv(2), p.deriv(3)
    jm = _abs_max_on_unit(j) if j.degree() >= 0 else 0.0
    a0, a1 = float(a(0.0)), float(a(1.0))
    jm_dwell = math.inf if abs(a0) > 1e-9 or abs(a1) > 1e-9 else jm
    return CurveCharacteristics(Vm=_abs_max_on_unit(v), Am=_abs_max_on_unit(a), Jm=jm, Jm_dwell=jm_dwell,
                                V0=float(v(0.0)), V1=float(v(1.0)), A0=a0, A1=a1, accel_jump_inside=False)


def evaluate(curve: _eMC_CAM_CURVE | int, x: np.ndarray, order: int = 0) -> np.ndarray:
    """f^(order)(x) of a fixed law (vectorised); `_mcConstantLine` is 0; polynomials need their boundary values,
    so this gives the zero-boundary forms (use `polynomial_derivatives` with real coefficients instead)."""
    curve = _eMC_CAM_CURVE(curve)
    x = np.asarray(x, dtype=float)
    if curve == _C._mcConstantLine:
        return np.zeros_like(x)
    if curve == _C._mcPolynomic3:
        return polynomial_derivatives(poly3_coefficients(1.0, 0.0, 0.0), x, order)
    if curve == _C._mcPolynomic5:
        return polynomial_derivatives(poly5_coefficients(1.0, 0.0, 0.0, 0.0, 0.0), x, order)
    return LAWS[curve](x, order)
