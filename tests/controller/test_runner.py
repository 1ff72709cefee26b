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
