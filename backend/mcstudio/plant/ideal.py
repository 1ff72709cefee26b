"""Mechanical data of the mechanism behind each drive, and its validation.

The dynamics live in `plant/mechanism.py` (`Mechanism`): per drive either the *ideal* position follower of the first
version (model 0: in CSP the shaft is at the target by the end of the period) or a *second-order* closed position loop
(model 1), with a rigid inertia behind both (``J·dω/dt = T − b·ω − T_load``) for CST and for torque-limited motion.
This module keeps the parameters (`Mechanics`, one row per drive, SI units at the motor shaft), their defaults and
the ranges the second-order model accepts (`validate_mechanics`).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

# Defaults of the mechanism (ServoDriveSettings): a 400 W, 3000 r/min servo motor (rated torque 1.27 N·m, rotor
# inertia 0.67e-4 kg·m²) with a load of about three times the rotor inertia.
DEFAULT_RATED_TORQUE = 1.27  # N·m
DEFAULT_INERTIA = 2.7e-4  # kg·m², rotor + load at the motor shaft
DEFAULT_VISCOUS_FRICTION = 1.0e-4  # N·m per rad/s
DEFAULT_LOAD_TORQUE = 0.0  # N·m
# Second-order position loop (model 1)
DEFAULT_BANDWIDTH_HZ = 50.0  # natural frequency fn of the closed position loop, ωn = 2π·fn
DEFAULT_DAMPING = 0.7  # damping ratio ζ
DEFAULT_FEEDFORWARD = 0.0  # velocity feed-forward fraction kff (0 … 1)

MODEL_IDEAL = 0
MODEL_SECOND_ORDER = 1

# accepted ranges of the second-order model (checked by `validate_mechanics`)
DAMPING_RANGE = (0.05, 5.0)
FEEDFORWARD_RANGE = (0.0, 1.0)
MAX_BANDWIDTH_PER_SAMPLE_RATE = 0.25  # fn ≤ 0.25 / period: at least four periods per oscillation


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
    model: np.ndarray = field(init=False)  # int8: 0 ideal follower, 1 second-order position loop
    bandwidth_hz: np.ndarray = field(init=False)  # model 1: natural frequency of the position loop [Hz]
    damping: np.ndarray = field(init=False)  # model 1: damping ratio ζ
    feedforward: np.ndarray = field(init=False)  # model 1: velocity feed-forward fraction (0 … 1)

    def __post_init__(self) -> None:
        n = self.n
        self.pulses_per_rev = np.full(n, 8192.0)
        self.rated_torque = np.full(n, DEFAULT_RATED_TORQUE)
        self.inertia = np.full(n, DEFAULT_INERTIA)
        self.viscous = np.full(n, DEFAULT_VISCOUS_FRICTION)
        self.load = np.full(n, DEFAULT_LOAD_TORQUE)
        self.cst = np.ones(n, dtype=bool)
        self.model = np.zeros(n, dtype=np.int8)
        self.bandwidth_hz = np.full(n, DEFAULT_BANDWIDTH_HZ)
        self.damping = np.full(n, DEFAULT_DAMPING)
        self.feedforward = np.full(n, DEFAULT_FEEDFORWARD)


def validate_mechanics(mech: Mechanics, period_s: float) -> list[str]:
    """Problems of the mechanical data, one message per bad value (empty: usable).

    Every drive needs pulses_per_rev > 0, rated_torque > 0, inertia > 0 and viscous ≥ 0 (finite). A drive with the
    second-order model (model 1) also needs 0 < bandwidth_hz ≤ 0.25/period_s, 0.05 ≤ damping ≤ 5 and
    0 ≤ feedforward ≤ 1; these are not checked for ideal drives (model 0), which do not use them.
    """
    out: list[str] = []

    def bad(name: str, ok: np.ndarray, rule: str) -> None:
        values = getattr(mech, name)
        for i in np.flatnonzero(~ok):
            out.append(f"drive {int(i)}: {name} = {values[i]!r} ({rule})")

    with np.errstate(invalid="ignore"):
        bad("pulses_per_rev", np.isfinite(mech.pulses_per_rev) & (mech.pulses_per_rev > 0), "must be > 0")
        bad("rated_torque", np.isfinite(mech.rated_torque) & (mech.rated_torque > 0), "must be > 0")
        bad("inertia", np.isfinite(mech.inertia) & (mech.inertia > 0), "must be > 0")
        bad("viscous", np.isfinite(mech.viscous) & (mech.viscous >= 0), "must be ≥ 0")
        bad("load", np.isfinite(mech.load), "must be finite")
        bad("model", np.isin(mech.model, (MODEL_IDEAL, MODEL_SECOND_ORDER)), "0 ideal or 1 second order")
        second = mech.model == MODEL_SECOND_ORDER
        f_max = MAX_BANDWIDTH_PER_SAMPLE_RATE / period_s
        bad("bandwidth_hz", ~second | ((mech.bandwidth_hz > 0) & (mech.bandwidth_hz <= f_max)),
            f"0 < bandwidth ≤ {f_max:g} Hz = 0.25/period")
        lo, hi = DAMPING_RANGE
        bad("damping", ~second | ((mech.damping >= lo) & (mech.damping <= hi)), f"{lo} ≤ damping ≤ {hi}")
        lo, hi = FEEDFORWARD_RANGE
        bad("feedforward", ~second | ((mech.feedforward >= lo) & (mech.feedforward <= hi)),
            f"{lo} ≤ feedforward ≤ {hi}")
    return out
