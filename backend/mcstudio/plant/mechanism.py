"""The mechanism behind the drives: a rigid inertia moved by the drive's position, velocity or torque control.

All quantities are per drive (numpy arrays); positions are motor pulses (the integer encoder count in the drive's
``position`` array plus a fraction ``frac`` here, |frac| ≤ ½), velocities pulse/s, torques 0.1 % of the rated torque
(the unit of 6071h/6074h/6077h/60E0h/60E1h/6072h). Every period `Mechanism.advance` moves each drive by one of four
kinds of control:

* **hold** — the drive is not enabled: the shaft holds (brake/servo lock, no coasting), velocity and torque are 0.
* **position** — the drive controls the position to a reference r (CSP target, or the drive's own profile in
  PP/PV/HM and the quick-stop/halt/fault-reaction ramps):

  - *model 0, ideal*: the shaft is exactly at r (rounded to a pulse) at the end of the period; the torque reported is
    the constant torque that takes the inertia from the previous to the new velocity; torque limits are not applied
    (an infinitely stiff drive, the behaviour of the first version).
  - *model 1, second order*: the closed loop ``ẍ = ωn²(r − x) + 2ζωn(kff·ṙ − ẋ)`` with ωn = 2π·bandwidth_hz. The
    drive interpolates r linearly over the period from the previous reference (ṙ = (r − r_prev)/T, as CSP drives
    interpolate their set-points), so the loop is an LTI system with a ramp input, integrated exactly with the 2×2
    transition matrix Φ = exp(A·T), A = [[0, 1], [−ωn², −2ζωn]], computed once per drive. In the error coordinates
    e = x − r(t), w = ẋ − ṙ the input is constant, ``ë = −ωn²e − 2ζωn·ė − 2ζωn(1 − kff)ṙ``, with the equilibrium
    e∞ = −2ζ(1 − kff)ṙ/ωn: a ramp is followed with the error 2ζ(1 − kff)·v/ωn, an (interpolated) step overshoots by
    about exp(−ζπ/√(1 − ζ²)).
* **velocity** (CSV) — model 0: the shaft turns at the command velocity from the start of the period; model 1: the
  first-order velocity loop ``ω̇ = ωn(ω_cmd − ω)`` with the same ωn, integrated exactly.
* **torque** (CST) — the rigid body ``J·dω/dt = T − b·ω − T_load`` (J total inertia at the motor shaft, b viscous
  friction, T_load a constant external torque, e.g. gravity, positive acting in the negative direction). T is
  constant over a period, so the model is integrated exactly whatever the period. T is the target torque limited to
  the torque limits and, as the drive's velocity-limit function (607Fh), to the torque that keeps |ω| ≤ the limit.

Torque limits in models 1: the torque a period of position or velocity control needs (the constant torque taking
the inertia from ω0 to ω1, ``J·(ω1 − e·ω0)/g1 + T_load`` — i.e. J·ẍ + b·ẋ + T_load averaged over the period) is
compared with the limits [t_lo, t_hi]; when it is outside, the period is integrated with the rigid-body model at the
saturated torque instead, and `limited` is set (statusword bit 11). The loop then continues from where the shaft
really is, so the following error grows while the limit bites.

`advance` is one call per period for all drives (tests may wrap it, e.g. to emulate a mechanical stop by clamping
``position`` afterwards). A position that was changed from outside since the last period is taken as it is (the
continuous position is ``position + frac``).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from .ideal import MODEL_SECOND_ORDER, Mechanics, validate_mechanics

KIND_HOLD = 0
KIND_POSITION = 1
KIND_VELOCITY = 2
KIND_TORQUE = 3

Sel = slice | np.ndarray


class Mechanism:
    """N mechanisms, one per drive (`Mechanics` rows), advanced one period at a time."""

    def __init__(self, n: int, mechanics: Mechanics | None = None, period_s: float = 0.001) -> None:
        self.n = n
        self.mech = mech = mechanics if mechanics is not None else Mechanics(n)
        problems = validate_mechanics(mech, period_s)
        if problems:
            raise ValueError("invalid mechanics: " + "; ".join(problems[:8]))
        self.period_s = T = period_s
        self._inv_period = np.array(1.0 / T)  # (0-d array: cheaper for numpy than a Python scalar operand)
        self.rad_per_pulse = 2.0 * math.pi / mech.pulses_per_rev
        # rigid body, exact over one period with the torque N constant:
        #   ω1 = e·ω0 + g1·N/J,  Δθ = g1·ω0 + g2·N/J  with k = b/J, e = exp(−kT), g1 = (1 − e)/k, g2 = (T − g1)/k
        k = mech.viscous / mech.inertia
        kt = k * T
        small = kt < 1e-6
        ks = np.where(small, 1.0, k)
        self._e = np.exp(-kt)
        self._g1 = np.where(small, T * (1.0 - kt / 2.0), -np.expm1(-kt) / ks)
        self._g2 = np.where(small, T * T / 2.0 * (1.0 - kt / 3.0), (T - self._g1) / ks)
        # torque [0.1 % of rated] that takes the shaft from ω0 to ω1 in one period: A·ω1 − C·ω0 + L (ω in pulse/s)
        per_mille = 1000.0 / mech.rated_torque
        self._a = mech.inertia / self._g1 * self.rad_per_pulse * per_mille
        self._c = self._a * self._e
        self._load_pm = mech.load * per_mille
        self._no_load = not bool(mech.load.any())
        # second-order loop (model 1): Φ = exp(A·T) per drive, the ramp-error coefficient 2ζ(1 − kff)/ωn and the
        # first-order velocity loop's exp(−ωn·T), (1 − exp(−ωn·T))/ωn. Ideal drives get harmless default numbers.
        second = mech.model == MODEL_SECOND_ORDER
        wn = 2.0 * math.pi * np.where(second, mech.bandwidth_hz, 50.0)
        zeta = np.where(second, mech.damping, 0.7)
        kff = np.where(second, mech.feedforward, 0.0)
        self._phi = phi = transition_matrix(wn, zeta, T)
        self._ramp_error = k_ramp = 2.0 * zeta * (1.0 - kff) / wn
        # the period's update is linear: x1 = Σ cx·(x0, v0, r, r_prev), v1 = Σ cv·(…) (see _second_position)
        c1 = phi[0] * k_ramp - phi[1] - k_ramp
        c2 = 1.0 + phi[2] * k_ramp - phi[3]
        self._cx = np.stack([phi[0], phi[1], 1.0 + c1 / T, -phi[0] - c1 / T])
        self._cv = np.stack([phi[2], phi[3], c2 / T, -phi[2] - c2 / T])
        # … and the torque without load, A·v1 − C·v0: one (3, 4, n) contraction gives x1, v1 and it
        v0_only = np.array([[0.0], [1.0], [0.0], [0.0]])
        self._cxvt = np.stack([self._cx, self._cv, self._a * self._cv - self._c * v0_only])
        self._inputs = np.zeros((4, n))
        self._veps = np.exp(-wn * T)
        self._vq = -np.expm1(-wn * T) / wn
        self._second = second
        self._second_idx = np.flatnonzero(second)
        self._ideal_idx = np.flatnonzero(~second)
        self._all_ideal = not bool(second.any())
        self._all_second = bool(second.all())
        # state at the end of the period
        self.velocity = np.zeros(n)  # shaft velocity [pulse/s]
        self.frac = np.zeros(n)  # continuous position = position + frac
        self.torque = np.zeros(n)  # applied torque [0.1 % of rated] (6077h)
        self.demand_torque = np.zeros(n)  # torque the control asked for before limiting (6074h)
        self.limited = np.zeros(n, dtype=bool)  # the torque was limited (statusword bit 11)
        self.any_limited = False  # limited.any()
        self.reference = np.zeros(n)  # position reference of the period (model 1: r_prev of the next period)
        self._frac_dirty = False  # frac or limited may be nonzero (not only ideal position control since)

    # ------------------------------------------------------------------ one period
    def advance(self, position: np.ndarray, kind: int | np.ndarray, demand: np.ndarray | None = None,
                velocity_cmd: np.ndarray | None = None, torque_cmd: np.ndarray | None = None,
                t_hi: np.ndarray | None = None, t_lo: np.ndarray | None = None,
                v_limit: np.ndarray | None = None) -> None:
        """Move every drive one period. `kind`: one KIND_* for all drives or an int8 array per drive; `demand`
        position reference [pulse] (position kind), `velocity_cmd` [pulse/s] (velocity kind), `torque_cmd` [0.1 %]
        (torque kind), `t_hi`/`t_lo` torque limits [0.1 %] (t_lo ≤ 0), `v_limit` CST velocity limit [pulse/s]."""
        if isinstance(kind, (int, np.integer)) and kind == KIND_POSITION and self._all_ideal:
            assert demand is not None
            self._ideal_position(slice(None), position, demand)
            return
        if self.demand_torque is self.torque:  # shared by the all-ideal path: separate before writing rows
            self.demand_torque = self.torque.copy()
        self._frac_dirty = True
        self.any_limited = False
        if isinstance(kind, (int, np.integer)):
            groups: list[tuple[int, Sel]] = [(int(kind), slice(None))]
        else:
            groups = []
            for k in (KIND_HOLD, KIND_POSITION, KIND_VELOCITY, KIND_TORQUE):
                idx = np.flatnonzero(kind == k)
                if idx.size:
                    groups.append((k, idx))
        for k, sl in groups:
            if k == KIND_POSITION:
                assert demand is not None
                self._by_model(sl, self._ideal_position, self._second_position, position, demand, t_hi, t_lo)
            elif k == KIND_VELOCITY:
                assert velocity_cmd is not None
                self._by_model(sl, self._ideal_velocity, self._second_velocity, position, velocity_cmd, t_hi, t_lo)
            elif k == KIND_TORQUE:
                assert torque_cmd is not None and t_hi is not None and t_lo is not None and v_limit is not None
                self._torque(sl, position, torque_cmd, t_hi, t_lo, v_limit)
            else:
                self._hold(sl, position)

    def _by_model(self, sl: Sel, ideal: Callable[..., None], second: Callable[..., None], *args: object) -> None:
        """Run the ideal or the second-order version of a control on the drives `sl` of each model."""
        if self._all_ideal:
            ideal(sl, *args)
        elif self._all_second:
            second(sl, *args)
        elif isinstance(sl, slice) and sl == slice(None):  # every drive: the models' index arrays, made once
            ideal(self._ideal_idx, *args)
            second(self._second_idx, *args)
        else:
            idx = np.arange(self.n)[sl]
            is2 = self._second[idx]
            if (~is2).any():
                ideal(idx[~is2], *args)
            if is2.any():
                second(idx[is2], *args)

    def _hold(self, sl: Sel, position: np.ndarray) -> None:
        self.velocity[sl] = 0.0
        self.torque[sl] = 0.0
        self.demand_torque[sl] = 0.0
        self.frac[sl] = 0.0
        self.limited[sl] = False
        self.reference[sl] = position[sl]

    def _ideal_position(self, sl: Sel, position: np.ndarray, demand: np.ndarray, *_: object) -> None:
        """Model 0: at the reference by the end of the period (the first version's CSP, bit for bit). `demand` may
        be int64 (CSP targets) or float (profiles)."""
        d = demand[sl]
        new = d if d.dtype.kind == "i" else np.rint(d).astype(np.int64)
        moved = new - position[sl]
        position[sl] = new
        w1 = moved * self._inv_period
        if isinstance(sl, slice) and sl == slice(None):
            # every drive: rebind the state arrays instead of copying (the common CSP case)
            t = self._a * w1 - self._c * self.velocity
            if not self._no_load:
                t += self._load_pm
            self.torque = self.demand_torque = t
            self.any_limited = False
            self.velocity = w1
            if self._frac_dirty:
                self.frac = np.zeros(self.n)
                self.limited = np.zeros(self.n, dtype=bool)
                self._frac_dirty = False
            # (no reference: with every drive ideal nothing reads it)
            return
        t = self._a[sl] * w1 - self._c[sl] * self.velocity[sl] + self._load_pm[sl]
        self.torque[sl] = t
        self.demand_torque[sl] = t
        self.velocity[sl] = w1
        self.frac[sl] = 0.0
        self.limited[sl] = False
        self.reference[sl] = d

    def _second_position(self, sl: Sel, position: np.ndarray, demand: np.ndarray, t_hi: np.ndarray | None,
                         t_lo: np.ndarray | None) -> None:
        """Model 1: the closed position loop over one period, exactly (see the module docstring).

        With ṙ = (r − r_prev)/T, e∞ = −k·ṙ (k = 2ζ(1 − kff)/ωn) and Φ = exp(A·T):
        x1 = r + e∞ + φ11·(x0 − r_prev − e∞) + φ12·(v0 − ṙ), v1 = ṙ + φ21·(x0 − r_prev − e∞) + φ22·(v0 − ṙ),
        collected per drive into coefficients of (x0, v0, r, r_prev) at construction (`_cx`, `_cv`)."""
        r = demand[sl]
        rp = self.reference[sl]
        x0 = position[sl] + self.frac[sl]
        v0 = self.velocity[sl]
        if isinstance(sl, slice):
            u = self._inputs
            u[0], u[1], u[2], u[3] = x0, v0, r, rp
            x1, v1, t = np.einsum("kin,in->kn", self._cxvt, u)
            self._finish(sl, position, x0, v0, x1, v1, t_hi, t_lo, t)
        else:
            cx, cv = self._cx[:, sl], self._cv[:, sl]
            x1 = cx[0] * x0 + cx[1] * v0 + cx[2] * r + cx[3] * rp
            v1 = cv[0] * x0 + cv[1] * v0 + cv[2] * r + cv[3] * rp
            self._finish(sl, position, x0, v0, x1, v1, t_hi, t_lo)
        if isinstance(sl, slice):
            self.reference = r.astype(np.float64)
        else:
            self.reference[sl] = r

    def _ideal_velocity(self, sl: Sel, position: np.ndarray, vc: np.ndarray, *_: object) -> None:
        """Model 0 in CSV: the command velocity from the start of the period."""
        v1 = vc[sl]
        v0 = self.velocity[sl]
        x1 = position[sl] + self.frac[sl] + v1 * self.period_s
        self._finish(sl, position, x0=None, v0=v0, x1=x1, v1=v1, t_hi=None, t_lo=None)
        self.reference[sl] = x1

    def _second_velocity(self, sl: Sel, position: np.ndarray, vc: np.ndarray, t_hi: np.ndarray | None,
                         t_lo: np.ndarray | None) -> None:
        """Model 1 in CSV: first-order velocity loop ω̇ = ωn(ω_cmd − ω), exactly."""
        c = vc[sl]
        v0 = self.velocity[sl]
        x0 = position[sl] + self.frac[sl]
        dv = v0 - c
        v1 = c + dv * self._veps[sl]
        x1 = x0 + c * self.period_s + dv * self._vq[sl]
        self._finish(sl, position, x0, v0, x1, v1, t_hi, t_lo)
        self.reference[sl] = self.frac[sl] + position[sl]

    def _finish(self, sl: Sel, position: np.ndarray, x0: np.ndarray | None, v0: np.ndarray, x1: np.ndarray,
                v1: np.ndarray, t_hi: np.ndarray | None, t_lo: np.ndarray | None,
                t_no_load: np.ndarray | None = None) -> None:
        """Torque of the period, its limits (rigid body at the saturated torque), new position and velocity."""
        t = self._a[sl] * v1 - self._c[sl] * v0 if t_no_load is None else t_no_load
        if not self._no_load:
            t += self._load_pm[sl]
        self.demand_torque[sl] = t
        limited = np.zeros(t.shape, dtype=bool)
        if t_hi is not None and t_lo is not None and x0 is not None:
            hi, lo = t_hi[sl], t_lo[sl]
            limited = (t > hi) | (t < lo)
            if limited.any():
                self.any_limited = True
                k = np.flatnonzero(limited)
                ii = np.arange(self.n)[sl][k]
                ts = np.clip(t[k], lo[k], hi[k])
                m = self.mech
                rpp = self.rad_per_pulse[ii]
                n_acc = (ts * m.rated_torque[ii] / 1000.0 - m.load[ii]) / m.inertia[ii]
                w0 = v0[k] * rpp
                g1 = self._g1[ii]
                x1 = x1.copy()
                v1 = v1.copy()
                t = t.copy()
                v1[k] = (self._e[ii] * w0 + g1 * n_acc) / rpp
                x1[k] = x0[k] + (g1 * w0 + self._g2[ii] * n_acc) / rpp
                t[k] = ts
        whole = np.rint(x1)
        position[sl] = whole.astype(np.int64)
        if isinstance(sl, slice):  # every drive: rebind instead of copying
            self.frac = x1 - whole
            self.velocity = v1
            self.torque = t
            self.limited = limited
        else:
            self.frac[sl] = x1 - whole
            self.velocity[sl] = v1
            self.torque[sl] = t
            self.limited[sl] = limited

    def _torque(self, sl: Sel, position: np.ndarray, demand: np.ndarray, t_hi: np.ndarray, t_lo: np.ndarray,
                v_limit: np.ndarray) -> None:
        """CST: torque `demand` [0.1 %] limited to [t_lo, t_hi] and by the velocity limit `v_limit` [pulse/s]; the
        shaft follows the rigid-body dynamics (the first version's CST, bit for bit)."""
        m = self.mech
        J, L = m.inertia[sl], m.load[sl]
        rated = m.rated_torque[sl] / 1000.0  # N·m per 0.1 %
        rpp = self.rad_per_pulse[sl]
        e, g1, g2 = self._e[sl], self._g1[sl], self._g2[sl]
        w0 = self.velocity[sl] * rpp  # rad/s
        lo, hi = t_lo[sl] * rated, t_hi[sl] * rated
        want = demand[sl] * rated
        t = np.clip(want, lo, hi)
        # velocity limit: the torque that ends the period exactly at ±limit, if the torque would pass it
        w_lim = v_limit[sl] * rpp
        w_free = e * w0 + g1 * (t - L) / J
        over = w_free > w_lim
        under = w_free < -w_lim
        if over.any() or under.any():
            cap = np.where(over, w_lim, -w_lim)
            t = np.where(over | under, np.clip(J * (cap - e * w0) / g1 + L, lo, hi), t)
        n_acc = (t - L) / J
        w1 = e * w0 + g1 * n_acc
        dtheta = g1 * w0 + g2 * n_acc
        p = position[sl] + self.frac[sl] + dtheta / rpp
        whole = np.rint(p)
        position[sl] = whole.astype(np.int64)
        self.frac[sl] = p - whole
        self.velocity[sl] = w1 / rpp
        self.torque[sl] = t / rated
        self.demand_torque[sl] = demand[sl]
        self.limited[sl] = lim = t != want
        if lim.any():
            self.any_limited = True
        self.reference[sl] = p


def transition_matrix(wn: np.ndarray, zeta: np.ndarray, T: float) -> np.ndarray:
    """Φ = exp(A·T) for A = [[0, 1], [−ωn², −2ζωn]], per drive, as rows (φ11, φ12, φ21, φ22) of a (4, n) array.

    With α = ζωn and s = ωn·√(ζ² − 1) (imaginary when underdamped): exp(A·T) = e^(−αT)·(cosh(sT)·I +
    sinh(sT)/s·(A + αI)); sinh(sT)/s → T for ζ = 1.
    """
    wn = np.asarray(wn, dtype=float)
    zeta = np.asarray(zeta, dtype=float)
    alpha = zeta * wn
    s = wn * np.sqrt((zeta * zeta - 1.0).astype(complex))
    st = s * T
    c = np.cosh(st).real
    tiny = np.abs(st) < 1e-8
    s_safe = np.where(tiny, 1.0, s)
    sh = np.where(tiny, T, (np.sinh(st) / s_safe).real).real
    decay = np.exp(-alpha * T)
    return np.stack([decay * (c + sh * alpha), decay * sh, -decay * sh * wn * wn, decay * (c - sh * alpha)])
