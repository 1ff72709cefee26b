"""Device descriptions: what an EtherCAT slave offers (identity, sync managers, PDOs, objects).

The same model describes the built-in devices (a generic CiA402 servo drive and an encoder input slave) and the
devices imported from ESI XML files (`fieldbus/esi.py`). It follows the ESI schema (ETG.2000): `Device/Type`
(ProductCode, RevisionNo), `Profile/ProfileNo`, `Sm`, `RxPdo`/`TxPdo` with `Fixed`, `Mandatory`, `Sm`,
`Exclude`, `Entry` (Index, SubIndex, BitLen, Name, DataType) and `Dictionary/Objects` (PdoMapping flags).
"""

from __future__ import annotations

from typing import Literal

from pydantic import Field

from ..modelbase import StrictModel

_M = StrictModel


class PdoEntryDescription(_M):
    index: int = Field(ge=0, le=0xFFFF, description="Object index; 0 = padding (a gap of bit_len bits)")
    subindex: int = Field(0, ge=0, le=255)
    bit_len: int = Field(ge=1, le=0xFFFF, description="Width in bits; entries wider than 64 bits (strings, byte "
                         "arrays, gaps) only reserve their bits in the process image")
    name: str = ""
    data_type: str = Field("", description="ESI data type name (UINT, DINT, BOOL …); empty for padding")


class PdoDescription(_M):
    index: int = Field(ge=0, le=0xFFFF, description="PDO mapping object: 1600h–17FFh (Rx) or 1A00h–1BFFh (Tx)")
    name: str = ""
    fixed: bool = Field(False, description="The entries cannot be changed")
    mandatory: bool = Field(False, description="Must be assigned")
    sm: int | None = Field(None, description="Sync manager the PDO is assigned to by default (None = not assigned)")
    excludes: list[int] = Field(default_factory=list, description="PDOs that cannot be assigned together with it")
    depend_on_slot: bool = Field(False, description="ESI DependOnSlot: the PDO belongs to a module slot")
    entries: list[PdoEntryDescription] = Field(default_factory=list)
    esi_index: int | None = Field(None, description="The index the ESI file gives, when the importer had to move "
                                  "the PDO into the Rx/Tx range (SoE drives number their MDT/AT by IDN)")

    @property
    def bit_size(self) -> int:
        return sum(e.bit_len for e in self.entries)


class SyncManagerDescription(_M):
    index: int
    type: Literal["MBoxOut", "MBoxIn", "Outputs", "Inputs", "Unknown"] = "Unknown"
    start_address: int | None = None
    default_size: int | None = None
    min_size: int | None = None
    max_size: int | None = None
    control_byte: int | None = None
    enable: bool = True


class ObjectDescription(_M):
    index: int
    subindex: int = 0
    name: str = ""
    data_type: str = ""
    bit_len: int = 0
    access: str = ""  # ro, rw, wo
    pdo_mapping: str = ""  # "", "R", "T", "RT" (ESI Flags/PdoMapping)
    default: str | None = None


class DeviceDescription(_M):
    id: str = Field(description="Library key: 'builtin:…' or 'esi:<vendor>:<product>:<revision>' (8 hex digits "
                    "each; ':<n>' added for the n-th different device of one file with the same identity)")
    name: str
    vendor_id: int
    vendor_name: str = ""
    product_code: int
    revision: int = 0
    profile: int | None = Field(None, description="CoE device profile number (402 = drive), if the ESI gives one")
    group: str = ""
    kind: Literal["servo", "encoder", "other"] = Field(
        "other", description="What the emulator runs for it: a CiA402 servo drive, an encoder input, or nothing "
        "(the slave exchanges its process image, no object behind it)")
    mailbox: list[str] = Field(default_factory=list, description="Mailbox protocols: CoE, SoE, FoE, EoE …")
    sync_managers: list[SyncManagerDescription] = Field(default_factory=list)
    rx_pdos: list[PdoDescription] = Field(default_factory=list)
    tx_pdos: list[PdoDescription] = Field(default_factory=list)
    objects: list[ObjectDescription] = Field(default_factory=list)
    max_entries_per_pdo: int = Field(32, description="Most entries one mapping object takes (its subindex 0 range)")
    source: str = Field("builtin", description="'builtin' or the ESI file name")

    def pdo(self, index: int) -> PdoDescription | None:
        return next((p for p in (*self.rx_pdos, *self.tx_pdos) if p.index == index), None)

    def sm_of_type(self, sm_type: str) -> SyncManagerDescription | None:
        return next((s for s in self.sync_managers if s.type == sm_type), None)


class VendorDescription(_M):
    id: int
    name: str = ""


class EsiFile(_M):
    """What one ESI file contains."""

    vendor: VendorDescription
    devices: list[DeviceDescription]
    warnings: list[str] = Field(default_factory=list, description="What was skipped and why")
