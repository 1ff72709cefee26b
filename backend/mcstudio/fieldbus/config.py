"""The network a project configures: its slaves (explicit, or one built-in device per servo/encoder axis), each with
its device description and PDO configuration resolved from the device library, and the project-level checks."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from ..controller.mc.enums import _eMC_AXIS_TYPE
from .builtin import ENCODER_ID, SERVO_ID
from .devices import DeviceDescription
from .library import BUILTIN_LIBRARY, DeviceLibrary
from .pdo import SlavePdoConfig, default_pdo_config, validate_pdo_config

if TYPE_CHECKING:  # project.models imports fieldbus.pdo
    from ..project.models import EtherCATSlaveConfig, Project


@dataclass
class ResolvedSlave:
    config: EtherCATSlaveConfig
    device: DeviceDescription
    pdo: SlavePdoConfig
    axis: str | None  # the axis using the slave, if any


def effective_slaves(project: Project) -> list[EtherCATSlaveConfig]:
    """The configured slaves; a project without an `ethercat.slaves` list gets one built-in device per axis with a
    node address (servo axes: CiA402 servo drive; encoder axes: encoder input), in node-address order."""
    from ..project.models import EtherCATSlaveConfig

    if project.ethercat.slaves:
        return list(project.ethercat.slaves)
    out = []
    for a in sorted((a for a in project.axes if a.node_address is not None), key=lambda a: a.node_address or 0):
        device = ENCODER_ID if a.type == _eMC_AXIS_TYPE._mcEncdr else SERVO_ID
        out.append(EtherCATSlaveConfig(node_address=a.node_address or 0, name=f"E{a.node_address:03d}",
                                       device=device))
    return out


def resolve_slaves(project: Project, library: DeviceLibrary | None = None) -> list[ResolvedSlave]:
    """Slaves with their device descriptions and PDO configurations (the project must have passed its checks)."""
    lib = library or BUILTIN_LIBRARY
    by_node = {a.node_address: a.name for a in project.axes if a.node_address is not None}
    out = []
    for s in effective_slaves(project):
        device = lib.get(s.device)
        if device is None:
            raise ValueError(f"unknown device {s.device!r}")
        pdo = s.pdo if s.pdo is not None else default_pdo_config(device)
        out.append(ResolvedSlave(s, device, pdo, by_node.get(s.node_address)))
    return out


def check_network(project: Project, library: DeviceLibrary | None = None) -> list[tuple[str, str]]:
    """(JSON path, message) for every problem of the network configuration and of the axes' slaves."""
    lib = library or BUILTIN_LIBRARY
    issues: list[tuple[str, str]] = []
    slaves = project.ethercat.slaves
    seen: dict[int, int] = {}
    kinds: dict[int, str] = {}
    for k, s in enumerate(slaves):
        base = f"ethercat.slaves[{k}]"
        if s.node_address in seen:
            issues.append((f"{base}.node_address",
                           f"node address {s.node_address} is already used by ethercat.slaves[{seen[s.node_address]}]"))
        seen.setdefault(s.node_address, k)
        device = lib.get(s.device)
        if device is None:
            issues.append((f"{base}.device", f"unknown device {s.device!r}; import its ESI file (POST /api/v1/esi) "
                                             f"or use one of: {lib.known_ids()}"))
            continue
        kinds[s.node_address] = device.kind
        if s.pdo is not None:
            for issue in validate_pdo_config(device, s.pdo):
                path = base + ".pdo" + "".join(f"[{p}]" if isinstance(p, int) else f".{p}" for p in issue.loc)
                issues.append((path, issue.msg))
        if s.emulation.wired_device is not None and lib.get(s.emulation.wired_device) is None:
            issues.append((f"{base}.emulation.wired_device", f"unknown device {s.emulation.wired_device!r}"))
    if not slaves:
        return issues
    for i, a in enumerate(project.axes):
        if a.node_address is None:
            continue
        path = f"axes[{i}].node_address"
        kind = kinds.get(a.node_address)
        if a.node_address not in seen:
            issues.append((path, f"no slave with node address {a.node_address} in ethercat.slaves"))
        elif kind is None:
            continue
        elif a.type == _eMC_AXIS_TYPE._mcServo and kind != "servo":
            issues.append((path, f"a servo axis needs a CiA402 servo drive; node {a.node_address} is "
                                 + ("an encoder input" if kind == "encoder" else "a device without a drive profile")))
        elif a.type == _eMC_AXIS_TYPE._mcEncdr and kind not in ("encoder", "servo"):
            issues.append((path, f"an encoder axis needs an encoder input or a servo drive; node {a.node_address} "
                                 "is a device without a drive or encoder profile"))
    return issues
