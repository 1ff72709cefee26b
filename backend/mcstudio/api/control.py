"""Shared control of the test run (issue 8, decisions D115–D117).

Several browsers (and scripts) may watch one controller; one *client* at a time holds test-run control. A client is
identified by the id it sends in the `X-MCStudio-Client` header (REST) and the `client` query parameter of the
WebSocket; it has a display name ("browser 2 · 127.0.0.1" or one the user typed).

* Test-run operations (`TEST_RUN` below) need control: from a client id while nobody holds it they take it
  (a single browser never sees a lock), from the holder they pass, from any other client they are refused with 423
  naming the holder. Requests without a client id (scripts, CI: the automation channel) are not arbitrated.
* Configuration writes that restart the controller (`CONFIGURATION`) are refused the same way while another client
  holds control, but do not take it.
* Control ends with `POST /control/release`, with a forced take by another client, or when the holder is lost: its
  last WebSocket closes, or it sends nothing for `client_timeout_s`. Whenever control leaves a client, the leased
  (dead-man) instances that client created, patched or renewed drop their Execute/Enable inputs at once — its jog
  stops.

Control coordinates people who may move the machine; it is not access control (that is the token, `auth.py`).
"""

from __future__ import annotations

import contextlib
import re
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Literal

from fastapi import HTTPException, Request
from pydantic import Field, StrictBool

from ..modelbase import StrictModel

if TYPE_CHECKING:
    from ..controller.kernel import Controller
    from .state import Studio

CLIENT_HEADER = "X-MCStudio-Client"
CLIENT_ID_RE = re.compile(r"^[A-Za-z0-9_.-]{1,64}$")
NAME_MAX = 48
CLIENT_TIMEOUT_S = 10.0  # D117: a WebSocket client that sends nothing for this long is lost

Kind = Literal["test-run", "configuration"]

# D116: which requests need control. Keys are (method, route path under /api/v1); everything else (reads, cam tables,
# traces, project save, ESI import, kinematics, the event log) is open to every client.
TEST_RUN: frozenset[tuple[str, str]] = frozenset({
    ("POST", "/fb"), ("PATCH", "/fb/{fb_id}"), ("DELETE", "/fb/{fb_id}"),
    ("PUT", "/controller/mode"), ("POST", "/controller/step"), ("POST", "/controller/reset"),
    ("POST", "/controller/reset-errors"),
    ("POST", "/faults"), ("POST", "/ethercat/slaves/{address}/connect"),
})
CONFIGURATION: frozenset[tuple[str, str]] = frozenset({
    ("PUT", "/axes/{name}/config"), ("PUT", "/groups/{name}/config"),
    ("PUT", "/ethercat"), ("PUT", "/ethercat/slaves/{address}/pdo"),
    ("PUT", "/project"), ("POST", "/project/revert"), ("POST", "/projects/open"), ("POST", "/projects/new"),
})


def kind_of(method: str, path: str) -> Kind | None:
    """`path`: the route's declared path, with or without the `/api/v1` prefix."""
    key = (method.upper(), path.removeprefix("/api/v1"))
    if key in TEST_RUN:
        return "test-run"
    if key in CONFIGURATION:
        return "configuration"
    return None


# ---------------------------------------------------------------------------------------------------- models
_Model = StrictModel


class ControlHolder(_Model):
    id: str = Field(description="The holder's client id (what it sends in X-MCStudio-Client)")
    name: str = Field(description="Display name, e.g. 'browser 2 · 127.0.0.1'")
    since_s: float = Field(description="UNIX time [s] at which it took control")


class ControlClient(_Model):
    id: str
    name: str
    connected: bool = Field(description="It has an open WebSocket")


class ControlChange(_Model):
    reason: Literal["taken", "forced", "released", "lost"] = Field(
        description="taken: took free control; forced: took it from `previous`; released: gave it up; lost: its "
        "connection closed or went silent")
    previous: str | None = Field(None, description="Name of the client that held control before")
    by: str | None = Field(None, description="Name of the client that took control (taken, forced)")


class ControlState(_Model):
    holder: ControlHolder | None = Field(description="Who holds test-run control (null: nobody)")
    clients: list[ControlClient] = Field(default_factory=list, description="Known clients, connected ones first")
    change: ControlChange | None = Field(None, description="The last change of holder")
    version: int = Field(0, description="Increments with every change of holder or client list")


class ControlTakeIn(_Model):
    force: StrictBool = Field(False, description="Take control from another holder (it becomes read-only; its jogs "
                              "stop)")
    name: str | None = Field(None, min_length=1, max_length=NAME_MAX,
                             description="Display name to show (default: the one given on the WebSocket, or "
                             "'client N · address')")


class ControlOut(ControlState):
    you: str | None = Field(None, description="The client id of this request (X-MCStudio-Client), if any")


# ---------------------------------------------------------------------------------------------------- registry
@dataclass
class ClientInfo:
    id: str
    name: str
    address: str
    sockets: int = 0
    owned: set[tuple[int, int]] = field(default_factory=set)  # (controller epoch, instance id) of leased instances


class ControlRefusedError(Exception):
    def __init__(self, message: str) -> None:
        super().__init__(message)
        self.message = message


class ControlRegistry:
    """Thread-safe: REST handlers run in the thread pool, the WebSocket in the event loop. `wall` stamps `since_s`;
    `clock` (monotonic, injectable) measures a client's silence."""

    def __init__(self, *, clock: Callable[[], float] = time.monotonic, wall: Callable[[], float] = time.time,
                 client_timeout_s: float = CLIENT_TIMEOUT_S) -> None:
        self.clock = clock
        self.wall = wall
        self.client_timeout_s = client_timeout_s
        self._lock = threading.Lock()
        self._clients: dict[str, ClientInfo] = {}
        self._holder: str | None = None
        self._since = 0.0
        self._change: ControlChange | None = None
        self._counter = 0
        self.version = 0
        self._state_cache: tuple[int, ControlState] | None = None

    # ------------------------------------------------------------------ views
    @property
    def holder(self) -> str | None:
        return self._holder

    def state(self) -> ControlState:
        with self._lock:
            cached = self._state_cache
            if cached is not None and cached[0] == self.version:
                return cached[1]
            holder = None
            if self._holder is not None:
                h = self._clients[self._holder]
                holder = ControlHolder(id=h.id, name=h.name, since_s=round(self._since, 3))
            clients = sorted(self._clients.values(), key=lambda c: (c.sockets == 0, c.name))
            st = ControlState(holder=holder, change=self._change, version=self.version,
                              clients=[ControlClient(id=c.id, name=c.name, connected=c.sockets > 0)
                                       for c in clients[:32]])
            self._state_cache = (self.version, st)
            return st

    def name_of(self, client_id: str | None) -> str | None:
        c = self._clients.get(client_id) if client_id else None
        return c.name if c else None

    # ------------------------------------------------------------------ clients
    def _ensure(self, client_id: str, address: str, name: str | None, kind: str) -> ClientInfo:
        c = self._clients.get(client_id)
        if c is None:
            self._counter += 1
            c = ClientInfo(id=client_id, name=name or f"{kind} {self._counter} · {address}", address=address)
            self._clients[client_id] = c
            self._prune()
            self.version += 1
        elif name and name != c.name:
            c.name = name
            self.version += 1
        return c

    def _prune(self) -> None:
        """Forget disconnected clients that hold nothing, beyond the 64 most recent."""
        if len(self._clients) <= 64:
            return
        for cid in list(self._clients):
            c = self._clients[cid]
            if len(self._clients) <= 64:
                break
            if c.sockets == 0 and cid != self._holder:
                del self._clients[cid]

    def connect(self, client_id: str, address: str, name: str | None = None) -> ClientInfo:
        """A WebSocket of this client opened."""
        with self._lock:
            c = self._ensure(client_id, address, name, "browser")
            c.sockets += 1
            self.version += 1
            return c

    def disconnect(self, client_id: str) -> set[tuple[int, int]]:
        """A WebSocket of this client closed (or went silent). When it was the client's last one, the client is lost:
        it releases control. Returns the leased instances whose dead-man inputs must drop (all the client's, since
        nobody is left to hold its buttons)."""
        with self._lock:
            c = self._clients.get(client_id)
            if c is None:
                return set()
            c.sockets = max(0, c.sockets - 1)
            self.version += 1
            if c.sockets > 0:
                return set()
            if self._holder == client_id:
                self._set_holder(None, ControlChange(reason="lost", previous=c.name))
            owned, c.owned = c.owned, set()
            return owned

    # ------------------------------------------------------------------ control
    def _set_holder(self, client_id: str | None, change: ControlChange) -> None:
        self._holder = client_id
        self._since = self.wall()
        self._change = change
        self.version += 1

    def take(self, client_id: str, address: str, *, force: bool = False, name: str | None = None
             ) -> set[tuple[int, int]]:
        """Take control. Refused while another client holds it unless `force`; returns the previous holder's leased
        instances (to drop) when forced."""
        with self._lock:
            c = self._ensure(client_id, address, name, "client")
            if self._holder == client_id:
                return set()
            if self._holder is None:
                self._set_holder(client_id, ControlChange(reason="taken", by=c.name))
                return set()
            prev = self._clients[self._holder]
            if not force:
                raise ControlRefusedError(f"test-run control is held by '{prev.name}'; take it with force to continue")
            self._set_holder(client_id, ControlChange(reason="forced", previous=prev.name, by=c.name))
            owned, prev.owned = prev.owned, set()
            return owned

    def release(self, client_id: str) -> set[tuple[int, int]]:
        """Give up control (no-op for a client that does not hold it); returns its leased instances to drop."""
        with self._lock:
            c = self._clients.get(client_id)
            if c is None or self._holder != client_id:
                return set()
            self._set_holder(None, ControlChange(reason="released", previous=c.name))
            owned, c.owned = c.owned, set()
            return owned

    def admit(self, client_id: str | None, address: str, kind: Kind) -> None:
        """May this request run? A test-run request from a client id takes free control; a request without one always
        passes; raises ControlRefusedError."""
        if client_id is None:
            return  # the automation channel (D116): control arbitrates between clients that name themselves
        with self._lock:
            holder = self._holder
            c = self._ensure(client_id, address, None, "client")
            if holder == client_id:
                return
            if holder is None:
                if kind == "test-run":
                    self._set_holder(client_id, ControlChange(reason="taken", by=c.name))
                return
            h = self._clients[holder]
            since = time.strftime("%H:%M:%S", time.localtime(self._since))
            raise ControlRefusedError(
                f"test-run control is held by '{h.name}' (since {since}): this client may only watch; take control "
                "first (the studio's Take button, or POST /api/v1/control/take with force)")

    def note_instance(self, client_id: str, epoch: int, fb_id: int) -> None:
        """The client created, patched or renewed this instance: its dead-man inputs drop when the client goes."""
        with self._lock:
            c = self._clients.get(client_id)
            if c is not None:
                if len(c.owned) > 4096:  # instances of old controllers and deleted ones accumulate; keep it bounded
                    c.owned = {o for o in c.owned if o[0] == epoch}
                c.owned.add((epoch, fb_id))


def drop_instances(studio: Studio, owned: set[tuple[int, int]], reason: str, *, timeout: float | None = 5.0
                   ) -> None:
    """Drop the Execute/Enable-type inputs of these leased instances at the next cycle boundary, with an event for
    each one that had a dead-man input set (the jog stops)."""
    epoch = studio.runner.epoch
    ids = sorted(i for e, i in owned if e == epoch)
    if not ids:
        return

    def drop(c: Controller) -> None:
        if studio.runner.epoch != epoch:
            return
        for i in ids:
            entry = c.program.get(i)
            if entry is None or entry.lease_s is None:
                continue
            fb = entry.fb
            if any(fb.inp.get(v.name) for v in fb.DEF.inputs if v.dead_man):
                fb.drop_dead_man()
                c.events.add(cycle=c.cycle, time_s=c.time_s, source=fb.label, code="00000000", level="information",
                             message=f"{reason}: Execute/Enable inputs set FALSE", source_kind="instruction",
                             source_name=fb.label, instruction=fb.label)

    studio.runner.call(drop, timeout=timeout)


# ---------------------------------------------------------------------------------------------------- requests
def client_address(request: Request) -> str:
    return request.client.host if request.client else "unknown"


def client_id_of(request: Request) -> str | None:
    """The request's client id (X-MCStudio-Client); 422 naming the header when it is malformed."""
    raw = request.headers.get(CLIENT_HEADER)
    if raw is None or raw == "":
        return None
    if not CLIENT_ID_RE.match(raw):
        raise HTTPException(status_code=422, detail=[{
            "loc": ["header", CLIENT_HEADER], "type": "value_error",
            "msg": "a client id is 1 to 64 letters, digits, '_', '.' or '-'"}])
    return raw


def registry_of(request: Request) -> ControlRegistry:
    return request.app.state.control  # type: ignore[no-any-return]


def control_guard(request: Request) -> None:
    """Router dependency (app.py): refuses a request that needs control held by someone else (423), takes free
    control for a test-run request from a client id, and notes the instances a client patches or deletes."""
    route = request.scope.get("route")
    path = getattr(route, "path", None)
    if path is None:
        return
    kind = kind_of(request.method, path)
    if kind is None:
        return
    client_id = client_id_of(request)
    registry = registry_of(request)
    try:
        registry.admit(client_id, client_address(request), kind)
    except ControlRefusedError as err:
        raise HTTPException(status_code=423, detail=err.message) from None
    fb_id = request.path_params.get("fb_id")
    if client_id is not None and request.method == "PATCH" and fb_id is not None:
        studio: Studio = request.app.state.studio
        with contextlib.suppress(ValueError):  # not an integer: the route answers 422
            registry.note_instance(client_id, studio.runner.epoch, int(fb_id))


def note_created(request: Request, fb_id: int) -> None:
    """POST /fb: the instance belongs to the client that created it (for dropping its dead-man inputs later)."""
    client_id = request.headers.get(CLIENT_HEADER)
    registry: ControlRegistry | None = getattr(request.app.state, "control", None)
    if client_id and registry is not None and CLIENT_ID_RE.match(client_id):
        studio: Studio = request.app.state.studio
        registry.note_instance(client_id, studio.runner.epoch, fb_id)
