"""The conveyor of the 3-D view: a belt along X of its coordinate system, cleats that move with the conveyor axis,
and the workpieces the plant reports (`omron-robot-delta3.md` §12.8: "conveyor direction = X of the selected CS").

`ConveyorSpec` says where it is (a UCS pose, mm/deg) and how big; `ConveyorView.set(position, workpieces)` moves the
cleats to the conveyor axis position (mm) and puts the workpieces (x, y, z in the conveyor CS, mm; z = 0 on the
belt) — call it inside the caller's `server.atomic()`.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..controller.mc.kinematics import Delta3Workspace, UserCoordSystem
from .geometry import MM, box, merge, quat_from_matrix

BELT_COLOR = (52, 56, 64)
FRAME_COLOR = (150, 156, 166)
CLEAT_COLOR = (96, 104, 118)
WORKPIECE_COLOR = (64, 192, 87)
MAX_WORKPIECES = 64  # instances kept in the batched mesh; unused ones are scaled to zero


@dataclass(frozen=True)
class ConveyorSpec:
    """Where the conveyor is: `frame` = its coordinate system (X along the belt, Z up, origin on the belt surface
    at the middle); sizes in mm."""

    frame: UserCoordSystem
    length: float = 1600.0
    width: float = 400.0
    height: float = 800.0  # belt surface above the floor
    cleat_pitch: float = 100.0
    workpiece_size: tuple[float, float, float] = (60.0, 60.0, 40.0)

    @classmethod
    def under(cls, workspace: Delta3Workspace | None) -> ConveyorSpec:
        """The default place: along Xm under the robot, its surface at the workspace's bottom face, so the
        workspace stands on the belt and workpieces on it are within reach."""
        if workspace is None:
            return cls(frame=UserCoordSystem(Tz=-600.0))
        length = max(1000.0, 2.0 * workspace.Rcy + 600.0)
        return cls(frame=UserCoordSystem(Tz=workspace.z_bottom), length=length,
                   width=max(200.0, 1.0 * workspace.Rcy))


class ConveyorView:
    def __init__(self, server: Any, spec: ConveyorSpec, *, root: str = "/conveyor") -> None:
        self.server = server
        self.spec = spec
        self.root = root
        scene = server.scene
        L, W, H = spec.length, spec.width, spec.height
        self.frame = scene.add_frame(root, wxyz=quat_from_matrix(spec.frame.R), position=spec.frame.T * MM,
                                     show_axes=False)
        belt_t = 30.0
        body = merge(
            box((L, W, belt_t), (0.0, 0.0, -0.5 * belt_t)),
        )
        rail = 0.08 * W
        legs = [box((40.0, 40.0, H - belt_t), (sx * (0.5 * L - 60.0), sy * (0.5 * W + 0.5 * rail), -0.5 * (H + belt_t)))
                for sx in (-1, 1) for sy in (-1, 1)]
        frame = merge(box((L + 40.0, rail, 60.0), (0.0, 0.5 * (W + rail), -20.0)),
                      box((L + 40.0, rail, 60.0), (0.0, -0.5 * (W + rail), -20.0)), *legs)
        self.belt = scene.add_mesh_simple(f"{root}/belt", body.vertices * MM, body.faces, color=BELT_COLOR,
                                          flat_shading=True)
        self.body = scene.add_mesh_simple(f"{root}/frame", frame.vertices * MM, frame.faces, color=FRAME_COLOR,
                                          flat_shading=True)
        self.n_cleats = max(1, int(L // spec.cleat_pitch))
        cleat = box((0.15 * spec.cleat_pitch, W * 0.98, 4.0), (0.0, 0.0, 2.0))
        self.cleats = scene.add_batched_meshes_simple(
            f"{root}/cleats", cleat.vertices * MM, cleat.faces,
            batched_wxyzs=np.tile([1.0, 0.0, 0.0, 0.0], (self.n_cleats, 1)),
            batched_positions=self._cleat_positions(0.0), batched_colors=CLEAT_COLOR, lod="off")
        wp = box(spec.workpiece_size, (0.0, 0.0, 0.5 * spec.workpiece_size[2]))
        self.workpieces = scene.add_batched_meshes_simple(
            f"{root}/workpieces", wp.vertices * MM, wp.faces,
            batched_wxyzs=np.tile([1.0, 0.0, 0.0, 0.0], (MAX_WORKPIECES, 1)),
            batched_positions=np.zeros((MAX_WORKPIECES, 3)), batched_scales=np.zeros(MAX_WORKPIECES),
            batched_colors=WORKPIECE_COLOR, lod="off")
        self.position = 0.0
        self.workpiece_count = 0
        self.label = scene.add_label(f"{root}/label", "Conveyor (X of its coordinate system)",
                                     position=(0.5 * L * MM, 0.5 * W * MM, 0.05))

    def _cleat_positions(self, position: float) -> np.ndarray:
        L, pitch = self.spec.length, self.spec.cleat_pitch
        x = np.mod(np.arange(self.n_cleats) * pitch + position, self.n_cleats * pitch) - 0.5 * L
        return np.stack([x, np.zeros_like(x), np.zeros_like(x)], axis=-1) * MM

    def set(self, position: float, workpieces: Sequence[Sequence[float]] | None = None) -> None:
        """Conveyor axis position (mm) and the workpieces (x, y, z) mm in the conveyor CS (None: unchanged); more
        than `MAX_WORKPIECES` are not drawn."""
        if position != self.position:
            self.cleats.batched_positions = self._cleat_positions(position)
            self.position = position
        if workpieces is None:
            return
        pts = np.zeros((MAX_WORKPIECES, 3))
        scales = np.zeros(MAX_WORKPIECES)
        n = min(len(workpieces), MAX_WORKPIECES)
        if n:
            pts[:n] = np.asarray(workpieces[:n], dtype=np.float64)[:, :3] * MM
            scales[:n] = 1.0
        if n or self.workpiece_count:
            self.workpieces.batched_positions = pts
            self.workpieces.batched_scales = scales
        self.workpiece_count = n

    def remove(self) -> None:
        for h in (self.label, self.workpieces, self.cleats, self.body, self.belt, self.frame):
            h.remove()
