"""Live data: the snapshot over REST and the WebSocket that pushes it at a client-chosen rate.

WebSocket protocol (`/api/v1/ws?client=<id>&name=<display name>`, JSON text frames; both parameters optional):
  client → server  {"type": "subscribe", "rate_hz": 30, "axes": null, "fbs": null, "events": true}
                   {"type": "heartbeat", "fbs": [3]}        renews the dead-man leases of instances 3 …
                   {"type": "ping"}                          "still here" (clients with an id: at least every 10 s)
  server → client  {"type": "hello", "client": {"id", "name"}}  first message when a client id was given
                   {"type": "snapshot", "controller": {...}, "axes": [...], "fbs": {...}, "events": [...],
                    "control": {"holder": {...} | null, ...}}
                   {"type": "control", ...ControlState}       at once when the holder or the client list changes
                   {"type": "subscribed", ...}                acknowledges a subscribe (messages are handled in order)
                   {"type": "error", "detail": "..."}         for a malformed client message or a refused heartbeat
A snapshot is sent when the controller advanced, and at least once a second. When the socket closes, every instance
whose lease this socket renewed drops its Execute/Enable inputs at once (a lost browser stops its jog); a client's
last socket closing (or a client silent for `ControlRegistry.client_timeout_s`) releases its test-run control and
drops the leases of every instance it created, patched or renewed (api/control.py, decision D117).
"""

from __future__ import annotations

import asyncio
import contextlib
import json
from typing import Any

from fastapi import APIRouter, Depends, Request, WebSocket, WebSocketDisconnect
from pydantic import ValidationError

from ...controller.kernel import Controller, Snapshot
from ..control import CLIENT_ID_RE, NAME_MAX, ControlRefusedError, ControlRegistry, drop_instances
from ..deps import get_studio
from ..models import WsHeartbeat, WsPing, WsSnapshot, WsSubscribe
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


def _payload_text(studio: Studio, snap: Snapshot, sub: WsSubscribe, since_event: int,
                  control: ControlRegistry | None = None) -> tuple[str, int | None]:
    """The JSON text of a snapshot message and the last event number in it. Clients that subscribed alike and are
    at the same event share one encoding per snapshot (built in the event loop thread, which shares the GIL with
    the kernel: ten clients must not cost ten encodings)."""
    key = (id(snap), snap.cycle, studio.runner.epoch, tuple(sub.axes) if sub.axes is not None else None,
           tuple(sub.fbs) if sub.fbs is not None else None, sub.events, since_event,
           control.version if control is not None else None)
    cache: dict[Any, tuple[str, int | None]] = studio.ws_cache
    hit = cache.get(key)
    if hit is None:
        if len(cache) > 64 or (cache and next(iter(cache))[0] != id(snap)):
            cache.clear()  # (only the latest snapshot's messages are kept)
        payload = build_snapshot(studio, snap, sub, since_event)
        if control is not None:
            payload["control"] = control.state().model_dump()
        hit = (json.dumps(payload), payload["events"][-1]["seq"] if payload["events"] else None)
        cache[key] = hit
    return hit


@router.get("/snapshot", response_model=WsSnapshot, summary="The latest snapshot (the WebSocket's payload)")
def get_snapshot(request: Request, studio: Studio = Depends(get_studio)) -> dict[str, Any]:
    sub = WsSubscribe(type="subscribe")
    payload = build_snapshot(studio, studio.runner.snapshot, sub, studio.controller.events.last_seq)
    control: ControlRegistry | None = getattr(request.app.state, "control", None)
    if control is not None:
        payload["control"] = control.state().model_dump()
    return payload


@router.websocket("/ws")
async def websocket(ws: WebSocket) -> None:
    studio: Studio = ws.app.state.studio
    control: ControlRegistry = ws.app.state.control
    client_id = ws.query_params.get("client") or None
    if client_id is not None and not CLIENT_ID_RE.match(client_id):
        await ws.close(code=1008, reason="client: 1 to 64 letters, digits, '_', '.' or '-'")
        return
    name = (ws.query_params.get("name") or "").strip()[:NAME_MAX] or None
    address = ws.client.host if ws.client else "unknown"
    await ws.accept()
    if client_id is not None:
        info = control.connect(client_id, address, name)
        await ws.send_json({"type": "hello", "client": {"id": info.id, "name": info.name}})
    state: dict[str, Any] = {"sub": WsSubscribe(type="subscribe"), "heard": control.clock()}
    leased: set[int] = set()

    async def reader() -> None:
        while True:
            try:
                msg = await ws.receive_json()
            except (json.JSONDecodeError, ValueError, RecursionError):  # RecursionError: nested beyond the limit
                await ws.send_json({"type": "error", "detail": "messages must be JSON objects"})
                continue
            state["heard"] = control.clock()
            kind = msg.get("type") if isinstance(msg, dict) else None
            try:
                if kind == "subscribe":
                    state["sub"] = WsSubscribe.model_validate(msg)
                    await ws.send_json({**state["sub"].model_dump(), "type": "subscribed"})
                elif kind == "heartbeat":
                    hb = WsHeartbeat.model_validate(msg)
                    try:  # a client that may only watch cannot keep somebody's jog alive
                        control.admit(client_id, address, "configuration")
                    except ControlRefusedError as err:
                        await ws.send_json({"type": "error", "detail": err.message})
                        continue
                    leased.update(hb.fbs)
                    if client_id is not None:
                        for i in hb.fbs:
                            control.note_instance(client_id, studio.runner.epoch, i)

                    def renew(c: Controller, ids: list[int] = hb.fbs) -> None:
                        for i in ids:
                            c.renew_lease(i)

                    await asyncio.to_thread(studio.runner.call, renew)
                elif kind == "ping":
                    WsPing.model_validate(msg)
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
    control_version = control.version
    try:
        while not task.done():
            await asyncio.sleep(1.0 / state["sub"].rate_hz)
            if client_id is not None and control.clock() - state["heard"] > control.client_timeout_s:
                # Silent (suspended, half-open connection): the client is lost (D117); it may reconnect.
                await ws.close(code=4408, reason="no message within the client timeout")
                break
            if control.version != control_version:  # a change of holder reaches every browser at once
                control_version = control.version
                await ws.send_text(json.dumps({"type": "control", **control.state().model_dump()}))
            sub: WsSubscribe = state["sub"]
            snap = studio.runner.snapshot
            now = loop.time()
            if studio.runner.epoch != epoch:  # a new controller: its event numbers start again
                epoch, since_event, last_cycle = studio.runner.epoch, 0, -1
            new_events = studio.controller.events.last_seq != since_event
            if snap.cycle == last_cycle and not new_events and now - last_sent < 1.0:
                continue
            text, last_seq = _payload_text(studio, snap, sub, since_event, control)
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
        owned = control.disconnect(client_id) if client_id is not None else set()
        # Synchronous on purpose: the task may be cancelled, and an await in `finally` would be cancelled too.
        # The kernel serves the request at its next cycle boundary (≤ one period).
        if owned:
            with contextlib.suppress(Exception):
                drop_instances(studio, owned, f"client '{control.name_of(client_id)}' disconnected", timeout=2.0)
        if leased:
            def drop(c: Controller, ids: set[int] = leased) -> None:
                for i in ids:
                    entry = c.program.get(i)
                    if entry is not None and entry.lease_s is not None:
                        entry.fb.drop_dead_man()

            with contextlib.suppress(Exception):
                studio.runner.call(drop, timeout=2.0)
