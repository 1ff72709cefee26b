"""PDO assignment and mapping: validation against the device description, and the bit-exact process image.

A slave's outputs (RxPDOs, 1600h–17FFh, assigned through 1C12h to the outputs sync manager) and inputs (TxPDOs,
1A00h–1BFFh, 1C13h, inputs sync manager) are the concatenation of the entries of the assigned PDOs in assignment
order, each entry `bit_len` bits wide, little-endian, with no alignment added (a padding entry — index 0 — is a gap).
`Layout` compiles that once into byte copies (entries on byte boundaries whose width equals the value record's
field) and bit operations (everything else: odd bit lengths, unaligned entries, width conversions), so one period's
pack/unpack of a group of slaves with the same layout is a handful of numpy operations.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from pydantic import Field

from ..modelbase import StrictModel
from .devices import DeviceDescription, PdoDescription
from .objects import DATA_TYPES, object_def

RX_RANGE = (0x1600, 0x17FF)
TX_RANGE = (0x1A00, 0x1BFF)
DEFAULT_SM_LIMIT = 1024  # bytes, when the device description gives no maximum sync manager size
MAX_MAPPING_ENTRIES = 254  # subindexes 1–254 of a mapping object (`PdoMappingConfig.entries`)
MAX_ASSIGNED = 254  # subindexes 1–254 of 1C12h/1C13h (`SlavePdoConfig.rx_assign`/`tx_assign`)


_Strict = StrictModel


class PdoEntryConfig(_Strict):
    index: int = Field(ge=0, le=0xFFFF, description="Object index; 0 = padding")
    subindex: int = Field(0, ge=0, le=255)
    bit_len: int = Field(ge=1, le=0xFFFF)


class PdoMappingConfig(_Strict):
    index: int = Field(ge=0x1600, le=0x1BFF, description="PDO mapping object (1600h–17FFh Rx, 1A00h–1BFFh Tx)")
    entries: list[PdoEntryConfig] = Field(default_factory=list, max_length=MAX_MAPPING_ENTRIES)


class SlavePdoConfig(_Strict):
    """What a slave exchanges: the PDO assignment (1C12h/1C13h) and the content of the assigned PDOs."""

    rx_assign: list[int] = Field(default_factory=list, max_length=MAX_ASSIGNED, description="1C12h: RxPDOs, in order")
    tx_assign: list[int] = Field(default_factory=list, max_length=MAX_ASSIGNED, description="1C13h: TxPDOs, in order")
    mappings: list[PdoMappingConfig] = Field(
        default_factory=list, description="Entries of the assigned PDOs (a PDO not listed has its description's)")


def default_pdo_config(device: DeviceDescription) -> SlavePdoConfig:
    """The device's default, as a configurator makes it from the ESI: the PDOs the description assigns to a sync
    manager (`Sm`) or marks mandatory, in file order, with their default entries — less those a PDO taken before
    excludes (or that exclude it), and less those that would map an object a PDO taken before already maps (vendor
    files mark alternatives with `Sm` too; a mandatory PDO is always taken). A direction where no PDO carries `Sm`
    takes the default assignment of the dictionary (1C12h/1C13h subindex defaults), when it names PDOs of the device.
    The result always passes `validate_pdo_config` as far as the description allows."""
    rx = _default_assignment(device, device.rx_pdos, 0x1C12)
    tx = _default_assignment(device, device.tx_pdos, 0x1C13)
    return SlavePdoConfig(
        rx_assign=[p.index for p in rx], tx_assign=[p.index for p in tx],
        mappings=[_mapping_of(p) for p in (*rx, *tx) if len(p.entries) <= MAX_MAPPING_ENTRIES])


def _default_assignment(device: DeviceDescription, pdos: list[PdoDescription], assign_object: int
                        ) -> list[PdoDescription]:
    marked = [p for p in pdos if p.sm is not None or p.mandatory]
    if not any(p.sm is not None for p in pdos):
        by_index = {p.index: p for p in pdos}
        from_dictionary = [by_index[i] for i in _dictionary_assignment(device, assign_object) if i in by_index]
        marked = [*from_dictionary, *(p for p in marked if p not in from_dictionary)]
    soe = _is_soe(device)
    taken: list[PdoDescription] = []
    mapped: set[tuple[int, int]] = set()
    for p in sorted(marked, key=lambda q: not q.mandatory):  # mandatory first, file order otherwise
        if not p.mandatory:
            if any(p.index in q.excludes or q.index in p.excludes for q in taken):
                continue
            if not (soe and p.esi_index is not None) and mapped & _objects_of(p):
                continue
        taken.append(p)
        mapped |= _objects_of(p)
        if len(taken) == MAX_ASSIGNED:
            break
    order = {p.index: k for k, p in enumerate(pdos)}
    return sorted(taken, key=lambda q: order[q.index])


def _objects_of(p: PdoDescription) -> set[tuple[int, int]]:
    return {(e.index, e.subindex) for e in p.entries if e.index}


def _dictionary_assignment(device: DeviceDescription, index: int) -> list[int]:
    """The PDO indexes of the dictionary's default value of 1C12h/1C13h (subindexes 1… up to subindex 0's value)."""
    subs = {o.subindex: o.default for o in device.objects if o.index == index}
    count = _int(subs.get(0))
    out: list[int] = []
    for k in range(1, (count if count is not None else len(subs)) + 1):
        value = _int(subs.get(k))
        if value:
            out.append(value)
    return out


def _int(text: str | None) -> int | None:
    if text is None:
        return None
    s = text.strip()
    try:
        return int(s[2:], 16) if s[:2].lower() in ("#x", "0x") else int(s)
    except ValueError:
        return None


def _is_soe(device: DeviceDescription) -> bool:
    """A Servo-over-EtherCAT drive: its PDOs are telegrams (MDT/AT) numbered by IDN in the ESI, and the same IDN
    (e.g. S-0-0134, the control word) appears in the telegram of each channel of a multi-axis drive."""
    return "SoE" in device.mailbox


def _mapping_of(p: PdoDescription) -> PdoMappingConfig:
    return PdoMappingConfig(index=p.index, entries=[
        PdoEntryConfig(index=e.index, subindex=e.subindex, bit_len=e.bit_len) for e in p.entries])


@dataclass(frozen=True)
class PdoIssue:
    """A validation error: `loc` is the path of the offending field inside the PDO configuration."""

    loc: tuple[str | int, ...]
    msg: str


def _entry_info(device: DeviceDescription, direction: str) -> dict[tuple[int, int], tuple[int, str, str]]:
    """(index, subindex) → (bit_len, name, data type) of the objects the device can map in `direction`."""
    flag = "R" if direction == "rx" else "T"
    info: dict[tuple[int, int], tuple[int, str, str]] = {}
    for o in device.objects:
        if flag in o.pdo_mapping.upper() and o.bit_len:
            info[(o.index, o.subindex)] = (o.bit_len, o.name, o.data_type)
    for p in device.rx_pdos if direction == "rx" else device.tx_pdos:
        for e in p.entries:
            if e.index:
                info.setdefault((e.index, e.subindex), (e.bit_len, e.name, e.data_type))
    return info


def effective_mappings(device: DeviceDescription, cfg: SlavePdoConfig) -> dict[int, list[PdoEntryConfig]]:
    given = {m.index: m.entries for m in cfg.mappings}
    out: dict[int, list[PdoEntryConfig]] = {}
    for idx in (*cfg.rx_assign, *cfg.tx_assign):
        if idx in given:
            out[idx] = list(given[idx])
        else:
            p = device.pdo(idx)
            out[idx] = _mapping_of(p).entries if p is not None else []
    return out


def validate_pdo_config(device: DeviceDescription, cfg: SlavePdoConfig) -> list[PdoIssue]:
    """Every rule a configurator checks before download: ranges, PDOs the device has, Fixed, Mandatory, Exclude,
    sync manager, entries the object dictionary allows, entry counts and sync manager sizes."""
    issues: list[PdoIssue] = []
    assigned: set[int] = set()
    for key, lst, (lo, hi), pdos in (("rx_assign", cfg.rx_assign, RX_RANGE, device.rx_pdos),
                                     ("tx_assign", cfg.tx_assign, TX_RANGE, device.tx_pdos)):
        known = {p.index for p in pdos}
        for k, idx in enumerate(lst):
            if not lo <= idx <= hi:
                issues.append(PdoIssue((key, k), f"{idx:04X}h is not a{'n Rx' if key == 'rx_assign' else ' Tx'}PDO "
                                                 f"({lo:04X}h–{hi:04X}h)"))
            elif idx not in known:
                issues.append(PdoIssue((key, k), f"{device.name} has no PDO {idx:04X}h"))
            elif idx in assigned:
                issues.append(PdoIssue((key, k), f"PDO {idx:04X}h is assigned twice"))
            assigned.add(idx)
        for p in pdos:
            if p.mandatory and p.index not in lst:
                issues.append(PdoIssue((key,), f"PDO {p.index:04X}h ({p.name}) is mandatory and must be assigned"))
    for p in (*device.rx_pdos, *device.tx_pdos):
        if p.index in assigned:
            for ex in p.excludes:
                if ex in assigned and ex > p.index:
                    issues.append(PdoIssue(("rx_assign" if p.index < 0x1A00 else "tx_assign",),
                                           f"PDO {p.index:04X}h excludes {ex:04X}h: they cannot be assigned together"))
    for k, m in enumerate(cfg.mappings):
        p = device.pdo(m.index)
        if p is None:
            issues.append(PdoIssue(("mappings", k, "index"), f"{device.name} has no PDO {m.index:04X}h"))
            continue
        direction = "rx" if m.index < 0x1A00 else "tx"
        if p.fixed:
            want = [(e.index, e.subindex, e.bit_len) for e in p.entries]
            got = [(e.index, e.subindex, e.bit_len) for e in m.entries]
            if want != got:
                issues.append(PdoIssue(("mappings", k, "entries"),
                                       f"PDO {m.index:04X}h is fixed: its entries cannot be changed"))
            continue
        if len(m.entries) > device.max_entries_per_pdo:
            issues.append(PdoIssue(("mappings", k, "entries"),
                                   f"PDO {m.index:04X}h takes at most {device.max_entries_per_pdo} entries"))
        info = _entry_info(device, direction)
        seen: set[tuple[int, int]] = set()
        for j, e in enumerate(m.entries):
            loc = ("mappings", k, "entries", j)
            if e.index == 0:
                continue  # padding
            key2 = (e.index, e.subindex)
            if key2 not in info:
                issues.append(PdoIssue((*loc, "index"), f"{e.index:04X}h:{e.subindex:02X}h cannot be mapped into "
                                       f"a{'n Rx' if direction == 'rx' else ' Tx'}PDO of {device.name}"))
                continue
            if info[key2][0] != e.bit_len:
                issues.append(PdoIssue((*loc, "bit_len"), f"{e.index:04X}h:{e.subindex:02X}h is {info[key2][0]} "
                                       f"bits, not {e.bit_len}"))
            if key2 in seen:
                issues.append(PdoIssue((*loc, "index"), f"{e.index:04X}h:{e.subindex:02X}h is mapped twice"))
            seen.add(key2)
    if issues:
        return issues
    # objects mapped twice across the PDOs of one direction, sizes, and wide unaligned entries
    maps = effective_mappings(device, cfg)
    telegrams = {p.index for p in (*device.rx_pdos, *device.tx_pdos) if p.esi_index is not None} \
        if _is_soe(device) else set()
    for key, lst, sm_type in (("rx_assign", cfg.rx_assign, "Outputs"), ("tx_assign", cfg.tx_assign, "Inputs")):
        bits = 0
        seen2: dict[tuple[int, int], int] = {}
        for idx in lst:
            for e in maps[idx]:
                if e.index:
                    if (e.index, e.subindex) in seen2 and not {idx, seen2[(e.index, e.subindex)]} <= telegrams:
                        issues.append(PdoIssue((key,), f"{e.index:04X}h:{e.subindex:02X}h is in both PDO "
                                                       f"{seen2[(e.index, e.subindex)]:04X}h and {idx:04X}h"))
                    seen2[(e.index, e.subindex)] = idx
                    if e.bit_len > 56 and bits % 8:
                        issues.append(PdoIssue((key,), f"{e.index:04X}h:{e.subindex:02X}h ({e.bit_len} bits) must "
                                                       "start on a byte boundary"))
                bits += e.bit_len
        sm = device.sm_of_type(sm_type)
        limit = sm.max_size if sm is not None and sm.max_size else DEFAULT_SM_LIMIT
        size = (bits + 7) // 8
        if size > limit:
            issues.append(PdoIssue((key,), f"the {sm_type.lower()} are {size} bytes; the sync manager takes at most "
                                           f"{limit}"))
    return issues


# ------------------------------------------------------------------------------------------------ process image
@dataclass(frozen=True)
class MappedEntry:
    pdo: int
    index: int
    subindex: int
    bit_offset: int
    bit_len: int
    name: str
    data_type: str
    field: str | None  # field of the value record, None: padding or an object the emulator does not model


@dataclass
class Layout:
    """Compiled layout of one direction of one slave: where each entry sits in the image and in the record."""

    entries: list[MappedEntry]
    nbytes: int
    record_dtype: np.dtype
    # fast path: image byte k ← record byte src[k] (record byte `zero` for bytes not on the fast path)
    src: np.ndarray = field(init=False)
    fast_img: np.ndarray = field(init=False)  # image bytes that are copies of record bytes …
    fast_rec: np.ndarray = field(init=False)  # … and the record bytes they come from / go to
    slow: list[tuple[str, int, int, bool, int]] = field(init=False)  # (field, bit offset, bit len, signed, width)

    def __post_init__(self) -> None:
        dt = self.record_dtype
        zero = dt.fields["_zero"][1]  # type: ignore[index]
        src = np.full(self.nbytes, zero, dtype=np.intp)
        slow: list[tuple[str, int, int, bool, int]] = []
        for e in self.entries:
            if e.field is None:
                continue
            fdt, foff = dt.fields[e.field][0], dt.fields[e.field][1]  # type: ignore[index]
            if e.bit_offset % 8 == 0 and e.bit_len == fdt.itemsize * 8:
                b = e.bit_offset // 8
                src[b:b + fdt.itemsize] = np.arange(foff, foff + fdt.itemsize)
            else:
                slow.append((e.field, e.bit_offset, e.bit_len, fdt.kind == "i", fdt.itemsize * 8))
        self.src = src
        fast = np.flatnonzero(src != zero)
        self.fast_img = fast
        self.fast_rec = src[fast]
        self.slow = slow

    @property
    def signature(self) -> tuple:
        return (self.nbytes, tuple((e.bit_offset, e.bit_len, e.field) for e in self.entries))


def compile_layout(device: DeviceDescription, cfg: SlavePdoConfig, direction: str, record_dtype: np.dtype,
                   kind: str) -> Layout:
    maps = effective_mappings(device, cfg)
    info = _entry_info(device, direction)
    entries: list[MappedEntry] = []
    bit = 0
    for pdo in cfg.rx_assign if direction == "rx" else cfg.tx_assign:
        for e in maps.get(pdo, []):
            name, dtype_name, fld = "", "", None
            if e.index:
                _, name, dtype_name = info.get((e.index, e.subindex), (e.bit_len, "", ""))
                od = object_def((e.index, e.subindex), kind) if kind in ("servo", "encoder") else None
                if od is not None and od.direction == direction and od.field in record_dtype.names:
                    fld = od.field
                    name = name or od.name
                    dtype_name = dtype_name or od.data_type
            entries.append(MappedEntry(pdo, e.index, e.subindex, bit, e.bit_len, name or ("padding" if not e.index
                                                                                          else ""), dtype_name, fld))
            bit += e.bit_len
    return Layout(entries, (bit + 7) // 8, record_dtype)


def _u8(rec: np.ndarray) -> np.ndarray:
    return rec.view(np.uint8).reshape(len(rec), rec.dtype.itemsize)


def pack(layout: Layout, rec: np.ndarray, rows: np.ndarray | slice) -> np.ndarray:
    """Image bytes (k × nbytes) of the record rows `rows`."""
    src = _u8(rec)[rows]
    img = np.zeros((src.shape[0], layout.nbytes + 8), dtype=np.uint8)
    img[:, :layout.nbytes] = src[:, layout.src]
    for fld, off, blen, _signed, _w in layout.slow:
        b, s = divmod(off, 8)
        v = rec[fld][rows].astype(np.int64).view(np.uint64) & np.uint64((1 << blen) - 1)
        word = (v << np.uint64(s)).astype("<u8")
        span = (s + blen + 7) // 8
        img[:, b:b + span] |= word.view(np.uint8).reshape(-1, 8)[:, :span]
    return img[:, :layout.nbytes]


def unpack(layout: Layout, img: np.ndarray, rec: np.ndarray, rows: np.ndarray | slice) -> None:
    """Write the objects of the image bytes (k × nbytes) into the record rows `rows`."""
    if layout.fast_img.size:
        u8 = _u8(rec)
        if isinstance(rows, slice):
            u8[rows, layout.fast_rec] = img[:, layout.fast_img]
        else:
            u8[rows[:, None], layout.fast_rec[None, :]] = img[:, layout.fast_img]
    if layout.slow:
        padded = np.zeros((img.shape[0], layout.nbytes + 8), dtype=np.uint8)
        padded[:, :layout.nbytes] = img
        for fld, off, blen, signed, width in layout.slow:
            b, s = divmod(off, 8)
            word = np.ascontiguousarray(padded[:, b:b + 8]).view("<u8").ravel()
            v = ((word >> np.uint64(s)) & np.uint64((1 << blen) - 1)).astype(np.int64)
            if signed and blen < 64:
                v = np.where(v >= (1 << (blen - 1)), v - (1 << blen), v)
            if width < 64:
                v = v & ((1 << width) - 1)  # keep the field's width (two's complement wrap)
                if signed:
                    v = np.where(v >= (1 << (width - 1)), v - (1 << width), v)
            rec[fld][rows] = v.astype(rec.dtype[fld])


def data_type_bits(name: str) -> int | None:
    t = DATA_TYPES.get(name.upper())
    return t[0] if t else None
