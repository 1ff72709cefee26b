"""The viser scene nodes of one Delta3 robot (`omron-robot-delta3.md` §12.8) and how a reading moves them.

World frame = the MCS (Z up), in metres. Static: fixed frame (a cut triangle whose edges carry the motors at the
motor plane z = −Z0), motors, workspace (translucent cylinder + truncated cone with its edges), name label, UCS
frames. Moving (one `apply` per frame, inside the caller's `server.atomic()`): the twelve link cylinders (upper arms,
forearm rods, elbow bars) as one batched mesh, the twelve ball joints as another, the moving platform (it only
translates: its position is the TCP), the bounded TCP trail, the alarm colours and label.
"""

from __future__ import annotations

import math
import time
from collections.abc import Mapping
from typing import Any

import numpy as np

from ..controller.mc.kinematics import Status, UserCoordSystem
from .geometry import (
    ELBOW_BARS,
    MM,
    N_LINKS,
    RODS,
    UPPER_ARMS,
    Mesh,
    RobotPose,
    RobotStyle,
    base_polygon,
    merge,
    platform_polygon,
    prism,
    quat_from_matrix,
    robot_pose,
    rotate_by_quat,
    segment_transforms,
    unit_cylinder,
    workspace_mesh,
    workspace_outline,
)
from .robots import RobotReading, RobotSpec

# Colours (RGB 0–255): light machine parts, the studio's blue for the driven links, dark carbon forearm rods, an
# orange moving platform that stands out against the blue workspace, red for an alarm.
BASE_COLOR = (214, 219, 226)
MOTOR_COLOR = (72, 82, 98)
HUB_COLOR = (160, 166, 176)
ARM_COLOR = (34, 139, 230)
ROD_COLOR = (58, 62, 70)
JOINT_COLOR = (190, 195, 205)
PLATFORM_COLOR = (245, 140, 40)
WORKSPACE_COLOR = (90, 170, 255)
WORKSPACE_EDGE_COLOR = (70, 130, 210)
TRAIL_COLOR = (214, 51, 132)
ALARM_COLOR = (224, 49, 49)
ALARM_ROD_COLOR = (150, 30, 30)

TRAIL_POINTS = 600  # bounded TCP trail: the last 600 distinct points …
TRAIL_STEP_MM = 1.0  # … at least 1 mm apart
# The trail is the largest message of a frame (up to 600 segments): it is sent at most 10 times a second, and once
# more when the robot stops (SceneServer.update flushes it)
TRAIL_INTERVAL_S = 0.1


def _link_colors(alarm: bool) -> np.ndarray:
    c = np.empty((N_LINKS, 3), dtype=np.uint8)
    c[UPPER_ARMS] = ALARM_COLOR if alarm else ARM_COLOR
    c[RODS] = ALARM_ROD_COLOR if alarm else ROD_COLOR
    c[ELBOW_BARS] = ALARM_COLOR if alarm else ARM_COLOR
    return c


class RobotView:
    """Scene nodes of one robot under `/robots/<group>`; `apply(reading)` moves them (call inside atomic())."""

    def __init__(self, server: Any, spec: RobotSpec) -> None:
        self.server = server
        self.spec = spec
        self.style = RobotStyle.for_params(spec.params)
        self.root = f"/robots/{spec.group}"
        self._trail_buf = np.zeros((TRAIL_POINTS, 3))
        self._trail_head = 0
        self._trail_n = 0
        self._trail_last: tuple[float, float, float] = (0.0, 0.0, 0.0)
        self._trail_sent = 0.0
        self.trail_dirty = False
        self.pose: RobotPose | None = None
        self.reading: RobotReading | None = None
        self._alarm_shown: bool | None = None
        self.trail_visible = True
        self._ucs: dict[int, Any] = {}
        self._build()

    # ------------------------------------------------------------------ static parts
    def _build(self) -> None:
        scene = self.server.scene
        p, st, root = self.spec.params, self.style, self.root
        zm = p.motor_plane_z
        # fixed frame: a plate just above the motors
        plate_z0 = zm + st.motor_radius
        base = prism(base_polygon(p, margin=0.12 * p.Rf), plate_z0, plate_z0 + st.base_thickness)
        self.base = scene.add_mesh_simple(f"{root}/base", base.vertices * MM, base.faces, color=BASE_COLOR,
                                          flat_shading=True)
        # motors along tᵢ: a hub at the shoulder Mᵢ (where the upper arm turns) and the motor body beside it
        cyl = unit_cylinder(24)
        hubs, bodies = [], []
        for u, t in zip(p.radial, p.tangential, strict=True):
            m = np.array([0.0, 0.0, zm]) + p.Rf * u
            hubs.append([m - 0.6 * st.motor_radius * t, m + 0.6 * st.motor_radius * t])
            bodies.append([m + 0.6 * st.motor_radius * t, m + (0.6 * st.motor_radius + st.motor_length) * t])
        self.hubs = self._static_cylinders(f"{root}/hubs", cyl, np.array(hubs), 0.75 * st.motor_radius, HUB_COLOR)
        self.motors = self._static_cylinders(f"{root}/motors", cyl, np.array(bodies), st.motor_radius, MOTOR_COLOR)
        # moving parts: placed by apply()
        zeros = np.zeros((N_LINKS, 3))
        ident = np.tile([1.0, 0.0, 0.0, 0.0], (N_LINKS, 1))
        self.links = scene.add_batched_meshes_simple(
            f"{root}/links", cyl.vertices, cyl.faces, batched_wxyzs=ident, batched_positions=zeros,
            batched_scales=np.zeros((N_LINKS, 3)), batched_colors=_link_colors(False), lod="off")
        sphere = _icosphere(2)
        self.joints = scene.add_batched_meshes_simple(
            f"{root}/joints", sphere.vertices * st.joint_radius * MM, sphere.faces,
            batched_wxyzs=np.tile([1.0, 0.0, 0.0, 0.0], (12, 1)), batched_positions=np.zeros((12, 3)),
            batched_colors=JOINT_COLOR, lod="off")
        plat = prism(platform_polygon(p, st), -0.5 * st.platform_thickness, 0.5 * st.platform_thickness)
        self.platform = scene.add_mesh_simple(f"{root}/platform", plat.vertices * MM, plat.faces,
                                              color=PLATFORM_COLOR, flat_shading=True)
        # TCP marker: the moving frame's centre (no tool offset exists, §2.1); axes long enough to show through
        self.tcp = scene.add_frame(f"{root}/platform/tcp", axes_length=1.8 * p.Rm * MM,
                                   axes_radius=0.06 * p.Rm * MM, origin_radius=0.14 * p.Rm * MM,
                                   origin_color=(255, 255, 255))
        self.trail_handle = scene.add_line_segments(f"{root}/trail", np.zeros((1, 2, 3)), TRAIL_COLOR,
                                                    thickness=2.0, thickness_units="screen", visible=False)
        ws = self.spec.workspace
        if ws is not None:
            wm = workspace_mesh(ws)
            self.workspace = scene.add_mesh_simple(
                f"{root}/workspace", wm.vertices * MM, wm.faces, color=WORKSPACE_COLOR, opacity=0.13,
                side="double", cast_shadow=False, receive_shadow=False)
            self.workspace_edges = scene.add_line_segments(
                f"{root}/workspace_edges", workspace_outline(ws) * MM, WORKSPACE_EDGE_COLOR, thickness=1.5,
                thickness_units="screen")
        top = plate_z0 + st.base_thickness
        self.label = scene.add_label(f"{root}/label", f"{self.spec.group} (Delta3)",
                                     position=(0.0, 0.0, (top + 0.25 * p.Rf) * MM))
        self.alarm_label = scene.add_label(f"{root}/alarm", "", position=(0.0, 0.0, (top + 0.55 * p.Rf) * MM),
                                           visible=False)
        self.set_coord_systems(self.spec.coord_systems)

    def _static_cylinders(self, name: str, cyl: Mesh, segments: np.ndarray, radius: float,
                          color: tuple[int, int, int]) -> Any:
        tf = segment_transforms(segments * MM, radius * MM)
        parts = []
        for pos, q, s in zip(tf.positions, tf.wxyzs, tf.scales, strict=True):
            v = rotate_by_quat(q, cyl.vertices * s) + pos
            parts.append(Mesh(v, cyl.faces))
        m = merge(*parts)
        return self.server.scene.add_mesh_simple(name, m.vertices, m.faces, color=color)

    def set_coord_systems(self, systems: Mapping[int, UserCoordSystem]) -> None:
        """Show the user coordinate systems (CSID → pose, §4) as frames with labels; replaces the previous set."""
        scene = self.server.scene
        for h in self._ucs.values():
            h.remove()
        self._ucs = {}
        size = 0.4 * self.spec.params.Rf * MM
        for csid, ucs in sorted(systems.items()):
            name = f"{self.root}/ucs/{csid}"
            frame = scene.add_frame(name, wxyz=quat_from_matrix(ucs.R), position=ucs.T * MM, axes_length=size,
                                    axes_radius=0.04 * size, origin_radius=0.08 * size)
            scene.add_label(f"{name}/label", f"UCS {csid}", position=(0.0, 0.0, 0.3 * size))
            self._ucs[csid] = frame

    # ------------------------------------------------------------------ per frame
    def apply(self, reading: RobotReading) -> None:
        """Move the robot to `reading` (joint feedback, alarm). The caller holds `server.atomic()`."""
        self.reading = reading
        angles = np.array(reading.angles)
        if np.all(np.isfinite(angles)):
            pose = robot_pose(self.spec.params, angles, self.style)
            self.pose = pose
            tf = segment_transforms(np.nan_to_num(pose.links) * MM, pose.link_radii * MM)
            if not pose.ok:  # the forearms cannot close: draw the upper arms and elbow bars only
                tf.scales[RODS] = 0.0
            self.links.batched_positions = tf.positions
            self.links.batched_wxyzs = tf.wxyzs
            self.links.batched_scales = tf.scales
            if pose.ok:
                self.joints.batched_positions = pose.joints * MM
                tcp = pose.tcp * MM
                self.platform.position = tcp
                self._extend_trail(tuple(float(v) for v in pose.tcp))
            self.platform.visible = pose.ok
            self.joints.visible = pose.ok
        alarm = reading.alarm
        text = None
        if alarm is not None:
            text = f"⚠ {alarm[1]}"
        elif reading.kin_status != Status.OK:
            text = f"⚠ {self.spec.group}: no forward kinematics for A0..A2 (570F)"
        shown = text is not None
        if shown != self._alarm_shown:
            self.links.batched_colors = _link_colors(shown)
            self.platform.color = ALARM_COLOR if shown else PLATFORM_COLOR
            self.alarm_label.visible = shown
            self._alarm_shown = shown
        if shown and self.alarm_label.text != text:
            self.alarm_label.text = text

    def _extend_trail(self, p: tuple[float, float, float]) -> None:
        """Append a TCP point (mm) if it moved ≥ 1 mm; the last TRAIL_POINTS are kept in a ring buffer."""
        if self._trail_n and math.dist(self._trail_last, p) < TRAIL_STEP_MM:
            return
        self._trail_last = p
        buf = self._trail_buf
        buf[self._trail_head] = p
        self._trail_head = (self._trail_head + 1) % TRAIL_POINTS
        self._trail_n = min(self._trail_n + 1, TRAIL_POINTS)
        self.trail_dirty = True
        if time.monotonic() - self._trail_sent >= TRAIL_INTERVAL_S:
            self.flush_trail()

    def flush_trail(self) -> None:
        """Send the trail if points were added since it was last sent (caller holds `server.atomic()`)."""
        if not self.trail_dirty or self._trail_n < 2:
            return
        pts = self.trail * MM
        self.trail_handle.points = np.stack([pts[:-1], pts[1:]], axis=1)
        self.trail_handle.visible = self.trail_visible
        self.trail_dirty = False
        self._trail_sent = time.monotonic()

    @property
    def trail(self) -> np.ndarray:
        """The trail's points (n, 3) mm, oldest first."""
        if self._trail_n < TRAIL_POINTS:
            return self._trail_buf[:self._trail_n].copy()
        return np.roll(self._trail_buf, -self._trail_head, axis=0)

    def show_workspace(self, on: bool) -> None:
        for h in (getattr(self, "workspace", None), getattr(self, "workspace_edges", None)):
            if h is not None:
                h.visible = on

    def show_trail(self, on: bool) -> None:
        self.trail_visible = on
        self.trail_handle.visible = on and self._trail_n >= 2

    def clear_trail(self) -> None:
        self.trail_dirty = False
        self._trail_n = 0
        self._trail_head = 0
        self.trail_handle.visible = False

    def remove(self) -> None:
        for h in (self.base, self.hubs, self.motors, self.links, self.joints, self.platform, self.trail_handle,
                  self.label, self.alarm_label, *self._ucs.values(), getattr(self, "workspace", None),
                  getattr(self, "workspace_edges", None)):
            if h is not None:
                h.remove()


def _icosphere(subdivisions: int) -> Mesh:
    """Unit icosphere mesh (for the batched ball joints)."""
    t = (1.0 + math.sqrt(5.0)) / 2.0
    v = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
         (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    f = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2), (10, 7, 6),
         (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10),
         (8, 6, 7), (9, 8, 1)]
    verts = [np.array(p, dtype=np.float64) / np.linalg.norm(p) for p in v]
    faces = list(f)
    for _ in range(subdivisions):
        cache: dict[tuple[int, int], int] = {}

        def mid(a: int, b: int, cache: dict[tuple[int, int], int] = cache) -> int:
            key = (min(a, b), max(a, b))
            if key not in cache:
                m = verts[a] + verts[b]
                verts.append(m / np.linalg.norm(m))
                cache[key] = len(verts) - 1
            return cache[key]

        new = []
        for a, b, c in faces:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            new += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        faces = new
    return Mesh(np.array(verts), np.array(faces, dtype=np.uint32))
