"""Emulated EtherCAT network: a master and its slaves exchanging a bit-exact process image every primary period.

Start-up (invt-ivc5.md §2.2, codesys-lc1200.md §5.4): each slave goes Init → Pre-Op (identity checked against the
configuration, PDO assignment/mapping and the start-up SDO list written) → Safe-Op (inputs valid) → Op (outputs
applied). Topology is checked per slave and leniently (invt-ivc5.md §2.3, R2): a configured slave that is absent or
of another identity stays in Init with its reason; the others run.

One period (architecture.md): `exchange()` packs the master's output record of every slave in Op into its RxPDO
bytes by the slave's mapping and unpacks them into the device's record; the devices (CiA402 drives, encoder inputs)
run one period; their input records are packed into the TxPDO bytes and unpacked into the master's input record.
Only mapped objects cross; bytes are little-endian, entries packed back to back as the mapping lists them.

Drop-out and recovery (decision D29): a disconnected slave leaves the cyclic exchange at once (its inputs keep their
last value in the master's record, `pd_ok` is FALSE, the drive's sync-manager watchdog trips). When it is wired again
the master restarts it (Init → … → Op, one state per period, start-up SDOs written again) if the master setting
`auto_restart_slaves` is on, else when `connect()` is called (Omron's reconnect command) or the controller restarts.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..drives.cia402 import Cia402Drives, SensorLayout
from ..drives.encoder import EncoderInputs
from ..plant.ideal import Mechanics
from .config import ResolvedSlave
from .devices import DeviceDescription
from .library import BUILTIN_LIBRARY
from .objects import ENCODER_ALIASES, RX_DTYPE, RX_OBJECTS, TX_DTYPE, default_record, object_def
from .pdo import Layout, compile_layout, pack, unpack

# objects a servo axis needs in the mapping (omron-mc-basics.md §2.11 "Required objects"; else 3460)
SERVO_REQUIRED = (0x6040, 0x607A, 0x6041, 0x6064)
ENCODER_REQUIRED = (0x6064,)  # 4010h on an encoder input slave (aliased to 6064h)


class ESM(enum.IntEnum):
    """EtherCAT state machine states (AL status values)."""

    Init = 1
    PreOp = 2
    Boot = 3
    SafeOp = 4
    Op = 8


@dataclass
class Slave:
    position: int  # index on the bus (wiring order of the configuration)
    node_address: int
    name: str
    device: DeviceDescription
    resolved: ResolvedSlave
    kind: str  # servo / encoder / other
    row: int  # row in the records of its device model
    rx_layout: Layout
    tx_layout: Layout
    wired: bool = True  # physically on the wire (emulation)
    wired_device: DeviceDescription | None = None
    state: ESM = ESM.Init
    target: ESM = ESM.Op
    error: str = ""  # why the slave is not where it should be
    lost: bool = False  # dropped out after reaching Op
    connected_once: bool = False
    sdo_log: list[str] = field(default_factory=list)

    @property
    def identity(self) -> tuple[int, int]:
        return (self.device.vendor_id, self.device.product_code)


@dataclass
class _Group:
    """Slaves of one device model with the same layouts: one pack/unpack per period for all of them."""

    kind: str
    slaves: np.ndarray  # slave positions (rows of the master's records)
    rows: np.ndarray  # rows in the device model's records
    rx: Layout
    tx: Layout
    active: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=bool))
    inputs_valid: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=bool))
    all_active: bool = False
    any_active: bool = False
    all_valid: bool = False
    any_valid: bool = False
    slave_sel: Any = None  # `slaves` / `rows` as a slice when they are 0..n-1 in order (else the index arrays)
    row_sel: Any = None
    rx_img: np.ndarray = field(default_factory=lambda: np.zeros((0, 0), dtype=np.uint8))
    tx_img: np.ndarray = field(default_factory=lambda: np.zeros((0, 0), dtype=np.uint8))
    rx_copy: _Transfer | None = None  # compiled transfers of the whole group (every slave exchanging)
    tx_copy: _Transfer | None = None


class _Transfer:
    """One direction of a group compiled into flat byte indices: record bytes → image bytes (one gather) → record
    bytes (one scatter). Used when the layout has only whole, byte-aligned entries of their record field's width (the
    usual mappings); other layouts go through `pack`/`unpack` with their bit operations."""

    def __init__(self, layout: Layout, src: np.ndarray, src_rows: np.ndarray, dst: np.ndarray, dst_rows: np.ndarray,
                 img: np.ndarray) -> None:
        isz = src.dtype.itemsize
        assert dst.dtype.itemsize == isz and img.flags.c_contiguous
        self.src = src.view(np.uint8)
        self.dst = dst.view(np.uint8)
        self.img = img.reshape(-1)
        self.gather = (src_rows[:, None] * isz + layout.src[None, :]).reshape(-1)
        fast = layout.fast_img
        self.scatter = (dst_rows[:, None] * isz + layout.fast_rec[None, :]).reshape(-1)
        if fast.size == layout.nbytes:
            self.pick: np.ndarray | None = None  # every image byte is an object byte
        else:
            self.pick = (np.arange(len(src_rows))[:, None] * layout.nbytes + fast[None, :]).reshape(-1)

    def __call__(self) -> None:
        self.src.take(self.gather, None, self.img, "clip")  # (indices are valid; clip avoids a buffer)
        if self.pick is None:
            self.dst[self.scatter] = self.img
        else:
            self.dst[self.scatter] = self.img[self.pick]


def _sel(idx: np.ndarray, n: int) -> np.ndarray | slice:
    """A slice when `idx` is 0..n-1 in order (cheaper numpy indexing), else the index array."""
    if idx.size == n and (idx.size == 0 or (idx[0] == 0 and idx[-1] == n - 1 and np.all(np.diff(idx) == 1))):
        return slice(None)
    return idx


class Network:
    """Master plus N slaves. Row i of `rx`/`tx` is the master's view of slave i's objects."""

    def __init__(self, slaves: list[ResolvedSlave], sensors: SensorLayout | None = None, period_s: float = 0.001,
                 mechanics: Mechanics | None = None, *, auto_restart: bool = True,
                 library: Any = None) -> None:
        self.period_s = period_s
        self.auto_restart = auto_restart
        # (level, code, message, slave name) for the event log
        self.pending_events: list[tuple[str, str, str, str]] = []
        n = len(slaves)
        servo_pos = [k for k, s in enumerate(slaves) if s.device.kind == "servo"]
        enc_pos = [k for k, s in enumerate(slaves) if s.device.kind == "encoder"]
        self.slaves: list[Slave] = []
        row_of = {k: r for r, k in enumerate(servo_pos)} | {k: r for r, k in enumerate(enc_pos)}
        for k, rs in enumerate(slaves):
            cfg = rs.config
            kind = rs.device.kind
            rx_l = compile_layout(rs.device, rs.pdo, "rx", RX_DTYPE, kind)
            tx_l = compile_layout(rs.device, rs.pdo, "tx", TX_DTYPE, kind)
            wired_dev = None
            if cfg.emulation.wired_device is not None:
                wired_dev = (library or BUILTIN_LIBRARY).get(cfg.emulation.wired_device)
            name = cfg.name or f"E{cfg.node_address:03d}"
            self.slaves.append(Slave(k, cfg.node_address, name, rs.device, rs, kind, row_of.get(k, k), rx_l, tx_l,
                                     wired=cfg.emulation.connected, wired_device=wired_dev))
        self.index_of_node = {s.node_address: s.position for s in self.slaves}
        self.rx = np.zeros(n, dtype=RX_DTYPE)  # master outputs, written by the MC layer
        self.tx = np.zeros(n, dtype=TX_DTYPE)  # master inputs, read by the MC layer
        self.pd_ok = np.zeros(n, dtype=bool)  # process data communication established (Omron _EC_PDSlavTbl)
        self.servo_slaves = np.array(servo_pos, dtype=np.intp)
        self.encoder_slaves = np.array(enc_pos, dtype=np.intp)
        # device models: the CiA402 drives behind the servo slaves (and their mechanism), the encoder inputs
        sub = _subset_sensors(sensors, servo_pos) if sensors is not None else None
        mech = _subset_mechanics(mechanics, servo_pos) if mechanics is not None else None
        self.drives = Cia402Drives(len(servo_pos), sub, mech, period_s)
        self.plant = self.drives.plant
        self.drive_rx = default_record(RX_DTYPE, len(servo_pos), RX_OBJECTS)
        self.drive_tx = np.zeros(len(servo_pos), dtype=TX_DTYPE)
        enc_sensors = _subset_sensors(sensors, enc_pos) if sensors is not None else None
        self.encoders = EncoderInputs(len(enc_pos), enc_sensors, period_s)
        for k in enc_pos:
            self.encoders.velocity[row_of[k]] = slaves[k].config.emulation.encoder_velocity
        self.enc_rx = np.zeros(len(enc_pos), dtype=RX_DTYPE)
        self.enc_tx = np.zeros(len(enc_pos), dtype=TX_DTYPE)
        self.other_rx = np.zeros(n, dtype=RX_DTYPE)  # devices without a model: their bytes go nowhere
        self.other_tx = np.zeros(n, dtype=TX_DTYPE)
        self._online_servo = np.zeros(len(servo_pos), dtype=bool)
        self._online_enc = np.zeros(len(enc_pos), dtype=bool)
        self._groups = self._make_groups()
        self._changing = True
        for s in self.slaves:
            self._start_slave(s, at_power_up=True)
        self._refresh()
        # first inputs so that the MC layer reads the drives' power-on state in its first period
        self._run_devices()
        self._inputs()

    # ------------------------------------------------------------------ structure
    def _records(self, kind: str) -> tuple[np.ndarray, np.ndarray]:
        if kind == "servo":
            return self.drive_rx, self.drive_tx
        if kind == "encoder":
            return self.enc_rx, self.enc_tx
        return self.other_rx, self.other_tx

    def _make_groups(self) -> list[_Group]:
        by_sig: dict[tuple, list[Slave]] = {}
        for s in self.slaves:
            by_sig.setdefault((s.kind, s.rx_layout.signature, s.tx_layout.signature), []).append(s)
        groups = []
        for (kind, _, _), members in by_sig.items():
            g = _Group(kind, np.array([s.position for s in members], dtype=np.intp),
                       np.array([s.row for s in members], dtype=np.intp), members[0].rx_layout, members[0].tx_layout)
            g.slave_sel = _sel(g.slaves, len(self.slaves))
            g.row_sel = _sel(g.rows, len(self._records(kind)[0]))
            g.rx_img = np.zeros((len(members), g.rx.nbytes), dtype=np.uint8)
            g.tx_img = np.zeros((len(members), g.tx.nbytes), dtype=np.uint8)
            dev_rx, dev_tx = self._records(kind)
            if not g.rx.slow:
                g.rx_copy = _Transfer(g.rx, self.rx, g.slaves, dev_rx, g.rows, g.rx_img)
            if not g.tx.slow:
                g.tx_copy = _Transfer(g.tx, dev_tx, g.rows, self.tx, g.slaves, g.tx_img)
            groups.append(g)
        self._where = {}
        for gi, g in enumerate(groups):
            for k, pos in enumerate(g.slaves):
                self._where[int(pos)] = (gi, k)
        return groups

    def _refresh(self) -> None:
        """Recompute who exchanges what after a state change (rare)."""
        states = np.array([s.state for s in self.slaves], dtype=np.int8)
        op = (states == ESM.Op) & np.array([s.wired for s in self.slaves], dtype=bool)
        self.pd_ok[:] = op
        for g in self._groups:
            g.active = op[g.slaves]
            g.inputs_valid = (states[g.slaves] >= ESM.SafeOp) & np.array(
                [self.slaves[int(p)].wired for p in g.slaves], dtype=bool)
            g.all_active, g.any_active = bool(g.active.all()), bool(g.active.any())
            g.all_valid, g.any_valid = bool(g.inputs_valid.all()), bool(g.inputs_valid.any())
        if self.servo_slaves.size:
            self._online_servo[:] = op[self.servo_slaves]
        if self.encoder_slaves.size:
            self._online_enc[:] = op[self.encoder_slaves]
        self._changing = any(s.wired and s.state != s.target for s in self.slaves)

    # ------------------------------------------------------------------ ESM
    def _event(self, level: str, code: str, msg: str, slave: Slave) -> None:
        self.pending_events.append((level, code, msg, slave.name))

    def _start_slave(self, s: Slave, at_power_up: bool = False) -> None:
        """Init → Pre-Op → Safe-Op → Op; at power-up all at once (before the first period), else one step per
        period through `_step_esm`."""
        s.target = ESM.Op
        s.error = ""
        if at_power_up:
            while s.state != ESM.Op and self._esm_step(s):
                pass
        else:
            s.state = ESM.Init

    def _esm_step(self, s: Slave) -> bool:
        """One ESM transition towards Op. False when the slave cannot go further (it keeps its error)."""
        if not s.wired:
            if not s.error:
                s.error = "not found on the wire (configured, not connected)"
                self._event("minor fault", "84200000", f"slave {s.name} (node {s.node_address}): {s.error}", s)
            return False
        if s.state == ESM.Init:
            found = s.wired_device or s.device
            if (found.vendor_id, found.product_code) != s.identity:
                s.error = (f"identity mismatch: configured {s.device.name} (vendor {s.device.vendor_id:08X}h, product "
                           f"{s.device.product_code:08X}h), found {found.name} (vendor {found.vendor_id:08X}h, "
                           f"product {found.product_code:08X}h)")
                self._event("minor fault", "84210000", f"slave {s.name} (node {s.node_address}): {s.error}", s)
                return False
            s.state = ESM.PreOp
            return True
        if s.state == ESM.PreOp:
            if not self._write_startup_sdos(s):
                return False
            s.state = ESM.SafeOp
            return True
        if s.state == ESM.SafeOp:
            s.state = ESM.Op
            if s.connected_once:
                self._event("information", "00000000", f"slave {s.name} (node {s.node_address}) back in Op", s)
            s.connected_once = True
            s.lost = False
            return True
        return False

    def _write_startup_sdos(self, s: Slave) -> bool:
        """PDO assignment/mapping download (1C12h/1C13h, 16xxh/1Axxh) and the start-up SDO list, in order."""
        s.sdo_log = [f"1C12h ← {', '.join(f'{i:04X}h' for i in s.resolved.pdo.rx_assign) or '(none)'}",
                     f"1C13h ← {', '.join(f'{i:04X}h' for i in s.resolved.pdo.tx_assign) or '(none)'}"]
        rx, _ = self._records(s.kind)
        known = {(o.index, o.subindex) for o in s.device.objects}
        for k, sdo in enumerate(s.resolved.config.startup_sdos):
            key = (sdo.index, sdo.subindex)
            od = object_def(key, s.kind) if s.kind in ("servo", "encoder") else None
            if od is not None and od.direction == "rx":
                rx[od.field][s.row] = np.array(sdo.value).astype(rx.dtype[od.field])
                s.sdo_log.append(f"{sdo.index:04X}h:{sdo.subindex:02X}h ← {sdo.value}")
                continue
            if od is not None or key in known:
                if od is not None and od.direction == "tx":
                    reason = "06010002h attempt to write a read-only object"
                else:
                    s.sdo_log.append(f"{sdo.index:04X}h:{sdo.subindex:02X}h ← {sdo.value} (stored, no effect in the "
                                     "emulation)")
                    continue
            else:
                reason = "06020000h object does not exist in the object dictionary"
            s.sdo_log.append(f"{sdo.index:04X}h:{sdo.subindex:02X}h ← {sdo.value}: abort {reason}")
            if sdo.abort_on_error:
                s.error = f"start-up SDO line {k + 1} ({sdo.index:04X}h:{sdo.subindex:02X}h) aborted: {reason}"
                self._event("minor fault", "84220000", f"slave {s.name} (node {s.node_address}): {s.error}", s)
                return False
        return True

    def _step_esm(self) -> None:
        for s in self.slaves:
            if s.wired and s.state != s.target and not s.error:
                self._esm_step(s)
        self._refresh()

    # ------------------------------------------------------------------ faults (POST /api/v1/faults)
    def slave(self, node_address: int) -> Slave:
        k = self.index_of_node.get(node_address)
        if k is None:
            raise KeyError(node_address)
        return self.slaves[k]

    def disconnect(self, node_address: int) -> None:
        s = self.slave(node_address)
        if not s.wired:
            return
        s.wired = False
        if s.state >= ESM.SafeOp:
            s.lost = True
        s.state = ESM.Init
        s.error = "disconnected (no response: working counter error)"
        self._event("minor fault", "84230000", f"slave {s.name} (node {s.node_address}) disconnected", s)
        self._refresh()

    def reconnect(self, node_address: int) -> None:
        """The cable is plugged in again: the slave answers; the master restarts it if auto-restart is on."""
        s = self.slave(node_address)
        if s.wired:
            return
        s.wired = True
        s.error = "" if self.auto_restart else "on the wire again; waiting for a connect command (auto restart off)"
        if self.auto_restart:
            self._start_slave(s)
        self._refresh()

    def connect(self, node_address: int) -> None:
        """Omron's reconnect command: restart a wired slave that is not in Op."""
        s = self.slave(node_address)
        if not s.wired:
            raise ValueError(f"slave {s.name} (node {node_address}) is not on the wire")
        if s.state != ESM.Op:
            self._start_slave(s)
            self._refresh()

    def device_model(self, node_address: int) -> tuple[str, int]:
        s = self.slave(node_address)
        return s.kind, s.row

    # ------------------------------------------------------------------ one period
    def exchange(self) -> None:
        if self._changing:
            self._step_esm()
        self._outputs()
        self._run_devices()
        self._inputs()

    def _outputs(self) -> None:
        for g in self._groups:
            if not g.any_active:
                continue
            if g.all_active and g.rx_copy is not None:
                g.rx_copy()
                continue
            dev_rx, _ = self._records(g.kind)
            if g.all_active:
                img = pack(g.rx, self.rx, g.slave_sel)
                g.rx_img[:] = img
                unpack(g.rx, img, dev_rx, g.row_sel)
            else:
                a = g.active
                img = pack(g.rx, self.rx, g.slaves[a])
                g.rx_img[a] = img
                unpack(g.rx, img, dev_rx, g.rows[a])

    def _run_devices(self) -> None:
        if self.drives.n:
            self.drives.cycle(self.drive_rx, self.drive_tx, self._online_servo)
        if self.encoders.n:
            self.encoders.cycle(self.enc_rx, self.enc_tx, self._online_enc)

    def _inputs(self) -> None:
        for g in self._groups:
            if not g.any_valid:
                continue
            if g.all_valid and g.tx_copy is not None:
                g.tx_copy()
                continue
            valid = g.inputs_valid
            _, dev_tx = self._records(g.kind)
            if g.all_valid:
                img = pack(g.tx, dev_tx, g.row_sel)
                g.tx_img[:] = img
                unpack(g.tx, img, self.tx, g.slave_sel)
            else:
                img = pack(g.tx, dev_tx, g.rows[valid])
                g.tx_img[valid] = img
                unpack(g.tx, img, self.tx, g.slaves[valid])

    # ------------------------------------------------------------------ queries
    def mapped_objects(self, slave: int) -> frozenset[int]:
        """Object indices in the slave's PDO mapping (both directions), encoder-slave objects by their CiA402
        equivalents (4010h → 6064h …): instructions needing others give 3461."""
        s = self.slaves[slave]
        out = set()
        for e in (*s.rx_layout.entries, *s.tx_layout.entries):
            if e.index:
                out.add(ENCODER_ALIASES.get((e.index, e.subindex), (e.index, e.subindex))[0]
                        if s.kind == "encoder" else e.index)
        return frozenset(out)

    def image_bytes(self, slave: int) -> tuple[bytes, bytes]:
        """The RxPDO and TxPDO bytes of one slave as they last travelled on the wire."""
        gi, k = self._where[slave]
        g = self._groups[gi]
        return g.rx_img[k].tobytes(), g.tx_img[k].tobytes()


def _subset_sensors(sensors: SensorLayout, idx: list[int]) -> SensorLayout:
    out = SensorLayout(len(idx))
    for name in ("pos_limit", "neg_limit", "prox", "ext1", "ext2", "z_offset", "z_period"):
        setattr(out, name, getattr(sensors, name)[idx].copy())
    return out


def _subset_mechanics(mech: Mechanics, idx: list[int]) -> Mechanics:
    out = Mechanics(len(idx))
    for name, value in vars(mech).items():
        if isinstance(value, np.ndarray) and value.shape[:1] == (mech.n,):
            setattr(out, name, value[idx].copy())
    return out
