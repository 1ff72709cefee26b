"""Runner modes (architecture.md): paused does not advance, fast and realtime do; requests are applied between
cycles in the kernel thread; `see_cycle` requests return only after one cycle saw them. No sleeps and no
wall-clock assertions: progress is observed through blocking calls into the kernel thread."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from mcstudio.controller.kernel import Controller
from mcstudio.controller.runner import Runner
from tests.conftest import small_project


@pytest.fixture
def runner() -> Iterator[Runner]:
    r = Runner(Controller(small_project()), mode="paused")
    r.start()
    yield r
    r.stop()


def _cycle(r: Runner) -> int:
    return r.call(lambda c: c.cycle)


def test_paused_does_not_advance(runner: Runner) -> None:
    first = _cycle(runner)
    for _ in range(20):
        assert _cycle(runner) == first
    assert runner.status().rtf == 0.0


@pytest.mark.parametrize("mode", ["fast", "realtime"])
def test_running_modes_advance(runner: Runner, mode: str) -> None:
    runner.set_mode(mode)  # type: ignore[arg-type]
    start = _cycle(runner)
    seen = start
    for _ in range(10_000):
        seen = _cycle(runner)
        if seen > start + 5:
            break
    assert seen > start + 5


def test_requests_run_in_the_kernel_thread(runner: Runner) -> None:
    import threading

    name = runner.call(lambda c: threading.current_thread().name)
    assert name == "mcstudio-kernel"


def test_see_cycle_returns_after_the_instruction_was_called(runner: Runner) -> None:
    """PATCH semantics: with the controller running, the change has been seen by one call when the request
    returns, so two consecutive requests never land in the same gap between cycles (no lost edge)."""
    runner.set_mode("fast")
    fb_id = runner.call(lambda c: c.fb("MC_Power", Axis="MC_Axis002").id, see_cycle=True)
    for _ in range(50):
        runner.call(lambda c: c.set_inputs(fb_id, {"Enable": True}), see_cycle=True)
        busy = runner.call(lambda c: c.get_fb(fb_id).out["Busy"])
        assert busy, "the instance saw Enable = TRUE before the request returned"
        runner.call(lambda c: c.set_inputs(fb_id, {"Enable": False}), see_cycle=True)
        assert not runner.call(lambda c: c.get_fb(fb_id).out["Busy"])


def test_exception_in_request_reaches_caller_and_loop_survives(runner: Runner) -> None:
    def bad(c: Controller) -> None:
        raise ValueError("nope")

    with pytest.raises(ValueError, match="nope"):
        runner.call(bad)
    runner.set_mode("fast")
    a = _cycle(runner)
    for _ in range(10_000):
        if _cycle(runner) > a:
            break
    assert _cycle(runner) > a


def test_replace_controller(runner: Runner) -> None:
    runner.set_mode("fast")
    new = Controller(small_project())
    runner.replace_controller(new)
    assert runner.controller is new
    assert runner.snapshot.project == "test"


class FakeClock:
    def __init__(self, t: float = 1000.0) -> None:
        self.t = t

    def __call__(self) -> float:
        return self.t


def test_realtime_pacing_overruns_only_beyond_the_jitter_buffer() -> None:
    """D16: cycle k's period is [t0 + k·T, t0 + (k+1)·T]; it may be computed up to the jitter buffer early, and it is
    an overrun only when it completes after its period ended. The first period begins one buffer after the start,
    so a slow first cycle (cold code) is no overrun. Driven by an injected clock, without the runner's thread."""
    from mcstudio.controller.runner import REALTIME_LEAD_S

    c = Controller(small_project())
    r = Runner(c, mode="realtime")
    clock = r.clock = FakeClock()
    compute = {"s": 0.0}
    run = c.run_cycle

    def slow_cycle() -> None:
        run()
        clock.t += compute["s"]

    c.run_cycle = slow_cycle  # type: ignore[method-assign]
    T = c.period_s
    compute["s"] = 5 * T  # a slow first cycle
    r._realtime_cycle(c)
    assert c.cycle == 1 and r.overruns == 0
    compute["s"] = 0.0
    while clock.t + REALTIME_LEAD_S >= 1000.0 + REALTIME_LEAD_S + c.cycle * T:  # catch up to the buffer's edge
        r._realtime_cycle(c)
    ahead = 1000.0 + REALTIME_LEAD_S + c.cycle * T - clock.t
    assert ahead == pytest.approx(REALTIME_LEAD_S, abs=T) and r.overruns == 0
    # a stall shorter than the buffer: still no overrun
    clock.t += REALTIME_LEAD_S - 5 * T
    r._realtime_cycle(c)
    assert r.overruns == 0
    # a stall longer than what is left of the buffer: the next cycle completes after its period → one overrun
    clock.t += REALTIME_LEAD_S
    r._realtime_cycle(c)
    assert r.overruns == 1
