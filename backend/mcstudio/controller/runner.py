"""Runner: the thread that owns the controller and decides *when* the next cycle is computed.

Modes (architecture.md): `realtime` paces cycles to the wall clock and counts overruns, `fast` computes cycles as fast
as possible, `paused` only advances on explicit steps. Every request from another thread (API, WebSocket) is a
callable queued with `call()` and executed by this thread between two cycles, so kernel state is never touched
concurrently; readers use the published immutable snapshot.

Realtime pacing: period k spans [t0 + k·T, t0 + (k+1)·T] of wall time. The runner may compute cycle k up to
`REALTIME_LEAD_S` before its period begins — a jitter buffer, because the operating system (or the virtual machine)
sometimes stalls or wakes a thread milliseconds late — and counts an overrun when cycle k completes after
t0 + (k+1)·T, i.e. when simulated time really fell behind wall time (docs/decisions.md D16). If it falls more than
`MAX_LAG_PERIODS` behind (machine suspended, debugger), it re-anchors t0 instead of racing to catch up, and counts
the skipped periods as overruns.
"""

from __future__ import annotations

import logging
import sys
import threading
import time
from collections import deque
from collections.abc import Callable
from concurrent.futures import Future
from dataclasses import dataclass
from typing import Literal, TypeVar

import numpy as np

from .kernel import Controller, Snapshot

Mode = Literal["realtime", "fast", "paused"]
MODES: tuple[Mode, ...] = ("realtime", "fast", "paused")
T = TypeVar("T")
log = logging.getLogger(__name__)

MAX_LAG_PERIODS = 50
FAST_SLICE_S = 0.004  # fast mode: run cycles for this long, then serve requests and publish
PUBLISH_INTERVAL_S = 1 / 120  # snapshots in running modes at most this often (and after every request)
RTF_WINDOW_S = 0.5
REALTIME_LEAD_S = 0.050  # jitter buffer: see docs/decisions.md D16
OVERRUN_EVENT_INTERVAL_S = 1.0  # at most one "Task Period Exceeded" event per this much wall time (D123)
TASK_PERIOD_EXCEEDED = "60010000"  # the manual's controller event 6001 (seed 000 line 17849)


@dataclass(frozen=True)
class RunnerStatus:
    mode: Mode
    rtf: float
    overruns: int
    cycle_time_avg_s: float = 0.0  # kernel compute time per period (last RTF window, running modes)
    cycle_time_max_s: float = 0.0


class Runner:
    def __init__(self, controller: Controller, mode: Mode = "realtime") -> None:
        self._controller = controller
        self._mode: Mode = mode
        self._queue: deque[tuple[Callable[[Controller], object], Future[object], bool]] = deque()
        self._after_cycle: list[tuple[Future[object], object]] = []
        self._wake = threading.Condition()
        self._stop = False
        self._thread: threading.Thread | None = None
        self.overruns = 0
        self.epoch = 0  # increments each time the controller is replaced
        self.rtf = 0.0
        self._rt_anchor: tuple[float, int] | None = None
        self._rtf_mark: tuple[float, float] = (time.perf_counter(), controller.time_s)
        self._last_publish = 0.0
        self._listeners: list[Callable[[Controller], None]] = []
        # kernel load: compute time of the cycles run since the last RTF window (the task monitor of the status)
        self.cycle_time_avg_s = 0.0
        self.cycle_time_max_s = 0.0
        self._load_sum = 0.0
        self._load_max = 0.0
        self._load_n = 0
        # optional timing log of realtime cycles for benchmarks: rows (ideal period start, compute start, compute end)
        # in a buffer allocated beforehand (growing it in the loop would stall the kernel while it is copied)
        self.timing_log: np.ndarray | None = None
        self.timing_rows = 0
        self.clock: Callable[[], float] = time.perf_counter  # the wall clock of realtime pacing (tests inject one)
        self._overrun_logged_at: float | None = None  # wall time of the last 6001 event
        self._overruns_logged = 0  # overruns already reported by an event

    # ------------------------------------------------------------------ public (any thread)
    @property
    def controller(self) -> Controller:
        return self._controller

    @property
    def snapshot(self) -> Snapshot:
        return self._controller.snapshot

    @property
    def mode(self) -> Mode:
        return self._mode

    def status(self) -> RunnerStatus:
        running = self._mode != "paused"
        return RunnerStatus(self._mode, self.rtf if running else 0.0, self.overruns,
                            self.cycle_time_avg_s if running else 0.0, self.cycle_time_max_s if running else 0.0)

    def start(self) -> None:
        # Python switches threads every 5 ms by default; the kernel thread must get the GIL back within a period.
        if sys.getswitchinterval() > 0.0005:
            sys.setswitchinterval(0.0005)
        self._thread = threading.Thread(target=self._loop, name="mcstudio-kernel", daemon=True)
        self._thread.start()

    def stop(self) -> None:
        with self._wake:
            self._stop = True
            self._wake.notify_all()
        if self._thread is not None:
            self._thread.join(timeout=5)

    def call(self, fn: Callable[[Controller], T], timeout: float | None = 30.0, *, see_cycle: bool = False) -> T:
        """Run `fn(controller)` in the kernel thread at the next cycle boundary and return its result.

        With `see_cycle`, the result is returned only after one more cycle has run (unless paused), so the change is
        visible to the program: two requests in a row can then never fall into the same gap between cycles — an
        Execute edge set by one PATCH is never undone by the next before an instruction saw it.
        """
        if self._thread is None or threading.current_thread() is self._thread:
            result = fn(self._controller)
            self._controller.publish()
            return result
        fut: Future[object] = Future()
        with self._wake:
            self._queue.append((fn, fut, see_cycle))
            self._wake.notify_all()
        return fut.result(timeout=timeout)  # type: ignore[return-value]

    def set_mode(self, mode: Mode) -> None:
        def apply(_: Controller) -> None:
            if mode != self._mode:
                self._mode = mode
                self._rt_anchor = None
                self._rtf_mark = (time.perf_counter(), self._controller.time_s)

        self.call(apply)

    def replace_controller(self, controller: Controller) -> None:
        def apply(_: Controller) -> None:
            self._controller = controller
            self.epoch += 1
            self._rt_anchor = None
            self.overruns = 0
            self._overruns_logged = 0
            self._overrun_logged_at = None
            self._rtf_mark = (time.perf_counter(), controller.time_s)
            controller.publish()

        self.call(apply)

    def enable_timing_log(self, cycles: int) -> None:
        """Log the timing of the next `cycles` realtime cycles (`timing_log[:timing_rows]`, seconds of
        `time.perf_counter()`)."""
        self.timing_log = np.zeros((cycles, 3))
        self.timing_rows = 0

    def add_listener(self, fn: Callable[[Controller], None]) -> None:
        """`fn(controller)` runs in the kernel thread after each publication (e.g. the 3D view)."""
        self._listeners.append(fn)

    # ------------------------------------------------------------------ kernel thread
    def _serve_requests(self) -> bool:
        served = False
        answered: list[tuple[Future[object], object]] = []
        while True:
            with self._wake:
                if not self._queue:
                    break
                fn, fut, see_cycle = self._queue.popleft()
            served = True
            if fut.set_running_or_notify_cancel():
                try:
                    result = fn(self._controller)
                except BaseException as exc:  # the caller gets the exception; the loop carries on
                    fut.set_exception(exc)
                    continue
                if see_cycle and self._mode != "paused":
                    self._after_cycle.append((fut, result))
                else:
                    answered.append((fut, result))
        if served:
            # published before the answers: a caller reads the snapshot next (POST /fb while paused found its new
            # instance missing from it — an AssertionError, a 500 — when answered first; found by the soak)
            self._publish(force=True)
            for fut, result in answered:
                fut.set_result(result)
            time.sleep(0)  # hand the GIL to the threads whose requests were just answered
        return served

    def _release_after_cycle(self) -> None:
        """Answer the requests that waited for a cycle (called after a cycle, or when pausing)."""
        if self._after_cycle:
            waiting, self._after_cycle = self._after_cycle, []
            self._publish(force=True)
            for fut, result in waiting:
                fut.set_result(result)
            time.sleep(0)

    def _publish(self, *, force: bool = False) -> None:
        now = time.perf_counter()
        if not force and now - self._last_publish < PUBLISH_INTERVAL_S:
            return
        self._last_publish = now
        ctrl = self._controller
        ctrl.publish()
        for fn in self._listeners:
            try:
                fn(ctrl)
            except Exception:  # a listener (3D view) must never stop the kernel
                log.exception("snapshot listener failed")

    def _update_rtf(self) -> None:
        now = time.perf_counter()
        t0, sim0 = self._rtf_mark
        if now - t0 >= RTF_WINDOW_S:
            sim = self._controller.time_s
            self.rtf = (sim - sim0) / (now - t0)
            self._rtf_mark = (now, sim)
            if self._load_n:
                self.cycle_time_avg_s = self._load_sum / self._load_n
                self.cycle_time_max_s = self._load_max
                self._load_sum, self._load_max, self._load_n = 0.0, 0.0, 0

    def _loop(self) -> None:
        while True:
            with self._wake:
                if self._stop:
                    return
            self._serve_requests()
            mode = self._mode
            ctrl = self._controller
            try:
                if mode == "paused":
                    self._release_after_cycle()
                    self.rtf = 0.0
                    self._rtf_mark = (time.perf_counter(), ctrl.time_s)
                    with self._wake:
                        if not self._queue and not self._stop:
                            self._wake.wait(timeout=0.1)
                elif mode == "fast":
                    start = time.perf_counter()
                    end = start + FAST_SLICE_S
                    ctrl.check_leases()
                    ctrl.run_cycle()
                    self._release_after_cycle()
                    n = 1
                    while (now := time.perf_counter()) < end:
                        ctrl.check_leases()
                        ctrl.run_cycle()
                        n += 1
                    self._load_sum += now - start
                    self._load_n += n
                    self._load_max = max(self._load_max, (now - start) / n)
                    self._publish()
                    self._update_rtf()
                    # Let the API and WebSocket threads run: a busy kernel thread would otherwise starve them of
                    # the GIL for tens of milliseconds.
                    time.sleep(0)
                else:
                    self._realtime_cycle(ctrl)
            except Exception:
                # A bug in the kernel must not kill the studio: log it, pause, and keep serving requests.
                log.exception("kernel cycle failed; controller paused")
                ctrl.events.add(cycle=ctrl.cycle, time_s=ctrl.time_s, source="controller", code="00000000",
                                level="major fault", message="internal error in the control period; paused")
                self._mode = "paused"

    def _realtime_cycle(self, ctrl: Controller) -> None:
        period = ctrl.period_s
        lead = max(period, REALTIME_LEAD_S)
        if self._rt_anchor is None:
            # the first period begins one buffer from now: (re)starting, like any stall, may use the buffer
            self._rt_anchor = (self.clock() + lead, ctrl.cycle)
        t0, c0 = self._rt_anchor
        begin = t0 + (ctrl.cycle - c0) * period
        now = self.clock()
        if now < begin - lead:
            with self._wake:
                if not self._queue and not self._stop:
                    self._wake.wait(timeout=begin - lead - now)
            return
        lag = (now - begin) / period
        if lag > MAX_LAG_PERIODS:
            skipped = int(lag)
            self.overruns += skipped
            self._rt_anchor = (now + lead, ctrl.cycle)
            begin = now + lead
        start = self.clock()
        ctrl.check_leases()
        ctrl.run_cycle()
        done = self.clock()
        if done > begin + period:
            self.overruns += 1
        if self.overruns != self._overruns_logged:
            self._log_overruns(ctrl, done)
        took = done - start
        self._load_sum += took
        self._load_n += 1
        if took > self._load_max:
            self._load_max = took
        log = self.timing_log
        if log is not None and self.timing_rows < len(log):
            row = log[self.timing_rows]
            row[0], row[1], row[2] = begin, start, done
            self.timing_rows += 1
        self._release_after_cycle()
        self._publish()
        self._update_rtf()

    def _log_overruns(self, ctrl: Controller, now: float) -> None:
        """Task Period Exceeded (6001) as an observation, at most once per OVERRUN_EVENT_INTERVAL_S of wall time
        with the count since the last event; the control carries on (decision D123)."""
        last = self._overrun_logged_at
        if last is not None and now - last < OVERRUN_EVENT_INTERVAL_S:
            return
        new = self.overruns - self._overruns_logged
        self._overruns_logged = self.overruns
        self._overrun_logged_at = now
        ctrl.events.add(cycle=ctrl.cycle - 1, time_s=(ctrl.cycle - 1) * ctrl.period_s, source="controller",
                        code=TASK_PERIOD_EXCEEDED, level="observation", message="Task Period Exceeded",
                        detail=f"{new} period(s) computed after their deadline in realtime mode ({self.overruns} in "
                        "all); the control continued with every period computed (D16, D123)",
                        cause="the period's computation (or the host) was slower than the primary period",
                        correction="lengthen the primary period, lighten the program or the machine's load",
                        source_kind="controller", source_name="controller")
