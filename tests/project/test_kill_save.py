"""Killing a save (issue 9): a save killed at any moment leaves the old or the new project, never a broken one, and
`project.json.bak` is always a complete earlier version (docs/project-format.md "Saving", io.atomic_write).

1. A forked process saves a large project over and over; before the K-th file-system step of the save (each 64 KiB
   write, the fsync, the backup link, each rename, the folder fsync) it reports the step through a pipe and waits,
   and the test SIGKILLs it there. K is chosen per seed (every step of a save is hit, deterministically), and the
   same folder takes every kill in turn, so each run also starts from the debris of the previous one.
2. The real server (`mcstudio serve`) saving through REST is SIGKILLed while its temporary file exists, i.e. in the
   middle of writing a save; the acknowledged saves are all on disk afterwards.
No sleeps: every wait is a blocking read on a pipe or a bounded poll of a subprocess.
"""

from __future__ import annotations

import json
import os
import random
import shutil
import signal
import socket
import subprocess
import sys
import threading
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import httpx

from mcstudio.project import io as pio
from mcstudio.project.cams import load_cam_tables
from mcstudio.project.io import load_project
from mcstudio.project.models import Project
from tests.conftest import DEMO, ROOT

AXES = 96  # ≈ 360 KB of JSON: six 64-KiB writes per save


def _large_doc() -> dict[str, Any]:
    """The demo project with 88 more virtual servo axes (copies of MC_Axis003)."""
    doc = json.loads((DEMO / "project.json").read_text())
    template = next(a for a in doc["axes"] if a["type"] == "_mcVirServo")
    for k in range(len(doc["axes"]), AXES):
        axis = json.loads(json.dumps(template))
        axis["name"], axis["number"] = f"MC_Axis{k:03d}", k
        doc["axes"].append(axis)
    return doc


def _generation(project: Project) -> int:
    return int(project.description.rsplit(" ", 1)[1])


def _texts(n: int) -> list[str]:
    """Documents of generations 0 … n-1 (they differ in the description: 'generation k')."""
    doc = _large_doc()
    doc["description"] = "generation @"
    text = pio.dump_project(Project.model_validate(doc))
    return [text.replace('"generation @"', f'"generation {g}"') for g in range(n)]


# ------------------------------------------------------------------ 1. deterministic kills of a forked saver
STEPS = ("write", "fsync", "link", "replace", "fsync-dir")


def _saver(folder: Path, texts: list[str], first: int, kill_at: int, report: int) -> None:
    """Child: save generations first, first+1, … with atomic_write; stop before file-system step `kill_at`."""
    real = {name: getattr(os, name) for name in ("write", "fsync", "link", "replace")}
    count = 0

    def step(kind: str, fn: Callable[..., Any]) -> Callable[..., Any]:
        def wrapped(*args: Any, **kw: Any) -> Any:
            nonlocal count
            if kind == "fsync" and os.path.isdir(f"/proc/self/fd/{args[0]}"):
                kind_now = "fsync-dir"
            elif kind == "replace" and str(args[0]).endswith(".bak.tmp"):
                kind_now = "replace-bak"
            else:
                kind_now = kind
            if count == kill_at:
                real["write"](report, f"{kind_now} {count}\n".encode())
                while True:
                    signal.pause()  # here until SIGKILL
            count += 1
            return fn(*args, **kw)

        return wrapped

    for name in real:
        setattr(os, name, step(name, real[name]))
    for g in range(first, len(texts)):
        pio.atomic_write(folder / "project.json", texts[g])
    real["write"](report, b"done\n")


def _run_saver(folder: Path, texts: list[str], first: int, kill_at: int) -> str:
    r, w = os.pipe()
    pid = os.fork()
    if pid == 0:  # child
        try:
            os.close(r)
            _saver(folder, texts, first, kill_at, w)
        finally:
            os._exit(0)
    os.close(w)
    with os.fdopen(r, "rb") as pipe:
        line = pipe.readline().decode().strip()  # blocks until the child stands at step kill_at (or is done)
        os.kill(pid, signal.SIGKILL)
        os.waitpid(pid, 0)
    return line


def _state(folder: Path, check: Path) -> tuple[int, int]:
    """(generation in project.json, generation in project.json.bak); both must load as complete projects."""
    main = load_project(folder)
    load_cam_tables(main, folder)
    (check / "project.json").write_bytes((folder / "project.json.bak").read_bytes())
    return _generation(main), _generation(load_project(check))


def test_a_save_killed_at_any_step_leaves_the_old_or_the_new_project(tmp_path: Path) -> None:
    texts = _texts(100)
    folder, check = tmp_path / "big", tmp_path / "bak-check"
    check.mkdir()
    shutil.copytree(DEMO / "cams", folder / "cams")
    pio.atomic_write(folder / "project.json", texts[0])
    pio.atomic_write(folder / "project.json", texts[1])
    size = len(texts[1].encode())
    writes = -(-size // pio.WRITE_CHUNK)
    per_save = writes + 5  # writes, fsync, link, replace (backup), replace (document), fsync (folder)
    assert size > 300_000 and writes >= 5
    gen, bak = _state(folder, check)
    assert (gen, bak) == (1, 0)
    hit: dict[str, int] = {}
    rng = random.Random(9)
    for seed in range(per_save + 8):
        step = seed if seed < per_save else rng.randrange(per_save)  # every step once, then random ones
        complete = rng.randrange(2)  # saves finished before the one that is killed
        kill_at = complete * per_save + step
        line = _run_saver(folder, texts, gen + 1, kill_at)
        kind = line.split()[0]
        hit[kind] = hit.get(kind, 0) + 1
        before = gen + complete  # what project.json held when the killed save began
        # killed before the document's rename: the old document (and, once the backup link was renamed, the old
        # document as the backup too); killed after it: the new document with the old one as the backup
        expected = {"fsync-dir": (before + 1, before), "replace": (before, before)}.get(
            kind, (before, before - 1 if complete else bak))
        gen, bak = _state(folder, check)
        assert (gen, bak) == expected, (seed, line)
        # only the killed save's temporary files are left; the next save removes them
        debris = [p.name for p in folder.iterdir() if p.name.startswith(".")]
        assert all(p.endswith(".tmp") for p in debris), debris
    assert set(hit) == {"write", "fsync", "link", "replace-bak", "replace", "fsync-dir"}, hit
    assert hit["write"] >= writes
    # after the kills a normal save cleans up and works
    pio.atomic_write(folder / "project.json", texts[gen + 1])
    assert _state(folder, check) == (gen + 1, gen)
    assert [p.name for p in folder.iterdir() if p.name.startswith(".")] == []


# ------------------------------------------------------------------ 2. the real server, killed while it saves
def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def test_killing_the_server_in_the_middle_of_a_save_loses_nothing(tmp_path: Path) -> None:
    root = tmp_path / "projects"
    folder = root / "big"
    folder.mkdir(parents=True)
    doc = _large_doc()
    doc["description"] = "generation 0"
    (folder / "project.json").write_text(json.dumps(doc))
    shutil.copytree(DEMO / "cams", folder / "cams")
    port = _free_port()
    proc = subprocess.Popen(
        [sys.executable, "-m", "mcstudio", "serve", "--project", str(folder), "--port", str(port),
         "--viser-port", "0", "--mode", "paused"],
        cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
    )
    base = f"http://127.0.0.1:{port}/api/v1"
    acknowledged = 0
    try:
        output: list[str] = []
        banner = threading.Event()

        def drain() -> None:  # the server's output, read so that the pipe never fills
            assert proc.stdout is not None
            for line in proc.stdout:
                output.append(line)
                if line.startswith("MC Studio"):
                    banner.set()
            banner.set()

        threading.Thread(target=drain, daemon=True).start()
        banner.wait(60)  # printed just before the server binds its port
        client = httpx.Client(timeout=30)
        deadline = time.monotonic() + 60
        while True:  # the port opens a moment after the banner (bounded poll of a subprocess)
            try:
                client.get(f"{base}/health")
                break
            except httpx.TransportError:
                assert time.monotonic() < deadline and proc.poll() is None, "".join(output)
        current = client.get(f"{base}/project").json()
        rng = random.Random(3)
        first_kill_candidate = rng.randrange(1, 3)  # saves that complete before the watcher arms
        saving = threading.Event()
        done: list[int] = []
        failures: list[str] = []

        def save_generation(g: int) -> None:
            current["description"] = f"generation {g}"
            r = client.put(f"{base}/project", json=current)
            saving.set()
            if r.status_code != 200:
                failures.append(f"PUT {r.status_code} {r.text}")
                return
            try:
                r = client.post(f"{base}/project/save")
            except httpx.TransportError:
                return  # the server was killed during this save
            if r.status_code != 200:
                failures.append(f"save {r.status_code} {r.text}")
                return
            done.append(g)

        killed_in_save = False
        for g in range(1, 40):
            if g <= first_kill_candidate:
                save_generation(g)
                assert not failures and done[-1] == g, failures
                acknowledged = g
                continue
            saving.clear()
            t = threading.Thread(target=save_generation, args=(g,), daemon=True)
            t.start()
            saving.wait()
            prefix = ".project.json."
            while t.is_alive():  # watch the folder until the server's temporary file of this save exists
                if any(n.startswith(prefix) and n.endswith(".tmp") and not n.endswith("bak.tmp")
                       for n in os.listdir(folder)):
                    proc.kill()
                    killed_in_save = True
                    break
            t.join()
            assert not failures, failures
            if g in done:  # the response arrived (possibly just before the kill)
                acknowledged = g
            if killed_in_save:
                break
        if not killed_in_save:
            proc.kill()
        proc.wait()
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    assert killed_in_save, "the temporary file of a save was never seen: the server was not killed mid-save"
    assert acknowledged >= first_kill_candidate >= 1
    saved = load_project(folder)
    load_cam_tables(saved, folder)
    # every acknowledged save is on disk: the file holds the last acknowledged generation or the one being saved
    assert _generation(saved) in (acknowledged, acknowledged + 1)
    bak = (folder / "project.json.bak").read_text()
    assert json.loads(bak)["description"] in (f"generation {acknowledged - 1}", f"generation {acknowledged}")
    r = subprocess.run([sys.executable, "-m", "mcstudio", "validate", str(folder)], capture_output=True, text=True,
                       check=False)
    assert r.returncode == 0, r.stderr
