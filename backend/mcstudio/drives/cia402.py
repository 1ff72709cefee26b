"""CiA402 drive emulation: the power drive system (PDS) state machine, vectorised over all drives.

Each drive sees only its RxPDO entries (controlword 6040h, modes of operation 6060h, target position 607Ah …) and
answers through its TxPDO entries (statusword 6041h, modes display 6061h, position actual 6064h …), as a real drive
does. The state machine follows CiA402 (codesys-lc1200.md §B): states, controlword commands and statusword patterns.

Modes of operation: cyclic synchronous position (8) and cyclic synchronous torque (10, where the drive supports
it), with the mechanism behind the drive in `plant/`. A new mode of operation (6060h) takes effect with the frame
that carries it and is reported in 6061h at once; a mode the drive does not support is ignored (the drive keeps its
mode, as a drive that rejects the request). Statusword bit 11 (internal limit active) is set while the drive limits
its torque (60E0h/60E1h) or, in CST, the velocity (607Fh). CSV, drive faults and the limits in CSP come with the
EtherCAT issue.
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass, field

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


# 60FDh digital inputs: CiA402 bits 0–2; vendor bits for the external latch inputs (MC Studio layout)
DI_NEGATIVE_LIMIT = 1 << 0
DI_POSITIVE_LIMIT = 1 << 1
DI_HOME_SWITCH = 1 << 2
DI_EXT1 = 1 << 16
DI_EXT2 = 1 << 17

# 60B8h touch probe function / 60B9h touch probe status (CiA402)
TP1_ENABLE = 0x0001
TP1_CONTINUOUS = 0x0002
TP1_SOURCE_Z = 0x0004  # bits 2–3 = 01: zero impulse of the encoder; 00: touch probe input 1 (EXT1)
TP1_POS_EDGE = 0x0010
TP2_ENABLE = 0x0100
TP2_CONTINUOUS = 0x0200
TP2_SOURCE_Z = 0x0400
TP2_POS_EDGE = 0x1000
TS1_ENABLED = 0x0001
TS1_STORED = 0x0002
TS2_ENABLED = 0x0100
TS2_STORED = 0x0200


@dataclass
class SensorLayout:
    """Sensor positions of the mechanism behind each drive, in motor pulses (nan/inf when not fitted)."""

    n: int
    pos_limit: np.ndarray = field(init=False)
    neg_limit: np.ndarray = field(init=False)
    prox: np.ndarray = field(init=False)  # (n, 2) zone
    ext1: np.ndarray = field(init=False)
    ext2: np.ndarray = field(init=False)
    z_offset: np.ndarray = field(init=False)
    z_period: np.ndarray = field(init=False)

    def __post_init__(self) -> None:
        n = self.n
        self.pos_limit = np.full(n, np.inf)
        self.neg_limit = np.full(n, -np.inf)
        self.prox = np.full((n, 2), np.nan)
        self.ext1 = np.full((n, 2), np.nan)
        self.ext2 = np.full((n, 2), np.nan)
        self.z_offset = np.zeros(n)
        self.z_period = np.full(n, np.inf)


def _in_zone(p: np.ndarray, zone: np.ndarray) -> np.ndarray:
    with np.errstate(invalid="ignore"):
        return (p >= zone[:, 0]) & (p <= zone[:, 1])


def _zone_edge(p0: float, p1: float, lo: float, hi: float) -> float | None:
    """Position of the first OFF→ON edge of the zone [lo, hi] on the way p0 → p1 (exact, not sampled)."""
    if math.isnan(lo) or p0 == p1:
        return None
    inside0 = lo <= p0 <= hi
    if inside0:
        return None
    if p1 > p0 and p0 < lo <= p1:
        return lo
    if p1 < p0 and p0 > hi >= p1:
        return hi
    return None


def _z_edge(p0: float, p1: float, offset: float, period: float) -> float | None:
    if not math.isfinite(period) or p0 == p1:
        return None
    if p1 > p0:
        k = math.floor((p0 - offset) / period) + 1
        z = offset + k * period
        return z if z <= p1 else None
    k = math.ceil((p0 - offset) / period) - 1
    z = offset + k * period
    return z if z >= p1 else None


class Cia402Drives:
    """N CiA402 servo drives in cyclic synchronous position or torque mode, one row per drive, with the sensors wired
    to them (limit switches, home proximity, external latch inputs, encoder Z phase) and the touch-probe function."""

    def __init__(self, n: int, sensors: SensorLayout | None = None) -> None:
        self.n = n
        self.sensors = sensors if sensors is not None else SensorLayout(n)
        self.digital_inputs = np.zeros(n, dtype=np.uint32)
        self.probe_status = np.zeros(n, dtype=np.uint16)
        self.probe_pos1 = np.zeros(n, dtype=np.int64)
        self.probe_pos2 = np.zeros(n, dtype=np.int64)
        self._prev_tp = np.zeros(n, dtype=np.uint16)
        # A drive has finished its self-test (NotReadyToSwitchOn) by the time the network reaches Operational.
        self.state = np.full(n, PDS.SwitchOnDisabled, dtype=np.int8)
        self.main_power = np.ones(n, dtype=bool)
        self.mode_display = np.full(n, MODE_CSP, dtype=np.int8)
        self.cst_supported = np.ones(n, dtype=bool)  # CST in the supported drive modes (6502h bit 9)
        self.internal_limit = np.zeros(n, dtype=bool)  # statusword bit 11, set by the mechanism's torque control
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
        change = mode_of_operation != self.mode_display
        if change.any():
            ok = change & ((mode_of_operation == MODE_CSP) | ((mode_of_operation == MODE_CST) & self.cst_supported))
            self.mode_display[ok] = mode_of_operation[ok]

    def sense(self, previous: np.ndarray, probe_function: np.ndarray) -> None:
        """Inputs after the mechanism moved from `previous` to `position`: 60FDh bits and touch-probe latches."""
        p = self.position.astype(float)
        s = self.sensors
        di = np.where(p >= s.pos_limit, DI_POSITIVE_LIMIT, 0) | np.where(p <= s.neg_limit, DI_NEGATIVE_LIMIT, 0)
        di |= np.where(_in_zone(p, s.prox), DI_HOME_SWITCH, 0)
        di |= np.where(_in_zone(p, s.ext1), DI_EXT1, 0) | np.where(_in_zone(p, s.ext2), DI_EXT2, 0)
        self.digital_inputs[:] = di
        tp = probe_function
        active = np.flatnonzero((tp | self._prev_tp) & (TP1_ENABLE | TP2_ENABLE))
        for i in active:
            self._probe(int(i), float(previous[i]), float(p[i]), int(tp[i]), int(self._prev_tp[i]))
        self._prev_tp[:] = tp

    def _probe(self, i: int, p0: float, p1: float, fn: int, prev: int) -> None:
        """Touch probe 1 and 2 of drive i (first-event or continuous, positive edge, EXT input or Z phase)."""
        st = int(self.probe_status[i])
        s = self.sensors
        for enable, cont, src_z, pos_edge, ts_en, ts_st, zone, slot in (
            (TP1_ENABLE, TP1_CONTINUOUS, TP1_SOURCE_Z, TP1_POS_EDGE, TS1_ENABLED, TS1_STORED, s.ext1, 1),
            (TP2_ENABLE, TP2_CONTINUOUS, TP2_SOURCE_Z, TP2_POS_EDGE, TS2_ENABLED, TS2_STORED, s.ext2, 2),
        ):
            if not fn & enable:
                st &= ~(ts_en | ts_st)
                continue
            if not prev & enable or (fn & pos_edge and not prev & pos_edge):
                st &= ~ts_st  # (re-)armed
            st |= ts_en
            if not fn & pos_edge or (st & ts_st and not fn & cont):
                continue
            if fn & src_z:
                edge = _z_edge(p0, p1, float(s.z_offset[i]), float(s.z_period[i]))
            else:
                edge = _zone_edge(p0, p1, float(zone[i, 0]), float(zone[i, 1]))
            if edge is not None:
                st |= ts_st
                if slot == 1:
                    self.probe_pos1[i] = round(edge)
                else:
                    self.probe_pos2[i] = round(edge)
        self.probe_status[i] = st

    @property
    def _all_powered(self) -> bool:
        return bool(self.main_power.all())

    def statusword(self) -> np.ndarray:
        # bit 4 "voltage enabled": the main circuit (DC link) is powered — Omron's DrvStatus.MainPower; bit 9 remote
        sw = _SW[self.state] | (self.main_power.astype(np.uint16) << 4) | np.uint16(0x0200)
        if self.internal_limit.any():
            sw |= self.internal_limit.astype(np.uint16) << 11
        return sw

    @property
    def operation_enabled(self) -> np.ndarray:
        return self.state == _OE
