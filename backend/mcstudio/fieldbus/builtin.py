"""The built-in device descriptions: a generic CiA402 servo drive and a one-channel encoder input slave.

The servo drive offers what a typical EtherCAT servo does (modelled on Omron G5 / the LC1200 drive of
codesys-lc1200.md §5.2): one freely mappable RxPDO (1600h) and TxPDO (1A00h) whose default content is Omron's
default assignment (omron-mc-basics.md §2.11, 1704h/1B02h) plus 60FFh/606Ch, and fixed alternatives that exclude
them. Its object dictionary lists every object the emulated drive understands (`objects.py`) with its PDO mapping
direction.
"""

from __future__ import annotations

from .devices import (
    DeviceDescription,
    ObjectDescription,
    PdoDescription,
    PdoEntryDescription,
    SyncManagerDescription,
)
from .objects import DATA_TYPES, ENCODER_OBJECTS, OBJECTS, RX_OBJECTS, TX_OBJECTS

VENDOR_ID = 0x00004D43  # "MC": MC Studio's emulated devices
VENDOR_NAME = "MC Studio (emulated)"
SERVO_ID = "builtin:cia402-servo"
ENCODER_ID = "builtin:encoder-input"


def _e(index: int, sub: int = 0, objects: dict | None = None) -> PdoEntryDescription:
    o = (objects or OBJECTS)[(index, sub)]
    return PdoEntryDescription(index=index, subindex=sub, bit_len=DATA_TYPES[o.data_type][0], name=o.name,
                               data_type=o.data_type)


def _sms(out_max: int, in_max: int) -> list[SyncManagerDescription]:
    return [
        SyncManagerDescription(index=0, type="MBoxOut", start_address=0x1000, default_size=128, control_byte=0x26),
        SyncManagerDescription(index=1, type="MBoxIn", start_address=0x1080, default_size=128, control_byte=0x22),
        SyncManagerDescription(index=2, type="Outputs", start_address=0x1100, max_size=out_max, control_byte=0x64),
        SyncManagerDescription(index=3, type="Inputs", start_address=0x1180, max_size=in_max, control_byte=0x20),
    ]


def servo_drive() -> DeviceDescription:
    rx_default = [_e(0x6040), _e(0x607A), _e(0x60FF), _e(0x6071), _e(0x6060), _e(0x60B8), _e(0x607F), _e(0x60E0),
                  _e(0x60E1)]
    tx_default = [_e(0x603F), _e(0x6041), _e(0x6064), _e(0x606C), _e(0x6077), _e(0x6061), _e(0x60B9), _e(0x60BA),
                  _e(0x60BC), _e(0x60FD)]
    objects = [
        ObjectDescription(index=o.index, subindex=o.subindex, name=o.name, data_type=o.data_type,
                          bit_len=DATA_TYPES[o.data_type][0], access="rw" if o.direction == "rx" else "ro",
                          pdo_mapping="R" if o.direction == "rx" else "T", default=str(o.default))
        for o in (*RX_OBJECTS, *TX_OBJECTS)
    ]
    return DeviceDescription(
        id=SERVO_ID, name="Generic CiA402 Servo Drive", vendor_id=VENDOR_ID, vendor_name=VENDOR_NAME,
        product_code=0x00000402, revision=0x00010000, profile=402, group="Servo Drives", kind="servo",
        mailbox=["CoE"], sync_managers=_sms(64, 64), max_entries_per_pdo=16,
        rx_pdos=[
            PdoDescription(index=0x1600, name="Receive PDO mapping 1 (free)", sm=2, excludes=[0x1701, 0x1702],
                           entries=rx_default),
            PdoDescription(index=0x1701, name="CSP RxPDO", fixed=True, excludes=[0x1600, 0x1702],
                           entries=[_e(0x6040), _e(0x607A), _e(0x60B8), _e(0x60FE, 1)]),
            PdoDescription(index=0x1702, name="CSP/CSV/CST RxPDO", fixed=True, excludes=[0x1600, 0x1701],
                           entries=[_e(0x6040), _e(0x607A), _e(0x60FF), _e(0x6071), _e(0x6060), _e(0x60B8),
                                    _e(0x607F)]),
        ],
        tx_pdos=[
            PdoDescription(index=0x1A00, name="Transmit PDO mapping 1 (free)", sm=3, excludes=[0x1B01, 0x1B02],
                           entries=tx_default),
            PdoDescription(index=0x1B01, name="CSP TxPDO", fixed=True, excludes=[0x1A00, 0x1B02],
                           entries=[_e(0x603F), _e(0x6041), _e(0x6064), _e(0x6077), _e(0x60F4), _e(0x60FD)]),
            PdoDescription(index=0x1B02, name="CSP/CSV/CST TxPDO", fixed=True, excludes=[0x1A00, 0x1B01],
                           entries=[_e(0x603F), _e(0x6041), _e(0x6064), _e(0x6077), _e(0x6061), _e(0x60B9),
                                    _e(0x60BA), _e(0x60BC), _e(0x60FD)]),
        ],
        objects=objects,
    )


def encoder_input() -> DeviceDescription:
    enc = {o.key: o for o in ENCODER_OBJECTS}
    objects = [
        ObjectDescription(index=o.index, subindex=o.subindex, name=o.name, data_type=o.data_type,
                          bit_len=DATA_TYPES[o.data_type][0], access="rw" if o.direction == "rx" else "ro",
                          pdo_mapping="R" if o.direction == "rx" else "T")
        for o in ENCODER_OBJECTS
    ]
    return DeviceDescription(
        id=ENCODER_ID, name="Encoder Input (1 channel)", vendor_id=VENDOR_ID, vendor_name=VENDOR_NAME,
        product_code=0x00000E01, revision=0x00010000, profile=None, group="Encoder Inputs", kind="encoder",
        mailbox=["CoE"], sync_managers=_sms(16, 32), max_entries_per_pdo=8,
        rx_pdos=[PdoDescription(index=0x1600, name="Latch function", sm=2, fixed=True,
                                entries=[_e(0x4020, 0, enc)])],
        tx_pdos=[PdoDescription(index=0x1A00, name="Encoder inputs", sm=3, entries=[
            _e(0x4010, 0, enc), _e(0x4012, 0, enc), _e(0x4013, 0, enc), _e(0x4030, 0, enc), _e(0x60FD, 0, enc)])],
        objects=objects,
    )


BUILTIN_DEVICES: dict[str, DeviceDescription] = {d.id: d for d in (servo_drive(), encoder_input())}
