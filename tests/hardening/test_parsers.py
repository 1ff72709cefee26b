"""Parser fuzzing (issue 9): the ESI importer, the cam-table CSV reader and the project-document loader given
malformed, huge and hostile input — entity expansion and external entities, deep nesting, huge attributes, lines and
numbers, wrong encodings, truncation, binary garbage. Property: a clear error of the parser's own kind (EsiError,
CamCsvError, ProjectError; a 4xx at the API) or a result — never another exception — within bounded memory
(tracemalloc peak) and a bounded number of Python calls (a profile hook; no wall-clock asserts).

Hypothesis runs derandomized with `MCSTUDIO_FUZZ_EXAMPLES` examples (default 12) per strategy.
"""

from __future__ import annotations

import json
import os
from collections.abc import Iterator
from pathlib import Path

import pytest
from fastapi.testclient import TestClient
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from mcstudio.controller.mc.cam.csvio import CamCsvError, parse_cam_csv
from mcstudio.fieldbus.esi import EsiError, parse_esi
from mcstudio.project.io import ProjectError, load_project, parse_project
from tests.conftest import DEMO
from tests.hardening.bounded import measure
from tests.hardening.conftest import demo_app

EXAMPLES = int(os.environ.get("MCSTUDIO_FUZZ_EXAMPLES", "12"))
FUZZ = settings(max_examples=EXAMPLES, derandomize=True, deadline=None, database=None,
                suppress_health_check=list(HealthCheck))
MB = 1024 * 1024
SOES = Path("/work/shared/fixtures/esi/soes-cia402.xml")
needs_esi_fixture = pytest.mark.skipif(not SOES.is_file(), reason="ESI fixture not available")
DEMO_JSON = (DEMO / "project.json").read_bytes()


def _esi_base() -> bytes:
    return SOES.read_bytes() if SOES.is_file() else (
        b'<?xml version="1.0"?><EtherCATInfo><Vendor><Id>#x99</Id></Vendor><Descriptions><Devices><Device>'
        b'<Type ProductCode="#x1" RevisionNo="#x1">T</Type><Name>D</Name></Device></Devices></Descriptions>'
        b"</EtherCATInfo>")


# ------------------------------------------------------------------------------------------------ mutations
@st.composite
def mutated(draw: st.DrawFn, base: bytes) -> bytes:
    """`base` with a few byte-level mutations: truncation, flipped bytes, inserted hostile fragments, repetition."""
    data = bytearray(base)
    for _ in range(draw(st.integers(1, 4))):
        op = draw(st.integers(0, 4))
        pos = draw(st.integers(0, max(0, len(data) - 1)))
        if op == 0:
            del data[pos:]
        elif op == 1 and data:
            data[pos] = draw(st.integers(0, 255))
        elif op == 2:
            data[pos:pos] = draw(st.sampled_from(HOSTILE_FRAGMENTS))
        elif op == 3:
            n = draw(st.integers(2, 2000))
            data[pos:pos] = bytes(data[pos:pos + 16]) * n
        else:
            data[pos:pos] = draw(st.binary(max_size=64))
    return bytes(data)


HOSTILE_FRAGMENTS = [
    b'<!DOCTYPE x [<!ENTITY a "aaaaaaaaaa"><!ENTITY b "&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;">]>', b"&a;&b;", b"&#0;",
    b'<!ENTITY x SYSTEM "file:///etc/passwd">', b"<![CDATA[", b"]]>", b"<!--", b"-->", b"<?xml version='1.0'?>",
    b'encoding="UTF-16"', b"\xef\xbb\xbf", b"\xff\xfe", b"\x00", b"\xc3\x28", b"<" * 50, b"<a>" * 200,
    b'"' * 30, b"#x" + b"F" * 40, b"-" + b"9" * 400, b"NaN", b"1e999", b",,,,", b"\r\n" * 20, b"\t"]


# ------------------------------------------------------------------------------------------------ ESI
def _esi_ok(data: bytes, *, max_peak: int, max_calls: int) -> None:
    cost = measure(lambda: parse_esi(data, source="fuzz.xml"))
    assert cost.error is None or isinstance(cost.error, EsiError), repr(cost.error)
    assert cost.peak_bytes < max_peak, f"peak {cost.peak_bytes / MB:.1f} MiB"
    assert cost.calls < max_calls, f"{cost.calls} calls"


@FUZZ
@given(mutated(_esi_base()))
def test_esi_mutations(data: bytes) -> None:
    _esi_ok(data, max_peak=64 * MB, max_calls=2_000_000)


def test_esi_billion_laughs_and_external_entities_are_refused_before_parsing() -> None:
    """Entity declarations live in a DOCTYPE, which is refused before the parser sees the file, wherever it hides
    (after a BOM, comments, processing instructions, in UTF-16 and in lower case)."""
    lol = b'<!ENTITY l0 "lol">' + b"".join(b'<!ENTITY l%d "%s">' % (k, b"&l%d;" % (k - 1) * 10) for k in range(1, 10))
    for doc in (b'<?xml version="1.0"?><!DOCTYPE x [' + lol + b"]><EtherCATInfo>&l9;</EtherCATInfo>",
                b'\xef\xbb\xbf<!-- a --><?pi x?>\n<!doctype x [<!ENTITY e SYSTEM "file:///etc/passwd">]><x>&e;</x>',
                b'<!DOCTYPE x [<!ENTITY % p SYSTEM "http://127.0.0.1:9/p">%p;]><EtherCATInfo/>',
                ('<?xml version="1.0" encoding="UTF-16"?><!DOCTYPE x [<!ENTITY a "b">]><x>&a;</x>').encode("utf-16")):
        cost = measure(lambda doc=doc: parse_esi(doc))
        assert isinstance(cost.error, EsiError) and "DOCTYPE" in str(cost.error), cost.error
        assert cost.peak_bytes < MB and cost.calls < 5_000


def test_esi_undeclared_entity_is_a_clear_error() -> None:
    cost = measure(lambda: parse_esi(b"<EtherCATInfo><Vendor><Id>&lol9;</Id></Vendor></EtherCATInfo>"))
    assert isinstance(cost.error, EsiError) and "line 1" in str(cost.error)


@pytest.mark.parametrize(("name", "data"), [
    ("deep nesting 10^5", b"<EtherCATInfo>" + b"<a>" * 100_000 + b"</a>" * 100_000 + b"</EtherCATInfo>"),
    ("deep nesting inside a device", _esi_base().replace(b"<Name", b"<x>" * 100_000 + b"</x>" * 100_000 + b"<Name",
                                                         1)),
    ("8 MB attribute value", _esi_base().replace(b"<Device", b'<Device Junk="' + b"A" * 8 * MB + b'"', 1)),
    ("8 MB text", _esi_base().replace(b"<Name", b"<Name>" + b"B" * 8 * MB + b"</Name><Name", 1)),
    ("10^5 attributes", b"<EtherCATInfo " + b" ".join(b'a%d="1"' % i for i in range(100_000)) + b"/>"),
    ("unterminated comment", b"<!--" + b"-" * MB),
    ("unterminated declaration", b'<?xml version="1.0"' + b" " * MB),
    ("UTF-32", _esi_base().decode("latin-1").encode("utf-32")),
    ("EBCDIC", _esi_base().decode("latin-1").encode("cp500")),
    ("declared EBCDIC", b'<?xml version="1.0" encoding="cp500"?>' + _esi_base()),
    ("unknown encoding", b'<?xml version="1.0" encoding="x-no-such"?><EtherCATInfo/>'),
    ("NUL bytes", b"\x00" * 1000),
    ("binary", bytes(range(256)) * 1000),
    ("truncated", _esi_base()[: len(_esi_base()) // 2]),
    ("empty", b""),
    ("huge numbers", _esi_base().replace(b"<Index>", b"<Index>#x" + b"F" * 100_000, 1)),
])
def test_esi_hostile_files(name: str, data: bytes) -> None:
    """Each is an EsiError naming the line, or a file read with warnings; memory at most ~10× the input + 32 MiB."""
    _esi_ok(data, max_peak=10 * len(data) + 32 * MB, max_calls=2_000_000)


def test_esi_device_count_is_bounded() -> None:
    """Finding: 50,000 tiny distinct devices (2.5 MB of XML) took 125 MB and ~10 s to import; a file with more
    devices than MAX_ESI_DEVICES is refused at once (decision D122)."""
    from mcstudio.fieldbus.esi import MAX_ESI_DEVICES

    n = MAX_ESI_DEVICES + 1
    data = (b"<EtherCATInfo><Vendor><Id>1</Id></Vendor><Descriptions><Devices>"
            + b"".join(b'<Device><Type ProductCode="%d">x</Type></Device>' % i for i in range(n))
            + b"</Devices></Descriptions></EtherCATInfo>")
    cost = measure(lambda: parse_esi(data))
    assert isinstance(cost.error, EsiError) and str(MAX_ESI_DEVICES) in str(cost.error)
    assert cost.calls < 100_000


# ------------------------------------------------------------------------------------------------ cam CSV
CSV_OK = "phase,distance\n0,0\n90,10\n180,20\n360,0\n"


def _csv_ok(text: str, *, max_peak: int = 64 * MB, max_calls: int = 3_000_000) -> None:
    cost = measure(lambda: parse_cam_csv(text))
    assert cost.error is None or isinstance(cost.error, CamCsvError), repr(cost.error)
    assert cost.peak_bytes < max_peak, f"peak {cost.peak_bytes / MB:.1f} MiB"
    assert cost.calls < max_calls, f"{cost.calls} calls"
    if isinstance(cost.error, CamCsvError):
        assert 1 <= len(cost.error.problems) <= 21
        assert all(len(str(p)) < 400 for p in cost.error.problems), "an error message echoes a huge field"


@FUZZ
@given(mutated(CSV_OK.encode()))
def test_cam_csv_mutations(data: bytes) -> None:
    _csv_ok(data.decode("utf-8", errors="replace"))


@FUZZ
@given(st.lists(st.tuples(st.one_of(st.floats(), st.text(max_size=8)), st.one_of(st.floats(), st.text(max_size=8))),
                max_size=50))
def test_cam_csv_random_rows(rows: list[tuple[object, object]]) -> None:
    _csv_ok("phase,distance\n" + "\n".join(f"{a},{b}" for a, b in rows))


@pytest.mark.parametrize(("name", "text"), [
    ("10^6 lines", "phase,distance\n" + "".join(f"{k},{k % 7}\n" for k in range(1_000_000))),
    ("a 4 MB row", "phase,distance\n0,0\n" + "1" * 4 * MB + ",2\n"),
    ("a 4 MB header", "x" * 4 * MB),
    ("NaN and inf", "phase,distance\n0,0\nnan,1\ninf,2\n-inf,3\n1e999,4\n"),
    ("non-monotonic phase", "phase,distance\n0,0\n" + "".join(f"{(k * 37) % 100},{k}\n" for k in range(1000))),
    ("binary garbage", bytes(range(256)).decode("latin-1") * 1000),
    ("10^5 commas", "phase,distance\n0," + "," * 100_000 + "\n"),
    ("only comments", "# x\n" * 100_000),
])
def test_cam_csv_hostile(name: str, text: str) -> None:
    _csv_ok(text, max_peak=40 * len(text) + 32 * MB, max_calls=6_000_000)


# ------------------------------------------------------------------------------------------------ project JSON
def _project_ok(data: bytes, tmp: Path, *, max_peak: int = 64 * MB) -> None:
    folder = tmp / "p"
    folder.mkdir(exist_ok=True)
    (folder / "project.json").write_bytes(data)
    cost = measure(lambda: load_project(folder), count_calls=False)
    assert cost.error is None or isinstance(cost.error, ProjectError), repr(cost.error)
    assert cost.peak_bytes < max_peak, f"peak {cost.peak_bytes / MB:.1f} MiB"


@FUZZ
@given(mutated(DEMO_JSON))
def test_project_json_mutations(tmp_path_factory: pytest.TempPathFactory, data: bytes) -> None:
    _project_ok(data, tmp_path_factory.mktemp("pj"))


@pytest.mark.parametrize(("name", "data"), [
    ("truncated", DEMO_JSON[: len(DEMO_JSON) // 2]),
    ("UTF-16", DEMO_JSON.decode().encode("utf-16")),
    ("NUL bytes", b"\x00" * 100),
    ("empty", b""),
    ("not an object", b"[1, 2, 3]"),
    ("NaN literal", DEMO_JSON.replace(b'"MaxVel": ', b'"MaxVel": NaN, "x": ', 1)),
    ("1e999", DEMO_JSON.replace(b'"MaxVel": ', b'"MaxVel": 1e999, "x": ', 1)),
    ("a 1 MB name", json.dumps({**json.loads(DEMO_JSON), "name": "n" * MB}).encode()),
    ("deep nesting 10^5", b"[" * 100_000 + b"]" * 100_000),
    ("deep object nesting", b'{"a":' * 100_000 + b"1" + b"}" * 100_000),
    ("a 10^5-digit integer", b'{"name": "x", "n": 1' + b"0" * 100_000 + b"}"),
])
def test_project_json_hostile_files(name: str, data: bytes, tmp_path: Path) -> None:
    _project_ok(data, tmp_path)


def test_project_json_bom_is_read(tmp_path: Path) -> None:
    """A project.json saved by a Windows editor starts with a UTF-8 BOM."""
    (tmp_path / "project.json").write_bytes(b"\xef\xbb\xbf" + DEMO_JSON)
    assert load_project(tmp_path).name


@pytest.mark.parametrize(("name", "mutate"), [
    ("inf MaxVel", lambda d: d["axes"][0]["parameters"]["Operation"].update(MaxVel=float("inf"))),
    ("nan MaxVel", lambda d: d["axes"][0]["parameters"]["Operation"].update(MaxVel=float("nan"))),
    ("1e308 MaxVel", lambda d: d["axes"][0]["parameters"]["Operation"].update(MaxVel=1e308)),
    ("huge period", lambda d: d["controller"].update(primary_period_us=10**30)),
    ("wrong type axes", lambda d: d.update(axes="MC_Axis000")),
    ("deep parameters", lambda d: d["axes"][0].update(parameters=_deep(10_000))),
    ("10^4 axes", lambda d: d.update(axes=[d["axes"][0]] * 10_000)),
])
def test_project_document_hostile_values(name: str, mutate: object) -> None:
    data = json.loads(DEMO_JSON)
    mutate(data)  # type: ignore[operator]
    cost = measure(lambda: parse_project(data), count_calls=False)
    assert isinstance(cost.error, ProjectError), repr(cost.error)
    assert cost.peak_bytes < 256 * MB


def _deep(n: int) -> dict[str, object]:
    root: dict[str, object] = {}
    cur = root
    for _ in range(n):
        nxt: dict[str, object] = {}
        cur["a"] = nxt
        cur = nxt
    return root


# ------------------------------------------------------------------------------------------------ through the API
@pytest.fixture(scope="module")
def api(tmp_path_factory: pytest.TempPathFactory) -> TestClient:
    with TestClient(demo_app(tmp_path_factory.mktemp("parsers-api"))) as client:
        yield client  # type: ignore[misc]


@pytest.mark.parametrize(("name", "body"), [
    ("deep nesting", b"[" * 100_000 + b"]" * 100_000),
    ("deep object", b'{"a":' * 50_000 + b"1" + b"}" * 50_000),
    ("10^5 digits", b'{"name": "x", "n": 1' + b"0" * 100_000 + b"}"),
    ("NaN", DEMO_JSON.replace(b'"MaxVel": ', b'"MaxVel": NaN, "x": ', 1)),
    ("binary", bytes(range(256))),
])
def test_project_put_hostile_bodies_are_4xx(api: TestClient, name: str, body: bytes) -> None:
    r = api.put("/api/v1/project", content=body, headers={"Content-Type": "application/json"})
    assert 400 <= r.status_code < 500 and r.status_code != 404, (r.status_code, r.text[:300])


def test_project_put_with_a_bom_is_read(api: TestClient) -> None:
    r = api.put("/api/v1/project", content=b"\xef\xbb\xbf" + DEMO_JSON, headers={"Content-Type": "application/json"})
    assert r.status_code == 200, r.text[:300]


@pytest.mark.parametrize(("name", "data"), [
    ("billion laughs", b'<!DOCTYPE x [<!ENTITY a "aaaa"><!ENTITY b "&a;&a;&a;&a;">]><EtherCATInfo>&b;</EtherCATInfo>'),
    ("binary", bytes(range(256)) * 100),
    ("truncated", _esi_base()[:1000]),
])
def test_esi_upload_hostile_is_422(api: TestClient, name: str, data: bytes) -> None:
    r = api.post("/api/v1/esi", files={"file": ("x.xml", data, "application/xml")})
    assert r.status_code == 422 and r.json()["detail"][0]["loc"] == ["body", "file"], r.text[:300]


def test_cam_csv_upload_hostile_is_422(api: TestClient) -> None:
    r = api.put("/api/v1/cams/Fuzz/csv", content=b"phase,distance\n0,0\nnan,1\n\xff\xfe",
                headers={"Content-Type": "text/csv"})
    assert r.status_code == 422, r.text[:300]


def test_project_put_size_limit(api: TestClient) -> None:
    """Every JSON body is bounded (api/limits.py, D57): 413 naming the body, the open project unchanged."""
    before = api.get("/api/v1/project").json()
    body = b'{"name": "x", "description": "' + b"d" * (32 * MB) + b'"}'
    r = api.put("/api/v1/project", content=body, headers={"Content-Type": "application/json"})
    assert r.status_code == 413 and r.json()["detail"][0]["loc"] == ["body"], r.text[:300]
    assert api.get("/api/v1/project").json() == before


def test_a_chunked_body_is_cut_off_at_the_limit(api: TestClient) -> None:
    """Without Content-Length the body is read only up to the limit, then refused (it is never held whole)."""
    from mcstudio.api.limits import DEFAULT_BODY_LIMIT

    sent = 0

    def chunks() -> Iterator[bytes]:
        nonlocal sent
        yield b'{"name": "x", "description": "'
        while sent < 4 * DEFAULT_BODY_LIMIT:
            sent += MB
            yield b"d" * MB

    r = api.put("/api/v1/project", content=chunks(), headers={"Content-Type": "application/json"})
    assert r.status_code == 413, r.text[:300]


def test_a_chunked_body_within_the_limit_is_read(api: TestClient) -> None:
    r = api.put("/api/v1/project", content=iter([DEMO_JSON[:100], DEMO_JSON[100:]]),
                headers={"Content-Type": "application/json"})
    assert r.status_code == 200, r.text[:300]


@pytest.mark.parametrize(("method", "path", "ctype"), [
    ("POST", "/api/v1/esi", "multipart"),
    ("PUT", "/api/v1/cams/Big/csv", "text/csv"),
    ("PUT", "/api/v1/cams/Big/csv", "multipart"),
])
def test_upload_size_limits(api: TestClient, method: str, path: str, ctype: str) -> None:
    """Every upload endpoint refuses a body over its limit with a 413 (ESI 100 MB, cam CSV 4 MB)."""
    from mcstudio.api.routers.cams import MAX_CSV_BYTES
    from mcstudio.fieldbus.library import MAX_ESI_BYTES

    limit = MAX_ESI_BYTES if "esi" in path else MAX_CSV_BYTES
    data = b"0" * (limit + 1)
    if ctype == "multipart":
        r = api.request(method, path, files={"file": ("big", data, "application/octet-stream")})
    else:
        r = api.request(method, path, content=data, headers={"Content-Type": ctype})
    assert r.status_code == 413, r.text[:300]
