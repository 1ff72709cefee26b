"""Access control (issue 9, decisions D118–D119): the token, the Host and Origin checks.

* Bound to loopback (the default) nothing needs a token, but the `Host` header must name the loopback
  (`127.0.0.1`, `localhost`, `[::1]`): a web page cannot reach the studio through DNS rebinding.
* Bound to any other address, `mcstudio serve` generates a token (or takes `--token` / `MCSTUDIO_TOKEN`) and every
  request under `/api/` except `GET /api/v1/health`, and the WebSocket, must carry it: `Authorization: Bearer …`, the
  `mcstudio_token` cookie (set when the browser opens `/?token=…`), or — WebSocket only — a `token` query parameter.
  Without it: 401 (wrong token: 403); the WebSocket handshake is refused. The studio's files themselves stay open.
* Always: a mutating request (POST, PUT, PATCH, DELETE) or a WebSocket that carries an `Origin` header must come
  from the studio's own origin, the Vite development server (loopback binds) or a configured CORS origin (403
  otherwise), so another web site open in the same browser cannot drive the controller.
"""

from __future__ import annotations

import hmac
import ipaddress
import json
import secrets
from collections.abc import Awaitable, Callable, MutableMapping
from dataclasses import dataclass, field
from http.cookies import SimpleCookie
from typing import Any
from urllib.parse import parse_qsl, urlencode

Scope = MutableMapping[str, Any]
Message = MutableMapping[str, Any]
Receive = Callable[[], Awaitable[Message]]
Send = Callable[[Message], Awaitable[None]]
ASGIApp = Callable[[Scope, Receive, Send], Awaitable[None]]

COOKIE = "mcstudio_token"
LOOPBACK_NAMES = ("127.0.0.1", "localhost", "::1")
DEV_ORIGINS = ("http://localhost:5173", "http://127.0.0.1:5173")  # `npm run dev` (Vite proxies /api)
OPEN_API_PATHS = frozenset({"/api/v1/health"})
MUTATING = frozenset({"POST", "PUT", "PATCH", "DELETE"})


def is_loopback(host: str) -> bool:
    """`127.0.0.1`, `::1`, `localhost` and the rest of 127/8."""
    h = host.strip("[]").lower()
    if h == "localhost" or h.endswith(".localhost"):
        return True
    try:
        return ipaddress.ip_address(h).is_loopback
    except ValueError:
        return False


def new_token() -> str:
    return secrets.token_urlsafe(24)


@dataclass(frozen=True)
class AccessPolicy:
    """What the middleware checks. `AccessPolicy()` (what `create_app` uses by default: tests, embedding) checks
    only Origins; `for_bind` is what `mcstudio serve` uses."""

    token: str | None = None
    trusted_hosts: frozenset[str] | None = None  # Host header names accepted (None: any)
    origins: frozenset[str] = field(default_factory=frozenset)  # cross origins accepted besides the studio's own

    @classmethod
    def for_bind(cls, host: str, token: str | None = None, *, cors_origins: list[str] | None = None) -> AccessPolicy:
        """Loopback bind: no token, loopback Host names only. Any other bind: the token (required)."""
        extra = frozenset(o.rstrip("/") for o in cors_origins or [])
        if is_loopback(host):
            return cls(token=token, trusted_hosts=frozenset(LOOPBACK_NAMES), origins=extra | frozenset(DEV_ORIGINS))
        if not token:
            raise ValueError("a non-loopback bind needs a token")
        return cls(token=token, trusted_hosts=None, origins=extra)


def _headers(scope: Scope) -> dict[str, str]:
    out: dict[str, str] = {}
    for k, v in scope.get("headers", []):
        out.setdefault(k.decode("latin-1").lower(), v.decode("latin-1"))
    return out


def _host_name(host_header: str) -> str:
    if host_header.startswith("["):  # [::1]:8000
        return host_header[1:].split("]", 1)[0].lower()
    return host_header.rsplit(":", 1)[0].lower() if host_header.count(":") == 1 else host_header.lower()


class AccessMiddleware:
    """Pure ASGI, so it guards the WebSocket handshake as well as HTTP."""

    def __init__(self, app: ASGIApp, policy: AccessPolicy) -> None:
        self.app = app
        self.policy = policy

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        kind = scope["type"]
        if kind not in ("http", "websocket"):
            await self.app(scope, receive, send)
            return
        p = self.policy
        headers = _headers(scope)
        path: str = scope.get("path", "")
        method: str = scope.get("method", "GET") if kind == "http" else "GET"

        host = headers.get("host", "")
        if p.trusted_hosts is not None and _host_name(host) not in p.trusted_hosts:
            await self._refuse(scope, receive, send, 403,
                               f"host {host!r} refused: the studio is bound to the loopback; open it as "
                               "http://127.0.0.1:<port>/ or http://localhost:<port>/ (DNS rebinding guard)")
            return

        origin = headers.get("origin")
        if origin is not None and (kind == "websocket" or method in MUTATING):
            scheme = {"ws": "http", "wss": "https"}.get(scope.get("scheme", "http"), scope.get("scheme", "http"))
            own = f"{scheme}://{host}"
            if origin.rstrip("/") != own and origin.rstrip("/") not in p.origins:
                await self._refuse(scope, receive, send, 403, f"cross-origin request from {origin} refused: only "
                                   "the studio's own pages may change the controller")
                return

        if p.token is not None:
            query = dict(parse_qsl(scope.get("query_string", b"").decode("latin-1")))
            if kind == "http" and method == "GET" and "token" in query and not path.startswith("/api/"):
                await self._login(scope, receive, send, query, path)
                return
            if path.startswith("/api/") and path not in OPEN_API_PATHS and method != "OPTIONS":
                given = self._token_of(headers, query if kind == "websocket" else {})
                if given is None:
                    await self._refuse(scope, receive, send, 401,
                                       "this studio is served on a network address and needs its access token: open "
                                       "the address with ?token=… that 'mcstudio serve' printed, or send "
                                       "'Authorization: Bearer <token>'")
                    return
                if not hmac.compare_digest(given.encode(), p.token.encode()):
                    await self._refuse(scope, receive, send, 403, "wrong access token")
                    return
        await self.app(scope, receive, send)

    @staticmethod
    def _token_of(headers: dict[str, str], query: dict[str, str]) -> str | None:
        auth = headers.get("authorization", "")
        if auth[:7].lower() == "bearer ":
            return auth[7:].strip()
        cookie = headers.get("cookie")
        if cookie:
            jar: SimpleCookie = SimpleCookie()
            try:
                jar.load(cookie)
            except Exception:  # a malformed Cookie header counts as none
                jar = SimpleCookie()
            if COOKIE in jar:
                return jar[COOKIE].value
        return query.get("token")

    async def _login(self, scope: Scope, receive: Receive, send: Send, query: dict[str, str], path: str) -> None:
        """`GET /?token=…`: set the cookie and redirect to the same address without the token (so it does not stay
        in the address bar or the history)."""
        token = self.policy.token
        assert token is not None
        if not hmac.compare_digest(query["token"].encode(), token.encode()):
            await self._refuse(scope, receive, send, 403, "wrong access token")
            return
        rest = {k: v for k, v in query.items() if k != "token"}
        location = path + (f"?{urlencode(rest)}" if rest else "")
        secure = "; Secure" if scope.get("scheme") == "https" else ""
        await send({"type": "http.response.start", "status": 303, "headers": [
            (b"location", location.encode("latin-1")),
            (b"set-cookie", f"{COOKIE}={token}; Path=/; HttpOnly; SameSite=Strict{secure}".encode("latin-1")),
            (b"cache-control", b"no-store"),
            (b"content-length", b"0"),
        ]})
        await send({"type": "http.response.body", "body": b""})

    @staticmethod
    async def _refuse(scope: Scope, receive: Receive, send: Send, status: int, detail: str) -> None:
        if scope["type"] == "websocket":
            # Before accept: the server answers the handshake with 403 (policy violation).
            await receive()  # websocket.connect
            await send({"type": "websocket.close", "code": 1008, "reason": detail[:120]})
            return
        body = json.dumps({"detail": detail}).encode()
        headers = [(b"content-type", b"application/json"), (b"content-length", str(len(body)).encode())]
        if status == 401:
            headers.append((b"www-authenticate", b'Bearer realm="mcstudio"'))
        await send({"type": "http.response.start", "status": status, "headers": headers})
        await send({"type": "http.response.body", "body": body})
