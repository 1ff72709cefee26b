"""CiA402 servo drives, vectorised over N drives (codesys-lc1200.md §A homing, §B objects; CiA402-2).

Each drive reads its objects from a row of an RX value record (`fieldbus/objects.py` RX_DTYPE: controlword 6040h,
modes of operation 6060h, target position 607Ah …, whatever the PDO mapping carried this period and the start-up
SDO/default values for the rest) and writes every object of a TX row (statusword 6041h, position actual 6064h …),
once per period in `Cia402Drives.cycle`. The mechanism behind the drives is `plant/mechanism.py`.

**Power drive system (PDS) state machine** — states Not ready to switch on (left by itself), Switch on disabled,
Ready to switch on, Switched on, Operation enabled, Quick stop active, Fault reaction active, Fault; controlword
commands Shutdown (xxxx x110), Switch on (xxxx 0111), Enable operation (xxxx 1111), Disable voltage (xxxx xx0x),
Quick stop (xxxx x01x), Fault reset (bit 7 rising edge); transitions 0–16 of CiA402:

* 2 SOD→RTSO shutdown; 3 RTSO→SO switch on (switch on + enable operation in RTSO does 3 and 4 at once);
  4 SO→OE enable operation; 5 OE→SO disable operation; 6 SO→RTSO shutdown; 7 RTSO→SOD quick stop / disable
  voltage; 8 OE→RTSO shutdown; 9 OE→SOD disable voltage; 10 SO→SOD quick stop / disable voltage; 11 OE→QSA quick
  stop; 12 QSA→SOD disable voltage, or by itself when the quick-stop ramp ends with quick stop option code 605Ah =
  1–4 (0: at once); 13 any→FRA on a fault; 14 FRA→Fault when the fault reaction is done (it lasts at least the
  period of the fault, so the master sees FRA); 15 Fault→SOD on the fault reset edge, only when the cause is gone;
  16 QSA→OE enable operation with 605Ah = 5–8.
* Without main-circuit power (statusword bit 4 "voltage enabled" = `main_power`) a drive does not go beyond Ready
  to switch on (and falls back there from Switched on / Operation enabled).
* A drive that gets no valid frame (`online` False) takes no new command; if it is in Operation enabled or Quick
  stop active its sync-manager watchdog trips: fault 603Fh = 8700h (CiA DS301 emergency code group 87xx "sync
  error", used by EtherCAT drives for the SM watchdog / sync error), with the fault reaction.

**Stops** — quick stop option code 605Ah (default 2): 0 disable at once; 1 slow-down ramp (6084h) then Switch on
disabled; 2 quick-stop ramp (6085h) then SOD; 3, 4 (current/voltage limit) as 2; 5 slow-down ramp and stay in
Quick stop active; 6 (and 7, 8) quick-stop ramp and stay. Fault reaction option code 605Eh (CiA402 numbering,
default 0): 0 disable the drive function at once (the shaft holds, see below); 1 slow-down ramp (6084h); 2, 3, 4
quick-stop ramp (6085h); then Fault. Halt (controlword bit 8) in PP/PV/HM stops with 6084h (halt option code 605Dh
= 1, default; other values: 6085h) and stays in Operation enabled; releasing it resumes PP/PV; in HM it interrupts
the homing (stop with 609Ah). Halt is ignored in the cyclic modes, where the master owns the trajectory. The
option codes are not in the RX record: they are the per-drive arrays `quick_stop_option`, `fault_reaction_option`,
`halt_option` (an RX record with the fields quick_stop_option_code / fault_reaction_option_code / halt_option_code
overrides them, as does position_offset for 60B0h).

**Modes of operation** (6060h → 6061h at once; an unsupported request is ignored and the drive keeps its mode;
6502h reports pp, pv, hm, csp, csv and — unless `Mechanics.cst` is False — cst):

* CSP 8: the target 607Ah (+ 60B0h) is the position reference of the period (32-bit wrap-around unwrapped).
* CSV 9: 60FFh + 60B1h is the velocity command. CST 10: 6071h + 60B2h is the torque command, limited to the torque
  limits and by 607Fh as velocity limit.
* PP 1: a rising edge of controlword bit 4 (new set-point) takes 607Ah when set-point acknowledge (statusword bit
  12) is 0: absolute, or relative to the previous target with bit 6; with bit 5 (change set immediately) or at
  rest it starts at once, else it is buffered (one set-point) and started when the current one ends. Bit 12 falls
  when the master clears bit 4 and no set-point is buffered. Profile velocity 6081h, acceleration 6083h,
  deceleration 6084h; target reached (bit 10) when the profile has ended and |607Ah − 6064h| ≤ 6067h for 6068h ms.
  Bit 9 (change on set-point) is not supported (the buffered set-point starts after a stop).
* PV 3: 60FFh with 6083h/6084h; bit 10 target reached (the ramp has reached 60FFh, or has stopped under halt),
  bit 12 speed = 0 (|606Ch| ≤ `velocity_threshold`).
* HM 6: drive-side homing (`drives/homing.py`): methods 1–6, 17–22, 33, 34, 35, 37; bit 4 rising starts, bit 4
  falling or halt interrupts; statusword bits 13/12/10 per CiA402. At the home point 6064h becomes the home offset
  607Ch (the drive's coordinate shift `home_shift`: 6064h = mechanism position + home_shift).

The profile modes and the stop ramps use the drive's own generator (`drives/profile.py`) as position reference.

**Statusword** 6041h: bits 0–3, 5, 6 per state; 4 voltage enabled (main power); 7 warning (`warning`); 9 remote
(always 1); 10 target reached (PP, PV, HM; 0 in the cyclic modes); 11 internal limit active (torque limited: CST
limits, model-1 position/velocity control at its torque limit); 12 CSP/CSV/CST "drive follows the command value"
(Operation enabled), PP set-point acknowledge, PV speed zero, HM homing attained; 13 CSP/PP following error, HM
homing error.

**Following error** (position control: CSP, PP, HM and the ramps): 60F4h = 6062h position demand − 6064h; when
|60F4h| > 6065h for longer than 6066h ms the drive faults with 603Fh = 8611h (following error) in Operation enabled.
6065h = FFFFFFFFh switches the check off in practice. 60F4h is 0 in CSV/CST and when disabled.

**Torque limits** 60E0h/60E1h, each further limited by 6072h max torque; applied in CST and, with the second-order
model, in position and velocity control (the ideal model ignores them, as the first version did).

**Not enabled**: the shaft holds (no coasting), velocity and torque 0.

`inject_fault(i, code)` raises a drive alarm (e.g. 2310h overcurrent, 7305h encoder, 3210h overvoltage) at the
start of the next period; persistent alarms survive fault resets until `clear_fault_cause(i)`.
"""

from __future__ import annotations

import enum

import numpy as np

from ..fastnp import copyto, count_nonzero
from ..plant.ideal import Mechanics
from ..plant.mechanism import KIND_HOLD, KIND_POSITION, KIND_TORQUE, KIND_VELOCITY, Mechanism
from .homing import (
    HM_ATTAINED_MOVING,
    HM_DONE,
    HM_ERROR,
    HM_ERROR_MOVING,
    HM_IDLE,
    HM_RUNNING,
    IMMEDIATE_METHODS,
    Homing,
    homing_phases,
)
from .profile import ProfileGenerator
from .sensing import (
    DI_EXT1,
    DI_EXT2,
    DI_HOME_SWITCH,
    DI_NEGATIVE_LIMIT,
    DI_POSITIVE_LIMIT,
    TP1_CONTINUOUS,
    TP1_ENABLE,
    TP1_NEG_EDGE,
    TP1_POS_EDGE,
    TP1_SOURCE_Z,
    TP2_CONTINUOUS,
    TP2_ENABLE,
    TP2_NEG_EDGE,
    TP2_POS_EDGE,
    TP2_SOURCE_Z,
    TS1_ENABLED,
    TS1_NEG_STORED,
    TS1_STORED,
    TS2_ENABLED,
    TS2_NEG_STORED,
    TS2_STORED,
    DigitalInputs,
    SensorLayout,
    TouchProbes,
)

__all__ = [
    "CW_CHANGE_IMMEDIATELY", "CW_DISABLE_VOLTAGE", "CW_ENABLE_OPERATION", "CW_FAULT_RESET", "CW_HALT",
    "CW_NEW_SET_POINT", "CW_RELATIVE", "CW_SHUTDOWN",
    "CW_SWITCH_ON", "DI_EXT1", "DI_EXT2", "DI_HOME_SWITCH", "DI_NEGATIVE_LIMIT", "DI_POSITIVE_LIMIT",
    "ERR_FOLLOWING", "ERR_SYNC", "MODE_CSP", "MODE_CST", "MODE_CSV", "MODE_HM", "MODE_PP", "MODE_PV", "PDS",
    "TP1_CONTINUOUS", "TP1_ENABLE", "TP1_NEG_EDGE", "TP1_POS_EDGE", "TP1_SOURCE_Z", "TP2_CONTINUOUS", "TP2_ENABLE",
    "TP2_NEG_EDGE", "TP2_POS_EDGE", "TP2_SOURCE_Z", "TS1_ENABLED", "TS1_NEG_STORED", "TS1_STORED", "TS2_ENABLED",
    "TS2_NEG_STORED", "TS2_STORED", "Cia402Drives", "Cmd", "SensorLayout", "decode_command",
]


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
    """Controlword commands (bits 0–3; the fault reset is the rising edge of bit 7)."""

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
CW_NEW_SET_POINT = 0x0010  # PP new set-point / HM homing operation start
CW_CHANGE_IMMEDIATELY = 0x0020  # PP
CW_RELATIVE = 0x0040  # PP
CW_HALT = 0x0100

MODE_PP = 1
MODE_PV = 3
MODE_HM = 6
MODE_CSP = 8
MODE_CSV = 9
MODE_CST = 10
# 6502h supported drive modes: bit 0 pp, 2 pv, 5 hm, 7 csp, 8 csv, 9 cst
SUPPORTED_MODES = 0x01A5
SUPPORTED_CST = 0x0200
_PROFILE_MODES = (MODE_PP, MODE_PV, MODE_HM)

# 603Fh error codes raised by the drive itself
ERR_SYNC = 0x8700  # sync-manager watchdog: no valid frame while enabled (DS301 87xx "sync error")
ERR_FOLLOWING = 0x8611  # following error (DS402 8611h)

# statusword bits
SW_VOLTAGE_ENABLED = 0x0010
SW_WARNING = 0x0080
SW_REMOTE = 0x0200
SW_TARGET_REACHED = 0x0400
SW_INTERNAL_LIMIT = 0x0800
SW_BIT12 = 0x1000
SW_BIT13 = 0x2000

_S = PDS
# next state for (state, command); NotReadyToSwitchOn moves on by itself (self-test done); FaultReactionActive and
# Fault are left by the fault reaction and the fault reset, not by a command; QuickStopActive → OperationEnabled is
# only allowed with 605Ah = 5–8 (checked in the drive)
_NEXT = np.array(
    [
        # DisableVoltage, QuickStop, Shutdown, SwitchOn, EnableOperation
        [_S.SwitchOnDisabled] * 5,  # NotReadyToSwitchOn
        [_S.SwitchOnDisabled, _S.SwitchOnDisabled, _S.ReadyToSwitchOn, _S.SwitchOnDisabled, _S.SwitchOnDisabled],
        [_S.SwitchOnDisabled, _S.SwitchOnDisabled, _S.ReadyToSwitchOn, _S.SwitchedOn, _S.OperationEnabled],
        [_S.SwitchOnDisabled, _S.SwitchOnDisabled, _S.ReadyToSwitchOn, _S.SwitchedOn, _S.OperationEnabled],
        [_S.SwitchOnDisabled, _S.QuickStopActive, _S.ReadyToSwitchOn, _S.SwitchedOn, _S.OperationEnabled],
        [_S.SwitchOnDisabled, _S.QuickStopActive, _S.QuickStopActive, _S.QuickStopActive, _S.OperationEnabled],
        [_S.FaultReactionActive] * 5,
        [_S.Fault] * 5,
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
_FRA = int(PDS.FaultReactionActive)
_QSA = int(PDS.QuickStopActive)
_OE = int(PDS.OperationEnabled)
_SO = int(PDS.SwitchedOn)
_RTSO = int(PDS.ReadyToSwitchOn)
_SOD = int(PDS.SwitchOnDisabled)


# (state << 4 | controlword bits 0–3) → next state: one lookup per period
_NEXT_OF_CW = np.array([_NEXT[st, _CMD_OF_LOW_BITS[b]] for st in range(8) for b in range(16)], dtype=np.int8)
# statusword bits 0..6 per state with bit 9 (remote: the drive is controlled over the network)
_SW_REMOTE = _SW | np.uint16(0x0200)


def decode_command(cw: np.ndarray) -> np.ndarray:
    """Controlword → Cmd code per drive (vectorised)."""
    return _CMD_OF_LOW_BITS[cw & 0x000F]


def _enabled(state: np.ndarray) -> np.ndarray:
    """The drive function is on (the shaft is controlled): OE, QSA, FRA."""
    return (state == _OE) | (state == _QSA) | (state == _FRA)


def _f(a: np.ndarray) -> np.ndarray:
    return a.astype(np.float64)


class Cia402Drives:
    """N CiA402 servo drives (one row per drive) with the mechanism behind them (`plant`) and the sensors wired to
    them (limit switches, home switch, external latch inputs, encoder Z phase)."""

    def __init__(self, n: int, sensors: SensorLayout | None = None, mechanics: Mechanics | None = None,
                 period_s: float = 0.001) -> None:
        self.n = n
        self.period_s = period_s
        self._period_ms = period_s * 1000.0
        self._di = DigitalInputs(sensors if sensors is not None else SensorLayout(n))
        self.plant = Mechanism(n, mechanics, period_s)
        self.cst_supported = self.plant.mech.cst.astype(bool).copy()  # CST in 6502h (bit 9)
        # A drive has finished its self-test (NotReadyToSwitchOn) by the time the network reaches Operational.
        self.state = np.full(n, PDS.SwitchOnDisabled, dtype=np.int8)
        self.main_power = np.ones(n, dtype=bool)
        self.mode_display = np.full(n, MODE_CSP, dtype=np.int8)
        self.position = np.zeros(n, dtype=np.int64)  # motor position in encoder pulses (mechanism frame)
        self.home_shift = np.zeros(n, dtype=np.int64)  # 6064h = position + home_shift (set by homing)
        self.error_code = np.zeros(n, dtype=np.uint16)  # 603Fh
        self.warning = np.zeros(n, dtype=bool)  # statusword bit 7
        self.internal_limit = np.zeros(n, dtype=bool)  # statusword bit 11
        self.digital_inputs = np.zeros(n, dtype=np.uint32)  # 60FDh
        self.probes = TouchProbes(n)
        self.probe_status = self.probes.status
        self.probe_pos1 = self.probes.pos1
        self.probe_pos2 = self.probes.pos2
        self.probe_neg1 = self.probes.neg1
        self.probe_neg2 = self.probes.neg2
        # option codes (not in the RX record; see the module docstring)
        self.quick_stop_option = np.full(n, 2, dtype=np.int16)  # 605Ah
        self.halt_option = np.full(n, 1, dtype=np.int16)  # 605Dh
        self.fault_reaction_option = np.zeros(n, dtype=np.int16)  # 605Eh
        self.velocity_threshold = np.zeros(n)  # 606Fh [pulse/s]: PV statusword bit 12 "speed = 0"
        self.homing_timeout_s = np.full(n, 60.0)  # a homing phase that takes longer fails (bit 13)
        # internal state
        self._rx: np.ndarray | None = None
        self._rx_src: np.ndarray | None = None
        self._rx_bytes: tuple[np.ndarray, np.ndarray] = (np.zeros(0, np.uint8), np.zeros(0, np.uint8))
        # work arrays of the transmission (no allocation per period)
        self._t_vel = np.zeros(n)
        self._inv_T0 = np.array(1.0 / period_s)
        self._t_trq = np.zeros(n)
        self._t_fe = np.zeros(n, dtype=np.int64)
        self._t_abs = np.zeros(n, dtype=np.int64)
        self._any_fe_over = False
        self._opt_fields: tuple[bool, bool, bool, bool] = (False, False, False, False)
        self._prev_cw = np.zeros(n, dtype=np.uint16)
        self._demand = np.zeros(n)  # position reference of the period [pulse, mechanism frame]
        self._demand_int = np.zeros(n, dtype=np.int64)  # the same as integers (all drives in CSP)
        self._prev_demand = np.zeros(n)
        self._fe = np.zeros(n, dtype=np.int64)  # 60F4h
        self._fe_over = np.zeros(n, dtype=bool)
        self._fe_periods = np.zeros(n, dtype=np.int64)
        self._fe_counting = False
        self._sw_mode = np.zeros(n, dtype=np.uint16)  # statusword bits 10, 12, 13
        self._pending: list[tuple[int, int]] = []  # injected alarms, raised at the start of the next period
        self._persistent = np.zeros(n, dtype=bool)
        self._stop = np.zeros(n, dtype=bool)  # QSA / FRA ramp
        self._stop_dec = np.zeros(n)
        self._reaction_done = np.zeros(n, dtype=bool)  # FRA / QSA(1–4): the ramp has ended
        self._halt = np.zeros(n, dtype=bool)
        self._gen = ProfileGenerator(n)
        self._pp_goal = np.zeros(n, dtype=np.int64)  # PP target, 6064h frame
        self._pp_buffer = np.zeros(n, dtype=np.int64)
        self._pp_buffered = np.zeros(n, dtype=bool)
        self._pp_ack = np.zeros(n, dtype=bool)
        self._win_periods = np.zeros(n, dtype=np.int64)
        self.homing = Homing(n)
        self._shifted = False
        # classification of the drives by control (recomputed when a state or a mode changes)
        self._dirty = True
        self._all_csp = False
        self._kind: np.ndarray | int = KIND_HOLD
        self._csp_idx = np.zeros(0, dtype=np.intp)
        self._gen_idx = np.zeros(0, dtype=np.intp)
        self._poskind = np.zeros(n, dtype=bool)
        self._cst_any = False
        self._csv_any = False
        self._watch = False  # ramps/homing in progress: per-period checks needed
        self._last_tx: np.ndarray | None = None  # fields that rarely change are rewritten only when they do
        self._static_dirty = True
        self._probing = False
        self._sm_key: tuple[bytes, bytes, bytes] | None = None  # inputs of the last period without a transition
        self._sm_skipped = False
        self._state_seen = b""
        self._limits_key = b""
        self._limits: tuple[np.ndarray, np.ndarray] = (np.zeros(n), np.zeros(n))
        self._sw_last = np.zeros(n, dtype=np.uint16)
        self._sw_mode_last: np.ndarray | None = None

    # ------------------------------------------------------------------ public API
    @property
    def sensors(self) -> SensorLayout:
        return self._di.sensors

    @sensors.setter
    def sensors(self, layout: SensorLayout) -> None:
        self._di = DigitalInputs(layout)

    def sensors_changed(self) -> None:
        """Sensor positions were changed in place in `sensors`: take them into account."""
        self._di.refresh()

    @property
    def operation_enabled(self) -> np.ndarray:
        return self.state == _OE

    def inject_fault(self, i: int, code: int, persistent: bool = False) -> None:
        """Drive alarm on drive i with 603Fh = `code`, raised at the start of the next period (fault reaction →
        Fault). persistent: a fault reset does not clear it until `clear_fault_cause(i)`."""
        self._pending.append((int(i), int(code) & 0xFFFF))
        if persistent:
            self._persistent[i] = True

    def clear_fault_cause(self, i: int) -> None:
        """The cause of a persistent alarm is gone: the next fault reset clears the fault."""
        self._persistent[i] = False

    def cycle(self, rx: np.ndarray, tx: np.ndarray, online: np.ndarray) -> None:
        """One period. rx: n rows of RX_DTYPE as the drives received them; tx: n rows of TX_DTYPE, every field
        filled (fields that change only with events — 603Fh, 6061h, 60B9h–60BDh, 60FDh, 6502h — are rewritten
        when they change or when `tx` is another array than last period); online[i] False: drive i got no valid
        frame (it keeps its last rx values, takes no command, and its sync-manager watchdog trips if it is
        enabled)."""
        r, all_online = self._receive(rx, online)
        cw = r["controlword"]
        state_bytes = self.state.tobytes()
        if state_bytes != self._state_seen:  # states set from outside (tests, tools): classify again
            self._dirty = self._watch = True
        self._state_machine(r, cw, online, all_online, state_bytes)
        if self._dirty:
            self._classify()
        prev_pos = self.position.copy()
        self._motion(r, cw)
        self._sense(prev_pos, r)
        self._supervise(r)
        self._transmit(tx, prev_pos)
        self._prev_cw[:] = cw
        self._state_seen = self.state.tobytes()

    # ------------------------------------------------------------------ reception
    def _receive(self, rx: np.ndarray, online: np.ndarray) -> tuple[np.ndarray, bool]:
        """The drives' own copy of their objects: this period's values for the drives online, the last ones for
        the others."""
        all_online = count_nonzero(online) == self.n
        if self._rx is None or self._rx.dtype != rx.dtype:
            self._rx = rx.copy()
            names = rx.dtype.names or ()
            self._opt_fields = ("quick_stop_option_code" in names, "halt_option_code" in names,
                                "fault_reaction_option_code" in names, "position_offset" in names)
            return self._rx, all_online
        if all_online:
            if rx.flags.c_contiguous:
                if rx is not self._rx_src:  # byte views of the source and the copy, made once per source
                    self._rx_src, self._rx_bytes = rx, (rx.view(np.uint8), self._rx.view(np.uint8))
                copyto(self._rx_bytes[1], self._rx_bytes[0])  # bytes: much cheaper than field by field
            else:
                self._rx[:] = rx
        else:
            self._rx[online] = rx[online]
        return self._rx, all_online

    def _options(self, r: np.ndarray) -> None:
        qs, halt, fr, _ = self._opt_fields
        if qs:
            self.quick_stop_option[:] = r["quick_stop_option_code"]
        if halt:
            self.halt_option[:] = r["halt_option_code"]
        if fr:
            self.fault_reaction_option[:] = r["fault_reaction_option_code"]

    # ------------------------------------------------------------------ PDS state machine
    def _state_machine(self, r: np.ndarray, cw: np.ndarray, online: np.ndarray, all_online: bool,
                       state_bytes: bytes) -> None:
        state = self.state
        req = r["modes_of_operation"]
        events = bool(self._pending) or not all_online or self._watch
        if not events and self._sm_key is not None and count_nonzero(self.main_power) == self.n:
            # the same controlwords (so no fault reset edge), mode requests and states as in a period that changed
            # nothing: nothing to do
            key = (cw.tobytes(), req.tobytes(), state_bytes)
            if key == self._sm_key:
                self._sm_skipped = True
                return
        resets = bool((cw & CW_FAULT_RESET).any())
        if resets:  # a fault reset acts on drives that were in Fault when the frame came
            reset = ((cw & ~self._prev_cw & CW_FAULT_RESET) != 0) & (state == _FAULT) & ~self._persistent
        if events:
            self._options(r)
            self._events(online, all_online)
        self._sm_skipped = False
        self._sm_key = None
        nxt = _NEXT_OF_CW[(state << 4) | (cw & 0x000F)]
        if resets:
            ok = reset & (state == _FAULT)
            if ok.any():
                nxt[ok] = _SOD
                self.error_code[ok] = 0
                self._static_dirty = True
        stable = all_online and not self._pending and not self._watch
        if not self.main_power.all():
            # Without main-circuit power a drive cannot leave SwitchOnDisabled/ReadyToSwitchOn towards operation.
            stable = False
            blocked = ~self.main_power & (nxt >= _SO) & (nxt <= _OE)
            nxt[blocked] = np.minimum(state[blocked], _RTSO)
        if not all_online:
            off = ~online
            nxt[off] = state[off]
        if (nxt != state).any():
            self._options(r)
            self._change_states(nxt, r)
            stable = False
        if (req != self.mode_display).any():
            self._change_modes(req, online)
            stable = False
        if stable:
            self._sm_key = (cw.tobytes(), req.tobytes(), state.tobytes())

    def _events(self, online: np.ndarray, all_online: bool) -> None:
        """Alarms (injected, sync-manager watchdog) and the ends of fault reactions and quick stops."""
        state = self.state
        # a fault reaction or quick stop (605Ah 1–4) without a ramp, or whose ramp has ended, is over
        done = self._reaction_done | ~self._stop
        fra = done & (state == _FRA)
        qsa = done & (state == _QSA) & (self.quick_stop_option >= 1) & (self.quick_stop_option <= 4)
        if fra.any() or qsa.any():
            new = state.copy()
            new[fra] = _FAULT
            new[qsa] = _SOD
            self._reaction_done[fra | qsa] = False
            self._set_states(new)
        if not all_online:
            lost = ~online & ((state == _OE) | (state == _QSA))
            for i in np.flatnonzero(lost):
                self._fault(int(i), ERR_SYNC)
        pending, self._pending = self._pending, []
        for i, code in pending:
            self._fault(i, code)

    def _fault(self, i: int, code: int) -> None:
        """Transition 13: drive i → Fault reaction active with 603Fh = code (an alarm during a fault reaction or in
        Fault only updates the code)."""
        self.error_code[i] = code
        self._static_dirty = True
        st = int(self.state[i])
        if st in (_FRA, _FAULT):
            return
        opt = int(self.fault_reaction_option[i])
        moving = st in (_OE, _QSA)
        self._reaction_done[i] = False
        if moving and opt in (1, 2, 3, 4):
            rx = self._rx
            assert rx is not None
            dec = rx["profile_deceleration"][i] if opt == 1 else rx["quick_stop_deceleration"][i]
            self._start_stop(np.array([i]), float(dec))
        else:
            self._stop[i] = False  # disable at once: Fault from the next period
        new = self.state.copy()
        new[i] = _FRA
        self._set_states(new)

    def _change_states(self, nxt: np.ndarray, r: np.ndarray) -> None:
        """Entry/exit actions of the transitions of this period."""
        old = self.state
        to_qsa = (nxt == _QSA) & (old == _OE)
        if to_qsa.any():
            idx = np.flatnonzero(to_qsa)
            opt = self.quick_stop_option[idx]
            at_once = opt == 0
            nxt[idx[at_once]] = _SOD  # 605Ah = 0: disable drive function, transition 12 at once
            ramp = idx[~at_once]
            if ramp.size:
                o = self.quick_stop_option[ramp]
                dec = np.where((o == 1) | (o == 5), _f(r["profile_deceleration"][ramp]),
                               _f(r["quick_stop_deceleration"][ramp]))
                self._start_stop(ramp, dec)
        back = (old == _QSA) & (nxt == _OE)
        if back.any():
            # transition 16 only with 605Ah = 5–8
            stay = back & ((self.quick_stop_option < 5) | (self.quick_stop_option > 8))
            nxt[stay] = _QSA
            resume = back & ~stay
            self._stop[resume] = False
        self._set_states(nxt)

    def _set_states(self, nxt: np.ndarray) -> None:
        old = self.state
        was, now = _enabled(old), _enabled(nxt)
        on = now & ~was
        if on.any():
            # enabling: the reference starts at the shaft, profiles at rest, PP target = position
            idx = np.flatnonzero(on)
            x = _f(self.position[idx]) + self.plant.frac[idx]
            self._demand[idx] = x
            self._prev_demand[idx] = x
            self._gen.start(idx, x, 0.0)
            self._pp_reset(idx)
            self.homing.abort(idx)
            self._halt[idx] = False
            self._stop[idx] = False
        off = was & ~now
        if off.any():
            idx = np.flatnonzero(off)
            self._stop[idx] = False
            self._halt[idx] = False
            self._reaction_done[idx] = False
            self.homing.abort(idx)
            self._pp_buffered[idx] = False
            self._pp_ack[idx] = False
        self.state[:] = nxt
        self._dirty = True
        self._watch = True  # until the next classification

    def _start_stop(self, idx: np.ndarray, dec: np.ndarray | float) -> None:
        """A stop ramp (quick stop, fault reaction) from the current reference and its velocity."""
        self._continue_profile(idx)
        self._stop[idx] = True
        self._stop_dec[idx] = dec
        self._dirty = True

    def _continue_profile(self, idx: np.ndarray) -> None:
        """The generator takes over from the reference of the last period (continuity of position and velocity),
        unless it already drives these drives."""
        fresh = idx[~np.isin(idx, self._gen_idx)] if self._gen_idx.size else idx
        if fresh.size:
            pos_kind = self._poskind[fresh]
            v = np.where(pos_kind, (self._demand[fresh] - self._prev_demand[fresh]) / self.period_s,
                         self.plant.velocity[fresh])
            self._gen.start(fresh, self._demand[fresh], v)

    def _change_modes(self, req: np.ndarray, online: np.ndarray) -> None:
        change = (req != self.mode_display) & online
        ok = change & ((req == MODE_CSP) | (req == MODE_CSV) | (req == MODE_PP) | (req == MODE_PV)
                       | (req == MODE_HM) | ((req == MODE_CST) & self.cst_supported))
        if not ok.any():
            return
        idx = np.flatnonzero(ok)
        new = req[idx]
        enabled = _enabled(self.state[idx])
        profile = np.isin(new, _PROFILE_MODES) & enabled
        if profile.any():
            self._continue_profile(idx[profile])
        self.homing.abort(idx)
        self._pp_reset(idx)
        self._halt[idx] = False
        self.mode_display[idx] = new
        self._dirty = True
        self._static_dirty = True

    def _pp_reset(self, idx: np.ndarray) -> None:
        self._pp_goal[idx] = np.rint(self._demand[idx]).astype(np.int64) + self.home_shift[idx]
        self._pp_buffered[idx] = False
        self._pp_ack[idx] = False
        self._win_periods[idx] = 0

    def _classify(self) -> None:
        """Which control each drive is under this period."""
        self._dirty = False
        st, mode = self.state, self.mode_display
        oe = st == _OE
        stop = self._stop & ((st == _QSA) | (st == _FRA))
        gen = (oe & np.isin(mode, _PROFILE_MODES)) | stop | (st == _QSA)
        csp = oe & (mode == MODE_CSP) & ~gen
        csv = oe & (mode == MODE_CSV) & ~gen
        cst = oe & (mode == MODE_CST) & ~gen
        kind = np.zeros(self.n, dtype=np.int8)
        kind[csp | gen] = KIND_POSITION
        kind[csv] = KIND_VELOCITY
        kind[cst] = KIND_TORQUE
        self._all_csp = bool(csp.all())
        self._kind = int(kind[0]) if self.n and bool((kind == kind[0]).all()) else kind
        self._csp_idx = np.flatnonzero(csp)
        self._gen_idx = np.flatnonzero(gen)
        self._poskind = csp | gen
        self._csv_any = bool(csv.any())
        self._cst_any = bool(cst.any())
        self._watch = bool(gen.any()) or bool((st == _FRA).any())
        sw = np.zeros(self.n, dtype=np.uint16)
        sw[(csp | csv | cst)] = SW_BIT12  # the drive follows the command value
        self._sw_mode = sw

    # ------------------------------------------------------------------ motion
    def _torque_limits(self, r: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(t_hi, t_lo) [0.1 %]: 60E0h and −60E1h, each within 6072h (recomputed when one of them changes)."""
        mx, pos, neg = r["max_torque"], r["positive_torque_limit"], r["negative_torque_limit"]
        key = mx.tobytes() + pos.tobytes() + neg.tobytes()
        if key != self._limits_key:
            self._limits_key = key
            self._limits = (_f(np.minimum(pos, mx)), -_f(np.minimum(neg, mx)))
        return self._limits

    def _csp_reference(self, r: np.ndarray, idx: np.ndarray | slice) -> np.ndarray:
        """607Ah (+ 60B0h) as a position reference [pulse, int64, mechanism frame], unwrapped around the last
        reference (the int32 difference wraps like the 32-bit objects)."""
        tgt = r["target_position"][idx]
        if self._opt_fields[3]:
            tgt = tgt + r["position_offset"][idx]
        base = self._demand[idx].astype(np.int64)
        if self._shifted:
            shift = self.home_shift[idx]
            base += shift
            return base + (tgt - base.astype(np.int32)) - shift
        return base + (tgt - base.astype(np.int32))

    def _motion(self, r: np.ndarray, cw: np.ndarray) -> None:
        plant = self.plant
        if self._all_csp:
            demand = self._csp_reference(r, slice(None))
            self._demand_int = demand
            self._prev_demand = self._demand
            self._demand = _f(demand)
            if plant._all_ideal:
                plant.advance(self.position, KIND_POSITION, demand)
            else:
                hi, lo = self._torque_limits(r)
                plant.advance(self.position, KIND_POSITION, self._demand, t_hi=hi, t_lo=lo)
            return
        self._prev_demand[:] = self._demand
        demand = self._demand
        if self._csp_idx.size:
            demand[self._csp_idx] = _f(self._csp_reference(r, self._csp_idx))
        if self._gen_idx.size:
            self._generate(r, cw)
            demand[self._gen_idx] = self._gen.pos[self._gen_idx]
        vc = tc = vlim = None
        if self._csv_any:
            vc = _f(r["target_velocity"]) + _f(r["velocity_offset"])
        if self._cst_any:
            tc = _f(r["target_torque"]) + _f(r["torque_offset"])
            vlim = _f(r["max_profile_velocity"])
        hi = lo = None
        if self._cst_any or not plant._all_ideal:
            hi, lo = self._torque_limits(r)
        plant.advance(self.position, self._kind, demand, vc, tc, hi, lo, vlim)
        if not self._poskind.all():
            other = ~self._poskind
            demand[other] = _f(self.position[other]) + plant.frac[other]

    def _generate(self, r: np.ndarray, cw: np.ndarray) -> None:
        """Goals of the drive's own profile (PP, PV, HM, stop ramps) and one step of it."""
        g = self._gen_idx
        st, mode = self.state[g], self.mode_display[g]
        oe = st == _OE
        c = cw[g]
        prof = oe & np.isin(mode, _PROFILE_MODES)
        halt = prof & ((c & CW_HALT) != 0)
        self._halt[g] = halt
        bit4 = (c & CW_NEW_SET_POINT) != 0
        prev4 = (self._prev_cw[g] & CW_NEW_SET_POINT) != 0
        pp = oe & (mode == MODE_PP)
        pv = oe & (mode == MODE_PV)
        hm = oe & (mode == MODE_HM)
        if pp.any():
            self._pp_handshake(g[pp], bit4[pp], prev4[pp], c[pp], r)
        if hm.any():
            self._hm_control(g[hm], bit4[hm], prev4[hm], halt[hm], r)
        acc = _f(r["profile_acceleration"][g])
        dec = _f(r["profile_deceleration"][g])
        vmax = np.where(pp, _f(r["profile_velocity"][g]), np.inf)
        goal_p = np.where(pp & ~halt, _f(self._pp_goal[g] - self.home_shift[g]), np.nan)
        goal_v = np.where(pv & ~halt, _f(r["target_velocity"][g]), 0.0)
        if hm.any():
            goal_v = np.where(hm, self.homing.velocity_goal[g], goal_v)
            acc = np.where(hm, self.homing.acc[g], acc)
            dec = np.where(hm, self.homing.acc[g], dec)
            hm_idle = hm & ~self.homing.running[g] & ~self.homing.stopping[g]
            goal_v = np.where(hm_idle, 0.0, goal_v)
        if halt.any():
            opt = self.halt_option[g]
            hdec = np.where(opt == 1, _f(r["profile_deceleration"][g]), _f(r["quick_stop_deceleration"][g]))
            dec = np.where(halt & ~hm, hdec, dec)
        stop = self._stop[g]
        if stop.any():
            goal_p = np.where(stop, np.nan, goal_p)
            goal_v = np.where(stop, 0.0, goal_v)
            dec = np.where(stop, self._stop_dec[g], dec)
        self._gen.step(g, self.period_s, goal_p, goal_v, vmax, acc, dec)
        if pp.any():
            nxt = g[pp & self._pp_buffered[g] & self._gen.at_goal[g]]
            for i in nxt:
                self._pp_goal[i] = self._pp_buffer[i]
                self._pp_buffered[i] = False
                self._gen.at_goal[i] = False

    def _pp_handshake(self, idx: np.ndarray, bit4: np.ndarray, prev4: np.ndarray, c: np.ndarray,
                      r: np.ndarray) -> None:
        """PP set-point handshake: new set-point (bit 4 rising) ↔ set-point acknowledge (statusword bit 12)."""
        new = bit4 & ~prev4 & ~self._pp_ack[idx]
        for k in np.flatnonzero(new):
            i = int(idx[k])
            tgt = int(r["target_position"][i])
            cur = int(np.rint(self._demand[i])) + int(self.home_shift[i])
            if c[k] & CW_RELATIVE:
                goal = int(self._pp_goal[i]) + tgt
            else:
                goal = cur + ((tgt - cur + 2**31) % 2**32 - 2**31)
            moving = not (self._gen.at_goal[i] and self._gen.vel[i] == 0.0)
            if c[k] & CW_CHANGE_IMMEDIATELY or not moving:
                self._pp_goal[i] = goal
                self._gen.at_goal[i] = False
            else:
                self._pp_buffer[i] = goal
                self._pp_buffered[i] = True
            self._pp_ack[i] = True
            self._win_periods[i] = 0
        clear = ~bit4 & ~self._pp_buffered[idx]
        self._pp_ack[idx[clear]] = False

    def _hm_control(self, idx: np.ndarray, bit4: np.ndarray, prev4: np.ndarray, halt: np.ndarray,
                    r: np.ndarray) -> None:
        """HM: start on bit 4 rising, interrupt on bit 4 falling or halt."""
        hm = self.homing
        stop = (hm.running[idx]) & ((~bit4 & prev4) | halt)
        for i in idx[stop]:
            hm.stop(int(i), HM_RUNNING, HM_IDLE)
        start = bit4 & ~prev4 & ~halt
        for k in np.flatnonzero(start):
            i = int(idx[k])
            method = int(r["homing_method"][i])
            phases = homing_phases(method, int(self.digital_inputs[i]))
            offset = int(r["home_offset"][i])
            if phases is None:
                hm.abort(np.array([i]))
                hm.status[i] = HM_ERROR
            elif method in IMMEDIATE_METHODS:
                hm.abort(np.array([i]))
                self._set_home(i, float(self.position[i]), offset)
                hm.status[i] = HM_DONE
            else:
                hm.start(i, phases, float(r["homing_speed_fast"][i]), float(r["homing_speed_slow"][i]),
                         float(r["homing_acceleration"][i]), offset)

    def _set_home(self, i: int, at: float, offset: int) -> None:
        """The home point `at` [pulse, mechanism frame] gets the position 607Ch: 6064h = position + shift."""
        shift = offset - int(np.rint(at))
        delta = shift - int(self.home_shift[i])
        self.home_shift[i] = shift
        self._pp_goal[i] += delta
        self._shifted = bool(self.home_shift.any())

    # ------------------------------------------------------------------ inputs
    def _sense(self, prev_pos: np.ndarray, r: np.ndarray) -> None:
        """60FDh and the touch probes after the mechanism moved from `prev_pos` to `position`; homing edges."""
        fn = r["touch_probe_function"]
        probing = self._probing or bool(count_nonzero(fn))
        homing = bool(self._gen_idx.size) and bool(count_nonzero(self.homing.running))
        if not (self._di.fitted or probing or homing):
            return
        p1 = _f(self.position)
        p0 = _f(prev_pos)
        if self._di.fitted:
            di = self._di(p1)
            if self._di.changed:
                self.digital_inputs[:] = di
                self._static_dirty = True
        if probing:
            self.probes.update(p0, p1, fn, self.sensors, self.home_shift if self._shifted else None)
            self._probing = bool(count_nonzero(fn))
            self._static_dirty = True
        hm = self.homing
        if homing:
            timeout = self.homing_timeout_s / self.period_s
            for i, what, at in hm.detect(p0, p1, self.sensors, timeout):
                if what == "home":
                    self._set_home(i, at, int(hm.offset[i]))
                    hm.stop(i, HM_ATTAINED_MOVING, HM_DONE)
                else:
                    hm.stop(i, HM_ERROR_MOVING, HM_ERROR)

    # ------------------------------------------------------------------ supervision
    def _supervise(self, r: np.ndarray) -> None:
        """Following error (60F4h, 6065h/6066h → 8611h), statusword mode bits, ends of ramps."""
        if self._all_csp:
            fe = np.subtract(self._demand_int, self.position, self._fe)
            over = np.abs(fe, self._t_abs) > r["following_error_window"]
            any_over = bool(count_nonzero(over))
            if any_over or self._fe_counting:
                self._following_error(over, r)
            if any_over:
                self._sw_mode = np.where(over, SW_BIT12 | SW_BIT13, SW_BIT12).astype(np.uint16)
            elif self._any_fe_over:
                self._sw_mode = np.full(self.n, SW_BIT12, dtype=np.uint16)
            self._fe_over = over
            self._any_fe_over = any_over
            return
        pos = self._poskind
        fe = np.where(pos, np.rint(self._demand).astype(np.int64) - self.position, 0)
        self._fe[:] = fe
        over = pos & (np.abs(fe) > r["following_error_window"])
        if over.any() or self._fe_counting:
            self._following_error(over, r)
        self._fe_over = over
        self._any_fe_over = bool(over.any())
        st, mode = self.state, self.mode_display
        oe = st == _OE
        sw = np.zeros(self.n, dtype=np.uint16)
        cyclic = oe & ((mode == MODE_CSP) | (mode == MODE_CSV) | (mode == MODE_CST))
        sw[cyclic] = SW_BIT12
        sw[over & ((mode == MODE_CSP) | (mode == MODE_PP))] |= SW_BIT13
        if self._gen_idx.size:
            self._profile_status(r, sw)
        self._sw_mode = sw

    def _following_error(self, over: np.ndarray, r: np.ndarray) -> None:
        self._fe_periods = np.where(over, self._fe_periods + 1, 0)
        self._fe_counting = bool(over.any())
        trip = over & (self._fe_periods * self._period_ms > r["following_error_timeout"]) & (self.state == _OE)
        for i in np.flatnonzero(trip):
            self._options(r)
            self._fault(int(i), ERR_FOLLOWING)

    def _profile_status(self, r: np.ndarray, sw: np.ndarray) -> None:
        """PP/PV/HM statusword bits and the ends of stop ramps and homing decelerations."""
        g = self._gen_idx
        gen = self._gen
        stopped = gen.vel[g] == 0.0
        st, mode = self.state[g], self.mode_display[g]
        oe = st == _OE
        # stop ramps (QSA, FRA) that have ended
        ended = self._stop[g] & stopped
        if ended.any():
            e = g[ended]
            qsa_leaving = (self.state[e] == _QSA) & (self.quick_stop_option[e] >= 1) & (self.quick_stop_option[e] <= 4)
            self._reaction_done[e] = (self.state[e] == _FRA) | qsa_leaving
        hm = self.homing
        hstop = hm.stopping[g] & stopped
        for i in g[hstop]:
            hm.stopping[i] = False
            hm.status[i] = hm.final[i]
        halted = self._halt[g]
        pp = oe & (mode == MODE_PP)
        if pp.any():
            i = g[pp]
            win = np.abs(self._pp_goal[i] - self.home_shift[i] - self.position[i]) <= r["position_window"][i]
            inside = gen.at_goal[i] & ~self._pp_buffered[i] & win
            self._win_periods[i] = np.where(inside, self._win_periods[i] + 1, 0)
            reached = inside & (self._win_periods[i] * self._period_ms >= r["position_window_time"][i])
            reached |= halted[pp] & stopped[pp]
            sw[i] |= np.where(reached, SW_TARGET_REACHED, 0).astype(np.uint16)
            sw[i] |= np.where(self._pp_ack[i], SW_BIT12, 0).astype(np.uint16)
        pv = oe & (mode == MODE_PV)
        if pv.any():
            i = g[pv]
            reached = np.where(halted[pv], stopped[pv], gen.at_goal[i])
            zero = np.abs(self.plant.velocity[i]) <= self.velocity_threshold[i]
            sw[i] |= (np.where(reached, SW_TARGET_REACHED, 0) | np.where(zero, SW_BIT12, 0)).astype(np.uint16)
        hmm = oe & (mode == MODE_HM)
        if hmm.any():
            sw[g[hmm]] |= hm.status[g[hmm]]

    # ------------------------------------------------------------------ transmission
    def _transmit(self, tx: np.ndarray, prev_pos: np.ndarray) -> None:
        plant = self.plant
        self.internal_limit = limited = plant.limited
        if self._sm_skipped and self._sw_mode is self._sw_mode_last:
            sw = self._sw_last  # state, main power and mode bits as last period
        else:
            sw = _SW_REMOTE[self.state] | (self.main_power * np.uint16(SW_VOLTAGE_ENABLED)) | self._sw_mode
            self._sw_last = sw
            self._sw_mode_last = self._sw_mode
        if plant.any_limited:
            sw = sw | limited * np.uint16(SW_INTERNAL_LIMIT)
        if count_nonzero(self.warning):
            sw = sw | self.warning * np.uint16(SW_WARNING)
        tx["statusword"] = sw
        shifted = self._shifted
        demand = self._demand_int if self._all_csp else np.rint(self._demand).astype(np.int64)
        tx["position_demand"] = demand + self.home_shift if shifted else demand
        tx["position_actual"] = self.position + self.home_shift if shifted else self.position
        v = self._t_vel
        np.subtract(self.position, prev_pos, out=v, casting="unsafe")
        v *= self._inv_T0
        np.rint(v, v)
        tx["velocity_actual"] = _saturate(v, _LIM32F)  # (the object's range)
        torque = _saturate(np.rint(plant.torque, self._t_trq), _LIM16F)
        tx["torque_actual"] = torque
        tx["torque_demand"] = torque if plant.demand_torque is plant.torque else \
            _saturate(np.rint(plant.demand_torque), _LIM16F)
        copyto(self._t_fe, self._fe)
        tx["following_error_actual"] = _saturate(self._t_fe, _LIM32I)
        if self._static_dirty or tx is not self._last_tx:
            # fields that change only with events (faults, modes, sensors, latches)
            self._static_dirty = False
            self._last_tx = tx
            tx["error_code"] = self.error_code
            tx["modes_display"] = self.mode_display
            p = self.probes
            tx["touch_probe_status"] = p.status
            tx["touch_probe_pos1"] = p.pos1
            tx["touch_probe_neg1"] = p.neg1
            tx["touch_probe_pos2"] = p.pos2
            tx["touch_probe_neg2"] = p.neg2
            tx["digital_inputs"] = self.digital_inputs
            tx["supported_drive_modes"] = np.where(self.cst_supported, SUPPORTED_MODES | SUPPORTED_CST,
                                                   SUPPORTED_MODES)
            if "_zero" in (tx.dtype.names or ()):
                tx["_zero"] = 0


# object ranges as 0-d arrays (lo, hi): numpy handles a Python scalar operand several times slower than an array
_LIM32F = (np.array(-2.0**31), np.array(2.0**31 - 1))
_LIM16F = (np.array(-2.0**15), np.array(2.0**15 - 1))
_LIM32I = (np.array(-2**31, dtype=np.int64), np.array(2**31 - 1, dtype=np.int64))


def _saturate(x: np.ndarray, limits: tuple[np.ndarray, np.ndarray]) -> np.ndarray:
    """Clamp x in place to the object's range (lo, hi); returns x. (Two ufunc calls: much cheaper than np.clip's
    wrapper on small arrays.)"""
    np.minimum(x, limits[1], out=x)  # (keyword: numpy deprecates positional outputs of minimum/maximum)
    return np.maximum(x, limits[0], out=x)
