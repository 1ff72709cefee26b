from __future__ import annotations

import shutil
from collections.abc import Iterator
from pathlib import Path

import pytest
from fastapi.testclient import TestClient

from mcstudio.api.app import create_app
from mcstudio.api.state import Studio
from mcstudio.controller.kernel import Controller
from mcstudio.controller.runner import Runner
from mcstudio.project.cams import load_cam_tables
from mcstudio.project.io import load_project
from tests.conftest import DEMO


@pytest.fixture
def project_dir(tmp_path: Path) -> Path:
    root = tmp_path / "projects"
    root.mkdir()
    shutil.copytree(DEMO, root / "demo")
    return root / "demo"


@pytest.fixture
def studio(project_dir: Path) -> Studio:
    """The demo project in a paused controller; without a runner thread requests run inline (deterministic)."""
    project = load_project(project_dir)
    runner = Runner(Controller(project, cams=load_cam_tables(project, project_dir)), mode="paused")
    return Studio(runner=runner, project_dir=project_dir, projects_root=project_dir.parent)


@pytest.fixture
def client(studio: Studio) -> Iterator[TestClient]:
    with TestClient(create_app(studio, static_dir=Path("/nonexistent"))) as c:
        yield c
