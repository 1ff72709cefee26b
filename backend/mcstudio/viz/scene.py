"""The 3D view: a viser server showing the machine, bound to loopback by default.

World frame = the MCS of the robot (Z up, origin at the TCP's zero pose, §12.8), in metres. `rebuild(controller)`
draws every Delta3 robot of the project with the kinematics in force (`robots.robot_specs`; the viz thread rebuilds
when MC_SetKinTransform replaces them, D94) and a conveyor; a viz thread (`attach(runner)`) reads
the runner's **published snapshot** at `fps` frames per second — never kernel state — and moves the robots to their
axes' feedback positions, all scene changes of a frame in one `server.atomic()` block; a frame whose picture would
not change (same joint positions, alarm and conveyor) is skipped.
"""

from __future__ import annotations

import logging
import threading
import time
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from ..controller.mc.enums import _eMC_COUNT_MODE, _eMC_UNITS
from ..controller.mc.kinematics import UserCoordSystem
from ..plant.workpieces import WorkpieceSource
from .conveyor_view import ConveyorSpec, ConveyorView
from .geometry import MM
from .robot_view import RobotView
from .robots import RobotReading, RobotSpec, read_robot, robot_specs

if TYPE_CHECKING:
    from ..controller.kernel import Controller, Snapshot
    from ..controller.runner import Runner

log = logging.getLogger(__name__)

DEFAULT_FPS = 30.0  # frames per second of the viz thread (each frame holds the GIL ~0.5 ms; docs/robot.md)


@dataclass
class FrameStats:
    """Cost of the frames drawn (compute + queueing the scene messages, in the viz thread)."""

    frames: int = 0
    skipped: int = 0
    total_s: float = 0.0
    max_s: float = 0.0
    recent: list[float] = field(default_factory=list)

    def add(self, dt: float) -> None:
        self.frames += 1
        self.total_s += dt
        self.max_s = max(self.max_s, dt)
        self.recent.append(dt)
        if len(self.recent) > 1000:
            del self.recent[:500]

    @property
    def mean_s(self) -> float:
        return self.total_s / self.frames if self.frames else 0.0


@dataclass
class _Robot:
    view: RobotView
    indices: tuple[int | None, int | None, int | None]


def conveyor_axis(controller: Controller, specs: Sequence[RobotSpec]) -> int | None:
    """The conveyor axis the view follows: the first axis set up as the manual's conveyor axis (§6.3: rotary count
    mode, unit mm) that is not a robot axis; None if there is none."""
    members = {name for s in specs for name in s.axes}
    for axis in controller.mc.axes:
        p = axis.config.parameters
        if (axis.name not in members and p.PosCount.CountMode == _eMC_COUNT_MODE._mcCountModeRotary
                and p.UnitConversion.UnitDisplay == _eMC_UNITS._mcMm):
            return int(axis.i)
    return None


class SceneServer:
    def __init__(self, *, host: str = "127.0.0.1", port: int = 8080, fps: float = DEFAULT_FPS) -> None:
        import viser

        self.host = host
        self.server = viser.ViserServer(host=host, port=port, label="MC Studio 3D", verbose=False)
        self.port = self.server.get_port()
        self.fps = fps
        self.stats = FrameStats()
        self.robots: list[_Robot] = []
        self.conveyor: ConveyorView | None = None
        self._conveyor_index: int | None = None
        self._conveyor_position = 0.0
        self._workpieces: list[tuple[float, float, float]] = []
        self._workpieces_version = 0
        # the plant's workpieces (plant/workpieces.py) on the project's conveyor axis, until set_conveyor is called
        self._source: WorkpieceSource | None = None
        self._coord_seen: dict[str, dict[int, Any]] = {}
        self._kin_seen: dict[str, Any] = {}  # group → the kinematics object the robots were built with
        self._lock = threading.RLock()
        self._last_key: tuple[Any, ...] | None = None
        self._last_snap: Snapshot | None = None
        self._runner: Runner | None = None
        self._epoch = -1
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None
        self._build_static()

    def _build_static(self) -> None:
        server = self.server
        scene = server.scene
        server.gui.configure_theme(control_width="small", show_logo=False, show_share_button=False,
                                   brand_color=(34, 139, 230))
        # the view lives in an iframe next to the studio's own read-out: keep viser's panel out of the way
        server.gui.main_panel.float(x=-10, y=10)
        server.gui.main_panel.minimize()
        self._build_gui()
        self._set_camera(position=(1.1, -1.4, 0.9), look_at=(0.0, 0.0, 0.15), clients=False)
        with server.atomic():
            scene.set_up_direction("+z")
            # metres; 10 cm cells, 50 cm sections, a 3 m × 3 m machine floor (moved below the robot by rebuild)
            self.floor = scene.add_grid("/floor", width=3.0, height=3.0, cell_size=0.1, section_size=0.5, plane="xy",
                                        cell_color=(200, 200, 208), section_color=(130, 130, 145),
                                        section_thickness=1.5)
            self.mcs = scene.add_frame("/machine", axes_length=0.15, axes_radius=0.005, origin_radius=0.01)
            self.mcs_label = scene.add_label("/machine/label", "MCS", position=(0.0, 0.0, 0.17))

    def _build_gui(self) -> None:
        gui = self.server.gui
        self.gui_workspace = gui.add_checkbox("Workspace", initial_value=True)
        self.gui_trail = gui.add_checkbox("TCP trail", initial_value=True)
        self.gui_conveyor = gui.add_checkbox("Conveyor", initial_value=True)
        clear = gui.add_button("Clear trail")
        reset = gui.add_button("Frame the robot")

        @self.gui_workspace.on_update
        def _(_: Any) -> None:
            with self._lock:
                for r in self.robots:
                    r.view.show_workspace(self.gui_workspace.value)

        @self.gui_trail.on_update
        def _(_: Any) -> None:
            with self._lock:
                for r in self.robots:
                    r.view.show_trail(self.gui_trail.value)

        @self.gui_conveyor.on_update
        def _(_: Any) -> None:
            with self._lock:
                if self.conveyor is not None:
                    self.conveyor.frame.visible = self.gui_conveyor.value

        @clear.on_click
        def _(_: Any) -> None:
            with self._lock, self.server.atomic():
                for r in self.robots:
                    r.view.clear_trail()

        @reset.on_click
        def _(_: Any) -> None:
            with self._lock:
                self._place_floor_and_camera([r.view.spec for r in self.robots], move_clients=True)

    def _set_camera(self, *, position: tuple[float, float, float], look_at: tuple[float, float, float],
                    clients: bool = True) -> None:
        cam = self.server.initial_camera
        cam.up = (0.0, 0.0, 1.0)
        cam.position = position
        cam.look_at = look_at
        if clients:
            for client in self.server.get_clients().values():
                client.camera.up_direction = (0.0, 0.0, 1.0)
                client.camera.position = position
                client.camera.look_at = look_at

    # ------------------------------------------------------------------ building
    def attach(self, runner: Runner) -> None:
        """Draw the runner's project and start the viz thread that follows its snapshots."""
        self._runner = runner
        self.rebuild(runner.controller)
        self._thread = threading.Thread(target=self._loop, name="mcstudio-viz", daemon=True)
        self._thread.start()

    def rebuild(self, controller: Controller) -> None:
        """Draw the mechanism of `controller`'s project (called when a project is applied or reset). Reads the
        configuration only; the moving parts take the controller's current snapshot."""
        groups = dict(getattr(controller.mc, "groups_by_name", {}))
        specs = robot_specs(controller.project, groups)
        names = [a.name for a in controller.mc.axes]
        index = {a.name: int(a.i) for a in controller.mc.axes}
        with self._lock:
            old_specs = [r.view.spec for r in self.robots]
            with self.server.atomic():
                for r in self.robots:
                    r.view.remove()
                self.robots = []
                if self.conveyor is not None:
                    self.conveyor.remove()
                    self.conveyor = None
                for spec in specs:
                    view = RobotView(self.server, spec)
                    self.robots.append(_Robot(view, tuple(index.get(n) for n in spec.axes)))  # type: ignore[arg-type]
                self._conveyor_index = conveyor_axis(controller, specs)
                if specs:
                    self.conveyor = ConveyorView(self.server, ConveyorSpec.under(specs[0].workspace))
                    half = self.conveyor.spec.length / 2.0
                    self._source = WorkpieceSource(pitch=200.0, entry_x=-half, exit_x=half)
                else:
                    self._source = None
                self._coord_seen = {}
                self._kin_seen = {name: getattr(g, "kinematics", None) for name, g in groups.items()}
                self._place_floor_and_camera(specs, move_clients=[s.params for s in specs]
                                             != [s.params for s in old_specs])
            self._last_key = None
            self._epoch = self._runner.epoch if self._runner is not None else -1
            log.debug("3D view rebuilt: %d robots (axes %s)", len(specs), names)
        self.update(controller.snapshot, force=True)

    def _place_floor_and_camera(self, specs: Sequence[RobotSpec], *, move_clients: bool) -> None:
        if not specs:
            self.floor.position = (0.0, 0.0, 0.0)
            self._set_camera(position=(1.1, -1.4, 0.9), look_at=(0.0, 0.0, 0.15), clients=move_clients)
            return
        p, ws = specs[0].params, specs[0].workspace
        top = p.motor_plane_z + 0.3 * p.Rf
        bottom = ws.z_bottom if ws is not None else -0.5 * p.Lm
        if self.conveyor is not None:
            bottom = min(bottom, self.conveyor.spec.frame.Tz)
        radius = max(1.4 * p.Rf, ws.Rcy if ws is not None else 0.0, 0.5 * p.Lm)
        conv = self.conveyor
        floor = conv.spec.frame.Tz - conv.spec.height if conv is not None else bottom - 300.0
        self.floor.position = (0.0, 0.0, floor * MM)
        # frame the robot from its base down to the workspace bottom, seen from the front right and a bit above
        height = top - bottom
        centre = np.array([0.0, 0.0, 0.5 * (top + bottom) + 0.06 * (top - bottom)]) * MM
        extent = max(height, 2.0 * radius) * MM
        direction = np.array([0.62, -0.95, 0.72])
        direction /= np.linalg.norm(direction)
        eye = centre + direction * 1.05 * extent
        self._set_camera(position=tuple(float(v) for v in eye), look_at=tuple(float(v) for v in centre),
                         clients=move_clients)

    # ------------------------------------------------------------------ conveyor and coordinate systems
    def set_conveyor(self, position: float, workpieces: Sequence[Sequence[float]]) -> None:
        """Conveyor position (mm) and workpieces (x, y, z mm in the conveyor's coordinate system, z = 0 on the
        belt) — the plant calls this; the workpieces stay until the next call. With a conveyor axis in the project,
        the viz thread keeps following that axis' feedback position."""
        with self._lock:
            self._conveyor_position = float(position)
            self._workpieces = [(float(w[0]), float(w[1]), float(w[2]) if len(w) > 2 else 0.0) for w in workpieces]
            self._workpieces_version += 1
            if self.conveyor is not None:
                with self.server.atomic():
                    self.conveyor.set(self._conveyor_position, self._workpieces)

    def set_coord_systems(self, group: str, systems: Mapping[int, UserCoordSystem]) -> None:
        """Show a robot's user coordinate systems (CSID → pose), e.g. after MC_DefineCoordSystem."""
        with self._lock:
            for r in self.robots:
                if r.view.spec.group == group:
                    with self.server.atomic():
                        r.view.set_coord_systems(systems)

    def _follow_coord_systems(self) -> None:
        """Show the user coordinate systems MC_DefineCoordSystem defined. The viz thread copies the group's dict of
        immutable poses (one atomic read under the GIL) and redraws only when it changed."""
        runner = self._runner
        if runner is None:
            return
        groups = getattr(runner.controller.mc, "groups_by_name", {})
        for r in self.robots:
            g = groups.get(r.view.spec.group)
            if g is None:
                continue
            systems = dict(getattr(g, "coord_systems", {}))
            if systems != self._coord_seen.get(g.name, {}):
                self._coord_seen[g.name] = systems
                with self.server.atomic():
                    r.view.set_coord_systems(systems)

    def _follow_kinematics(self) -> bool:
        """Rebuild the robots when a group's kinematics in force changed (MC_SetKinTransform replaced them, or 571F
        deleted them: then the project's are drawn). One identity test per group and frame; True if it rebuilt."""
        runner = self._runner
        if runner is None:
            return False
        controller = runner.controller
        groups = getattr(controller.mc, "groups_by_name", {})
        seen = self._kin_seen
        if all(getattr(g, "kinematics", None) is seen.get(name) for name, g in groups.items()):
            return False
        log.debug("3D view: kinematics changed, rebuilding the robots")
        self.rebuild(controller)
        return True

    # ------------------------------------------------------------------ per frame
    def readings(self, snap: Snapshot) -> list[RobotReading]:
        return [read_robot(r.view.spec, snap, r.indices) for r in self.robots]

    def update(self, snap: Snapshot, *, force: bool = False) -> bool:
        """Move everything to `snap`; False (and nothing sent) when the picture would not change."""
        t0 = time.perf_counter()
        with self._lock:
            if self._follow_kinematics():
                return True  # rebuild drew the frame
            readings = self.readings(snap)
            conv = self._conveyor_position
            i = self._conveyor_index
            if i is not None and i < len(snap.mc["act_pos"]):
                conv = float(snap.mc["act_pos"][i])
            auto = self._source is not None and self._workpieces_version == 0 and i is not None
            self._follow_coord_systems()
            key = (tuple(r.key for r in readings), conv, self._workpieces_version)
            if key == self._last_key and not force:
                self.stats.skipped += 1
                dirty = [r.view for r in self.robots if r.view.trail_dirty]
                if dirty:  # the robot stopped: the trail's last points
                    with self.server.atomic():
                        for view in dirty:
                            view.flush_trail()
                return False
            with self.server.atomic():
                for r, reading in zip(self.robots, readings, strict=True):
                    r.view.apply(reading)
                if self.conveyor is not None:
                    if auto:  # the plant's workpieces move with the conveyor's feedback
                        assert self._source is not None
                        moved = force or self._last_key is None or self._last_key[1] != conv
                        self.conveyor.set(conv, self._source.positions(conv) if moved else None)
                    else:
                        changed = force or self._last_key is None or self._last_key[2] != self._workpieces_version
                        self.conveyor.set(conv, self._workpieces if changed else None)
            self._last_key = key
        self.stats.add(time.perf_counter() - t0)
        return True

    def _loop(self) -> None:
        period = 1.0 / self.fps
        next_t = time.perf_counter()
        while not self._stop.is_set():
            next_t += period
            delay = next_t - time.perf_counter()
            if delay < -period:  # fell behind (machine stalled): do not race to catch up
                next_t = time.perf_counter()
            elif delay > 0 and self._stop.wait(delay):
                return
            runner = self._runner
            if runner is None:
                continue
            snap = runner.snapshot
            if snap is self._last_snap or runner.epoch != self._epoch:
                continue  # nothing new, or a new controller not yet drawn (rebuild follows)
            self._last_snap = snap
            try:
                self.update(snap)
            except Exception:  # the view must never take the studio down
                log.exception("3D view update failed")

    def stop(self) -> None:
        self._stop.set()
        if self._thread is not None:
            self._thread.join(timeout=2)
        try:
            self.server.stop()
        except Exception:  # pragma: no cover - best effort at shutdown
            log.exception("stopping viser failed")
