"""CiA402 drive emulation: the power drive system (PDS) state machine, vectorised over all drives.

Each drive sees only its RxPDO entries (controlword 6040h, modes of operation 6060h, target position 607Ah …) and
answers through its TxPDO entries (statusword 6041h, modes display 6061h, position actual 6064h …), as a real drive
does. The state machine follows CiA402 (codesys-lc1200.md §B): states, controlword commands and statusword patterns.

This first version implements the cyclic synchronous position mode (8) with the mechanism behind it in `plant/`;
the EtherCAT issue adds CSV/CST/homing, touch probe, limits and faults.
"""

from __future__ import annotations

import enum

import numpy as np


class PDS(enum.IntEnum):
    NotReadyToSwitchOn = 0
    SwitchOnDisabled = 1
    ReadyToSwitchOn = 2
    SwitchedOn = 3
    OperationEnabled = 4
    QuickStopActive = 5
    FaultReactionActive = 6
    Fault = 7


class Cmd(enum.IntEnum):
    """Controlword commands (bits 0–3 and 7)."""

    DisableVoltage = 0  # xxxx xx0x
    QuickStop = 1  # xxxx x01x
    Shutdown = 2  # xxxx x110
    SwitchOn = 3  # xxxx 0111
    EnableOperation = 4  # xxxx 1111


CW_SHUTDOWN = 0x0006
CW_SWITCH_ON = 0x0007
CW_ENABLE_OPERATION = 0x000F
CW_DISABLE_VOLTAGE = 0x0000
CW_FAULT_RESET = 0x0080

MODE_CSP = 8
MODE_CSV = 9
MODE_CST = 10

_S = PDS
# next state for (state, command); NotReadyToSwitchOn moves on by itself (self-test done)
_NEXT = np.array(
    [
        # DisableVoltage, QuickStop, Shutdown, SwitchOn, EnableOperation
        [_S.SwitchOnDisabled] * 5,  # NotReadyToSwitchOn
        [_S.SwitchOnDisabled, _S.SwitchOnDisabled, _S.ReadyToSwitchOn, _S.SwitchOnDisabled, _S.SwitchOnDisabled],
        [_S.SwitchOnDisabled, _S.SwitchOnDisabled, _S.ReadyToSwitchOn, _S.SwitchedOn, _S.OperationEnabled],
        [_S.SwitchOnDisabled, _S.SwitchOnDisabled, _S.ReadyToSwitchOn, _S.SwitchedOn, _S.OperationEnabled],
        [_S.SwitchOnDisabled, _S.QuickStopActive, _S.ReadyToSwitchOn, _S.SwitchedOn, _S.OperationEnabled],
        [_S.SwitchOnDisabled, _S.QuickStopActive, _S.QuickStopActive, _S.QuickStopActive, _S.OperationEnabled],
        [_S.Fault] * 5,  # FaultReactionActive ends in Fault
        [_S.Fault] * 5,  # Fault: only a fault reset edge leaves it
    ],
    dtype=np.int8,
)

# statusword bits 0..6 per state (bit 4 "voltage enabled" is added from main power)
_SW = np.array([0x0000, 0x0040, 0x0021, 0x0023, 0x0027, 0x0007, 0x000F, 0x0008], dtype=np.uint16)


def _command_of(low_bits: int) -> int:
    ev, qs, so, eo = low_bits & 0x2, low_bits & 0x4, low_bits & 0x1, low_bits & 0x8
    if not ev:
        return int(Cmd.DisableVoltage)
    if not qs:
        return int(Cmd.QuickStop)
    if not so:
        return int(Cmd.Shutdown)
    return int(Cmd.EnableOperation) if eo else int(Cmd.SwitchOn)


# controlword bits 0–3 → command (a 16-entry table keeps the period free of per-bit array operations)
_CMD_OF_LOW_BITS = np.array([_command_of(b) for b in range(16)], dtype=np.int8)
_FAULT = int(PDS.Fault)
_OE = int(PDS.OperationEnabled)
_SO = int(PDS.SwitchedOn)
_RTSO = int(PDS.ReadyToSwitchOn)
_SOD = int(PDS.SwitchOnDisabled)


def decode_command(cw: np.ndarray) -> np.ndarray:
    """Controlword → Cmd code per drive (vectorised)."""
    return _CMD_OF_LOW_BITS[cw & 0x000F]


class Cia402Drives:
    """N CiA402 servo drives in cyclic synchronous position mode, one row per drive."""

    def __init__(self, n: int) -> None:
        self.n = n
        # A drive has finished its self-test (NotReadyToSwitchOn) by the time the network reaches Operational.
        self.state = np.full(n, PDS.SwitchOnDisabled, dtype=np.int8)
        self.main_power = np.ones(n, dtype=bool)
        self.mode_display = np.full(n, MODE_CSP, dtype=np.int8)
        self.position = np.zeros(n, dtype=np.int64)  # motor position in encoder pulses (64-bit internally)
        self._prev_cw = np.zeros(n, dtype=np.uint16)

    def step(self, controlword: np.ndarray, mode_of_operation: np.ndarray) -> None:
        """Apply one period's controlword (PDS transitions happen once per received frame)."""
        fault_reset = ((controlword & CW_FAULT_RESET) != 0) & ((self._prev_cw & CW_FAULT_RESET) == 0)
        self._prev_cw[:] = controlword
        cmd = decode_command(controlword)
        nxt = _NEXT[self.state, cmd]
        if not self._all_powered:
            # Without main-circuit power a drive cannot leave SwitchOnDisabled/ReadyToSwitchOn towards operation.
            blocked = ~self.main_power & (nxt >= _SO) & (nxt <= _OE)
            nxt[blocked] = np.minimum(self.state[blocked], _RTSO)
        if fault_reset.any():
            nxt[fault_reset & (self.state == _FAULT)] = _SOD
        self.state[:] = nxt
        self.mode_display[:] = np.where(mode_of_operation != 0, mode_of_operation, self.mode_display)

    @property
    def _all_powered(self) -> bool:
        return bool(self.main_power.all())

    def statusword(self) -> np.ndarray:
        # bit 4 "voltage enabled": the main circuit (DC link) is powered — Omron's DrvStatus.MainPower; bit 9 remote
        return _SW[self.state] | (self.main_power.astype(np.uint16) << 4) | np.uint16(0x0200)

    @property
    def operation_enabled(self) -> np.ndarray:
        return self.state == _OE
