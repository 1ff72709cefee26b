"""The studio server under load: REST latency and WebSocket fan-out while the kernel runs in realtime mode.

A real server process (`mcstudio serve`, a copy of the demo project, realtime mode, 3D view off) is started on a free
loopback port; every servo axis of the demo is powered and moves back and forth (MC_MoveAbsolute instances driven by
PATCH requests), as a commissioning script would.

* `rest` — latency of `PATCH /api/v1/fb/{id}` setting Execute TRUE until the instruction's Busy is visible: in the
  PATCH response (the server answers after the instance was called with the new input) and at the first WebSocket
  snapshot showing it; percentiles over many repetitions.
* `ws` — N WebSocket clients subscribed at R Hz (every axis, every instance, events) for S seconds while the axes
  move: messages received per client and their rate, inter-arrival percentiles, message size, and the kernel's
  overruns, real-time factor and computation time per period during the run (from `GET /api/v1/controller`).
"""

from __future__ import annotations

import asyncio
import contextlib
import json
import os
import resource
import shutil
import socket
import subprocess
import sys
import tempfile
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import httpx
import numpy as np
import websockets

DEMO = Path(__file__).resolve().parents[1] / "projects" / "demo"
API = "/api/v1"


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


@contextlib.contextmanager
def server(project: Path = DEMO) -> Iterator[str]:
    """A studio server process on a copy of `project`; yields its base URL."""
    tmp = Path(tempfile.mkdtemp(prefix="mcstudio-bench-"))
    copy = tmp / project.name
    shutil.copytree(project, copy)
    port = _free_port()
    env = {**os.environ, "PYTHONUNBUFFERED": "1"}
    proc = subprocess.Popen([sys.executable, "-m", "mcstudio", "serve", "--project", str(copy), "--port", str(port),
                             "--viser-port", "0", "--mode", "realtime"], env=env, stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL)
    base = f"http://127.0.0.1:{port}"
    try:
        deadline = time.monotonic() + 60
        while True:
            try:
                if httpx.get(base + API + "/health", timeout=1).status_code == 200:
                    break
            except httpx.HTTPError:
                pass
            if proc.poll() is not None or time.monotonic() > deadline:
                raise RuntimeError("the studio server did not start")
            time.sleep(0.1)
        yield base
    finally:
        proc.terminate()
        try:
            proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            proc.kill()
        shutil.rmtree(tmp, ignore_errors=True)


def _pct(x: list[float] | np.ndarray, scale: float = 1.0) -> dict[str, float]:
    a = np.asarray(x, dtype=float) * scale
    if a.size == 0:
        return {}
    q = np.percentile(a, [50, 95, 99])
    return {"p50": round(float(q[0]), 2), "p95": round(float(q[1]), 2), "p99": round(float(q[2]), 2),
            "max": round(float(a.max()), 2), "n": int(a.size)}


class Machine:
    """The demo's axes powered and moving back and forth through the REST API."""

    def __init__(self, client: httpx.Client) -> None:
        self.c = client
        axes = client.get(API + "/axes").json()
        self.servo = [a["name"] for a in axes if a["type"] == "_mcServo"]
        for name in [a["name"] for a in axes if a["type"] in ("_mcServo", "_mcVirServo")]:
            self._post({"type": "MC_Power", "inputs": {"Axis": name, "Enable": True}})
        deadline = time.monotonic() + 10
        while not all(a["variables"]["Status"]["Standstill"] for a in self._axes()):
            if time.monotonic() > deadline:
                raise RuntimeError("the demo's axes did not power on")
            time.sleep(0.05)
        self.moves = {name: self._post({"type": "MC_MoveAbsolute", "inputs": {
            "Axis": name, "Position": 60.0, "Velocity": 100.0, "Acceleration": 1000.0, "Deceleration": 1000.0}})
            for name in self.servo}
        self.target = {name: 60.0 for name in self.servo}

    def _post(self, body: dict[str, Any]) -> int:
        r = self.c.post(API + "/fb", json=body)
        r.raise_for_status()
        return int(r.json()["id"])

    def _axes(self) -> list[dict[str, Any]]:
        return [self.c.get(f"{API}/axes/{a['name']}").json() for a in self.c.get(API + "/axes").json()]

    def turn(self) -> None:
        """Restart every move that has ended, towards the other end (10 … 60)."""
        for name, fid in self.moves.items():
            out = self.c.get(f"{API}/fb/{fid}").json()
            if out["inputs"]["Execute"] and (out["outputs"]["Done"] or out["outputs"]["CommandAborted"]
                                            or out["outputs"]["Error"]):
                self.c.patch(f"{API}/fb/{fid}", json={"inputs": {"Execute": False}})
            elif not out["inputs"]["Execute"]:
                self.target[name] = 10.0 if self.target[name] == 60.0 else 60.0
                self.c.patch(f"{API}/fb/{fid}", json={"inputs": {"Execute": True, "Position": self.target[name]}})


def _status(client: httpx.Client) -> dict[str, Any]:
    return client.get(API + "/controller").json()


def run_rest(*, repetitions: int) -> dict[str, Any]:
    with server() as base, httpx.Client(base_url=base, timeout=10) as c:
        m = Machine(c)
        name = m.servo[0]
        probe = m._post({"type": "MC_MoveRelative", "inputs": {"Axis": name, "Distance": 0.5, "Velocity": 50.0,
                                                                "Acceleration": 1000.0, "Deceleration": 1000.0}})
        c.delete(f"{API}/fb/{m.moves.pop(name)}")  # only the probe moves this axis; the others keep moving
        ws_url = base.replace("http", "ws") + API + "/ws"
        patch_ms: list[float] = []
        ws_ms: list[float] = []

        async def measure() -> None:
            async with websockets.connect(ws_url, max_size=None) as ws:
                await ws.send(json.dumps({"type": "subscribe", "rate_hz": 120, "axes": [], "fbs": [probe],
                                          "events": False}))
                async with httpx.AsyncClient(base_url=base, timeout=10) as ac:
                    for k in range(repetitions):
                        if k % 5 == 0:
                            await asyncio.to_thread(m.turn)
                        # drain, then the edge
                        with contextlib.suppress(asyncio.TimeoutError):
                            while True:
                                await asyncio.wait_for(ws.recv(), timeout=0.002)
                        t0 = time.perf_counter()
                        task = asyncio.create_task(ac.patch(f"{API}/fb/{probe}", json={"inputs": {"Execute": True}}))
                        seen = None
                        while seen is None:
                            msg = json.loads(await ws.recv())
                            if msg.get("type") == "snapshot":
                                out = msg["fbs"].get(str(probe), {}).get("outputs", {})
                                if out.get("Busy") or out.get("Done"):
                                    seen = time.perf_counter()
                        r = await task
                        t_resp = time.perf_counter()
                        assert r.status_code == 200 and (r.json()["outputs"]["Busy"] or r.json()["outputs"]["Done"])
                        patch_ms.append((t_resp - t0) * 1e3)
                        ws_ms.append((seen - t0) * 1e3)
                        # wait for the end of the move, release Execute
                        while not (await ac.get(f"{API}/fb/{probe}")).json()["outputs"]["Done"]:
                            await asyncio.sleep(0.005)
                        await ac.patch(f"{API}/fb/{probe}", json={"inputs": {"Execute": False}})

        asyncio.run(measure())
        st = _status(c)
    return {
        "scenario": "rest",
        "repetitions": repetitions,
        "patch_to_output_ms": _pct(patch_ms),
        "patch_to_websocket_ms": _pct(ws_ms),
        "overruns": st["overruns"],
        "rtf": st["rtf"],
        "us_per_axis_period": round(st.get("cycle_time_us", 0.0) / 4, 2),
        "cycle_time_us": st.get("cycle_time_us"),
        "peak_mb": round(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024, 1),
    }


def run_ws(*, clients: int, rate_hz: float, seconds: float) -> dict[str, Any]:
    with server() as base, httpx.Client(base_url=base, timeout=10) as c:
        m = Machine(c)
        ws_url = base.replace("http", "ws") + API + "/ws"
        before = _status(c)
        received: list[list[float]] = [[] for _ in range(clients)]
        sizes: list[int] = []
        loads: list[tuple[float, float, float]] = []

        async def client(k: int) -> None:
            async with websockets.connect(ws_url, max_size=None) as ws:
                await ws.send(json.dumps({"type": "subscribe", "rate_hz": rate_hz, "axes": None, "fbs": None,
                                          "events": True}))
                end = time.perf_counter() + seconds
                while (left := end - time.perf_counter()) > 0:
                    try:
                        msg = await asyncio.wait_for(ws.recv(), timeout=left)
                    except TimeoutError:
                        break
                    if '"snapshot"' in msg[:40]:
                        received[k].append(time.perf_counter())
                        if k == 0:
                            sizes.append(len(msg))

        async def driver() -> None:
            async with httpx.AsyncClient(base_url=base, timeout=10):
                end = time.perf_counter() + seconds
                while time.perf_counter() < end:
                    await asyncio.to_thread(m.turn)
                    st = await asyncio.to_thread(_status, c)
                    loads.append((st["rtf"], st.get("cycle_time_us", 0.0), st.get("cycle_time_max_us", 0.0)))
                    await asyncio.sleep(0.25)

        async def main() -> None:
            await asyncio.gather(driver(), *(client(k) for k in range(clients)))

        asyncio.run(main())
        after = _status(c)
    counts = [len(r) for r in received]
    gaps = np.concatenate([np.diff(r) for r in received if len(r) > 1]) if any(len(r) > 1 for r in received) \
        else np.zeros(0)
    rtf = [x[0] for x in loads if x[0] > 0]
    cyc = [x[1] for x in loads if x[1] > 0]
    return {
        "scenario": "ws",
        "clients": clients,
        "rate_hz": rate_hz,
        "seconds": seconds,
        "messages_per_client": {"min": min(counts), "max": max(counts)},
        "rate_per_client_hz": round(float(np.mean(counts)) / seconds, 1),
        "interarrival_ms": _pct(gaps, 1e3),
        "message_kb": round(float(np.mean(sizes)) / 1024, 1) if sizes else 0.0,
        "overruns": after["overruns"] - before["overruns"],
        "rtf": round(float(np.mean(rtf)), 4) if rtf else 0.0,
        "cycle_time_us": _pct(cyc),
        "us_per_axis_period": round(float(np.mean(cyc)) / 4, 2) if cyc else 0.0,
        "peak_mb": round(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024, 1),
    }
