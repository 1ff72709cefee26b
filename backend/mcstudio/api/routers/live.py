"""Live data: the snapshot over REST and the WebSocket that pushes it at a client-chosen rate.

WebSocket protocol (`/api/v1/ws`, JSON text frames):
  client → server  {"type": "subscribe", "rate_hz": 30, "axes": null, "fbs": null, "events": true}
                   {"type": "heartbeat", "fbs": [3]}        renews the dead-man leases of instances 3 …
  server → client  {"type": "snapshot", "controller": {...}, "axes": [...], "fbs": {...}, "events": [...]}
                   {"type": "subscribed", ...}                acknowledges a subscribe (messages are handled in order)
                   {"type": "error", "detail": "..."}         for a malformed client message
A snapshot is sent when the controller advanced, and at least once a second. When the socket closes, every instance
whose lease this socket renewed drops its Execute/Enable inputs at once (a lost browser stops its jog).
"""

from __future__ import annotations

import asyncio
import contextlib
import json
from typing import Any

from fastapi import APIRouter, Depends, WebSocket, WebSocketDisconnect
from pydantic import ValidationError

from ...controller.kernel import Controller, Snapshot
from ..deps import get_studio
from ..models import WsHeartbeat, WsSnapshot, WsSubscribe
from ..state import Studio

router = APIRouter(tags=["live"])


def build_snapshot(studio: Studio, snap: Snapshot, sub: WsSubscribe, since_event: int) -> dict[str, Any]:
    fbs = {}
    for fid in snap.fbs:
        if sub.fbs is None or fid in sub.fbs:
            out = studio.fb_out(snap, fid)
            if out is not None:
                fbs[str(fid)] = out.model_dump()
    events = (
        [e.as_dict() for e in studio.controller.events.list(since_seq=since_event, limit=200)] if sub.events else []
    )
    return {
        "type": "snapshot",
        "controller": studio.status(snap).model_dump(),
        "axes": [{"name": n, "variables": v} for n, v in studio.axis_views(snap, sub.axes)],
        "fbs": fbs,
        "events": events,
    }


def _payload_text(studio: Studio, snap: Snapshot, sub: WsSubscribe, since_event: int) -> tuple[str, int | None]:
    """The JSON text of a snapshot message and the last event number in it. Clients that subscribed alike and are
    at the same event share one encoding per snapshot (built in the event loop thread, which shares the GIL with
    the kernel: ten clients must not cost ten encodings)."""
    key = (id(snap), snap.cycle, studio.runner.epoch, tuple(sub.axes) if sub.axes is not None else None,
           tuple(sub.fbs) if sub.fbs is not None else None, sub.events, since_event)
    cache: dict[Any, tuple[str, int | None]] = studio.ws_cache
    hit = cache.get(key)
    if hit is None:
        if len(cache) > 64 or (cache and next(iter(cache))[0] != id(snap)):
            cache.clear()  # (only the latest snapshot's messages are kept)
        payload = build_snapshot(studio, snap, sub, since_event)
        hit = (json.dumps(payload), payload["events"][-1]["seq"] if payload["events"] else None)
        cache[key] = hit
    return hit


@router.get("/snapshot", response_model=WsSnapshot, summary="The latest snapshot (the WebSocket's payload)")
def get_snapshot(studio: Studio = Depends(get_studio)) -> dict[str, Any]:
    sub = WsSubscribe(type="subscribe")
    return build_snapshot(studio, studio.runner.snapshot, sub, studio.controller.events.last_seq)


@router.websocket("/ws")
async def websocket(ws: WebSocket) -> None:
    studio: Studio = ws.app.state.studio
    await ws.accept()
    state: dict[str, Any] = {"sub": WsSubscribe(type="subscribe")}
    leased: set[int] = set()

    async def reader() -> None:
        while True:
            try:
                msg = await ws.receive_json()
            except (json.JSONDecodeError, ValueError):
                await ws.send_json({"type": "error", "detail": "messages must be JSON objects"})
                continue
            kind = msg.get("type") if isinstance(msg, dict) else None
            try:
                if kind == "subscribe":
                    state["sub"] = WsSubscribe.model_validate(msg)
                    await ws.send_json({**state["sub"].model_dump(), "type": "subscribed"})
                elif kind == "heartbeat":
                    hb = WsHeartbeat.model_validate(msg)
                    leased.update(hb.fbs)

                    def renew(c: Controller, ids: list[int] = hb.fbs) -> None:
                        for i in ids:
                            c.renew_lease(i)

                    await asyncio.to_thread(studio.runner.call, renew)
                else:
                    await ws.send_json({"type": "error", "detail": f"unknown message type {kind!r}"})
            except ValidationError as err:
                await ws.send_json({"type": "error", "detail": err.errors(include_url=False, include_context=False)})

    task = asyncio.create_task(reader())
    last_cycle = -1
    last_sent = 0.0
    loop = asyncio.get_running_loop()
    since_event = studio.controller.events.last_seq
    epoch = studio.runner.epoch
    try:
        while not task.done():
            await asyncio.sleep(1.0 / state["sub"].rate_hz)
            sub: WsSubscribe = state["sub"]
            snap = studio.runner.snapshot
            now = loop.time()
            if studio.runner.epoch != epoch:  # a new controller: its event numbers start again
                epoch, since_event, last_cycle = studio.runner.epoch, 0, -1
            new_events = studio.controller.events.last_seq != since_event
            if snap.cycle == last_cycle and not new_events and now - last_sent < 1.0:
                continue
            text, last_seq = _payload_text(studio, snap, sub, since_event)
            if last_seq is not None:
                since_event = last_seq
            elif studio.controller.events.last_seq < since_event:  # log cleared
                since_event = studio.controller.events.last_seq
            last_cycle, last_sent = snap.cycle, now
            await ws.send_text(text)
    except (WebSocketDisconnect, RuntimeError):
        pass
    finally:
        task.cancel()
        with contextlib.suppress(BaseException):
            await task
        if leased:
            def drop(c: Controller, ids: set[int] = leased) -> None:
                for i in ids:
                    entry = c.program.get(i)
                    if entry is not None and entry.lease_s is not None:
                        entry.fb.drop_dead_man()

            # Synchronous on purpose: the task may be cancelled, and an await in `finally` would be cancelled too.
            # The kernel serves the request at its next cycle boundary (≤ one period).
            with contextlib.suppress(Exception):
                studio.runner.call(drop, timeout=2.0)
