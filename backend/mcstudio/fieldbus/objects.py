"""The CoE objects MC Studio's emulated devices understand, and the value records that carry them.

Every slave has two *value records* on each side of the wire, one row per slave (numpy structured arrays):

* `RX_DTYPE` — outputs (RxPDO, master → slave): written by the MC layer into the master's record, packed into the
  slave's RxPDO bytes by its mapping, unpacked into the slave's record, read by the drive.
* `TX_DTYPE` — inputs (TxPDO, slave → master): written by the drive into its record, packed into the TxPDO bytes,
  unpacked into the master's record, read by the MC layer.

Only what the PDO mapping carries crosses the wire: an object that is not mapped keeps its start-up (SDO) value on
the slave side and reads 0 on the master side. The record field of an object is found through `FIELD_OF`, per
device kind (`ALIASES` lets an encoder input slave's vendor objects 4010h … land in the same fields).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class ObjectDef:
    index: int
    subindex: int
    name: str
    field: str  # field of the value record
    data_type: str  # IEC/ESI data type name
    direction: str  # "rx" (master → slave) or "tx" (slave → master)
    default: int = 0  # value in the slave's object dictionary at power-on

    @property
    def key(self) -> tuple[int, int]:
        return (self.index, self.subindex)


# data type → (bit length, numpy dtype of the value record, signed)
DATA_TYPES: dict[str, tuple[int, str, bool]] = {
    "BOOL": (1, "u1", False),
    "BIT1": (1, "u1", False), "BIT2": (2, "u1", False), "BIT3": (3, "u1", False), "BIT4": (4, "u1", False),
    "BIT5": (5, "u1", False), "BIT6": (6, "u1", False), "BIT7": (7, "u1", False), "BIT8": (8, "u1", False),
    "SINT": (8, "i1", True), "USINT": (8, "u1", False), "BYTE": (8, "u1", False),
    "INT": (16, "<i2", True), "UINT": (16, "<u2", False), "WORD": (16, "<u2", False),
    "DINT": (32, "<i4", True), "UDINT": (32, "<u4", False), "DWORD": (32, "<u4", False), "REAL": (32, "<f4", True),
    "LINT": (64, "<i8", True), "ULINT": (64, "<u8", False), "LWORD": (64, "<u8", False), "LREAL": (64, "<f8", True),
    "INTEGER8": (8, "i1", True), "UNSIGNED8": (8, "u1", False), "INTEGER16": (16, "<i2", True),
    "UNSIGNED16": (16, "<u2", False), "INTEGER32": (32, "<i4", True), "UNSIGNED32": (32, "<u4", False),
}

RX_OBJECTS: tuple[ObjectDef, ...] = (
    ObjectDef(0x6040, 0, "Controlword", "controlword", "UINT", "rx"),
    ObjectDef(0x6060, 0, "Modes of operation", "modes_of_operation", "SINT", "rx", 8),
    ObjectDef(0x607A, 0, "Target position", "target_position", "DINT", "rx"),
    ObjectDef(0x60FF, 0, "Target velocity", "target_velocity", "DINT", "rx"),
    ObjectDef(0x6071, 0, "Target torque", "target_torque", "INT", "rx"),
    ObjectDef(0x6072, 0, "Max torque", "max_torque", "UINT", "rx", 3000),
    ObjectDef(0x607F, 0, "Max profile velocity", "max_profile_velocity", "UDINT", "rx", 0),
    ObjectDef(0x60B8, 0, "Touch probe function", "touch_probe_function", "UINT", "rx"),
    ObjectDef(0x60E0, 0, "Positive torque limit value", "positive_torque_limit", "UINT", "rx", 3000),
    ObjectDef(0x60E1, 0, "Negative torque limit value", "negative_torque_limit", "UINT", "rx", 3000),
    ObjectDef(0x60B1, 0, "Velocity offset", "velocity_offset", "DINT", "rx"),
    ObjectDef(0x60B2, 0, "Torque offset", "torque_offset", "INT", "rx"),
    ObjectDef(0x6081, 0, "Profile velocity", "profile_velocity", "UDINT", "rx", 100000),
    ObjectDef(0x6083, 0, "Profile acceleration", "profile_acceleration", "UDINT", "rx", 1000000),
    ObjectDef(0x6084, 0, "Profile deceleration", "profile_deceleration", "UDINT", "rx", 1000000),
    ObjectDef(0x6085, 0, "Quick stop deceleration", "quick_stop_deceleration", "UDINT", "rx", 10000000),
    ObjectDef(0x6098, 0, "Homing method", "homing_method", "SINT", "rx", 0),
    ObjectDef(0x6099, 1, "Speed during search for switch", "homing_speed_fast", "UDINT", "rx", 100000),
    ObjectDef(0x6099, 2, "Speed during search for zero", "homing_speed_slow", "UDINT", "rx", 10000),
    ObjectDef(0x609A, 0, "Homing acceleration", "homing_acceleration", "UDINT", "rx", 1000000),
    ObjectDef(0x607C, 0, "Home offset", "home_offset", "DINT", "rx"),
    ObjectDef(0x6065, 0, "Following error window", "following_error_window", "UDINT", "rx", 3145728),
    ObjectDef(0x6066, 0, "Following error time out", "following_error_timeout", "UINT", "rx", 0),
    ObjectDef(0x6067, 0, "Position window", "position_window", "UDINT", "rx", 10),
    ObjectDef(0x6068, 0, "Position window time", "position_window_time", "UINT", "rx", 0),
    ObjectDef(0x60FE, 1, "Physical outputs", "physical_outputs", "UDINT", "rx"),
)

TX_OBJECTS: tuple[ObjectDef, ...] = (
    ObjectDef(0x603F, 0, "Error code", "error_code", "UINT", "tx"),
    ObjectDef(0x6041, 0, "Statusword", "statusword", "UINT", "tx"),
    ObjectDef(0x6061, 0, "Modes of operation display", "modes_display", "SINT", "tx"),
    ObjectDef(0x6062, 0, "Position demand value", "position_demand", "DINT", "tx"),
    ObjectDef(0x6064, 0, "Position actual value", "position_actual", "DINT", "tx"),
    ObjectDef(0x606C, 0, "Velocity actual value", "velocity_actual", "DINT", "tx"),
    ObjectDef(0x6074, 0, "Torque demand value", "torque_demand", "INT", "tx"),
    ObjectDef(0x6077, 0, "Torque actual value", "torque_actual", "INT", "tx"),
    ObjectDef(0x60B9, 0, "Touch probe status", "touch_probe_status", "UINT", "tx"),
    ObjectDef(0x60BA, 0, "Touch probe 1 positive edge", "touch_probe_pos1", "DINT", "tx"),
    ObjectDef(0x60BB, 0, "Touch probe 1 negative edge", "touch_probe_neg1", "DINT", "tx"),
    ObjectDef(0x60BC, 0, "Touch probe 2 positive edge", "touch_probe_pos2", "DINT", "tx"),
    ObjectDef(0x60BD, 0, "Touch probe 2 negative edge", "touch_probe_neg2", "DINT", "tx"),
    ObjectDef(0x60F4, 0, "Following error actual value", "following_error_actual", "DINT", "tx"),
    ObjectDef(0x60FD, 0, "Digital inputs", "digital_inputs", "UDINT", "tx"),
    ObjectDef(0x6502, 0, "Supported drive modes", "supported_drive_modes", "UDINT", "tx", 0x3AD),
)

# Encoder input slave (Omron GX-EC02xx style, omron-mc-basics.md §2.11 "Encoder axis"): vendor objects that land
# in the same record fields as the CiA402 objects an encoder axis reads.
ENCODER_ALIASES: dict[tuple[int, int], tuple[int, int]] = {
    (0x4010, 0): (0x6064, 0),  # position actual value (encoder)
    (0x4012, 0): (0x60BA, 0),  # latch position 1
    (0x4013, 0): (0x60BC, 0),  # latch position 2
    (0x4020, 0): (0x60B8, 0),  # latch function
    (0x4030, 0): (0x60B9, 0),  # latch status
}
ENCODER_OBJECTS: tuple[ObjectDef, ...] = (
    ObjectDef(0x4010, 0, "Encoder present position", "position_actual", "DINT", "tx"),
    ObjectDef(0x4012, 0, "Latch input 1 data", "touch_probe_pos1", "DINT", "tx"),
    ObjectDef(0x4013, 0, "Latch input 2 data", "touch_probe_pos2", "DINT", "tx"),
    ObjectDef(0x4030, 0, "Latch status", "touch_probe_status", "UINT", "tx"),
    ObjectDef(0x4020, 0, "Latch function", "touch_probe_function", "UINT", "rx"),
    ObjectDef(0x60FD, 0, "Digital inputs", "digital_inputs", "UDINT", "tx"),
)

_PAD = [("_zero", "u1")]  # one byte that is always 0: the source of padding bytes when packing
RX_DTYPE = np.dtype([(o.field, DATA_TYPES[o.data_type][1]) for o in RX_OBJECTS] + _PAD)
TX_DTYPE = np.dtype([(o.field, DATA_TYPES[o.data_type][1]) for o in TX_OBJECTS] + _PAD)

OBJECTS: dict[tuple[int, int], ObjectDef] = {o.key: o for o in (*RX_OBJECTS, *TX_OBJECTS)}
ENCODER_OBJECT_DEFS: dict[tuple[int, int], ObjectDef] = {o.key: o for o in ENCODER_OBJECTS}


def object_def(key: tuple[int, int], kind: str = "servo") -> ObjectDef | None:
    """The object an emulated device of `kind` ("servo" or "encoder") knows at index:subindex, if any."""
    if kind == "encoder":
        return ENCODER_OBJECT_DEFS.get(key)
    return OBJECTS.get(key)


def default_record(dtype: np.dtype, n: int, objects: tuple[ObjectDef, ...]) -> np.ndarray:
    """n rows of a value record with every object at its power-on default."""
    rec = np.zeros(n, dtype=dtype)
    for o in objects:
        if o.default:
            rec[o.field] = o.default
    return rec
