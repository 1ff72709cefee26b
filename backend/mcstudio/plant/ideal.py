"""Ideal mechanism: the motor shaft is exactly where the drive puts it.

Placeholder-free first plant: a drive in *Operation enabled* that receives a target position is at that position by
the end of the period. The EtherCAT issue replaces it with a second-order position loop, inertia and friction; the
interface (advance one period from drive state and targets, in pulses) stays.
"""

from __future__ import annotations

import numpy as np


def wrap32(x: np.ndarray) -> np.ndarray:
    """Two's-complement wrap of int64 values to the 32-bit range of 607Ah/6064h."""
    return x.astype(np.int32)


class IdealPlant:
    def __init__(self, n: int) -> None:
        self.n = n

    def advance(self, position: np.ndarray, target32: np.ndarray, enabled: np.ndarray) -> None:
        """Move enabled motors to their 32-bit targets (unwrapping into the 64-bit motor position)."""
        delta = (target32.astype(np.int64) - wrap32(position).astype(np.int64) + 2**31) % 2**32 - 2**31
        position += np.where(enabled, delta, 0)
