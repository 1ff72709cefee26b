"""API fuzzing (issue 9): schemathesis generates requests from the OpenAPI document — valid ones and ones that break
the schema (wrong types, missing fields, undecodable bodies) — for every operation and sends them in-process (ASGI
transport, no server). Checks: no 5xx (`not_a_server_error`), every response matches its declared schema
(`response_schema_conformance`) and its status code is one the operation documents (`status_code_conformance`).

Bounded: `MCSTUDIO_FUZZ_EXAMPLES` examples per operation and generation mode (default 12; derandomized, so CI sees
the same requests every run); a fresh studio (copy of the demo project) per operation. Nothing is excluded; one
request field is capped (see `_bounded`). Findings and how to run deeper: docs/hardening.md.
"""

from __future__ import annotations

import os
import re
from pathlib import Path
from typing import Any

import pytest
import schemathesis
from fastapi.testclient import TestClient
from hypothesis import HealthCheck, Phase, given, settings
from hypothesis import strategies as st
from schemathesis.checks import not_a_server_error
from schemathesis.generation.modes import GenerationMode
from schemathesis.specs.openapi.checks import response_schema_conformance, status_code_conformance

from mcstudio.api.app import create_app
from mcstudio.api.openapi_export import openapi_document
from tests.hardening.conftest import demo_app, demo_studio

EXAMPLES = int(os.environ.get("MCSTUDIO_FUZZ_EXAMPLES", "12"))
CHECKS = [not_a_server_error, response_schema_conformance, status_code_conformance]
MAX_FUZZ_STEP = 100  # cycles per generated POST /controller/step (see _bounded)

OPERATIONS = [(method.upper(), path) for path, item in openapi_document()["paths"].items()
              for method in item if method in ("get", "put", "post", "patch", "delete")]


def _bounded(case: Any) -> None:
    """POST /controller/step runs up to 10^6 periods by design (a few seconds each 10^5 on this VM); the fuzzer
    would spend its budget stepping. Cycles above MAX_FUZZ_STEP are lowered to it — the request stays valid and
    the limit itself is checked by `test_step_limit`."""
    body = case.body
    if case.path.endswith("/controller/step") and isinstance(body, dict):
        cycles = body.get("cycles")  # an integral float (1e5) is an integer to pydantic as well
        if isinstance(cycles, int | float) and not isinstance(cycles, bool) and cycles > MAX_FUZZ_STEP:
            body["cycles"] = MAX_FUZZ_STEP


@pytest.mark.parametrize(("method", "path"), OPERATIONS, ids=[f"{m} {p}" for m, p in OPERATIONS])
def test_operation(method: str, path: str, tmp_path: Path) -> None:
    app = demo_app(tmp_path)
    schema = schemathesis.openapi.from_asgi("/api/v1/openapi.json", app)
    op = schema[path][method].ok() if hasattr(schema[path][method], "ok") else schema[path][method]
    strategy = st.one_of(op.as_strategy(GenerationMode.POSITIVE), op.as_strategy(GenerationMode.NEGATIVE))

    @settings(max_examples=2 * EXAMPLES, derandomize=True, deadline=None, database=None,
              suppress_health_check=list(HealthCheck), phases=[Phase.explicit, Phase.generate, Phase.shrink])
    @given(strategy)
    def run(case: Any) -> None:
        _bounded(case)
        case.call_and_validate(checks=CHECKS)

    run()


def test_step_limit(tmp_path: Path) -> None:
    """The documented maximum is refused one above it with a 422 naming `cycles` (api.md Controller)."""
    from mcstudio.api.models import MAX_STEP_CYCLES

    with TestClient(demo_app(tmp_path)) as c:
        r = c.post("/api/v1/controller/step", json={"cycles": MAX_STEP_CYCLES + 1})
        assert r.status_code == 422 and r.json()["detail"][0]["loc"] == ["body", "cycles"]


# ---------------------------------------------------------------------------------------------- regressions
# Each of these was a finding of the fuzzing above (docs/hardening.md "Findings fixed").

@pytest.mark.parametrize("body", [b"\xff\xfe{", b"\x80abc", b'{"mode": "fast"\xff}'])
def test_undecodable_json_body_is_422_naming_the_body(tmp_path: Path, body: bytes) -> None:
    """Bytes that are not UTF-8 JSON: FastAPI answered a bare 400 (undocumented); now 422 with loc ["body"] (D121)."""
    with TestClient(demo_app(tmp_path)) as c:
        r = c.put("/api/v1/controller/mode", content=body, headers={"Content-Type": "application/json"})
    assert r.status_code == 422, r.text
    assert r.json()["detail"][0]["loc"] == ["body"]


def test_malformed_multipart_is_422(tmp_path: Path) -> None:
    """A multipart form with more fields than the form parser allows: Starlette's 400 → 422 naming the body."""
    boundary = "b0undary"
    parts = "".join(f'--{boundary}\r\nContent-Disposition: form-data; name="f{k}"\r\n\r\n{k}\r\n' for k in range(2000))
    data = (parts + f"--{boundary}--\r\n").encode()
    with TestClient(demo_app(tmp_path)) as c:
        r = c.put("/api/v1/cams/CamProfile0/csv", content=data,
                  headers={"Content-Type": f"multipart/form-data; boundary={boundary}"})
    assert r.status_code == 422, r.text
    assert r.json()["detail"][0]["loc"] == ["body"]


def test_missing_client_header_stays_400(tmp_path: Path) -> None:
    """Only body-reading failures are turned into 422: a route's own 400 (shared control) keeps its status."""
    with TestClient(demo_app(tmp_path)) as c:
        r = c.post("/api/v1/control/take", json={})
    assert r.status_code in (400, 422), r.text
    if r.status_code == 400:
        assert isinstance(r.json()["detail"], list)


@pytest.mark.parametrize(("method", "path", "body"), [
    ("POST", "/api/v1/controller/step", {"cycles": 1, "until": {"fb": 4242, "output": "Done", "equals": True}}),
    ("GET", "/api/v1/ethercat/slaves/120/image", None),
    ("GET", "/api/v1/devices/no-such-device", None),
])
def test_not_found_is_documented(tmp_path: Path, method: str, path: str, body: Any) -> None:
    """These answered 404 without declaring it in the OpenAPI document (status-code conformance)."""
    app = demo_app(tmp_path)
    with TestClient(app) as c:
        r = c.request(method, path, json=body)
        assert r.status_code == 404, r.text
        doc = c.get("/api/v1/openapi.json").json()
    template = path.replace("/120/", "/{address}/").replace("/no-such-device", "/{device_id}")
    assert "404" in doc["paths"][template][method.lower()]["responses"]


@pytest.mark.parametrize("key", ["[", "]", "a[", "[²]", "x[1", "[]", "a.b[c]d["])
def test_project_error_paths_with_brackets_in_keys(tmp_path: Path, key: str) -> None:
    """Finding: PUT /project with an unknown key "[" made the 422's path splitting raise ValueError (a 500); keys
    with brackets are now kept as text in `loc`."""
    with TestClient(demo_app(tmp_path)) as c:
        r = c.put("/api/v1/project", json={key: None})
    assert r.status_code == 422, r.text
    assert all(isinstance(d["loc"], list) and d["loc"][0] == "body" for d in r.json()["detail"])


# A JSON true/false where a number is expected (D129). Found by `st run --checks all`: pydantic's lax mode read
# `"pre_trigger_percent": false` as 0.0 and answered 200.
def _axis_config_with_bool(c: TestClient) -> tuple[str, str, Any, list[Any]]:
    cfg = c.get("/api/v1/axes/MC_Axis001").json()["config"]
    cfg["parameters"]["Operation"]["MaxVel"] = True
    return "PUT", "/api/v1/axes/MC_Axis001/config", cfg, ["parameters", "Operation", "MaxVel"]


_TRIGGER = {"variable": {"kind": "axis", "target": "MC_Axis000", "name": "Cmd.Pos"}, "condition": "rising",
            "level": 0.5, "pre_trigger_percent": False}
_TRACE = {"name": "T", "variables": [{"kind": "axis", "target": "MC_Axis000", "name": "Cmd.Pos"}], "mode": "single",
          "trigger": _TRIGGER}


@pytest.mark.parametrize("request_of", [
    lambda c: ("PUT", "/api/v1/project/traces", [_TRACE], [0, "trigger", "pre_trigger_percent"]),
    lambda c: ("POST", "/api/v1/traces", {**_TRACE, "samples": True}, ["samples"]),
    lambda c: ("POST", "/api/v1/controller/step", {"cycles": True}, ["cycles"]),
    lambda c: ("POST", "/api/v1/groups/MC_Group000/kinematics/inverse", {"position": [0, True, -400]}, ["position"]),
    _axis_config_with_bool,
], ids=["trace-trigger-percent", "trace-samples", "step-cycles", "kinematics-list-item", "axis-MaxVel"])
def test_boolean_is_not_a_number(tmp_path: Path, request_of: Any) -> None:
    """A boolean for an int/float field (or an item of a list of numbers) is a 422 naming the field — never 1/0."""
    with TestClient(demo_app(tmp_path)) as c:
        before = c.get("/api/v1/project").json()
        method, path, body, loc = request_of(c)
        r = c.request(method, path, json=body)
        assert r.status_code == 422, r.text
        errors = r.json()["detail"]
        assert any(e["loc"][1:len(loc) + 1] == loc and "boolean" in e["msg"] for e in errors), errors
        assert c.get("/api/v1/project").json() == before  # nothing applied
    if path.endswith("inverse"):
        assert "position[1]" in errors[0]["msg"]


@pytest.mark.parametrize(("path", "body", "loc"), [
    ("/api/v1/project/save-as", {"name": "copy", "overwrite": 0}, ["overwrite"]),
    ("/api/v1/faults", {"kind": "drive_fault", "node_address": 1, "code": 8976, "persistent": 1}, ["persistent"]),
    ("/api/v1/faults", {"kind": "drive_fault", "node_address": 1, "code": 8976, "persistent": "yes"}, ["persistent"]),
    ("/api/v1/controller/step", {"cycles": 1, "until": {"fb": 1, "output": "ErrorID", "equals": 0}}, None),
])
def test_a_bool_field_takes_only_true_or_false(tmp_path: Path, path: str, body: Any, loc: list[str] | None) -> None:
    """0/1 or "yes" for a BOOL field is a 422 naming it (pydantic would read them as false/true and act on them).
    `until.equals` compares with any output (BOOL or a number), so a number stays valid there."""
    with TestClient(demo_app(tmp_path)) as c:
        if loc is None:
            fb = c.post("/api/v1/fb", json={"type": "MC_Power", "inputs": {"Axis": "MC_Axis000", "Enable": True}})
            body["until"]["fb"] = fb.json()["id"]
            assert c.post(path, json=body).status_code == 200
            return
        r = c.post(path, json=body)
        assert r.status_code == 422, r.text
        assert any(e["loc"][1:] == loc and "true or false" in e["msg"] for e in r.json()["detail"]), r.text
        assert not (tmp_path / "projects" / "copy").exists()


# 405s (D128). Found by `st run`: a method a path does not serve answered 404 behind the studio's page fallback
# (GET /control/release), 422 (DELETE /traces/variables parsed "variables" as a trace id), or a 405 whose `Allow`
# named only the first route's methods (OPTIONS /cams/{name}: `Allow: GET`, not DELETE, GET, PUT).
_DOC = openapi_document()["paths"]
_METHODS = ("GET", "PUT", "POST", "PATCH", "DELETE", "OPTIONS")


def _concrete(template: str) -> str:
    return re.sub(r"\{[^/]+\}", "1", template)


@pytest.mark.parametrize("template", list(_DOC), ids=list(_DOC))
def test_undocumented_method_is_405_with_allow(tmp_path: Path, template: str) -> None:
    """Every method the path does not serve is a 405 whose `Allow` lists the methods it does serve: each
    documented one, and each of them answers something other than 405. (/cams/generate also serves GET, PUT,
    DELETE: there it is the cam table named "generate".)"""
    documented = {m.upper() for m in _DOC[template] if m.upper() in _METHODS}
    static = tmp_path / "static"
    static.mkdir()
    (static / "index.html").write_text("<!doctype html><title>MC Studio</title>")
    app = create_app(demo_studio(tmp_path), static_dir=static)  # with the page fallback, as `mcstudio serve`
    with TestClient(app) as c:
        path = _concrete(template)
        status = {m: c.request(m, path).status_code for m in _METHODS}
        answered = {m for m, code in status.items() if code != 405}
        assert documented <= answered, status
        for method in sorted(set(_METHODS) - answered):
            r = c.request(method, path)
            assert set(r.headers["allow"].split(", ")) == answered, (method, r.headers["allow"], status)
            assert method in r.json()["detail"]


def test_page_fallback_still_serves_the_studio(tmp_path: Path) -> None:
    static = tmp_path / "static"
    static.mkdir()
    (static / "index.html").write_text("<!doctype html><title>MC Studio</title>")
    with TestClient(create_app(demo_studio(tmp_path), static_dir=static)) as c:
        assert "MC Studio" in c.get("/axes/MC_Axis000").text  # a studio route, not an API one
        assert c.get("/api/v1/no-such-thing").status_code == 404
        assert c.get("/api/v1/traces/not-a-number").status_code == 404  # not a trace id: no such trace


def test_cam_master_velocity_is_a_positive_real(tmp_path: Path) -> None:
    """Found by `st run` (seed 7): master_velocity 5e-324 (a double denormal, no REAL) made every segment's time_s
    infinite, sent as null against the schema's number. The smallest positive normal REAL is the floor now."""
    from mcstudio.project.cam_models import REAL_MIN_NORMAL

    nodes = [{"Phase": 90.0, "Distance": 10.0, "Curve": "_mcPolynomic5"},
             {"Phase": 180.0, "Distance": 0.0, "Curve": "_mcCycloidal"}]
    with TestClient(demo_app(tmp_path)) as c:
        r = c.post("/api/v1/cams/generate", json={"nodes": nodes, "master_velocity": 5e-324})
        assert r.status_code == 422 and r.json()["detail"][0]["loc"] == ["body", "master_velocity"], r.text
        r = c.post("/api/v1/cams/generate", json={"nodes": nodes, "master_velocity": REAL_MIN_NORMAL})
        assert r.status_code == 200, r.text
        assert all(isinstance(s["time_s"], float) for s in r.json()["characteristics"]["segments"])
