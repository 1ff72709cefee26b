"""EtherCAT: the network view, PDO configuration, ESI import, the device library and fault injection (api.md)."""

from __future__ import annotations

from typing import Any, Literal

from fastapi import APIRouter, Depends, File, HTTPException, UploadFile
from pydantic import BaseModel, Field

from ...controller.kernel import Controller
from ...fieldbus.config import effective_slaves
from ...fieldbus.devices import DeviceDescription, EsiFile, PdoDescription
from ...fieldbus.library import ESI_FOLDER, MAX_ESI_BYTES
from ...fieldbus.network import ESM, Network, Slave
from ...fieldbus.pdo import SlavePdoConfig, validate_pdo_config
from ...modelbase import StrictModel
from ...project.io import Issue, ProjectError, atomic_write, parse_project
from ...project.models import EtherCATConfig, EtherCATMasterConfig
from ..deps import get_studio
from ..state import ConflictError, Studio

router = APIRouter(tags=["ethercat"])


# ------------------------------------------------------------------------------------------------ models
class MappedEntryOut(BaseModel):
    index: int
    subindex: int
    bit_len: int
    name: str
    data_type: str
    bit_offset: int = Field(description="Offset in the slave's process image of its direction [bit]")
    byte_offset: float = Field(description="Offset as bytes.bits, e.g. 2.0 or 4.3")
    emulated: bool = Field(description="The emulated device reads/writes this object (else it travels as zeros)")


class PdoOut(BaseModel):
    index: int
    name: str
    fixed: bool
    mandatory: bool
    excludes: list[int]
    assigned: bool
    bit_size: int
    entries: list[MappedEntryOut]


class SlaveOut(BaseModel):
    position: int
    node_address: int
    name: str
    device_id: str
    device_name: str
    vendor_id: int
    vendor_name: str
    product_code: int
    revision: int
    profile: int | None
    kind: str
    axis: str | None
    state: Literal["Init", "PreOp", "Boot", "SafeOp", "Op"]
    wired: bool
    pd_ok: bool = Field(description="Process data communication established (Omron _EC_PDSlavTbl)")
    error: str
    drive_state: str | None = Field(None, description="CiA402 power drive system state (servo slaves)")
    drive_error_code: int | None = Field(None, description="603Fh of the drive (servo slaves)")
    rx_bytes: int
    tx_bytes: int
    rx_assign: list[int]
    tx_assign: list[int]
    rx_pdos: list[PdoOut]
    tx_pdos: list[PdoOut]
    startup_log: list[str]


class MasterOut(BaseModel):
    cycle_time_us: int = Field(description="The primary period")
    settings: EtherCATMasterConfig
    slaves_configured: int
    slaves_in_op: int
    explicit: bool = Field(description="The project lists its slaves (else one built-in device per axis)")


class EtherCATOut(BaseModel):
    master: MasterOut
    slaves: list[SlaveOut]


class ImageOut(BaseModel):
    node_address: int
    rx_hex: str = Field(description="RxPDO bytes (master → slave) as last sent, hex")
    tx_hex: str = Field(description="TxPDO bytes (slave → master) as last received, hex")
    cycle: int


class DeviceSummary(BaseModel):
    id: str
    name: str
    vendor_id: int
    vendor_name: str
    product_code: int
    revision: int
    profile: int | None
    kind: str
    source: str
    rx_pdos: int
    tx_pdos: int


class FaultIn(StrictModel):
    kind: Literal["slave_disconnect", "slave_reconnect", "drive_fault", "drive_fault_clear", "main_power_off",
                  "main_power_on", "encoder_velocity"] = Field(description="What happens on the machine")
    node_address: int = Field(ge=1, le=65534, description="The slave it happens to")
    code: int = Field(0x2310, ge=1, le=0xFFFF, description="drive_fault: the drive's 603Fh error code")
    persistent: bool = Field(False, description="drive_fault: the cause stays until drive_fault_clear")
    value: float = Field(0.0, ge=-1e9, le=1e9, description="encoder_velocity: pulses per second")


class FaultOut(BaseModel):
    kind: str
    node_address: int
    cycle: int
    slave_state: str


# ------------------------------------------------------------------------------------------------ views
_PDS_NAMES = ("NotReadyToSwitchOn", "SwitchOnDisabled", "ReadyToSwitchOn", "SwitchedOn", "OperationEnabled",
              "QuickStopActive", "FaultReactionActive", "Fault")


def _pdo_views(s: Slave, pdos: list[PdoDescription], assign: list[int], direction: str) -> list[PdoOut]:
    layout = s.rx_layout if direction == "rx" else s.tx_layout
    by_pdo: dict[int, list[MappedEntryOut]] = {}
    for e in layout.entries:
        by_pdo.setdefault(e.pdo, []).append(MappedEntryOut(
            index=e.index, subindex=e.subindex, bit_len=e.bit_len, name=e.name, data_type=e.data_type,
            bit_offset=e.bit_offset, byte_offset=float(f"{e.bit_offset // 8}.{e.bit_offset % 8}"),
            emulated=e.field is not None))
    out = []
    for p in pdos:
        assigned = p.index in assign
        entries = by_pdo.get(p.index) if assigned else None
        if entries is None:
            entries, bit = [], 0
            for e in p.entries:
                entries.append(MappedEntryOut(index=e.index, subindex=e.subindex, bit_len=e.bit_len, name=e.name,
                                              data_type=e.data_type, bit_offset=bit,
                                              byte_offset=float(f"{bit // 8}.{bit % 8}"), emulated=False))
                bit += e.bit_len
        out.append(PdoOut(index=p.index, name=p.name, fixed=p.fixed, mandatory=p.mandatory, excludes=p.excludes,
                          assigned=assigned, bit_size=sum(e.bit_len for e in entries), entries=entries))
    return out


def _slave_view(c: Controller, s: Slave) -> SlaveOut:
    net: Network = c.network
    d = s.device
    pdo = s.resolved.pdo
    drive_state, drive_code = None, None
    if s.kind == "servo" and net.drives.n:
        drive_state = _PDS_NAMES[int(net.drives.state[s.row])]
        drive_code = int(net.drive_tx["error_code"][s.row])
    return SlaveOut(
        position=s.position, node_address=s.node_address, name=s.name, device_id=d.id, device_name=d.name,
        vendor_id=d.vendor_id, vendor_name=d.vendor_name, product_code=d.product_code, revision=d.revision,
        profile=d.profile, kind=s.kind, axis=s.resolved.axis, state=ESM(s.state).name,  # type: ignore[arg-type]
        wired=s.wired, pd_ok=bool(net.pd_ok[s.position]), error=s.error, drive_state=drive_state,
        drive_error_code=drive_code, rx_bytes=s.rx_layout.nbytes, tx_bytes=s.tx_layout.nbytes,
        rx_assign=list(pdo.rx_assign), tx_assign=list(pdo.tx_assign),
        rx_pdos=_pdo_views(s, d.rx_pdos, pdo.rx_assign, "rx"), tx_pdos=_pdo_views(s, d.tx_pdos, pdo.tx_assign, "tx"),
        startup_log=list(s.sdo_log))


def _summary(d: DeviceDescription) -> DeviceSummary:
    return DeviceSummary(id=d.id, name=d.name, vendor_id=d.vendor_id, vendor_name=d.vendor_name,
                         product_code=d.product_code, revision=d.revision, profile=d.profile, kind=d.kind,
                         source=d.source, rx_pdos=len(d.rx_pdos), tx_pdos=len(d.tx_pdos))


# ------------------------------------------------------------------------------------------------ routes
@router.get("/ethercat", response_model=EtherCATOut, summary="Master settings and slaves (ESM state, PDO "
            "assignment and mapping with offsets, device identity)")
def get_ethercat(studio: Studio = Depends(get_studio)) -> EtherCATOut:
    def view(c: Controller) -> EtherCATOut:
        slaves = [_slave_view(c, s) for s in c.network.slaves]
        return EtherCATOut(master=MasterOut(
            cycle_time_us=c.project.controller.primary_period_us, settings=c.project.ethercat.master,
            slaves_configured=len(slaves), slaves_in_op=sum(1 for s in slaves if s.pd_ok),
            explicit=bool(c.project.ethercat.slaves)), slaves=slaves)

    return studio.runner.call(view)


@router.get("/ethercat/slaves/{address}/image", response_model=ImageOut,
            summary="The slave's process image bytes as they last travelled on the wire",
            responses={404: {"description": "No such slave"}})
def get_image(address: int, studio: Studio = Depends(get_studio)) -> ImageOut:
    def view(c: Controller) -> ImageOut:
        k = c.network.index_of_node.get(address)
        if k is None:
            raise HTTPException(status_code=404, detail=f"no slave with node address {address}")
        rx, tx = c.network.image_bytes(k)
        return ImageOut(node_address=address, rx_hex=rx.hex(), tx_hex=tx.hex(), cycle=c.cycle)

    return studio.runner.call(view)


def _apply_ethercat(studio: Studio, ethercat: EtherCATConfig) -> None:
    doc = studio.project.model_dump(mode="json")
    doc["ethercat"] = ethercat.model_dump(mode="json")
    project = parse_project(doc, studio.library)
    studio.apply_project(project)


def _explicit(studio: Studio) -> EtherCATConfig:
    """The project's network with its slaves listed (a project without a list gets its implicit slaves)."""
    cfg = studio.project.ethercat.model_copy(deep=True)
    if not cfg.slaves:
        cfg.slaves = effective_slaves(studio.project)
    return cfg


@router.put("/ethercat/slaves/{address}/pdo", response_model=SlaveOut,
            summary="Set a slave's PDO assignment and mapping",
            description="Validated against the device description (Fixed, Mandatory, Exclude, object dictionary, "
            "entry counts, sync manager sizes); each problem is a 422 entry whose `loc` names the field. Applying "
            "restarts the controller like a download (409 while an axis moves); POST /project/save keeps it.",
            responses={404: {"description": "No such slave"}, 409: {"description": "Axes are moving"}})
def put_pdo(address: int, body: SlavePdoConfig, studio: Studio = Depends(get_studio)) -> SlaveOut:
    cfg = _explicit(studio)
    k = next((i for i, s in enumerate(cfg.slaves) if s.node_address == address), None)
    if k is None:
        raise HTTPException(status_code=404, detail=f"no slave with node address {address}")
    device = studio.library.get(cfg.slaves[k].device)
    if device is None:
        raise ProjectError("the slave's device is not in the library",
                           [Issue(f"ethercat.slaves[{k}].device", f"unknown device {cfg.slaves[k].device!r}")])
    issues = validate_pdo_config(device, body)
    if issues:
        raise ProjectError("the PDO configuration is invalid", [
            Issue("".join(f"[{p}]" if isinstance(p, int) else (f".{p}" if n else p) for n, p in enumerate(i.loc)),
                  i.msg) for i in issues])
    cfg.slaves[k].pdo = body
    _apply_ethercat(studio, cfg)
    return studio.runner.call(lambda c: _slave_view(c, c.network.slaves[c.network.index_of_node[address]]))


@router.put("/ethercat", response_model=EtherCATOut, summary="Replace the network configuration (master settings "
            "and slaves)", description="Validated like the project document; restarts the controller (409 while "
            "an axis moves).", responses={409: {"description": "Axes are moving"}})
def put_ethercat(body: EtherCATConfig, studio: Studio = Depends(get_studio)) -> EtherCATOut:
    _apply_ethercat(studio, body)
    return get_ethercat(studio)


@router.post("/ethercat/slaves/{address}/connect", response_model=SlaveOut,
             summary="Reconnect a slave (Omron's reconnect command): restart it towards Op if it is on the wire",
             responses={404: {"description": "No such slave"}, 409: {"description": "Not on the wire"}})
def post_connect(address: int, studio: Studio = Depends(get_studio)) -> SlaveOut:
    def run(c: Controller) -> SlaveOut:
        k = c.network.index_of_node.get(address)
        if k is None:
            raise HTTPException(status_code=404, detail=f"no slave with node address {address}")
        try:
            c.network.connect(address)
        except ValueError as err:
            raise ConflictError(str(err)) from None
        return _slave_view(c, c.network.slaves[k])

    return studio.runner.call(run)


@router.get("/devices", response_model=list[DeviceSummary], summary="The device library (built-in and imported)")
def list_devices(studio: Studio = Depends(get_studio)) -> list[DeviceSummary]:
    return [_summary(d) for d in studio.library.devices.values()]


@router.get("/devices/{device_id}", response_model=DeviceDescription, summary="One device description",
            responses={404: {"description": "No such device in the library"}})
def get_device(device_id: str, studio: Studio = Depends(get_studio)) -> DeviceDescription:
    d = studio.library.get(device_id)
    if d is None:
        raise HTTPException(status_code=404, detail=f"no device {device_id!r} in the library")
    return d


@router.post("/esi", response_model=EsiFile, summary="Import an ESI XML file (multipart upload)",
             description="Every device of the file joins the device library; the file is kept in the project's "
             "`esi/` folder (written atomically). The answer lists each device's identity and PDOs (its object "
             "dictionary: GET /devices/{id}). Malformed XML is a 422 naming the line.",
             responses={413: {"description": "File too large"}, 422: {"description": "Not a valid ESI file"}})
async def post_esi(file: UploadFile = File(..., description="ESI XML file"),
                   studio: Studio = Depends(get_studio)) -> EsiFile:
    from ...fieldbus.esi import EsiError, parse_esi

    data = await file.read(MAX_ESI_BYTES + 1)
    if len(data) > MAX_ESI_BYTES:
        raise HTTPException(status_code=413, detail=f"ESI files are limited to {MAX_ESI_BYTES // (1024 * 1024)} MB")
    name = _safe_name(file.filename or "device.xml")
    try:
        esi = parse_esi(data, source=name)
    except EsiError as err:
        raise HTTPException(status_code=422, detail=[{"loc": ["body", "file"], "msg": str(err),
                                                      "type": "esi_error"}]) from None
    if studio.project_dir is not None:
        folder = studio.project_dir / ESI_FOLDER
        folder.mkdir(exist_ok=True)
        atomic_write(folder / name, data, keep_backup=False)
    studio.library.add(esi)
    # the object dictionaries stay in the library (GET /devices/{id}); the answer lists identities and PDOs
    return esi.model_copy(update={"devices": [d.model_copy(update={"objects": []}) for d in esi.devices]})


def _safe_name(name: str) -> str:
    """The file name the ESI is kept under in `esi/`: its base name, safe characters only, not hidden, ending in
    `.xml` in lower case (the project loads `esi/*.xml`; `Vendor.XML` would be imported now and missed on reopening)."""
    base = name.replace("\\", "/").rsplit("/", 1)[-1]
    keep = "".join(ch if ch.isalnum() or ch in "-_." else "_" for ch in base)[:100].lstrip(".")
    stem = keep[:-4] if keep.lower().endswith(".xml") else keep
    return (stem if stem.strip("._") else "device") + ".xml"


@router.post("/faults", response_model=FaultOut, summary="Fault injection for commissioning drills",
             description="slave_disconnect / slave_reconnect (the cable), drive_fault / drive_fault_clear (a drive "
             "alarm with its 603Fh code), main_power_off / main_power_on (the drive's main circuit), "
             "encoder_velocity (turn an encoder input slave's encoder).",
             responses={404: {"description": "No such slave"}, 422: {"description": "Not possible on that slave"}})
def post_fault(body: FaultIn, studio: Studio = Depends(get_studio)) -> FaultOut:
    def run(c: Controller) -> FaultOut:
        net = c.network
        k = net.index_of_node.get(body.node_address)
        if k is None:
            raise HTTPException(status_code=404, detail=f"no slave with node address {body.node_address}")
        s = net.slaves[k]
        kind = body.kind
        if kind == "slave_disconnect":
            net.disconnect(body.node_address)
        elif kind == "slave_reconnect":
            net.reconnect(body.node_address)
        elif kind == "encoder_velocity":
            if s.kind != "encoder":
                _not_for(s, "an encoder input slave", "kind")
            net.encoders.velocity[s.row] = body.value
        else:
            if s.kind != "servo":
                _not_for(s, "a servo drive", "kind")
            if kind == "drive_fault":
                net.drives.inject_fault(s.row, body.code, body.persistent)
            elif kind == "drive_fault_clear":
                net.drives.clear_fault_cause(s.row)
            else:
                net.drives.main_power[s.row] = kind == "main_power_on"
        c.events.add(cycle=c.cycle, time_s=c.time_s, source="fault injection", code="00000000",
                     level="information", message=f"{kind} on node {body.node_address}"
                     + (f" (603Fh {body.code:04X}h)" if kind == "drive_fault" else ""),
                     source_kind="slave", source_name=s.name)
        return FaultOut(kind=kind, node_address=body.node_address, cycle=c.cycle, slave_state=ESM(s.state).name)

    return studio.runner.call(run)


def _not_for(s: Slave, what: str, field: str) -> Any:
    raise HTTPException(status_code=422, detail=[{"loc": ["body", field], "type": "value_error",
                                                  "msg": f"node {s.node_address} ({s.device.name}) is not {what}"}])
