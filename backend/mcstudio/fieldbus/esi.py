"""Import of EtherCAT Slave Information files (ESI, ETG.2000) into device descriptions (`devices.py`).

`parse_esi` reads the vendor and every `Descriptions/Devices/Device` of an `EtherCATInfo` document: identity
(`Type` ProductCode/RevisionNo), name, group, profile number, mailbox protocols, sync managers, RxPDOs/TxPDOs with
their entries, and the CoE object dictionary (`Profile/Dictionary`). It is lenient with what real vendor files do
(hex as `#x…`, `0x…` or decimal, namespaces, several languages, missing optional values, Latin-1 text in a file
that claims UTF-8): what it cannot use is skipped and reported in `EsiFile.warnings`, each warning naming the place
in the file (`Descriptions/Devices/Device[2]/RxPdo[1]/Entry[3]: …`). Only a file that is not usable at all raises
`EsiError` (not well-formed XML — with its line —, another root element, no vendor id, no devices, a DOCTYPE).

DOCTYPE declarations are refused before parsing: no ESI needs one, and it is where entity declarations (entity
expansion, external entities) would come from. The parser is the standard library's `xml.etree.ElementTree`.
"""

from __future__ import annotations

import functools
import re
import xml.etree.ElementTree as ET
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from typing import Literal, TypedDict
from xml.parsers import expat

from pydantic import ValidationError

from .devices import DeviceDescription, EsiFile, VendorDescription

RX_RANGE = (0x1600, 0x17FF)
TX_RANGE = (0x1A00, 0x1BFF)
DEFAULT_MAX_ENTRIES = 32
MAX_ENTRY_BITS = 0xFFFF  # the model's bound (`PdoEntryDescription.bit_len`); a CoE mapping entry stores 8 bits
MAX_WARNINGS = 200
# Device descriptions per file (decision D122): vendor catalogues hold hundreds of device revisions; a file of tens of
# thousands of tiny devices would cost ~2.5 kB and ~0.2 ms each to import — refused before reading them.
MAX_ESI_DEVICES = 10_000
MAILBOX_PROTOCOLS = ("AoE", "EoE", "CoE", "FoE", "SoE", "VoE")
SM_TYPES = ("MBoxOut", "MBoxIn", "Outputs", "Inputs")
# Beckhoff's sync managers for dynamic process data (AX5000 SoE drives: `<Sm …>DynamicOutputs</Sm>`): known, carried
# as "Unknown" (no PDO is assigned to them by default), without a warning
SM_TYPES_OTHER = ("DynamicOutputs", "DynamicInputs")
ENGLISH = "1033"  # LcId of English (United States), the language ESI tools fall back to

_HEX_DIGITS = frozenset("0123456789abcdefABCDEF")
_WS = re.compile(r"\s*")
_XML_DECL = re.compile(r"<\?xml[\s?]")
_XMLNS = re.compile(r"xmlns(?::([\w.-]+))?\s*=")
_ENCODING = re.compile(r"""encoding\s*=\s*["']([A-Za-z0-9._-]+)["']""")

Warn = Callable[[str], None]


class EsiError(ValueError):
    """The file cannot be imported; the message says what is wrong and where (a line or a path in the file)."""


# ------------------------------------------------------------------------------------------------ entry point
def parse_esi(data: bytes, source: str = "") -> EsiFile:
    """Read an ESI file: its vendor, every device it describes and the warnings about what was skipped."""
    warnings = _Warnings()
    root = _read_xml(data, warnings.add)
    if root.tag != "EtherCATInfo":
        raise EsiError(f"the root element is <{root.tag}>, not <EtherCATInfo>: this is not an ESI file")
    vendor = _vendor(root)
    devices_el = root.find("Descriptions/Devices")
    device_els = devices_el.findall("Device") if devices_el is not None else []
    if not device_els:
        raise EsiError("Descriptions/Devices: the file describes no device (no Device element)")
    if len(device_els) > MAX_ESI_DEVICES:
        raise EsiError(f"Descriptions/Devices: {len(device_els)} devices; an ESI file may describe at most "
                       f"{MAX_ESI_DEVICES} (D122)")
    n_modules = len(root.findall("Descriptions/Modules/Module"))
    if n_modules:
        warnings.add(f"Descriptions/Modules: {n_modules} module description(s) not imported (modular devices get "
                     "their device-level PDOs only)")
    devices: list[DeviceDescription] = []
    seen: dict[str, list[tuple[str, DeviceDescription]]] = {}
    for k, el in enumerate(device_els, 1):
        path = f"Descriptions/Devices/Device[{k}]"
        try:
            dev = _DeviceReader(el, path, vendor, source, warnings.add).read()
        except Exception as err:  # a device the importer cannot make sense of must not stop the others
            warnings.add(f"{path}: device skipped: {_describe_exception(err)}")
            continue
        same = seen.setdefault(dev.id, [])
        if same:
            # vendors list one identity under several names (power ratings of one drive firmware): each different
            # description is kept, the later ones under '<id>:<n>'; an identical repetition is dropped
            twin = next((where for where, other in same if _same_description(other, dev)), None)
            if twin is not None:
                warnings.add(f"{path}: {dev.name!r} repeats {twin} (same identity {dev.id} and PDOs); skipped")
                continue
            new_id = f"{dev.id}:{len(same) + 1}"
            warnings.add(f"{path}: {dev.name!r} has the same identity ({dev.id}) as {same[0][0]}; imported as "
                         f"{new_id}")
            same.append((f"{path} ({dev.name!r})", dev))
            dev = dev.model_copy(update={"id": new_id})
        else:
            same.append((f"{path} ({dev.name!r})", dev))
        devices.append(dev)
    if not devices:
        raise EsiError("no device could be imported: " + "; ".join(warnings.items[:3]))
    return EsiFile(vendor=vendor, devices=devices, warnings=warnings.items)


def _same_description(a: DeviceDescription, b: DeviceDescription) -> bool:
    return (a.name, a.rx_pdos, a.tx_pdos, a.sync_managers) == (b.name, b.rx_pdos, b.tx_pdos, b.sync_managers)


@dataclass
class _Warnings:
    items: list[str] = field(default_factory=list)
    dropped: int = 0

    def add(self, msg: str) -> None:
        if len(self.items) < MAX_WARNINGS:
            self.items.append(msg)
            return
        self.dropped += 1
        note = f"… and {self.dropped} more warning(s)"
        if self.dropped == 1:
            self.items.append(note)
        else:
            self.items[-1] = note


def _describe_exception(err: Exception) -> str:
    if isinstance(err, ValidationError) and err.errors():
        e = err.errors()[0]
        loc = ".".join(str(x) for x in e["loc"])
        return f"{loc}: {e['msg']}" if loc else str(e["msg"])
    return f"{type(err).__name__}: {err}" if not isinstance(err, ValueError) else str(err)


# ------------------------------------------------------------------------------------------------ XML
def _read_xml(data: bytes, warn: Warn) -> ET.Element:
    if not data.strip():
        raise EsiError("line 1: the file is empty")
    utf16 = _utf16_codec(data)
    # Latin-1 keeps byte offsets (and the ASCII markup) of any ASCII-compatible encoding.
    text = data.decode(utf16, errors="replace") if utf16 else data.decode("latin-1")
    misplaced = _check_prolog(text)
    # UTF-16 (told by its byte order mark or its first bytes): parsed as text, whatever the declaration says — a
    # file an editor saved as "Unicode" keeps its `encoding="UTF-8"`, which the parser would refuse
    source: bytes | str = text.removeprefix("\ufeff") if utf16 else data
    declared = _declared_encoding(text)
    if misplaced is not None:
        start, end = misplaced
        line = text.count("\n", 0, start) + 1
        warn(f"line {line}: the XML declaration is not at the start of the file; it is ignored")
        keep_lines = "\n" * text.count("\n", start, end)
        if utf16:
            source = (text[:start] + keep_lines + text[end:]).removeprefix("\ufeff")
        else:
            raw = data[:start] + keep_lines.encode() + data[end:]
            source = _decode(raw, declared, warn)
    root = _parse(source, data, declared, utf16, warn)
    if _declares_namespaces(text):
        _strip_namespaces(root)
    return root


def _utf16_codec(data: bytes) -> str | None:
    if data[:2] in (b"\xff\xfe", b"\xfe\xff"):
        return "utf-16"  # the byte order mark tells the order
    if data[:2] == b"\x00<":
        return "utf-16-be"
    if data[:2] == b"<\x00":
        return "utf-16-le"
    return None


def _parse(source: bytes | str, data: bytes, declared: str | None, utf16: str | None, warn: Warn) -> ET.Element:
    try:
        return ET.fromstring(source)
    except ET.ParseError as err:
        failure = err
    except (LookupError, ValueError) as err:  # an encoding the parser does not know or support
        if not isinstance(source, bytes):
            raise EsiError(f"line 1: the file cannot be decoded: {err}") from None
        fallback = "UTF-8" if _is_utf8(data) else "Windows-1252"
        warn(f"line 1: the declared encoding {declared!r} is not supported; the file was read as {fallback}")
        source = data.decode("utf-8-sig") if fallback == "UTF-8" else _decode_cp1252(data)
        try:
            return ET.fromstring(source)
        except ET.ParseError as err2:
            failure = err2
    invalid_token = failure.code == expat.errors.codes[expat.errors.XML_ERROR_INVALID_TOKEN]
    if (isinstance(source, bytes) and not utf16 and invalid_token
            and (declared is None or declared.lower().replace("_", "-") in ("utf-8", "utf8"))
            and not _is_utf8(data)):
        warn("the file is not valid UTF-8 (as it declares or as XML assumes); it was read as Windows-1252")
        try:
            return ET.fromstring(_decode_cp1252(data))
        except ET.ParseError as err:
            failure = err
    raise EsiError(_xml_error(failure)) from None


def _check_prolog(text: str) -> tuple[int, int] | None:
    """Refuse a DOCTYPE; return the span of an XML declaration that is not at the start (some vendor files put a
    comment first), None if there is none."""
    pos = 0
    if text.startswith("\ufeff"):
        pos = 1
    elif text.startswith("\xef\xbb\xbf"):  # UTF-8 byte order mark seen through Latin-1
        pos = 3
    first = pos
    misplaced: tuple[int, int] | None = None
    n = len(text)
    while pos < n:
        match = _WS.match(text, pos)
        pos = match.end() if match else pos
        if text.startswith("<?", pos):
            end = text.find("?>", pos)
            if end < 0:
                break
            if _XML_DECL.match(text, pos) and pos != first:
                misplaced = (pos, end + 2)
            pos = end + 2
        elif text.startswith("<!--", pos):
            end = text.find("-->", pos + 4)
            if end < 0:
                break
            pos = end + 3
        elif text[pos:pos + 9].upper() == "<!DOCTYPE":
            line = text.count("\n", 0, pos) + 1
            raise EsiError(f"line {line}: DOCTYPE declarations are not accepted in ESI files (they can declare "
                           "ENTITY expansions or external entities)")
        else:
            break
    return misplaced


def _declared_encoding(text: str) -> str | None:
    start = text.find("<?xml")
    if start < 0 or start > 4096:
        return None
    end = text.find("?>", start)
    match = _ENCODING.search(text, start, end if end > 0 else start + 200)
    return match.group(1) if match else None


def _decode(raw: bytes, encoding: str | None, warn: Warn) -> str:
    try:
        return raw.decode(encoding or "utf-8-sig")
    except (LookupError, UnicodeDecodeError):
        warn(f"the file is not valid {encoding or 'UTF-8'}; it was read as Windows-1252")
        return _decode_cp1252(raw)


def _decode_cp1252(raw: bytes) -> str:
    try:
        return raw.decode("cp1252")
    except UnicodeDecodeError:  # bytes Windows-1252 leaves undefined
        return raw.decode("latin-1")


def _is_utf8(data: bytes) -> bool:
    try:
        data.decode("utf-8")
    except UnicodeDecodeError:
        return False
    return True


def _xml_error(err: ET.ParseError) -> str:
    line, column = err.position
    reason = expat.ErrorString(err.code) if err.code else str(err)
    return f"line {line}: not well-formed XML: {reason} (column {column + 1})"


def _declares_namespaces(text: str) -> bool:
    """Whether elements can carry a namespace: a default namespace or a prefix other than `xsi` (which real ESI
    files declare for `xsi:noNamespaceSchemaLocation` only)."""
    return any(prefix != "xsi" for prefix in _XMLNS.findall(text))


def _strip_namespaces(root: ET.Element) -> None:
    for el in root.iter():
        tag = el.tag
        if isinstance(tag, str) and tag[:1] == "{":
            el.tag = tag.split("}", 1)[1]
        if el.attrib and any(k[:1] == "{" for k in el.attrib):
            el.attrib = {k.split("}", 1)[1] if k[:1] == "{" else k: v for k, v in el.attrib.items()}


# ------------------------------------------------------------------------------------------------ values
@functools.lru_cache(maxsize=8192)  # the same few texts ("16", "#x01" …) come back thousands of times
def parse_int(value: str | None) -> int | None:
    """`#x1A00`, `#X1a00`, `0x1A00` (hex) or `6656` (decimal); None if missing or not a number."""
    if value is None:
        return None
    s = value.strip()
    if s[:2] in ("#x", "#X", "0x", "0X"):
        digits = s[2:]
        return int(digits, 16) if digits and _HEX_DIGITS.issuperset(digits) else None
    digits = s[1:] if s[:1] in ("+", "-") else s
    return int(s, 10) if digits.isascii() and digits.isdigit() else None


def parse_bool(value: str | None) -> bool | None:
    """ESI booleans: `1`/`0`/`true`/`false` (any case); None if missing or something else."""
    if value is None:
        return None
    s = value.strip().lower()
    if s in ("1", "true"):
        return True
    if s in ("0", "false"):
        return False
    return None


def _text(el: ET.Element | None) -> str:
    return (el.text or "").strip() if el is not None else ""


def _localized(el: ET.Element, tag: str = "Name") -> str:
    """The English text of the `tag` children (LcId 1033), else the first non-empty one."""
    first = ""
    for child in el.findall(tag):
        text = (child.text or "").strip()
        if not text:
            continue
        if child.get("LcId", "").strip() == ENGLISH:
            return text
        first = first or text
    return first


def _bool_of(el: ET.Element, attr: str, default: bool, path: str, warn: Warn) -> bool:
    raw = el.get(attr)
    if raw is None:
        return default
    value = parse_bool(raw)
    if value is None:
        warn(f"{path}: {attr}={raw!r} is not a boolean; {str(default).lower()} is used")
        return default
    return value


def _int_of(el: ET.Element, attr: str, path: str, warn: Warn) -> int | None:
    raw = el.get(attr)
    if raw is None or not raw.strip():
        return None
    value = parse_int(raw)
    if value is None:
        warn(f"{path}: {attr}={raw!r} is not a number; ignored")
    return value


def _u32(value: int) -> int | None:
    if -(1 << 31) <= value < 0:
        return value & 0xFFFFFFFF  # a signed rendering of a 32-bit identity value
    return value if value <= 0xFFFFFFFF else None


# ------------------------------------------------------------------------------------------------ vendor
def _vendor(root: ET.Element) -> VendorDescription:
    vendor = root.find("Vendor")
    if vendor is None:
        raise EsiError("Vendor: missing (an ESI file names its vendor)")
    raw = vendor.find("Id")
    if raw is None or not _text(raw):
        raise EsiError("Vendor/Id: missing")
    value = parse_int(raw.text)
    vendor_id = _u32(value) if value is not None else None
    if vendor_id is None:
        raise EsiError(f"Vendor/Id: {_text(raw)!r} is not a 32-bit number (#x…, 0x… or decimal)")
    return VendorDescription(id=vendor_id, name=_localized(vendor))


# ------------------------------------------------------------------------------------------------ devices
# A device is gathered as plain data and validated once (`DeviceDescription.model_validate`): one call into
# pydantic per device instead of one per entry and object keeps a large file fast.
class _Entry(TypedDict):
    """A `PdoEntryDescription`."""

    index: int
    subindex: int
    bit_len: int
    name: str
    data_type: str


class _Object(TypedDict):
    """An `ObjectDescription`."""

    index: int
    subindex: int
    name: str
    data_type: str
    bit_len: int
    access: str
    pdo_mapping: str
    default: str | None


@dataclass
class _Pdo:
    """A PDO while its device is read (the index may still move into the Rx/Tx range)."""

    index: int
    name: str
    fixed: bool
    mandatory: bool
    sm: int | None
    excludes: list[int]
    depend_on_slot: bool
    entries: list[_Entry]
    esi_index: int | None = None


class _DeviceReader:
    def __init__(self, el: ET.Element, path: str, vendor: VendorDescription, source: str, warn: Warn) -> None:
        self.el = el
        self.path = path
        self.vendor = vendor
        self.source = source
        self.warn = warn

    def read(self) -> DeviceDescription:
        el = self.el
        product, revision, type_text = self._identity()
        name = _localized(el) or type_text or f"Device {product:08X}"
        profiles = self._profiles()
        objects = self._objects()
        object_types = {(o["index"], o["subindex"]): o["data_type"] for o in objects if o["data_type"]}
        rx = self._pdos("RxPdo", object_types)
        tx = self._pdos("TxPdo", object_types)
        max_entries = self._max_entries(rx + tx, objects)
        moved = [f"{tag} {old:04X}h → {new:04X}h" for tag, pdos, bounds in (("RxPdo", rx, RX_RANGE),
                                                                               ("TxPdo", tx, TX_RANGE))
                 for old, new in _fit_range(pdos, bounds).items()]
        if moved:
            self.warn(f"{self.path}: PDO indexes outside 1600h–17FFh (Rx) / 1A00h–1BFFh (Tx) are imported as "
                      f"{', '.join(moved)} (the ESI index stays in esi_index)")
        # a CiA402 drive maps its control word 6040h:00 into an RxPDO or its status word 6041h:00 into a TxPDO;
        # index 6040h alone is not enough: Beckhoff's MDP 742 terminals (EL7xxx) report "POS Status" as 6040h:01…
        servo = 402 in profiles or any((e["index"], e["subindex"]) == (0x6040, 0) for p in rx for e in p.entries) \
            or any((e["index"], e["subindex"]) == (0x6041, 0) for p in tx for e in p.entries)
        kind: Literal["servo", "other"] = "servo" if servo else "other"
        return DeviceDescription.model_validate({
            "id": f"esi:{self.vendor.id:08X}:{product:08X}:{revision:08X}",
            "name": name,
            "vendor_id": self.vendor.id,
            "vendor_name": self.vendor.name,
            "product_code": product,
            "revision": revision,
            "profile": profiles[0] if profiles else None,
            "group": _text(el.find("GroupType")),
            "kind": kind,
            "mailbox": self._mailbox(),
            "sync_managers": self._sync_managers(),
            "rx_pdos": [_pdo_data(p) for p in rx],
            "tx_pdos": [_pdo_data(p) for p in tx],
            "objects": objects,
            "max_entries_per_pdo": max_entries,
            "source": self.source,
        })

    # -- identity
    def _identity(self) -> tuple[int, int, str]:
        type_el = self.el.find("Type")
        where = f"{self.path}/Type"
        if type_el is None:
            self.warn(f"{where}: missing; product code and revision number 0 are used")
            return 0, 0, ""
        values = []
        for attr in ("ProductCode", "RevisionNo"):
            raw = type_el.get(attr)
            value = parse_int(raw)
            value = _u32(value) if value is not None else None
            if value is None:
                what = "missing" if raw is None or not raw.strip() else f"{raw!r} is not a 32-bit number"
                self.warn(f"{where}: {attr} {what}; 0 is used")
                value = 0
            values.append(value)
        return values[0], values[1], _text(type_el)

    def _profiles(self) -> list[int]:
        found: list[int] = []
        for k, prof in enumerate(self.el.findall("Profile"), 1):
            for no in (*prof.findall("ProfileNo"), *prof.iterfind("ChannelInfo/ProfileNo")):
                value = parse_int(no.text)
                if value is None:
                    self.warn(f"{self.path}/Profile[{k}]/ProfileNo: {_text(no)!r} is not a number; ignored")
                elif value not in found:
                    found.append(value)
        return found

    def _mailbox(self) -> list[str]:
        box = self.el.find("Mailbox")
        if box is None:
            return []
        protocols: list[str] = []
        for child in box:
            if child.tag in MAILBOX_PROTOCOLS and child.tag not in protocols:
                protocols.append(child.tag)
        return protocols

    def _sync_managers(self) -> list[dict[str, object]]:
        """`SyncManagerDescription`s, by order (the type from the text, else from the ControlByte)."""
        out: list[dict[str, object]] = []
        for k, sm in enumerate(self.el.findall("Sm")):
            where = f"{self.path}/Sm[{k + 1}]"
            values = {attr: _int_of(sm, attr, where, self.warn)
                      for attr in ("StartAddress", "DefaultSize", "MinSize", "MaxSize", "ControlByte")}
            text = _text(sm)
            sm_type = next((t for t in SM_TYPES if t.lower() == text.lower()), None)
            if sm_type is None and any(t.lower() == text.lower() for t in SM_TYPES_OTHER):
                sm_type = "Unknown"
            if sm_type is None:
                sm_type = _sm_type_of_control_byte(values["ControlByte"]) if not text else None
                if sm_type is None:
                    self.warn(f"{where}: sync manager type {text!r} not recognised; 'Unknown' is used")
                    sm_type = "Unknown"
            out.append({"index": k, "type": sm_type, "start_address": values["StartAddress"],
                        "default_size": values["DefaultSize"], "min_size": values["MinSize"],
                        "max_size": values["MaxSize"], "control_byte": values["ControlByte"],
                        "enable": _bool_of(sm, "Enable", True, where, self.warn)})
        return out

    # -- PDOs
    def _pdos(self, tag: str, object_types: dict[tuple[int, int], str]) -> list[_Pdo]:
        out: list[_Pdo] = []
        seen: set[int] = set()
        for k, pel in enumerate(self.el.findall(tag), 1):
            where = f"{self.path}/{tag}[{k}]"
            pdo = self._pdo(pel, where, object_types)
            if pdo is None:
                continue
            if pdo.index in seen:
                self.warn(f"{where}: a second {tag} {pdo.index:04X}h; the first one is kept")
                continue
            seen.add(pdo.index)
            out.append(pdo)
        return out

    def _pdo(self, pel: ET.Element, where: str, object_types: dict[tuple[int, int], str]) -> _Pdo | None:
        index_el = pel.find("Index")
        index = parse_int(index_el.text) if index_el is not None else None
        if index is None or not 0 <= index <= 0xFFFF:
            what = "missing" if index_el is None or not _text(index_el) else f"{_text(index_el)!r} is not an index"
            self.warn(f"{where}/Index: {what}; PDO skipped")
            return None
        sm = _int_of(pel, "Sm", where, self.warn)
        excludes: list[int] = []
        for j, ex in enumerate(pel.findall("Exclude"), 1):
            value = parse_int(ex.text)
            if value is None or not 0 <= value <= 0xFFFF:
                self.warn(f"{where}/Exclude[{j}]: {_text(ex)!r} is not a PDO index; ignored")
            elif value not in excludes:
                excludes.append(value)
        depend = (parse_bool(pel.get("DependOnSlot")) is True
                  or (index_el is not None and (parse_bool(index_el.get("DependOnSlot")) is True
                                                or parse_bool(index_el.get("DependOnSlotGroup")) is True))
                  or any(parse_bool(d.text or "1") is not False for d in pel.findall("DependOnSlot")))
        entries: list[_Entry] = []
        for j, entry in enumerate(pel.findall("Entry"), 1):
            entries.extend(self._entry(entry, f"{where}/Entry[{j}]", object_types))
        return _Pdo(index=index, name=_localized(pel), fixed=_bool_of(pel, "Fixed", False, where, self.warn),
                    mandatory=_bool_of(pel, "Mandatory", False, where, self.warn), sm=sm, excludes=excludes,
                    depend_on_slot=depend, entries=entries)

    def _entry(self, entry: ET.Element, where: str,
               object_types: dict[tuple[int, int], str]) -> list[_Entry]:
        bit_len = parse_int(entry.findtext("BitLen"))
        if bit_len is None or not 0 < bit_len <= MAX_ENTRY_BITS:
            self.warn(f"{where}/BitLen: {entry.findtext('BitLen')!r} is not a bit length; entry skipped")
            return []
        name = _localized(entry)
        raw_index = entry.findtext("Index")
        index = parse_int(raw_index)
        sub_text = entry.findtext("SubIndex")
        subindex = parse_int(sub_text) if sub_text is not None and sub_text.strip() else 0
        if index is None or not 0 <= index <= 0xFFFF or subindex is None or not 0 <= subindex <= 255:
            self.warn(f"{where}: index {raw_index!r}, subindex {sub_text!r} not understood; the entry is kept as a "
                      f"gap of {bit_len} bits")
            return _padding(bit_len, name)
        if index == 0:
            return _padding(bit_len, name)
        # wider than 64 bits (a STRING, an ARRAY OF BYTE in a gateway's or IO-Link master's PDO): kept as it is —
        # the process image reserves its bits; no emulated object is that wide
        data_type = _text(entry.find("DataType")) or object_types.get((index, subindex), "")
        return [{"index": index, "subindex": subindex, "bit_len": bit_len, "name": name, "data_type": data_type}]

    def _max_entries(self, pdos: Iterable[_Pdo], objects: list[_Object]) -> int:
        """Subindex count of the mapping objects of the configurable PDOs, when the dictionary describes them."""
        subs: dict[int, int] = {}
        for o in objects:
            if o["subindex"] >= 1:
                subs[o["index"]] = subs.get(o["index"], 0) + 1
        best = 0
        longest = 0
        for p in pdos:
            if not p.fixed:
                best = max(best, subs.get(p.index, 0))
                longest = max(longest, len(p.entries))
        return min(254, max(best or DEFAULT_MAX_ENTRIES, longest))

    # -- object dictionary
    def _objects(self) -> list[_Object]:
        out: list[_Object] = []
        for k, prof in enumerate(self.el.findall("Profile"), 1):
            if prof.find("DictionaryFile") is not None:
                self.warn(f"{self.path}/Profile[{k}]/DictionaryFile: a dictionary in a separate file "
                          f"({_text(prof.find('DictionaryFile'))}) is not read")
            for dictionary in prof.findall("Dictionary"):
                out.extend(_Dictionary(dictionary, f"{self.path}/Profile[{k}]/Dictionary", self.warn).objects())
        unique: dict[tuple[int, int], _Object] = {}
        for o in out:
            unique.setdefault((o["index"], o["subindex"]), o)
        return list(unique.values())


def _fit_range(pdos: list[_Pdo], bounds: tuple[int, int]) -> dict[int, int]:
    """Move the PDOs whose index lies outside the Rx/Tx range into it, to the first free indexes (SoE drives number
    their MDT/AT by IDN, e.g. 0018h/0010h), and follow the moves in the exclusion lists; returns old → new."""
    lo, hi = bounds
    used = {p.index for p in pdos if lo <= p.index <= hi}
    moved: dict[int, int] = {}
    free = lo
    for p in pdos:
        if lo <= p.index <= hi:
            continue
        while free in used:
            free += 1
        if free > hi:
            break
        moved[p.index] = free
        p.esi_index, p.index = p.index, free
        used.add(free)
    if moved:
        for p in pdos:
            p.excludes = [moved.get(x, x) for x in p.excludes]
    return moved


def _padding(bit_len: int, name: str = "") -> list[_Entry]:
    """A gap of `bit_len` bits (one entry, as the file gives it)."""
    return [{"index": 0, "subindex": 0, "bit_len": bit_len, "name": name, "data_type": ""}]


def _pdo_data(p: _Pdo) -> dict[str, object]:
    """A `PdoDescription`."""
    return {"index": p.index, "name": p.name, "fixed": p.fixed, "mandatory": p.mandatory, "sm": p.sm,
            "excludes": p.excludes, "depend_on_slot": p.depend_on_slot, "entries": p.entries,
            "esi_index": p.esi_index}


def _sm_type_of_control_byte(control: int | None) -> str | None:
    """ControlByte bits 0–1: 00 buffered, 10 mailbox; bits 2–3: 01 written by the master (outputs)."""
    if control is None:
        return None
    mode, write = control & 0x03, (control >> 2) & 0x03 == 1
    if mode == 0x02:
        return "MBoxOut" if write else "MBoxIn"
    if mode == 0x00:
        return "Outputs" if write else "Inputs"
    return None


@dataclass
class _Sub:
    subindex: int
    name: str
    data_type: str
    bit_len: int
    flags: ET.Element | None
    from_array: bool = False


class _Dictionary:
    """`Profile/Dictionary`: objects, their sub-items expanded from `DataTypes` (records and arrays)."""

    def __init__(self, el: ET.Element, path: str, warn: Warn) -> None:
        self.el = el
        self.path = path
        self.warn = warn
        self.types: dict[str, ET.Element] = {}
        for dt in el.iterfind("DataTypes/DataType"):
            self.types.setdefault(_text(dt.find("Name")), dt)

    def objects(self) -> list[_Object]:
        out: list[_Object] = []
        for k, obj in enumerate(self.el.iterfind("Objects/Object"), 1):
            where = f"{self.path}/Objects/Object[{k}]"
            index = parse_int(obj.findtext("Index"))
            if index is None or not 0 <= index <= 0xFFFF:
                self.warn(f"{where}/Index: {obj.findtext('Index')!r} is not an object index; object skipped")
                continue
            try:
                out.extend(self._object(obj, index))
            except (ValueError, TypeError) as err:
                self.warn(f"{where}: object {index:04X}h skipped: {_describe_exception(err)}")
        return out

    def _object(self, obj: ET.Element, index: int) -> list[_Object]:
        name = _localized(obj)
        type_name = _text(obj.find("Type"))
        bit_len = parse_int(obj.findtext("BitSize")) or 0
        flags = obj.find("Flags")
        info = obj.find("Info")
        subs = self._subitems(type_name)
        if not subs:
            return [{"index": index, "subindex": 0, "name": name, "data_type": type_name, "bit_len": max(bit_len, 0),
                     "access": _access(flags), "pdo_mapping": _pdo_mapping(flags), "default": _default(info)}]
        info_subs = [(_localized(s), _default(s.find("Info"))) for s in info.findall("SubItem")] \
            if info is not None else []
        by_name = {n: d for n, d in info_subs if n}
        positional = len(info_subs) == len(subs)
        out: list[_Object] = []
        for k, s in enumerate(subs):
            sub_name, default = s.name, by_name.get(s.name)
            if positional:
                info_name, default = info_subs[k]
                if s.from_array and info_name:
                    sub_name = info_name
            sub_flags = s.flags if s.flags is not None else flags
            out.append({"index": index, "subindex": s.subindex, "name": sub_name, "data_type": s.data_type,
                        "bit_len": max(s.bit_len, 0), "access": _access(sub_flags) or _access(flags),
                        "pdo_mapping": _pdo_mapping(sub_flags), "default": default})
        return out

    def _subitems(self, type_name: str) -> list[_Sub]:
        dt = self.types.get(type_name)
        if dt is None:
            return []
        if dt.find("SubItem") is None:
            if dt.find("ArrayInfo") is not None:  # an array type used directly: elements from LBound on
                return self._array(dt, "", dt.find("Flags"), 0)
            return []
        out: list[_Sub] = []
        previous = -1
        for si in dt.findall("SubItem"):
            name = _localized(si)
            sub_type = _text(si.find("Type"))
            sub_bits = parse_int(si.findtext("BitSize")) or 0
            flags = si.find("Flags")
            subindex = parse_int(si.findtext("SubIdx"))
            sub_dt = self.types.get(sub_type)
            if subindex is None and sub_dt is not None and sub_dt.find("ArrayInfo") is not None:
                elements = self._array(sub_dt, name, flags, previous + 1)
                out.extend(elements)
                previous = elements[-1].subindex if elements else previous
                continue
            if subindex is None:
                subindex = previous + 1
            if 0 <= subindex <= 255:
                out.append(_Sub(subindex, name, sub_type, sub_bits, flags))
            previous = subindex
        return out

    def _array(self, dt: ET.Element, name: str, flags: ET.Element | None, first: int) -> list[_Sub]:
        arr = dt.find("ArrayInfo")
        if arr is None:
            return []
        lbound = parse_int(arr.findtext("LBound"))
        count = parse_int(arr.findtext("Elements")) or 0
        start = lbound if lbound is not None else max(first, 1)
        base = _text(dt.find("BaseType"))
        base_dt = self.types.get(base)
        total = parse_int(dt.findtext("BitSize")) or 0
        each = (parse_int(base_dt.findtext("BitSize")) if base_dt is not None else None) or \
            (total // count if count else 0)
        last = min(start + count, 256)  # subindexes end at 255, whatever Elements says
        return [_Sub(sub, f"{name} {sub}".strip(), base, each, flags, from_array=True)
                for sub in range(max(start, 0), last)]


def _access(flags: ET.Element | None) -> str:
    return _text(flags.find("Access")).lower() if flags is not None else ""


def _pdo_mapping(flags: ET.Element | None) -> str:
    raw = _text(flags.find("PdoMapping")).upper() if flags is not None else ""
    return ("R" if "R" in raw else "") + ("T" if "T" in raw else "")


def _default(info: ET.Element | None) -> str | None:
    if info is None:
        return None
    value = info.findtext("DefaultValue")
    if value is not None and value.strip():
        return value.strip()
    text = info.findtext("DefaultString")
    if text is not None:
        return text
    data = (info.findtext("DefaultData") or "").strip()
    if data:
        try:
            raw = bytes.fromhex(data)
        except ValueError:
            return data
        return str(int.from_bytes(raw, "little")) if len(raw) <= 8 else data
    return None


__all__ = ["EsiError", "parse_bool", "parse_esi", "parse_int"]
