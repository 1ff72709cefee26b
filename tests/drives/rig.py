"""A bench for emulated CiA402 drives and encoder inputs: the RX record the drives read (start-up defaults of
`fieldbus/objects.py`), the TX record they fill, and one `cycle` per step — no network in between."""

from __future__ import annotations

from typing import Any

import numpy as np

from mcstudio.drives.cia402 import Cia402Drives, SensorLayout
from mcstudio.fieldbus.objects import RX_DTYPE, RX_OBJECTS, TX_DTYPE, default_record
from mcstudio.plant.ideal import Mechanics

PERIOD = 0.001


class Rig:
    def __init__(self, n: int = 1, sensors: SensorLayout | None = None, mechanics: Mechanics | None = None,
                 period_s: float = PERIOD) -> None:
        self.d = Cia402Drives(n, sensors, mechanics, period_s)
        self.rx = default_record(RX_DTYPE, n, RX_OBJECTS)
        self.tx = np.zeros(n, dtype=TX_DTYPE)
        self.online = np.ones(n, dtype=bool)
        self.history: list[np.ndarray] = []

    def step(self, k: int = 1, **fields: Any) -> np.ndarray:
        """Set RX fields (scalars or per-drive arrays), run k periods; the TX record of the last one (a copy)."""
        for name, value in fields.items():
            self.rx[name] = value
        for _ in range(k):
            self.d.cycle(self.rx, self.tx, self.online)
            self.history.append(self.tx.copy())
        return self.tx.copy()

    def enable(self, mode: int = 8) -> None:
        self.step(modes_of_operation=mode, controlword=0x0006)
        self.step(controlword=0x0007)
        self.step(controlword=0x000F)
        assert (self.d.state == 4).all()

    def run_until(self, cond: Any, limit: int = 100000, **fields: Any) -> int:
        """Step until cond(tx) holds; the number of periods it took."""
        for name, value in fields.items():
            self.rx[name] = value
        for k in range(1, limit + 1):
            self.d.cycle(self.rx, self.tx, self.online)
            if cond(self.tx):
                return k
        raise AssertionError(f"condition not met within {limit} periods")

    def sw(self, i: int = 0) -> int:
        return int(self.tx["statusword"][i])

    def pos(self, i: int = 0) -> int:
        return int(self.tx["position_actual"][i])

    def field(self, name: str, i: int = 0) -> int:
        return int(self.tx[name][i])
