"""Mechanism behind the drives: an ideal position follower in CSP, a rigid inertia in CST.

* **CSP** (cyclic synchronous position): a drive in *Operation enabled* that receives a target position is at that
  position by the end of the period (an ideal, infinitely stiff position loop). The torque it reports is the torque
  that motion takes (inverse dynamics of the model below); the drive's torque limits do not hold the shaft back.
* **CST** (cyclic synchronous torque): the shaft is one rigid inertia driven by the motor torque T,
  ``J·dω/dt = T − b·ω − T_load`` (J total inertia at the motor shaft, b viscous friction, T_load a constant external
  torque, e.g. gravity; positive acts in the negative direction). T is constant over a period (the drive's torque
  command), so the model is integrated exactly, whatever the period. The drive limits T to its torque limits
  (60E0h/60E1h) and, as its velocity limit (607Fh) function, to the torque that keeps |ω| at or below the limit.
* A drive that is not enabled holds the shaft (no coasting), as the first version did.

Positions are motor pulses (int64, plus a fractional part in CST); the interface advances all drives one period.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

# Defaults of the mechanism (ServoDriveSettings): a 400 W, 3000 r/min servo motor (rated torque 1.27 N·m, rotor
# inertia 0.67e-4 kg·m²) with a load of about three times the rotor inertia.
DEFAULT_RATED_TORQUE = 1.27  # N·m
DEFAULT_INERTIA = 2.7e-4  # kg·m², rotor + load at the motor shaft
DEFAULT_VISCOUS_FRICTION = 1.0e-4  # N·m per rad/s
DEFAULT_LOAD_TORQUE = 0.0  # N·m


def wrap32(x: np.ndarray) -> np.ndarray:
    """Two's-complement wrap of int64 values to the 32-bit range of 607Ah/6064h."""
    return x.astype(np.int32)


@dataclass
class Mechanics:
    """Mechanical data of the mechanism behind each drive, one row per drive (SI units at the motor shaft)."""

    n: int
    pulses_per_rev: np.ndarray = field(init=False)  # encoder pulses per motor revolution
    rated_torque: np.ndarray = field(init=False)  # N·m = 100 % (the unit of 6071h/6077h/60E0h/60E1h)
    inertia: np.ndarray = field(init=False)  # kg·m²
    viscous: np.ndarray = field(init=False)  # N·m/(rad/s)
    load: np.ndarray = field(init=False)  # N·m
    cst: np.ndarray = field(init=False)  # the drive supports cyclic synchronous torque mode

    def __post_init__(self) -> None:
        n = self.n
        self.pulses_per_rev = np.full(n, 8192.0)
        self.rated_torque = np.full(n, DEFAULT_RATED_TORQUE)
        self.inertia = np.full(n, DEFAULT_INERTIA)
        self.viscous = np.full(n, DEFAULT_VISCOUS_FRICTION)
        self.load = np.full(n, DEFAULT_LOAD_TORQUE)
        self.cst = np.ones(n, dtype=bool)


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
