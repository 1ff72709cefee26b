"""Request body size limits for every endpoint, enforced while the body streams in (D57).

A body whose `Content-Length` is over the limit is refused with 413 before any of it is read; a body without a length
(chunked) is read up to the limit and refused with 413 as soon as it passes it, so a client cannot make the server
hold more than the limit in memory. Upload endpoints with a smaller limit of their own (cam CSV 4 MB) check it
themselves; the ESI upload gets the larger limit its files need.
"""

from __future__ import annotations

import json
from typing import Any

from starlette.types import ASGIApp, Message, Receive, Scope, Send

from ..fieldbus.library import MAX_ESI_BYTES

DEFAULT_BODY_LIMIT = 16 * 1024 * 1024
"""Every JSON body: the demo project is ~40 kB, a project with 256 axes and 64 cams of 65,535 points well under this."""
MULTIPART_OVERHEAD = 1024 * 1024


def body_limit(path: str) -> int:
    if path.rstrip("/").endswith("/esi"):
        return MAX_ESI_BYTES + MULTIPART_OVERHEAD
    return DEFAULT_BODY_LIMIT


class BodyLimitMiddleware:
    """Pure ASGI middleware (no buffering of bodies that declare a length within the limit)."""

    def __init__(self, app: ASGIApp) -> None:
        self.app = app

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        limit = body_limit(scope.get("path", ""))
        length: int | None = None
        for key, value in scope.get("headers", []):
            if key == b"content-length":
                try:
                    length = int(value)
                except ValueError:
                    length = None
                break
        if length is not None:
            if length > limit:
                await _too_large(send, limit)
                return
            await self.app(scope, receive, send)
            return
        # No declared length: read the body here, at most `limit` bytes, then replay it to the application.
        chunks: list[bytes] = []
        size = 0
        more = True
        while more:
            message = await receive()
            if message["type"] != "http.request":  # the client went away
                await self.app(scope, _replay([message]), send)
                return
            body = message.get("body", b"")
            size += len(body)
            if size > limit:
                await _too_large(send, limit)
                return
            chunks.append(body)
            more = message.get("more_body", False)
        await self.app(scope, _replay([{"type": "http.request", "body": b"".join(chunks), "more_body": False}],
                                      receive), send)


def _replay(messages: list[Message], then: Receive | None = None) -> Receive:
    queue = list(messages)

    async def receive() -> Message:
        if queue:
            return queue.pop(0)
        if then is not None:
            return await then()
        return {"type": "http.disconnect"}

    return receive


async def _too_large(send: Send, limit: int) -> None:
    payload: dict[str, Any] = {"detail": [{
        "loc": ["body"], "type": "too_large",
        "msg": f"the request body is larger than this endpoint's limit of {limit // (1024 * 1024)} MB",
    }]}
    body = json.dumps(payload).encode()
    await send({"type": "http.response.start", "status": 413,
                "headers": [(b"content-type", b"application/json"), (b"content-length", str(len(body)).encode())]})
    await send({"type": "http.response.body", "body": body})
