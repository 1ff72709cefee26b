"""Controller event log: every error, warning and notable action with cycle, simulated time, source and code.

Codes are the manual's 32-bit event codes as eight hex digits (`54220000`); the message is the manual's event name,
with its cause and correction attached so the studio can show what to do. The log is a bounded ring (oldest entries
drop first); readers in other threads take a consistent copy under the lock.
"""

from __future__ import annotations

import threading
from collections import deque
from dataclasses import asdict, dataclass
from typing import Any, Literal

Level = Literal["major fault", "partial fault", "minor fault", "observation", "information"]
# What the event is about (decision D125): an axis or an axes group (their errors and observations, also when an
# instruction raised them), an EtherCAT slave, an instruction instance (MC common errors, instance notes) or the
# controller itself (project loaded, internal errors, ResetMCError).
SourceKind = Literal["axis", "group", "slave", "instruction", "controller"]

MAX_EVENTS = 10_000


@dataclass(frozen=True, slots=True)
class Event:
    seq: int
    cycle: int
    time_s: float
    source: str  # "MC_Axis000", "MC_Axis000 / fb 3 MC_MoveAbsolute", "controller" …
    code: str  # eight hex digits, "00000000" for information without a manual code
    level: Level
    message: str
    cause: str = ""
    correction: str = ""
    detail: str = ""
    source_kind: SourceKind = "controller"
    source_name: str = ""  # the axis, group or slave name, the instance label, or "controller"
    instruction: str = ""  # the instance involved, "fb 3 MC_MoveAbsolute", if any

    def as_dict(self) -> dict[str, Any]:
        return asdict(self)


class EventLog:
    def __init__(self, maxlen: int = MAX_EVENTS) -> None:
        self._lock = threading.Lock()
        self._events: deque[Event] = deque(maxlen=maxlen)
        self._seq = 0

    def add(self, *, cycle: int, time_s: float, source: str, code: str, level: Level, message: str,
            cause: str = "", correction: str = "", detail: str = "", source_kind: SourceKind = "controller",
            source_name: str = "", instruction: str = "") -> Event:
        if not cause and not correction and code != "00000000":
            # codes outside the MC catalog's callers (EtherCAT master events …) still get the manual's text
            from .mc.errors import describe

            d = describe(code)
            if d is not None:
                cause, correction = d.cause, d.correction
        with self._lock:
            self._seq += 1
            ev = Event(self._seq, cycle, time_s, source, code, level, message, cause, correction, detail,
                       source_kind, source_name or source, instruction)
            self._events.append(ev)
            return ev

    def list(self, *, since_seq: int = 0, limit: int | None = None) -> list[Event]:
        with self._lock:
            out = [e for e in self._events if e.seq > since_seq]
        return out[-limit:] if limit else out

    def clear(self) -> None:
        with self._lock:
            self._events.clear()

    @property
    def last_seq(self) -> int:
        with self._lock:
            return self._seq
