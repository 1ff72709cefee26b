"""Reference: the first version's mechanism (`plant/ideal.py` `IdealPlant` before the second-order model), verbatim.

`test_mechanism.py` checks that the ideal model of `plant/mechanism.py` reproduces it bit for bit in CSP and CST.
"""

# ruff: noqa
from __future__ import annotations

import math

import numpy as np

from mcstudio.plant.ideal import Mechanics, wrap32


class IdealPlant:
    def __init__(self, n: int, mechanics: Mechanics | None = None, period_s: float = 0.001) -> None:
        self.n = n
        self.mech = mech = mechanics if mechanics is not None else Mechanics(n)
        self.period_s = T = period_s
        self.rad_per_pulse = 2.0 * math.pi / mech.pulses_per_rev
        # exact solution of J·dω/dt = N − b·ω over one period with N constant:
        #   ω1 = e·ω0 + g1·N/J,  Δθ = g1·ω0 + g2·N/J  with k = b/J, e = exp(−kT), g1 = (1 − e)/k, g2 = (T − g1)/k
        k = mech.viscous / mech.inertia
        kt = k * T
        small = kt < 1e-6
        ks = np.where(small, 1.0, k)
        self._e = np.exp(-kt)
        self._g1 = np.where(small, T * (1.0 - kt / 2.0), -np.expm1(-kt) / ks)
        self._g2 = np.where(small, T * T / 2.0 * (1.0 - kt / 3.0), (T - self._g1) / ks)
        # CSP: reported torque [0.1 % of rated] = A·ω1 − C·ω0 + L (ω in pulses/s): the constant torque that takes the
        # shaft from ω0 to ω1 in one period
        per_mille = 1000.0 / mech.rated_torque
        self._a = mech.inertia / self._g1 * self.rad_per_pulse * per_mille
        self._c = self._a * self._e
        self._load_pm = mech.load * per_mille
        self._inv_period = 1.0 / T
        self._cst_before = False
        self.velocity = np.zeros(n)  # shaft velocity [pulse/s] at the end of the period
        self.frac = np.zeros(n)  # CST: continuous position = position + frac (|frac| ≤ 0.5 pulse)
        self.torque = np.zeros(n)  # applied torque [0.1 % of rated]
        self.limited = np.zeros(n, dtype=bool)  # the drive limited the torque (torque or velocity limit)

    def advance(self, position: np.ndarray, target32: np.ndarray, enabled: np.ndarray,
                cst: np.ndarray | None = None) -> None:
        """CSP: move enabled motors to their 32-bit targets (unwrapping into the 64-bit motor position). Drives in
        CST (`cst`) are left to `advance_torque`."""
        csp = enabled if cst is None else enabled & ~cst
        delta = (target32.astype(np.int64) - wrap32(position).astype(np.int64) + 2**31) % 2**32 - 2**31
        moved = np.where(csp, delta, 0)
        position += moved
        w1 = moved * self._inv_period
        torque = np.where(csp, self._a * w1 - self._c * self.velocity + self._load_pm, 0.0)
        if cst is None:
            self.velocity = w1
            self.torque = torque
            if self._cst_before:  # leaving CST: no fraction, no limit
                self._cst_before = False
                self.frac[:] = 0.0
                self.limited[:] = False
        else:
            self.velocity = np.where(cst, self.velocity, w1)
            self.torque = np.where(cst, self.torque, torque)
            self.frac[~cst] = 0.0
            self.limited[~cst] = False
            self._cst_before = True

    def advance_torque(self, idx: np.ndarray, position: np.ndarray, demand: np.ndarray, t_max: np.ndarray,
                       t_min: np.ndarray, v_limit: np.ndarray) -> None:
        """CST for the drives `idx` (after `advance` moved the others): torque `demand` [0.1 %] limited to
        [t_min, t_max] and by the velocity limit `v_limit` [pulse/s]; the shaft follows the dynamics."""
        m = self.mech
        J, L = m.inertia[idx], m.load[idx]
        rated = m.rated_torque[idx] / 1000.0  # N·m per 0.1 %
        rpp = self.rad_per_pulse[idx]
        e, g1, g2 = self._e[idx], self._g1[idx], self._g2[idx]
        w0 = self.velocity[idx] * rpp  # rad/s
        lo, hi = t_min * rated, t_max * rated
        want = demand * rated
        t = np.clip(want, lo, hi)
        # velocity limit: the torque that ends the period exactly at ±limit, if the torque would pass it
        w_lim = v_limit * rpp
        w_free = e * w0 + g1 * (t - L) / J
        over = w_free > w_lim
        under = w_free < -w_lim
        if over.any() or under.any():
            cap = np.where(over, w_lim, -w_lim)
            t = np.where(over | under, np.clip(J * (cap - e * w0) / g1 + L, lo, hi), t)
        n_acc = (t - L) / J
        w1 = e * w0 + g1 * n_acc
        dtheta = g1 * w0 + g2 * n_acc
        p = position[idx] + self.frac[idx] + dtheta / rpp
        whole = np.rint(p)
        position[idx] = whole.astype(np.int64)
        self.frac[idx] = p - whole
        self.velocity[idx] = w1 / rpp
        self.torque[idx] = t / rated
        self.limited[idx] = t != want
