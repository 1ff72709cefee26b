"""PDO mapping: validation against the device description and the bit-exact process image (issue 4)."""

from __future__ import annotations

import numpy as np
import pytest

from mcstudio.fieldbus.builtin import servo_drive
from mcstudio.fieldbus.devices import DeviceDescription, ObjectDescription, PdoDescription, PdoEntryDescription
from mcstudio.fieldbus.objects import RX_DTYPE, TX_DTYPE
from mcstudio.fieldbus.pdo import (
    PdoEntryConfig,
    PdoMappingConfig,
    SlavePdoConfig,
    compile_layout,
    default_pdo_config,
    pack,
    unpack,
    validate_pdo_config,
)


def _odd_device() -> DeviceDescription:
    """A device whose free RxPDO maps 6060h and 607Ah at odd bit offsets (after a 4-bit gap)."""
    objs = [ObjectDescription(index=0x6040, name="Controlword", data_type="UINT", bit_len=16, pdo_mapping="R"),
            ObjectDescription(index=0x6060, name="Modes of operation", data_type="SINT", bit_len=8, pdo_mapping="R"),
            ObjectDescription(index=0x607A, name="Target position", data_type="DINT", bit_len=32, pdo_mapping="R"),
            ObjectDescription(index=0x6041, name="Statusword", data_type="UINT", bit_len=16, pdo_mapping="T"),
            ObjectDescription(index=0x6064, name="Position actual value", data_type="DINT", bit_len=32,
                              pdo_mapping="T")]
    return DeviceDescription(
        id="test:odd", name="Odd", vendor_id=1, product_code=2, kind="servo", objects=objs,
        rx_pdos=[PdoDescription(index=0x1600, name="free", sm=2, entries=[
            PdoEntryDescription(index=0x6040, bit_len=16, data_type="UINT"),
            PdoEntryDescription(index=0, bit_len=4),
            PdoEntryDescription(index=0x6060, bit_len=8, data_type="SINT"),
            PdoEntryDescription(index=0x607A, bit_len=32, data_type="DINT"),
            PdoEntryDescription(index=0, bit_len=4)])],
        tx_pdos=[PdoDescription(index=0x1A00, name="free", sm=3, entries=[
            PdoEntryDescription(index=0x6041, bit_len=16, data_type="UINT"),
            PdoEntryDescription(index=0x6064, bit_len=32, data_type="DINT")])])


def test_odd_bit_offsets_pack_to_hand_computed_bytes_and_back() -> None:
    """6040h=000Fh @0, 4-bit gap, 6060h=8 @20 (unaligned), 607Ah=−2 @28 (unaligned), 4-bit gap: 8 bytes.
    Byte 2 = low nibble of 6060h in its upper half (0x80); byte 3 = 6060h's high nibble (0) | 607Ah bits 0–3 (0xE)
    in the upper half; bytes 4–6 = 607Ah bits 4–27 (FF FF FF); byte 7 = 607Ah bits 28–31 (F)."""
    dev = _odd_device()
    layout = compile_layout(dev, default_pdo_config(dev), "rx", RX_DTYPE, "servo")
    assert layout.nbytes == 8
    assert [(e.bit_offset, e.bit_len) for e in layout.entries] == [(0, 16), (16, 4), (20, 8), (28, 32), (60, 4)]
    rec = np.zeros(2, dtype=RX_DTYPE)
    rec["controlword"] = 0x000F
    rec["modes_of_operation"] = [8, -3]
    rec["target_position"] = [-2, 0x12345678]
    img = pack(layout, rec, slice(None))
    assert img[0].tobytes() == bytes([0x0F, 0x00, 0x80, 0xE0, 0xFF, 0xFF, 0xFF, 0x0F])
    # -3 = FDh at bits 20..27; 12345678h at bits 28..59
    assert img[1].tobytes() == bytes([0x0F, 0x00, 0xD0, 0x8F, 0x67, 0x45, 0x23, 0x01])
    back = np.zeros(2, dtype=RX_DTYPE)
    unpack(layout, img, back, slice(None))
    assert back["controlword"].tolist() == [15, 15]
    assert back["modes_of_operation"].tolist() == [8, -3]
    assert back["target_position"].tolist() == [-2, 0x12345678]
    assert back["target_velocity"].tolist() == [0, 0], "unmapped objects do not cross"


def test_builtin_default_mapping_bytes() -> None:
    """Default RxPDO 1600h of the generic drive: 6040h UINT | 607Ah DINT | 60FFh DINT | 6071h INT | 6060h SINT |
    60B8h UINT | 607Fh UDINT | 60E0h UINT | 60E1h UINT = 23 bytes, little-endian, no alignment."""
    dev = servo_drive()
    layout = compile_layout(dev, default_pdo_config(dev), "rx", RX_DTYPE, "servo")
    rec = np.zeros(1, dtype=RX_DTYPE)
    rec["controlword"] = 0x000F
    rec["target_position"] = 0x01020304
    rec["target_velocity"] = -2
    rec["target_torque"] = 0x0A0B
    rec["modes_of_operation"] = 8
    rec["touch_probe_function"] = 0x0011
    rec["max_profile_velocity"] = 0x00010000
    rec["positive_torque_limit"] = 3000
    rec["negative_torque_limit"] = 1000
    rec["profile_velocity"] = 777  # not mapped: must not appear
    assert pack(layout, rec, slice(None))[0].tobytes() == bytes([
        0x0F, 0x00, 0x04, 0x03, 0x02, 0x01, 0xFE, 0xFF, 0xFF, 0xFF, 0x0B, 0x0A, 0x08, 0x11, 0x00, 0x00, 0x00, 0x01,
        0x00, 0xB8, 0x0B, 0xE8, 0x03])
    tx = compile_layout(dev, default_pdo_config(dev), "tx", TX_DTYPE, "servo")
    assert tx.nbytes == 2 + 2 + 4 + 4 + 2 + 1 + 2 + 4 + 4 + 4


def test_fast_path_rows_subset() -> None:
    dev = servo_drive()
    layout = compile_layout(dev, default_pdo_config(dev), "rx", RX_DTYPE, "servo")
    src = np.zeros(4, dtype=RX_DTYPE)
    src["target_position"] = [10, 20, 30, 40]
    dst = np.zeros(4, dtype=RX_DTYPE)
    rows = np.array([3, 1])
    unpack(layout, pack(layout, src, rows), dst, np.array([0, 2]))
    assert dst["target_position"].tolist() == [40, 0, 20, 0]


def _cfg(**kw: object) -> SlavePdoConfig:
    dev = servo_drive()
    base = default_pdo_config(dev).model_dump()
    base.update(kw)
    return SlavePdoConfig.model_validate(base)


@pytest.mark.parametrize(("cfg", "loc", "words"), [
    (dict(rx_assign=[0x1600, 0x1701]), ("rx_assign",), "excludes"),
    (dict(rx_assign=[0x1A00]), ("rx_assign", 0), "not an RxPDO"),
    (dict(rx_assign=[0x1655]), ("rx_assign", 0), "has no PDO 1655h"),
    (dict(rx_assign=[0x1600, 0x1600]), ("rx_assign", 1), "assigned twice"),
    (dict(rx_assign=[0x1701], mappings=[{"index": 0x1701, "entries": [{"index": 0x6040, "bit_len": 16}]}]),
     ("mappings", 0, "entries"), "fixed"),
    (dict(mappings=[{"index": 0x1600, "entries": [{"index": 0x6041, "bit_len": 16}]}]),
     ("mappings", 0, "entries", 0, "index"), "cannot be mapped into an RxPDO"),
    (dict(mappings=[{"index": 0x1600, "entries": [{"index": 0x607A, "bit_len": 16}]}]),
     ("mappings", 0, "entries", 0, "bit_len"), "32 bits, not 16"),
    (dict(mappings=[{"index": 0x1600, "entries": [{"index": 0x607A, "bit_len": 32}] * 2}]),
     ("mappings", 0, "entries", 1, "index"), "mapped twice"),
    (dict(mappings=[{"index": 0x1600, "entries": [{"index": 0x6040, "bit_len": 16}] + [
        {"index": 0, "bit_len": 8}] * 16}]), ("mappings", 0, "entries"), "at most 16 entries"),
    (dict(mappings=[{"index": 0x1600, "entries": [{"index": 0, "bit_len": 64}] * 9}]), ("rx_assign",),
     "sync manager takes at most 64"),
])
def test_invalid_edits_are_refused_with_the_field(cfg: dict, loc: tuple, words: str) -> None:
    issues = validate_pdo_config(servo_drive(), _cfg(**cfg))
    assert issues, "the edit must be refused"
    assert any(i.loc == loc and words in i.msg for i in issues), [(i.loc, i.msg) for i in issues]


def test_mandatory_pdo_must_be_assigned() -> None:
    dev = _odd_device()
    dev.tx_pdos[0].mandatory = True
    issues = validate_pdo_config(dev, SlavePdoConfig(rx_assign=[0x1600], tx_assign=[]))
    assert [i.loc for i in issues] == [("tx_assign",)] and "mandatory" in issues[0].msg


def test_valid_edit_passes_and_removes_an_object() -> None:
    cfg = SlavePdoConfig(rx_assign=[0x1600], tx_assign=[0x1A00], mappings=[
        PdoMappingConfig(index=0x1600, entries=[PdoEntryConfig(index=0x6040, bit_len=16),
                                                PdoEntryConfig(index=0, bit_len=3),
                                                PdoEntryConfig(index=0x60FE, subindex=1, bit_len=32)])])
    dev = servo_drive()
    assert validate_pdo_config(dev, cfg) == []
    layout = compile_layout(dev, cfg, "rx", RX_DTYPE, "servo")
    assert layout.nbytes == 7 and [e.index for e in layout.entries] == [0x6040, 0, 0x60FE]
