"""The device library of a project: the built-in devices plus the devices of the ESI files in `<project>/esi/`."""

from __future__ import annotations

import os
from pathlib import Path

from .builtin import BUILTIN_DEVICES, ENCODER_ID, SERVO_ID
from .devices import DeviceDescription, EsiFile

ESI_FOLDER = "esi"
MAX_ESI_BYTES = 100 * 1024 * 1024  # vendor catalogue files reach tens of MB (Beckhoff); ~12× in memory while parsed


class DeviceLibrary:
    def __init__(self, folder: str | os.PathLike[str] | None = None) -> None:
        self.devices: dict[str, DeviceDescription] = dict(BUILTIN_DEVICES)
        self.files: dict[str, EsiFile] = {}
        self.warnings: list[str] = []
        self.folder = Path(folder) if folder is not None else None
        if self.folder is not None:
            esi_dir = self.folder / ESI_FOLDER
            if esi_dir.is_dir():
                for path in sorted(esi_dir.glob("*.xml")):
                    self._load(path)

    def _load(self, path: Path) -> None:
        from .esi import EsiError, parse_esi

        try:
            esi = parse_esi(path.read_bytes(), source=path.name)
        except (OSError, EsiError) as err:
            self.warnings.append(f"{path.name}: {err}")
            return
        self.add(esi)

    def add(self, esi: EsiFile) -> None:
        for d in esi.devices:
            self.devices.setdefault(d.id, d)
        self.files[esi.devices[0].source if esi.devices else f"file{len(self.files)}"] = esi

    def get(self, device_id: str) -> DeviceDescription | None:
        return self.devices.get(device_id)

    def known_ids(self) -> str:
        ids = list(self.devices)
        return ", ".join(ids[:8]) + (f" … ({len(ids)} devices)" if len(ids) > 8 else "")


BUILTIN_LIBRARY = DeviceLibrary()

__all__ = ["BUILTIN_LIBRARY", "ENCODER_ID", "ESI_FOLDER", "MAX_ESI_BYTES", "SERVO_ID", "DeviceLibrary"]
