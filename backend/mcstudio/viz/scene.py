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
        scene = self.server.scene
        with self.server.atomic():
            scene.set_up_direction("+z")
            scene.add_grid("/floor", width=2.0, height=2.0, cell_size=0.1, section_size=0.5, plane="xy")
            scene.add_frame("/machine", axes_length=0.25, axes_radius=0.008)
            scene.add_label("/machine/label", "MCS", position=(0.0, 0.0, 0.3))

    def rebuild(self, controller: Controller) -> None:
        """Called when a new project is applied (the robot issue draws the configured mechanism)."""

    def stop(self) -> None:
        try:
            self.server.stop()
        except Exception:  # pragma: no cover - best effort at shutdown
            log.exception("stopping viser failed")
