"""Emulated EtherCAT network: slaves at node addresses exchanging a process image every primary period.

The process image of each slave is a packed byte record (numpy structured dtype without alignment), so what flows
is exactly the bytes of the PDO mapping. This first version uses one fixed mapping for every CiA402 servo drive
(the generic CSP assignment below); the EtherCAT issue makes the mapping editable per slave (1600h–17FFh,
1A00h–1BFFh, 1C12h/1C13h) and packs it bit-exactly from the device description.

One period (architecture.md): `exchange()` hands the drives last period's RxPDO bytes, lets the mechanism advance one
period and latches the drives' TxPDO bytes for the MC layer to read.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..drives.cia402 import MODE_CST, Cia402Drives, SensorLayout
from ..plant.ideal import IdealPlant, Mechanics, wrap32

# RxPDO 1600h (master → drive) and TxPDO 1A00h (drive → master) of the generic CiA402 servo drive: the objects of
# Omron's default assignment (omron-mc-basics.md §2.11) plus 606Ch velocity actual value.
RX_ENTRIES: tuple[tuple[str, int, str], ...] = (
    ("controlword", 0x6040, "<u2"),
    ("target_position", 0x607A, "<i4"),
    ("target_velocity", 0x60FF, "<i4"),
    ("target_torque", 0x6071, "<i2"),
    ("modes_of_operation", 0x6060, "i1"),
    ("touch_probe_function", 0x60B8, "<u2"),
    ("max_profile_velocity", 0x607F, "<u4"),
    ("positive_torque_limit", 0x60E0, "<u2"),
    ("negative_torque_limit", 0x60E1, "<u2"),
)
TX_ENTRIES: tuple[tuple[str, int, str], ...] = (
    ("error_code", 0x603F, "<u2"),
    ("statusword", 0x6041, "<u2"),
    ("position_actual", 0x6064, "<i4"),
    ("velocity_actual", 0x606C, "<i4"),
    ("torque_actual", 0x6077, "<i2"),
    ("modes_display", 0x6061, "i1"),
    ("touch_probe_status", 0x60B9, "<u2"),
    ("touch_probe_pos1", 0x60BA, "<i4"),
    ("touch_probe_pos2", 0x60BC, "<i4"),
    ("digital_inputs", 0x60FD, "<u4"),
)
MAPPED_OBJECTS = frozenset(index for _, index, _ in (*RX_ENTRIES, *TX_ENTRIES))
RX_DTYPE = np.dtype([(n, t) for n, _, t in RX_ENTRIES])
TX_DTYPE = np.dtype([(n, t) for n, _, t in TX_ENTRIES])


@dataclass(frozen=True)
class SlaveInfo:
    position: int  # index on the bus (order of the configuration)
    node_address: int
    name: str
    device: str


class Network:
    """Master plus N CiA402 servo slaves. Row i of `rx`/`tx` is the process image of slave i."""

    def __init__(self, node_addresses: list[int], names: list[str], sensors: SensorLayout | None = None,
                 period_s: float = 0.001, mechanics: Mechanics | None = None) -> None:
        n = len(node_addresses)
        self.period_s = period_s
        self.slaves = [
            SlaveInfo(i, addr, names[i], "Generic CiA402 servo drive") for i, addr in enumerate(node_addresses)
        ]
        self.index_of_node = {addr: i for i, addr in enumerate(node_addresses)}
        self.rx = np.zeros(n, dtype=RX_DTYPE)  # written by the MC layer (outputs stage)
        self.tx = np.zeros(n, dtype=TX_DTYPE)  # read by the MC layer (inputs stage)
        self.drives = Cia402Drives(n, sensors)
        self.plant = IdealPlant(n, mechanics, period_s)
        self.drives.cst_supported[:] = self.plant.mech.cst
        self._latch_inputs()

    def exchange(self) -> None:
        rx = self.rx
        d = self.drives
        d.step(rx["controlword"], rx["modes_of_operation"])
        previous = d.position.copy()
        enabled = d.operation_enabled
        cst = enabled & (d.mode_display == MODE_CST)
        if cst.any():
            # cyclic synchronous torque: 6071h target torque within 60E0h/60E1h and the 607Fh velocity limit
            idx = np.flatnonzero(cst)
            self.plant.advance(d.position, rx["target_position"], enabled, cst)
            self.plant.advance_torque(idx, d.position, rx["target_torque"][idx].astype(float),
                                      rx["positive_torque_limit"][idx].astype(float),
                                      -rx["negative_torque_limit"][idx].astype(float),
                                      rx["max_profile_velocity"][idx].astype(float))
            d.internal_limit[:] = self.plant.limited
        else:
            self.plant.advance(d.position, rx["target_position"], enabled)
            if d.internal_limit.any():
                d.internal_limit[:] = False
        d.sense(previous, rx["touch_probe_function"])
        self.velocity = (d.position - previous) / self.period_s
        self._latch_inputs()

    def _latch_inputs(self) -> None:
        tx = self.tx
        d = self.drives
        tx["statusword"] = d.statusword()
        tx["position_actual"] = wrap32(d.position)
        tx["velocity_actual"] = np.clip(np.rint(getattr(self, "velocity", 0.0)), -(2**31), 2**31 - 1).astype(np.int32)
        tx["modes_display"] = d.mode_display
        tx["error_code"] = 0
        tx["torque_actual"] = np.clip(np.rint(self.plant.torque), -32768, 32767).astype(np.int16)
        tx["touch_probe_status"] = d.probe_status
        tx["touch_probe_pos1"] = wrap32(d.probe_pos1)
        tx["touch_probe_pos2"] = wrap32(d.probe_pos2)
        tx["digital_inputs"] = d.digital_inputs

    def mapped_objects(self, slave: int) -> frozenset[int]:
        """Object indices in the PDO mapping of a slave (instructions needing others give 3461 at start)."""
        return MAPPED_OBJECTS

    def image_bytes(self, slave: int) -> tuple[bytes, bytes]:
        """The RxPDO and TxPDO bytes of one slave as they travel on the wire."""
        return self.rx[slave].tobytes(), self.tx[slave].tobytes()
