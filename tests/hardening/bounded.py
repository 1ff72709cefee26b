"""Measure a call's cost deterministically: peak Python memory (tracemalloc) and the number of Python-level
function calls (a profile hook) — never wall-clock time (conventions.md)."""

from __future__ import annotations

import sys
import tracemalloc
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any


@dataclass
class Cost:
    peak_bytes: int
    calls: int
    result: Any = None
    error: BaseException | None = None


def measure(fn: Callable[[], Any], *, count_calls: bool = True) -> Cost:
    """Run `fn`, catching any exception into `Cost.error` (the caller decides which are allowed)."""
    calls = 0

    def prof(_frame: Any, event: str, _arg: Any) -> None:
        nonlocal calls
        if event in ("call", "c_call"):
            calls += 1

    tracing = tracemalloc.is_tracing()
    if not tracing:
        tracemalloc.start()
    tracemalloc.reset_peak()
    base = tracemalloc.get_traced_memory()[0]
    result: Any = None
    error: BaseException | None = None
    if count_calls:
        sys.setprofile(prof)
    try:
        result = fn()
    except Exception as exc:
        error = exc
    finally:
        if count_calls:
            sys.setprofile(None)
        peak = tracemalloc.get_traced_memory()[1] - base
        if not tracing:
            tracemalloc.stop()
    return Cost(peak, calls, result, error)
