"""Fixtures of the hardening tests: a fresh studio on a copy of the demo project, paused, without a runner thread
(requests run inline, deterministic)."""

from __future__ import annotations

import shutil
from pathlib import Path

from fastapi import FastAPI

from mcstudio.api.app import create_app
from mcstudio.api.state import Studio
from mcstudio.controller.kernel import Controller
from mcstudio.controller.runner import Runner
from mcstudio.project.cams import load_cam_tables
from mcstudio.project.io import load_project
from tests.conftest import DEMO


def demo_studio(root: Path) -> Studio:
    """The demo project copied under `root/projects/demo`, in a paused controller."""
    projects = root / "projects"
    projects.mkdir(parents=True, exist_ok=True)
    folder = projects / "demo"
    if not folder.exists():
        shutil.copytree(DEMO, folder)
    project = load_project(folder)
    runner = Runner(Controller(project, cams=load_cam_tables(project, folder)), mode="paused")
    return Studio(runner=runner, project_dir=folder, projects_root=projects)


def demo_app(root: Path) -> FastAPI:
    return create_app(demo_studio(root), static_dir=Path("/nonexistent"))
