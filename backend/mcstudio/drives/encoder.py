"""Encoder input slaves (Omron GX-EC02xx style, omron-mc-basics.md §2.11 "Encoder axis"), vectorised over N slaves.

An external mechanism turns each encoder at `velocity` [pulse/s] (default 0, settable any time); the slave counts
pulses (4010h encoder present position → record field position_actual, 32-bit wrap-around), reports its external
inputs in 60FDh (EXT1 bit 16, EXT2 bit 17, and the limit/home bits if such sensors are set in its `SensorLayout`) and
latches positions with the same function as a servo drive's touch probe (`drives/sensing.py` `TouchProbes`): latch
function 4020h (↔ 60B8h bits), latch status 4030h (↔ 60B9h), latch input 1/2 data 4012h/4013h (↔ 60BAh/60BCh; the
negative-edge positions go to the 60BBh/60BDh fields). `fieldbus/objects.py` maps the vendor objects to these fields.
"""

from __future__ import annotations

import numpy as np

from .sensing import SensorLayout, TouchProbes, digital_inputs


class EncoderInputs:
    def __init__(self, n: int, sensors: SensorLayout | None = None, period_s: float = 0.001) -> None:
        self.n = n
        self.period_s = period_s
        self.sensors = sensors if sensors is not None else SensorLayout(n)
        self.velocity = np.zeros(n)  # pulse/s of the external mechanism
        self.position = np.zeros(n, dtype=np.int64)  # counted pulses (64-bit internally)
        self.frac = np.zeros(n)  # continuous position = position + frac
        self.digital_inputs = np.zeros(n, dtype=np.uint32)
        self.probes = TouchProbes(n)
        self.probe_status = self.probes.status
        self.probe_pos1 = self.probes.pos1
        self.probe_pos2 = self.probes.pos2
        self._rx: np.ndarray | None = None

    def cycle(self, rx: np.ndarray, tx: np.ndarray, online: np.ndarray) -> None:
        """One period: the encoders turn (online or not: the mechanism does not wait for the bus), the inputs and
        latches are sampled; `tx` is filled completely (fields an encoder slave does not have are 0). A slave that
        got no valid frame keeps its last latch function."""
        if self._rx is None or self._rx.dtype != rx.dtype:
            self._rx = rx.copy()
        elif online.all():
            np.copyto(self._rx, rx)
        else:
            self._rx[online] = rx[online]
        prev = self.position.copy()
        x = self.position + self.frac + self.velocity * self.period_s
        whole = np.rint(x)
        self.position[:] = whole.astype(np.int64)
        self.frac[:] = x - whole
        p0, p1 = prev.astype(np.float64), self.position.astype(np.float64)
        self.digital_inputs[:] = digital_inputs(p1, self.sensors)
        self.probes.update(p0, p1, self._rx["touch_probe_function"], self.sensors)
        tx[...] = np.zeros(1, dtype=tx.dtype)[0]
        p = self.probes
        tx["position_actual"] = self.position
        tx["velocity_actual"] = np.clip(np.rint((self.position - prev) / self.period_s), -(2**31), 2**31 - 1)
        tx["touch_probe_status"] = p.status
        tx["touch_probe_pos1"] = p.pos1
        tx["touch_probe_neg1"] = p.neg1
        tx["touch_probe_pos2"] = p.pos2
        tx["touch_probe_neg2"] = p.neg2
        tx["digital_inputs"] = self.digital_inputs
