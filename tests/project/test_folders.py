"""Project folders: name rules (D110), templates (D111), folders built under a hidden name and renamed into place
(D112), `mcstudio new` / `mcstudio schema`."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from mcstudio.project.cams import load_cam_tables
from mcstudio.project.folders import (
    build_project_folder,
    check_project_name,
    copy_template,
    list_templates,
    resolve_in_root,
)
from mcstudio.project.io import load_project, remove_stale_temp_files, save_project
from tests.conftest import DEMO


@pytest.mark.parametrize("name", ["demo", "Line 2", "Maschine Ä-3 (Test)", "x" * 64, "a.b", "v1.0_final", "机器"])
def test_good_names(name: str) -> None:
    assert check_project_name(name) == name


@pytest.mark.parametrize(("name", "reason"), [
    ("", "empty"), ("..", "'..'"), ("../x", "'..'"), ("a/b", "without '/'"), ("a\\b", "without '/'"),
    ("/etc", "without '/'"), (".git", "start with '.'"), ("x" * 65, "at most 64"), ("é" * 64 + "é", "at most 64"),
    ("\U0001F600" * 51, "bytes"), ("a\x00b", "U+0000"), ("a\nb", "U+000A"), ("a\u202eb", "U+202E"), ("a:b", "':'"),
    ("a*b", "'*'"), ("name ", "end with a space"), ("name.", "end with"), ("NUL", "reserved"), ("com1.txt", "reserved"),
])
def test_bad_names_say_why(name: str, reason: str) -> None:
    with pytest.raises(ValueError, match=r"project name|not a project name") as exc:
        check_project_name(name)
    assert reason in str(exc.value)


def test_resolve_refuses_links_out_of_the_root(tmp_path: Path) -> None:
    root = tmp_path / "root"
    root.mkdir()
    (tmp_path / "elsewhere").mkdir()
    os.symlink(tmp_path / "elsewhere", root / "link")
    assert resolve_in_root(root, "p") == (root / "p").resolve()
    with pytest.raises(ValueError, match="outside the projects folder"):
        resolve_in_root(root, "link")


def test_templates_are_valid_projects() -> None:
    """Each template loads with its cam data (CI also runs `mcstudio validate` on them, Makefile)."""
    templates = {t.name: t for t in list_templates()}
    assert list(templates)[:3] == ["empty", "single-axis", "demo"]
    demo = templates["demo"].folder  # the checkout's example project (the Docker image copies it into the package)
    assert (demo / "project.json").read_text() == (DEMO / "project.json").read_text()
    for t in templates.values():
        project = load_project(t.folder)
        load_cam_tables(project, t.folder)
    assert load_project(templates["empty"].folder).axes == []
    single = load_project(templates["single-axis"].folder)
    assert [(a.name, a.type.name, a.node_address) for a in single.axes] == [("MC_Axis000", "_mcServo", 1)]


def test_build_folder_from_template(tmp_path: Path) -> None:
    demo = next(t for t in list_templates() if t.name == "demo")
    folder = build_project_folder(tmp_path, "copy", lambda staging: copy_template(demo, staging))
    assert folder == (tmp_path / "copy").resolve()
    assert sorted(p.name for p in (folder / "cams").iterdir()) == ["FlyingSync.csv", "RiseDwellReturn.csv"]
    assert load_project(folder).name == "Demo machine"
    assert [p.name for p in tmp_path.iterdir()] == ["copy"]
    with pytest.raises(FileExistsError, match="already exists"):
        build_project_folder(tmp_path, "copy", lambda staging: copy_template(demo, staging))


def test_a_failing_build_leaves_nothing(tmp_path: Path) -> None:
    """D112: the folder appears only complete; a failure while filling it removes the staging folder."""

    def fill(staging: Path) -> None:
        (staging / "project.json").write_text("{}")
        raise OSError("disk full")

    with pytest.raises(OSError, match="disk full"):
        build_project_folder(tmp_path, "p", fill)
    assert list(tmp_path.iterdir()) == []


def test_overwrite_keeps_the_previous_document_as_bak(tmp_path: Path) -> None:
    single = next(t for t in list_templates() if t.name == "single-axis")
    build_project_folder(tmp_path, "p", lambda staging: copy_template(single, staging))
    old = (tmp_path / "p" / "project.json").read_bytes()
    project = load_project(tmp_path / "p").model_copy(update={"description": "second"})
    build_project_folder(tmp_path, "p", lambda staging: save_project(staging, project), overwrite=True)
    assert load_project(tmp_path / "p").description == "second"
    assert (tmp_path / "p" / "project.json.bak").read_bytes() == old
    assert [p.name for p in tmp_path.iterdir()] == ["p"]  # the old folder set aside is gone


def test_stale_temp_files_of_another_process_are_removed(tmp_path: Path) -> None:
    path = tmp_path / "project.json"
    path.write_text("{}")
    stale = tmp_path / ".project.json.999999999.abcd.tmp"
    mine = tmp_path / f".project.json.{os.getpid()}.efgh.tmp"
    other = tmp_path / ".cams.csv.999999999.x.tmp"
    for p in (stale, mine, other):
        p.write_text("partial")
    assert remove_stale_temp_files(path) == [stale]
    assert mine.exists() and other.exists()


def _cli(*args: str, cwd: Path | None = None) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-m", "mcstudio", *args], capture_output=True, text=True, check=False,
                          cwd=cwd)


def test_cli_new_and_schema(tmp_path: Path) -> None:
    r = _cli("new", str(tmp_path / "line1"), "--template", "single-axis")
    assert r.returncode == 0, r.stderr
    assert load_project(tmp_path / "line1").name == "line1"
    r = _cli("new", str(tmp_path / "line1"))
    assert r.returncode == 1 and "already exists" in r.stderr
    r = _cli("new", str(tmp_path / "x"), "--template", "nope")
    assert r.returncode == 2 and "single-axis" in r.stderr
    r = _cli("schema", "-o", str(tmp_path / "schema.json"))
    assert r.returncode == 0, r.stderr
    schema = json.loads((tmp_path / "schema.json").read_text())
    assert schema["title"] == "Project" and "$schema" in schema["properties"]
