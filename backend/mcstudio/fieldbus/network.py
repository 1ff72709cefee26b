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

from ..drives.cia402 import Cia402Drives
from ..plant.ideal import IdealPlant, wrap32

# RxPDO 1600h (master → drive) and TxPDO 1A00h (drive → master) of the generic CiA402 servo drive.
RX_ENTRIES: tuple[tuple[str, int, str], ...] = (
    ("controlword", 0x6040, "<u2"),
    ("target_position", 0x607A, "<i4"),
    ("target_velocity", 0x60FF, "<i4"),
    ("target_torque", 0x6071, "<i2"),
    ("modes_of_operation", 0x6060, "i1"),
)
TX_ENTRIES: tuple[tuple[str, int, str], ...] = (
    ("error_code", 0x603F, "<u2"),
    ("statusword", 0x6041, "<u2"),
    ("position_actual", 0x6064, "<i4"),
    ("torque_actual", 0x6077, "<i2"),
    ("modes_display", 0x6061, "i1"),
    ("digital_inputs", 0x60FD, "<u4"),
)
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

    def __init__(self, node_addresses: list[int], names: list[str]) -> None:
        n = len(node_addresses)
        self.slaves = [
            SlaveInfo(i, addr, names[i], "Generic CiA402 servo drive") for i, addr in enumerate(node_addresses)
        ]
        self.index_of_node = {addr: i for i, addr in enumerate(node_addresses)}
        self.rx = np.zeros(n, dtype=RX_DTYPE)  # written by the MC layer (outputs stage)
        self.tx = np.zeros(n, dtype=TX_DTYPE)  # read by the MC layer (inputs stage)
        self.drives = Cia402Drives(n)
        self.plant = IdealPlant(n)
        self._latch_inputs()

    def exchange(self) -> None:
        rx = self.rx
        self.drives.step(rx["controlword"], rx["modes_of_operation"])
        self.plant.advance(self.drives.position, rx["target_position"], self.drives.operation_enabled)
        self._latch_inputs()

    def _latch_inputs(self) -> None:
        tx = self.tx
        tx["statusword"] = self.drives.statusword()
        tx["position_actual"] = wrap32(self.drives.position)
        tx["modes_display"] = self.drives.mode_display
        tx["error_code"] = 0
        tx["torque_actual"] = 0
        tx["digital_inputs"] = 0

    def image_bytes(self, slave: int) -> tuple[bytes, bytes]:
        """The RxPDO and TxPDO bytes of one slave as they travel on the wire."""
        return self.rx[slave].tobytes(), self.tx[slave].tobytes()
