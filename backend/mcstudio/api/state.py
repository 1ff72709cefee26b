"""Application state shared by the routers: the runner (and its controller), the project folder, the 3D view."""

from __future__ import annotations

import shutil
import threading
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from .. import __version__
from ..controller.kernel import Controller, Snapshot
from ..controller.mc.axis import axis_variables
from ..controller.mc.cam.table import CamTable
from ..controller.mc.enums import AxisState
from ..controller.mc.module import drv_status
from ..controller.runner import Runner
from ..fieldbus.library import DeviceLibrary
from ..project.cams import load_cam_tables, sync_cam_files, tables_for, write_cam_file
from ..project.folders import (
    Template,
    build_project_folder,
    copy_project_files,
    copy_template,
    resolve_in_root,
)
from ..project.io import ProjectError, dump_project, load_project, save_project
from ..project.models import PROJECT_FILE, Project
from .models import AxisSummary, ControllerStatus, FBOut

if TYPE_CHECKING:
    from ..viz.scene import SceneServer

_MOVING = {AxisState.Discrete, AxisState.Continuous, AxisState.Synchronized, AxisState.Homing, AxisState.Stopping}


class ConflictError(Exception):
    """The request is valid but cannot be applied in the controller's current state (HTTP 409)."""


@dataclass
class Studio:
    runner: Runner
    project_dir: Path | None
    projects_root: Path | None
    version: str = __version__
    viz: SceneServer | None = None
    saved_text: str = ""
    lock: threading.Lock = field(default_factory=threading.Lock)
    ws_cache: dict[Any, Any] = field(default_factory=dict)  # encoded WebSocket messages of the latest snapshot

    def __post_init__(self) -> None:
        self.library: DeviceLibrary = self.runner.controller.library or DeviceLibrary(self.project_dir)
        self._dirty_memo: tuple[Project, str, bool] | None = None
        if not self.saved_text:
            self.saved_text = dump_project(self.runner.controller.project)
        self.attach(self.runner.controller)

    def attach(self, controller: Controller) -> None:
        """Connect a controller to the project folder: MC_SaveCamTable writes `cams/<name>.csv` (it runs in a
        background thread, decision D44) and the saved data become the table's downloaded value."""
        if self.project_dir is None:
            return

        def save_cam(name: str, table: CamTable) -> None:
            folder = self.project_dir  # at the time of the save: save-as moves the project to another folder
            if folder is None:
                return
            write_cam_file(folder, name, table)
            controller.cams[name] = table

        controller.mc.cam_saver = save_cam

    # ------------------------------------------------------------------ controller views
    @property
    def controller(self) -> Controller:
        return self.runner.controller

    @property
    def project(self) -> Project:
        return self.runner.controller.project

    def status(self, snap: Snapshot | None = None) -> ControllerStatus:
        snap = snap or self.runner.snapshot
        st = self.runner.status()
        return ControllerStatus(
            mode=st.mode,
            period_s=snap.period_s,
            cycle=snap.cycle,
            time_s=round(snap.time_s, 9),
            rtf=round(st.rtf, 3),
            overruns=st.overruns,
            project=snap.project,
            project_dirty=self.dirty,
            epoch=self.runner.epoch,
            cycle_time_us=round(st.cycle_time_avg_s * 1e6, 1),
            cycle_time_max_us=round(st.cycle_time_max_s * 1e6, 1),
        )

    @property
    def dirty(self) -> bool:
        project = self.project
        memo = self._dirty_memo
        if memo is None or memo[0] is not project or memo[1] != self.saved_text:
            memo = (project, self.saved_text, dump_project(project) != self.saved_text)
            self._dirty_memo = memo
        return memo[2]

    def axis_views(self, snap: Snapshot, names: list[str] | None = None) -> list[tuple[str, dict[str, Any]]]:
        mc = snap.mc
        out = []
        for axis in self.controller.mc.axes:
            if names is not None and axis.name not in names:
                continue
            i = axis.i
            if i >= len(mc["discrete"]):
                continue
            row = {
                "cmd_pos": float(mc["cmd_pos"][i]),
                "cmd_vel": float(mc["cmd_vel"][i]),
                "cmd_accdec": float(mc["cmd_accdec"][i]),
                "cmd_jerk": float(mc["cmd_jerk"][i]),
                "act_pos": float(mc["act_pos"][i]),
                "act_vel": float(mc["act_vel"][i]),
                "cmd_trq": float(mc["cmd_trq"][i]),
                "act_trq": float(mc["act_trq"][i]),
                "drv": drv_status(int(mc["drv"][i])),
            }
            out.append((axis.name, axis_variables(axis, mc["discrete"][i], row)))
        return out

    def axis_summaries(self, snap: Snapshot) -> list[AxisSummary]:
        res = []
        by_name = {a.name: a for a in self.controller.mc.axes}
        for name, v in self.axis_views(snap):
            a = by_name[name]
            state = next(k for k, flag in v["Status"].items() if flag and k != "Ready")
            res.append(AxisSummary(
                name=name, number=a.number, type=a.type.name, use=a.config.use.name,
                node_address=a.config.node_address, units=a.params.UnitConversion.UnitDisplay.name, state=state,
                cmd_pos=v["Cmd"]["Pos"], act_pos=v["Act"]["Pos"], cmd_vel=v["Cmd"]["Vel"], act_vel=v["Act"]["Vel"],
                servo_on=v["DrvStatus"]["ServoOn"], error_code=v["MFaultLvl"]["Code"],
            ))
        return res

    def fb_out(self, snap: Snapshot, fb_id: int) -> FBOut | None:
        view = snap.fbs.get(fb_id)
        if view is None:
            return None
        return FBOut(id=view.id, type=view.type, inputs=view.inputs, outputs=view.outputs, lease_s=view.lease_s,
                     cycle=snap.cycle)

    # ------------------------------------------------------------------ project operations
    def apply_project(self, project: Project, cams: Mapping[str, CamTable] | None = None) -> None:
        """Replace the running controller with one built from `project` (cycle 0, like a download).

        `cams`: the cam data (default: the running controller's, for the tables `project` defines).
        Refused (409) while an axis moves: a download restarts the controller."""
        if cams is None:
            cams = tables_for(project, self.controller.cams, self.project)
        controller = Controller(project, library=self.library, cams=cams)
        self.attach(controller)

        def swap(current: Controller) -> None:
            moving = [a.name for a in current.mc.axes if a.state in _MOVING]
            if moving:
                raise ConflictError(
                    "axes are moving (" + ", ".join(moving) + "); stop them before applying a new configuration, "
                    "which restarts the controller like a download"
                )
            self.runner.replace_controller(controller)

        self.runner.call(swap)
        if self.viz is not None:
            self.viz.rebuild(controller)

    def save(self) -> Path:
        if self.project_dir is None:
            raise ConflictError("this studio was started without a project folder; nothing to save to")
        with self.lock:
            try:
                sync_cam_files(self.project_dir, self.project, self.controller.cams)  # the data before the definitions
                path = save_project(self.project_dir, self.project)
            except OSError as err:
                raise ConflictError(f"the project could not be written to {self.project_dir}: {err}") from None
            self.saved_text = dump_project(self.project)
        return path

    def _root(self) -> Path:
        if self.projects_root is None:
            raise ConflictError("no projects folder configured (start the studio with --projects-root)")
        return self.projects_root

    def save_as(self, name: str, *, overwrite: bool = False) -> Path:
        """Save the running project (with its unsaved changes) as a new folder `name` of the projects root, with the
        current folder's cam data and ESI files, and continue in it (D112). The current folder is not changed."""
        root = self._root()
        target = resolve_in_root(root, name)
        if self.project_dir is not None and target == self.project_dir.resolve():
            if not overwrite:
                raise FileExistsError(f"{name!r} is the open project; use Save, or overwrite")
            return self.save()
        project, tables, source = self.project, dict(self.controller.cams), self.project_dir

        def fill(staging: Path) -> None:
            copy_project_files(source, staging)
            sync_cam_files(staging, project, tables)
            save_project(staging, project)

        with self.lock:
            try:
                folder = build_project_folder(root, name, fill, overwrite=overwrite)
            except (FileExistsError, ValueError):
                raise
            except OSError as err:
                raise ConflictError(f"the project could not be written to {root / name}: {err}") from None
            self.project_dir = folder
            self.library.folder = folder
            self.saved_text = dump_project(project)
        return folder / PROJECT_FILE

    def list_projects(self) -> list[dict[str, Any]]:
        root = self.projects_root
        if root is None or not root.is_dir():
            return []
        out = []
        base = root.resolve()
        folders = (p for p in root.iterdir() if not p.name.startswith(".") and p.is_dir()  # hidden: staging (D112)
                   and p.resolve().parent == base and (p / "project.json").is_file())  # no links out of the root
        for d in sorted(folders):
            try:
                proj = load_project(d)
                load_cam_tables(proj, d)
                out.append({"name": d.name, "title": proj.name, "path": str(d), "valid": True, "error": None})
            except ProjectError as err:
                out.append({"name": d.name, "title": d.name, "path": str(d), "valid": False, "error": str(err)})
            out[-1]["current"] = self.project_dir is not None and d.resolve() == self.project_dir.resolve()
        return out

    def resolve_project_name(self, name: str) -> Path:
        """The folder of a project of the projects root (ValueError naming the rule a bad name breaks, D110)."""
        return resolve_in_root(self._root(), name)

    def open_project(self, name: str) -> Project:
        return self.open_folder(self.resolve_project_name(name))

    def open_folder(self, folder: Path) -> Project:
        """Load a project folder and restart the controller with it. Nothing is written: a corrupt project raises
        ProjectError (every problem with its path) and the running project stays open; 409 while an axis moves."""
        library = DeviceLibrary(folder)
        project = load_project(folder, library)
        cams = load_cam_tables(project, folder)
        previous, self.library = self.library, library
        try:
            self.apply_project(project, cams)
        except Exception:
            self.library = previous
            raise
        self.project_dir = folder
        self.saved_text = dump_project(project)
        return project

    def revert(self) -> Project:
        """Reload the project from its folder, discarding the unsaved changes (like opening it again)."""
        if self.project_dir is None:
            raise ConflictError("this studio was started without a project folder; there is nothing to revert to")
        return self.open_folder(self.project_dir)

    def new_project(self, name: str, template: Template) -> Project:
        """Create project `name` from a template (the document's name becomes `name`) and open it. If it cannot be
        opened (409: axes move) the new folder is removed again: nothing else was touched."""
        root = self._root()
        tpl_project = load_project(template.folder)

        def fill(staging: Path) -> None:
            copy_template(template, staging)
            save_project(staging, tpl_project.model_copy(update={"name": name}))
            (staging / (PROJECT_FILE + ".bak")).unlink(missing_ok=True)

        try:
            folder = build_project_folder(root, name, fill)
        except (FileExistsError, ValueError):
            raise
        except OSError as err:
            raise ConflictError(f"the project could not be created in {root}: {err}") from None
        try:
            return self.open_folder(folder)
        except BaseException:
            shutil.rmtree(folder, ignore_errors=True)
            raise
