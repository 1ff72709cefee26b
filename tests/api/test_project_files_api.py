"""Projects through REST (issue 8/9): save-as, revert, new from a template, corrupt projects refused untouched, names
that cannot leave the projects folder (decisions D110–D112, docs/project-format.md)."""

from __future__ import annotations

import hashlib
import json
import os
import shutil
from pathlib import Path

import pytest
from fastapi.testclient import TestClient

from mcstudio.api.state import Studio
from mcstudio.project.io import load_project
from tests.api.test_rest import API, post, power_on


def _tree(folder: Path) -> dict[str, str]:
    """Every file below `folder` with its SHA-256: 'left untouched' means this is equal before and after."""
    return {str(p.relative_to(folder)): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(folder.rglob("*")) if p.is_file()}


def _edit_max_jog(client: TestClient, value: float) -> None:
    doc = client.get(f"{API}/project").json()
    doc["axes"][2]["parameters"]["Operation"]["MaxJogVel"] = value
    assert client.put(f"{API}/project", json=doc).status_code == 200


def _max_jog(client: TestClient) -> float:
    return float(client.get(f"{API}/project").json()["axes"][2]["parameters"]["Operation"]["MaxJogVel"])


def _status(client: TestClient) -> dict:
    return client.get(f"{API}/controller").json()


# ------------------------------------------------------------------ save-as
def test_save_as_copies_the_folder_and_continues_in_it(client: TestClient, project_dir: Path,
                                                       studio: Studio) -> None:
    (project_dir / "esi").mkdir()
    (project_dir / "esi" / "vendor.xml").write_text("<EtherCATInfo/>")
    before = _tree(project_dir)
    _edit_max_jog(client, 42.0)
    out = post(client, "/project/save-as", {"name": "Line 2"})
    new = project_dir.parent / "Line 2"
    assert Path(out["path"]) == new / "project.json"
    # the unsaved change went into the new folder; the old folder is byte-for-byte as it was
    assert load_project(new).axes[2].parameters.Operation.MaxJogVel == 42.0
    assert _tree(project_dir) == before
    assert {p.name for p in (new / "cams").iterdir()} == {"RiseDwellReturn.csv", "FlyingSync.csv"}
    assert (new / "esi" / "vendor.xml").read_text() == "<EtherCATInfo/>"
    assert not (new / "project.json.bak").exists()  # a new project has no previous version
    assert [p.name for p in project_dir.parent.iterdir() if p.name.startswith(".")] == []  # no staging left
    # the studio now works in the new folder: clean, and Save writes there
    assert _status(client)["project_dirty"] is False and studio.project_dir == new
    listing = {p["name"]: p for p in client.get(f"{API}/projects").json()}
    assert listing["Line 2"]["current"] and not listing["demo"]["current"]
    _edit_max_jog(client, 43.0)
    post(client, "/project/save", None)
    assert load_project(new).axes[2].parameters.Operation.MaxJogVel == 43.0
    assert _tree(project_dir) == before


def test_save_as_refuses_an_existing_name_unless_overwrite(client: TestClient, project_dir: Path) -> None:
    post(client, "/project/save-as", {"name": "copy"})
    post(client, "/projects/open", {"name": "demo"})
    copy = project_dir.parent / "copy"
    old_copy = (copy / "project.json").read_bytes()
    _edit_max_jog(client, 41.0)
    r = client.post(f"{API}/project/save-as", json={"name": "copy"})
    assert r.status_code == 409 and "already exists" in r.json()["detail"]
    assert (copy / "project.json").read_bytes() == old_copy
    post(client, "/project/save-as", {"name": "copy", "overwrite": True})
    assert load_project(copy).axes[2].parameters.Operation.MaxJogVel == 41.0
    assert (copy / "project.json.bak").read_bytes() == old_copy  # the replaced version is kept
    # a folder that is not a project is never replaced
    (project_dir.parent / "notes").mkdir()
    (project_dir.parent / "notes" / "todo.txt").write_text("keep me")
    r = client.post(f"{API}/project/save-as", json={"name": "notes", "overwrite": True})
    assert r.status_code == 409 and "not a project folder" in r.json()["detail"]
    assert (project_dir.parent / "notes" / "todo.txt").read_text() == "keep me"


def test_save_as_own_name_needs_overwrite(client: TestClient, project_dir: Path) -> None:
    assert client.post(f"{API}/project/save-as", json={"name": "demo"}).status_code == 409
    _edit_max_jog(client, 44.0)
    post(client, "/project/save-as", {"name": "demo", "overwrite": True})  # = Save
    assert load_project(project_dir).axes[2].parameters.Operation.MaxJogVel == 44.0


@pytest.mark.parametrize("name", ["../outside", "..", ".", "a/b", "a\\b", "/etc", ".hidden", "x" * 65, "ü" * 70,
                                  "", "bad\x00name", "tab\tname", "con", "trailing.", " lead", "what?", "a:b"])
def test_names_cannot_escape_the_projects_folder(client: TestClient, project_dir: Path, name: str) -> None:
    """D110: every route that takes a project name refuses these with 422 naming `name`; nothing is created."""
    root = project_dir.parent
    before = sorted(p.name for p in root.parent.iterdir())
    for path, body in (("/project/save-as", {"name": name}), ("/projects/new", {"name": name, "template": "empty"}),
                       ("/projects/open", {"name": name})):
        r = client.post(API + path, json=body)
        assert r.status_code == 422, (path, name, r.text)
        assert r.json()["detail"][0]["loc"] == ["body", "name"], r.text
    assert sorted(p.name for p in root.parent.iterdir()) == before
    assert sorted(p.name for p in root.iterdir()) == ["demo"]


def test_a_link_out_of_the_projects_folder_is_refused(client: TestClient, project_dir: Path,
                                                      tmp_path: Path) -> None:
    outside = tmp_path / "outside"
    shutil.copytree(project_dir, outside)
    os.symlink(outside, project_dir.parent / "sneaky")
    for path, body in (("/projects/open", {"name": "sneaky"}), ("/project/save-as", {"name": "sneaky"})):
        r = client.post(API + path, json=body)
        assert r.status_code == 422 and "outside the projects folder" in r.json()["detail"][0]["msg"], r.text
    assert "sneaky" not in {p["name"] for p in client.get(f"{API}/projects").json()}


def test_unicode_and_spaces_are_fine(client: TestClient, project_dir: Path) -> None:
    post(client, "/project/save-as", {"name": "Maschine Ä-3 (Test)"})
    assert (project_dir.parent / "Maschine Ä-3 (Test)" / "project.json").is_file()


# ------------------------------------------------------------------ revert
def test_revert_discards_unsaved_changes(client: TestClient, project_dir: Path) -> None:
    before = _tree(project_dir)
    _edit_max_jog(client, 42.0)
    post(client, "/controller/step", {"cycles": 10})
    assert _status(client)["project_dirty"] is True
    doc = post(client, "/project/revert", None)
    assert doc["axes"][2]["parameters"]["Operation"]["MaxJogVel"] == 100.0 == _max_jog(client)
    st = _status(client)
    assert st["project_dirty"] is False and st["cycle"] == 0  # a fresh controller, like opening the project
    assert _tree(project_dir) == before


def test_revert_refused_while_an_axis_moves(client: TestClient) -> None:
    _edit_max_jog(client, 42.0)
    power_on(client)
    post(client, "/fb", {"type": "MC_MoveVelocity", "inputs": {"Axis": "MC_Axis000", "Execute": True,
                                                               "Velocity": 10}}, 201)
    post(client, "/controller/step", {"cycles": 5})
    r = client.post(f"{API}/project/revert")
    assert r.status_code == 409 and "MC_Axis000" in r.json()["detail"]
    assert _max_jog(client) == 42.0


def test_revert_to_a_corrupt_file_changes_nothing(client: TestClient, project_dir: Path) -> None:
    _edit_max_jog(client, 42.0)
    (project_dir / "project.json").write_text('{"format": "mcstudio-project", "name": ')
    before = _tree(project_dir)
    r = client.post(f"{API}/project/revert")
    assert r.status_code == 422
    assert "not valid JSON" in r.json()["detail"][0]["msg"] and r.json()["detail"][0]["loc"] == ["project.json"]
    assert _max_jog(client) == 42.0 and _status(client)["project_dirty"] is True
    assert _tree(project_dir) == before


# ------------------------------------------------------------------ corrupt projects
def _corrupt_projects(root: Path, demo: Path) -> dict[str, str]:
    """Folders that cannot be opened, and a word of the message each must give."""
    cases = {}
    (root / "badjson").mkdir()
    (root / "badjson" / "project.json").write_bytes(b'{"format": "mcstudio-project",\n "name": "x", "axes": [ }')
    cases["badjson"] = "line 2, column"
    (root / "binary").mkdir()
    (root / "binary" / "project.json").write_bytes(b"\xff\xfe\x00garbage")
    cases["binary"] = "not UTF-8"
    doc = json.loads((demo / "project.json").read_text())
    doc["axes"][1]["parameters"]["Operation"]["MaxVel"] = -5
    doc["axes"][2]["type"] = "_mcStepper"
    (root / "invalid").mkdir()
    (root / "invalid" / "project.json").write_text(json.dumps(doc))
    shutil.copytree(demo / "cams", root / "invalid" / "cams")
    cases["invalid"] = "axes[1].parameters.Operation.MaxVel"
    shutil.copytree(demo, root / "nocams")
    (root / "nocams" / "cams" / "FlyingSync.csv").unlink()
    cases["nocams"] = "cams/FlyingSync.csv: the data file"
    shutil.copytree(demo, root / "badcsv")
    (root / "badcsv" / "cams" / "RiseDwellReturn.csv").write_text("phase,distance\n0,0\n5,1\n3,2\n")
    cases["badcsv"] = "phases must ascend"
    return cases


def test_a_corrupt_project_is_refused_listing_the_problems_and_left_untouched(client: TestClient,
                                                                              project_dir: Path) -> None:
    root = project_dir.parent
    cases = _corrupt_projects(root, project_dir)
    _edit_max_jog(client, 42.0)  # unsaved work in the open project must survive every refusal
    listing = {p["name"]: p for p in client.get(f"{API}/projects").json()}
    for name, words in cases.items():
        before = _tree(root / name)
        r = client.post(f"{API}/projects/open", json={"name": name})
        assert r.status_code == 422, (name, r.text)
        detail = r.json()["detail"]
        assert all(d["loc"] == ["body", "name"] for d in detail)
        assert words in " ".join(d["msg"] for d in detail), (name, detail)
        assert _tree(root / name) == before, name
        assert _status(client)["project"] == "Demo machine" and _max_jog(client) == 42.0
        assert listing[name]["valid"] is False and words in listing[name]["error"], listing[name]
    invalid = client.post(f"{API}/projects/open", json={"name": "invalid"}).json()["detail"]
    paths = {d.get("path") for d in invalid}
    assert {"axes[1].parameters.Operation.MaxVel", "axes[2].type"} <= paths
    assert client.post(f"{API}/projects/open", json={"name": "nothere"}).status_code == 404


# ------------------------------------------------------------------ templates
def test_templates_listed(client: TestClient) -> None:
    tpl = {t["name"]: t for t in client.get(f"{API}/project-templates").json()}
    assert list(tpl)[:3] == ["empty", "single-axis", "demo"]
    assert tpl["empty"]["axes"] == 0 and tpl["single-axis"]["axes"] == 1
    assert tpl["demo"]["axes"] == 8 and tpl["demo"]["cams"] == 2 and tpl["demo"]["title"] == "Demo machine"


@pytest.mark.parametrize(("template", "axes"), [("empty", 0), ("single-axis", 1), ("demo", 8)])
def test_new_project_from_template(client: TestClient, project_dir: Path, template: str, axes: int) -> None:
    before = _tree(project_dir)
    r = client.post(f"{API}/projects/new", json={"name": f"new {template}", "template": template})
    assert r.status_code == 201, r.text
    folder = project_dir.parent / f"new {template}"
    project = load_project(folder)
    assert project.name == f"new {template}" and len(project.axes) == axes
    assert r.json()["name"] == project.name
    st = _status(client)
    assert st["project"] == f"new {template}" and st["project_dirty"] is False and st["cycle"] == 0
    assert len(client.get(f"{API}/axes").json()) == axes
    assert not (folder / "project.json.bak").exists()
    assert _tree(project_dir) == before
    # and it is a real project folder: edit, save, reopen
    if axes:
        doc = client.get(f"{API}/project").json()
        doc["axes"][0]["parameters"]["Operation"]["MaxJogVel"] = 12.5
        assert client.put(f"{API}/project", json=doc).status_code == 200
        post(client, "/project/save", None)
        assert load_project(folder).axes[0].parameters.Operation.MaxJogVel == 12.5


def test_new_project_refusals(client: TestClient, project_dir: Path) -> None:
    r = client.post(f"{API}/projects/new", json={"name": "demo", "template": "empty"})
    assert r.status_code == 409 and "already exists" in r.json()["detail"]
    r = client.post(f"{API}/projects/new", json={"name": "x", "template": "robot-cell"})
    assert r.status_code == 422 and r.json()["detail"][0]["loc"] == ["body", "template"]
    assert "single-axis" in r.json()["detail"][0]["msg"]
    assert not (project_dir.parent / "x").exists()
    # while an axis moves the new project is not opened, and its folder is removed again
    power_on(client)
    post(client, "/fb", {"type": "MC_MoveVelocity", "inputs": {"Axis": "MC_Axis000", "Execute": True,
                                                               "Velocity": 10}}, 201)
    post(client, "/controller/step", {"cycles": 5})
    r = client.post(f"{API}/projects/new", json={"name": "y", "template": "single-axis"})
    assert r.status_code == 409
    assert sorted(p.name for p in project_dir.parent.iterdir()) == ["demo"]
    assert _status(client)["project"] == "Demo machine"


def test_no_projects_root(studio: Studio, client: TestClient) -> None:
    studio.projects_root = None
    assert client.post(f"{API}/project/save-as", json={"name": "a"}).status_code == 409
    assert client.post(f"{API}/projects/new", json={"name": "a", "template": "empty"}).status_code == 409
    assert client.get(f"{API}/projects").json() == []


def test_schema_accepts_dollar_schema_and_keeps_it(client: TestClient, project_dir: Path) -> None:
    """D113: a `$schema` line for editors survives loading, PUT and saving."""
    url = "http://127.0.0.1:8000/api/v1/project/schema"
    schema = client.get(f"{API}/project/schema").json()
    assert schema["properties"]["$schema"]["anyOf"][0]["type"] == "string"
    doc = client.get(f"{API}/project").json()
    doc["$schema"] = url
    assert client.put(f"{API}/project", json=doc).status_code == 200
    post(client, "/project/save", None)
    text = (project_dir / "project.json").read_text()
    assert text.startswith('{\n  "$schema": "' + url + '",\n  "format": "mcstudio-project"')
    assert load_project(project_dir).schema_ref == url
