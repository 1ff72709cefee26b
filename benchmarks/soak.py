"""Soak: the demo project in fast mode for a long time under random valid commands (issue 9); not part of `all`.

    .venv/bin/python -m benchmarks soak --minutes 60 [--seed 1]

A copy of the demo project runs in a studio with its kernel thread in fast mode; commands reach it through the REST
API in-process (the same routers, models and runner calls as over HTTP), one WebSocket client reads snapshots
throughout. A seeded random sequence of valid commands: positioning, velocity moves, stops, jogs with a dead-man
lease, overrides, resets, instances created and deleted (program churn), data traces configured, read and deleted,
events read and cleared now and then. What is recorded:

* every exception escaping a request and every 5xx answer (both should be zero), major-fault events (an internal
  error that paused the kernel: zero), FFFF0000 events (an exception contained in one instance, D120: zero);
* the event count, the event log's length (bounded: 10,000), the program's size;
* the process's resident memory (VmRSS) at every sample (each minute, or a fifth of a short run) — flat memory
  means bounded trace and event buffers and no leak per command.

Prints one JSON object as its last line (with `rtf`, `us_per_axis_period`, `peak_mb` like every scenario).
"""

from __future__ import annotations

import random
import resource
import shutil
import tempfile
import threading
import time
import tracemalloc
from pathlib import Path
from typing import Any

from mcstudio.api.app import create_app
from mcstudio.api.state import Studio
from mcstudio.controller.kernel import Controller
from mcstudio.controller.runner import Runner
from mcstudio.project.cams import load_cam_tables
from mcstudio.project.io import load_project

DEMO = Path(__file__).resolve().parents[1] / "projects" / "demo"
API = "/api/v1"


def _rss_mb() -> float:
    for line in Path("/proc/self/status").read_text().splitlines():
        if line.startswith("VmRSS:"):
            return int(line.split()[1]) / 1024
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def _ranges(c: Controller) -> dict[str, tuple[float, float]]:
    """A safe positioning range per used, non-encoder axis: inside its limit switches and software limits."""
    out = {}
    for a in c.mc.axes:
        if a.encoder or not a.used:
            continue
        s, lim = a.config.sensors, a.params.Limit
        lo = max(s.NegativeLimit if s.NegativeLimit is not None else -1e9, lim.NegaSwLimit) + 10.0
        hi = min(s.PositiveLimit if s.PositiveLimit is not None else 1e9, lim.PosiSwLimit) - 10.0
        lo = max(lo, 0.0)
        out[a.name] = (lo, min(hi, lo + 60.0))
    return out


class _Soak:
    def __init__(self, client: Any, studio: Studio, seed: int) -> None:
        self.c = client
        self.studio = studio
        self.rng = random.Random(seed)
        self.ranges = _ranges(studio.controller)
        self.axes = list(self.ranges)
        self.commands = 0
        self.http_5xx = 0
        self.http_4xx = 0
        self.rejections: dict[str, int] = {}  # 4xx by method, path and status (valid commands can be refused: 409 …)
        self.exceptions: list[str] = []
        self.n_exceptions = 0
        self.instances: list[int] = []
        self.stops: list[int] = []  # MC_Stop instances whose Execute is still TRUE
        self.traces: list[int] = []

    def req(self, method: str, path: str, **kw: Any) -> Any:
        self.commands += 1
        try:
            r = self.c.request(method, API + path, **kw)
        except Exception as exc:  # an exception out of the app (TestClient re-raises server errors)
            self.n_exceptions += 1
            if len(self.exceptions) < 10:
                self.exceptions.append(f"{method} {path}: {type(exc).__name__}: {exc}"[:300])
            return None
        if r.status_code >= 500:
            self.http_5xx += 1
            if len(self.exceptions) < 10:
                self.exceptions.append(f"{method} {path}: {r.status_code} {r.text[:200]}")
        elif r.status_code >= 400:
            self.http_4xx += 1
            key = f"{method} {path.split('/')[1]} {r.status_code}"
            self.rejections[key] = self.rejections.get(key, 0) + 1
            if len(self.rejections) <= 3 and self.rejections[key] == 1:
                self.rejections[key + " e.g. " + r.text[:160]] = 0
        return r

    def new_fb(self, type_name: str, lease_s: float | None = None, **inputs: Any) -> int | None:
        body: dict[str, Any] = {"type": type_name, "inputs": inputs}
        if lease_s is not None:
            body["lease_s"] = lease_s
        r = self.req("POST", "/fb", json=body)
        if r is not None and r.status_code == 201:
            fid = int(r.json()["id"])
            self.instances.append(fid)
            return fid
        return None

    def setup(self) -> None:
        for a in self.axes:
            self.new_fb("MC_Power", Axis=a, Enable=True)
        self.powers = list(self.instances)
        self.instances.clear()

    def step(self) -> None:
        """One random valid command."""
        rng = self.rng
        a = rng.choice(self.axes)
        lo, hi = self.ranges[a]
        op = self.studio.controller.mc.by_name[a].params.Operation
        v = rng.uniform(0.05, 0.5) * (op.MaxVel or 100.0)
        acc = rng.uniform(0.05, 0.5) * (op.MaxAcc or 1000.0)
        k = rng.random()
        if k < 0.25:
            self.new_fb("MC_MoveAbsolute", Axis=a, Execute=True, Position=rng.uniform(lo, hi), Velocity=v,
                        Acceleration=acc, Deceleration=acc, BufferMode=rng.choice(["_mcAborting", "_mcBuffered"]))
        elif k < 0.35:
            self.new_fb("MC_MoveVelocity", Axis=a, Execute=True, Velocity=v / 10, Acceleration=acc,
                        Deceleration=acc, Direction=rng.choice(["_mcPositiveDirection", "_mcNegativeDirection"]))
        elif k < 0.45:
            held = [f for f in self.stops if f in self.instances]
            if held and rng.random() < 0.6:  # the Stop button released: Execute↓ ends Stopping (MC_Stop)
                fid = held[0]
                self.stops.remove(fid)
                self.req("PATCH", f"/fb/{fid}", json={"inputs": {"Execute": False}})
            else:  # pressed; held until released or until the instance is deleted (D133)
                fid = self.new_fb("MC_Stop", Axis=a, Execute=True, Deceleration=acc)
                if fid is not None:
                    self.stops.append(fid)
        elif k < 0.52:
            self.new_fb("MC_MoveJog", lease_s=rng.choice([0.2, 0.5, 1.0]), Axis=a,
                        PositiveEnable=rng.random() < 0.5, Velocity=v / 10, Acceleration=acc, Deceleration=acc)
        elif k < 0.58:
            self.new_fb("MC_SetOverride", Axis=a, Enable=True, VelFactor=rng.uniform(10, 150))
        elif k < 0.66:
            self.new_fb("MC_Reset", Axis=a, Execute=True)
        elif k < 0.70:
            self.req("POST", "/controller/reset-errors")
        elif k < 0.85 and self.instances:  # program churn: delete an instance (most are finished by now)
            fid = self.instances.pop(rng.randrange(len(self.instances)))
            self.req("DELETE", f"/fb/{fid}")
        elif k < 0.88:
            self.req("GET", "/events", params={"limit": 100})
        elif k < 0.89:
            self.req("DELETE", "/events")
        elif k < 0.93:
            self.trace()
        elif k < 0.97:
            self.req("GET", "/snapshot")
        else:
            self.req("GET", f"/axes/{a}")
        # keep the program bounded: a long soak must not grow it without end
        while len(self.instances) > 64:
            self.req("DELETE", f"/fb/{self.instances.pop(0)}")

    def trace(self) -> None:
        rng = self.rng
        if self.traces and (len(self.traces) >= 6 or rng.random() < 0.5):  # (8 traces at most per controller)
            tid = self.traces.pop(0)
            self.req("GET", f"/traces/{tid}")
            self.req("DELETE", f"/traces/{tid}")
            return
        a = rng.choice(self.axes)
        r = self.req("POST", "/traces", json={
            "variables": [{"kind": "axis", "target": a, "name": n} for n in ("Cmd.Pos", "Act.Pos", "Cmd.Vel")],
            "samples": rng.choice([1000, 10000]),
            "mode": "continuous"})
        if r is not None and r.status_code == 201:
            self.traces.append(int(r.json()["id"]))


def _orphan_holds(c: Controller) -> int:
    """Stop holds (MC_Stop / MC_GroupStop keeping Stopping) of instances that no longer exist: 0 (D133)."""
    holders = [h for x in (*c.mc.axes, *c.mc.groups) for h in x.stop_holders]
    return sum(1 for h in holders if h not in c.program)


def _axis_states(c: Controller) -> dict[str, int]:
    """How many axes are in each state at the sample (a state nobody leaves would show up here)."""
    out: dict[str, int] = {}
    for a in c.mc.axes:
        out[a.state.name] = out.get(a.state.name, 0) + 1
    return out


def _growth(before: tracemalloc.Snapshot, after: tracemalloc.Snapshot, top: int = 12) -> list[dict[str, Any]]:
    """The allocation sites whose live memory grew most between two snapshots (Python objects only)."""
    stats = after.compare_to(before, "lineno")
    return [{"site": f"{st.traceback[0].filename.split('site-packages/')[-1].split('backend/')[-1]}:"
                     f"{st.traceback[0].lineno}",
             "kib": round(st.size_diff / 1024, 1), "blocks": st.count_diff}
            for st in sorted(stats, key=lambda st: st.size_diff, reverse=True)[:top]]


def run(*, minutes: float, seed: int = 1, project_dir: Path = DEMO, trace_memory: bool = False) -> dict[str, Any]:
    """`trace_memory`: tracemalloc from the start; the growth of live Python memory by allocation site between the
    first sample after warm-up (the second) and the end is reported as `growth_sites` (slows everything ~2×)."""
    from fastapi.testclient import TestClient

    if trace_memory:
        tracemalloc.start()
    snapshots: list[tracemalloc.Snapshot] = []

    seconds = minutes * 60.0
    sample_every = min(60.0, seconds / 5)
    tmp = Path(tempfile.mkdtemp(prefix="mcstudio-soak-"))
    folder = tmp / "demo"
    shutil.copytree(project_dir, folder)
    project = load_project(folder)
    controller = Controller(project, cams=load_cam_tables(project, folder))
    runner = Runner(controller, mode="paused")
    studio = Studio(runner=runner, project_dir=folder, projects_root=tmp)
    app = create_app(studio, static_dir=Path("/nonexistent"))
    ws_messages = 0
    stop = threading.Event()
    samples: list[dict[str, Any]] = []
    runner.start()
    try:
        with TestClient(app) as client:
            soak = _Soak(client, studio, seed)
            soak.setup()
            runner.set_mode("fast")

            def ws_reader() -> None:
                nonlocal ws_messages
                with client.websocket_connect(f"{API}/ws") as ws:
                    ws.send_json({"type": "subscribe", "rate_hz": 30, "axes": None, "fbs": [], "events": True})
                    while not stop.is_set():
                        ws.receive_json()
                        ws_messages += 1

            reader = threading.Thread(target=ws_reader, daemon=True)
            reader.start()
            start = time.perf_counter()
            sim0 = controller.time_s
            next_sample = start
            paused = 0
            while (now := time.perf_counter()) - start < seconds:
                if now >= next_sample:
                    ctrl = studio.controller
                    samples.append({"t_s": round(now - start, 1), "rss_mb": round(_rss_mb(), 1),
                                    "cycle": ctrl.cycle, "events_total": ctrl.events.last_seq,
                                    "event_log": len(ctrl.events.list()), "instances": len(ctrl.program),
                                    "traces": len(soak.traces), "orphan_holds": _orphan_holds(ctrl),
                                    "axis_states": _axis_states(ctrl)})
                    if trace_memory and len(samples) == 2:
                        snapshots.append(tracemalloc.take_snapshot())
                    next_sample += sample_every
                soak.step()
                if runner.mode != "fast":  # an internal error paused the kernel: count it and go on
                    paused += 1
                    runner.set_mode("fast")
                stop.wait(0.002)  # a client's pace; lets the kernel thread have the GIL
            wall = time.perf_counter() - start
            ctrl = studio.controller
            sim = ctrl.time_s - sim0
            samples.append({"t_s": round(wall, 1), "rss_mb": round(_rss_mb(), 1), "cycle": ctrl.cycle,
                            "events_total": ctrl.events.last_seq, "event_log": len(ctrl.events.list()),
                            "instances": len(ctrl.program), "traces": len(soak.traces),
                            "orphan_holds": _orphan_holds(ctrl), "axis_states": _axis_states(ctrl)})
            if trace_memory:
                snapshots.append(tracemalloc.take_snapshot())
            stop.set()
            reader.join(timeout=30)  # its socket closes before the client does (else both wait on each other)
            events = ctrl.events.list()
    finally:
        stop.set()
        runner.stop()
        shutil.rmtree(tmp, ignore_errors=True)
    rss = [s["rss_mb"] for s in samples]
    n_axes = len(controller.mc.axes)
    cycles = samples[-1]["cycle"] - samples[0]["cycle"]
    return {
        "scenario": "soak", "minutes": minutes, "seed": seed, "wall_s": round(wall, 1), "sim_s": round(sim, 1),
        "cycles": cycles, "rtf": round(sim / wall, 2),
        "us_per_axis_period": round(wall / max(1, cycles) / n_axes * 1e6, 3),
        "peak_mb": round(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024, 1),
        "commands": soak.commands, "http_4xx": soak.http_4xx, "rejections": soak.rejections, "http_5xx": soak.http_5xx,
        "exceptions": soak.n_exceptions, "exception_samples": soak.exceptions, "kernel_paused": paused,
        "major_faults": sum(1 for e in events if e.level == "major fault"),
        "contained_faults": sum(1 for e in events if e.code == "FFFF0000"),
        "events_total": samples[-1]["events_total"], "event_log_len": samples[-1]["event_log"],
        "ws_messages": ws_messages, "orphan_holds_max": max(x["orphan_holds"] for x in samples),
        "rss_mb": rss, "rss_growth_mb": round(rss[-1] - rss[1 if len(rss) > 2 else 0], 1),
        "python_mb_growth": (round(sum(st.size_diff for st in snapshots[1].compare_to(snapshots[0], "filename"))
                                   / 2**20, 2) if len(snapshots) == 2 else None),
        "growth_sites": _growth(*snapshots) if len(snapshots) == 2 else None,
        "samples": samples,
    }
