"""The 3D view: a viser server showing the machine, bound to loopback by default.

This first version shows the machine frame and a floor grid; the robot issue builds the Delta3 robot from its
configured parameters and moves it from the controller's feedback.
"""

from __future__ import annotations

import logging
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ..controller.kernel import Controller

log = logging.getLogger(__name__)


class SceneServer:
    def __init__(self, *, host: str = "127.0.0.1", port: int = 8080) -> None:
        import viser

        self.host = host
        self.server = viser.ViserServer(host=host, port=port, label="MC Studio 3D", verbose=False)
        self.port = self.server.get_port()
        self._build_static()

    def _build_static(self) -> None:
        server = self.server
        scene = server.scene
        server.gui.configure_theme(control_layout="collapsible", control_width="small", show_logo=False,
                                   show_share_button=False, brand_color=(34, 139, 230))
        cam = server.initial_camera
        cam.up = (0.0, 0.0, 1.0)
        cam.position = (1.1, -1.4, 0.9)
        cam.look_at = (0.0, 0.0, 0.15)
        with server.atomic():
            scene.set_up_direction("+z")
            # metres; 10 cm cells, 50 cm sections, a 2 m × 2 m machine floor
            scene.add_grid("/floor", width=2.0, height=2.0, cell_size=0.1, section_size=0.5, plane="xy",
                           cell_color=(180, 180, 190), section_color=(110, 110, 125), section_thickness=1.5)
            scene.add_frame("/machine", axes_length=0.3, axes_radius=0.01, origin_radius=0.02)
            scene.add_label("/machine/label", "Machine coordinate system (MCS)", position=(0.0, 0.0, 0.36))

    def rebuild(self, controller: Controller) -> None:
        """Called when a new project is applied (the robot issue draws the configured mechanism)."""

    def stop(self) -> None:
        try:
            self.server.stop()
        except Exception:  # pragma: no cover - best effort at shutdown
            log.exception("stopping viser failed")
