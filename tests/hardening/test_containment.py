"""FB fault containment (issue 9, decision D120): an exception inside one instance's call is contained by that
instance — Error with ErrorID FFFF, an FFFF0000 event naming the instance and the exception, the axis it commands
error-stopped like any instruction error (omron-mc-basics.md §A-1 legend: a minor fault of an axis decelerates it
to a stop) — and the kernel keeps running; other axes are unaffected; MC_Reset releases it.

The fault is injected by replacing one instance's `execute` (a test-only injection)."""

from __future__ import annotations

from typing import Any

import pytest

from mcstudio.controller.kernel import Controller
from mcstudio.controller.mc.cam.table import CamTable
from mcstudio.controller.mc.enums import AxisState
from mcstudio.controller.mc.module import E_INTERNAL
from tests.conftest import power_on, small_project, step_until

A0, A1 = "MC_Axis000", "MC_Axis001"


def _mover(c: Controller, axis: str, velocity: float) -> Any:
    return c.fb("MC_MoveVelocity", Axis=axis, Velocity=velocity, Acceleration=1000.0, Deceleration=1000.0,
                Direction="_mcPositiveDirection")


@pytest.mark.parametrize("skip_settled", [True, False])
def test_exception_in_one_instance_is_contained(skip_settled: bool) -> None:
    """cycle 0 Execute↑ of a MoveVelocity on A0 whose execute() raises → that instance Error FFFF, event FFFF0000
    with the exception, A0 ErrorStop decelerating to standstill; A1's MoveVelocity (started before) keeps its
    velocity; the kernel steps on; the broken instance is not called again until MC_Reset."""
    c = Controller(small_project())
    c.skip_settled = skip_settled
    power_on(c, A0)
    power_on(c, A1)
    other = _mover(c, A1, 20.0)
    other.Execute = True
    step_until(c, other, "InVelocity")
    first = _mover(c, A0, 10.0)
    first.Execute = True
    step_until(c, first, "InVelocity")

    calls = []

    def boom(axis: Any) -> None:
        calls.append(c.cycle)
        raise RuntimeError("injected fault")

    broken = _mover(c, A0, 30.0)
    broken.execute = boom  # instance attribute: the next Execute edge runs it
    broken.Execute = True
    c.step(1)
    assert calls == [c.cycle - 1]
    assert broken.Error and broken.ErrorID == E_INTERNAL == 0xFFFF
    assert not broken.Busy and not broken.Active
    ev = [e for e in c.events.list() if e.code == "FFFF0000"]
    assert len(ev) == 1 and broken.label in ev[0].source and "RuntimeError: injected fault" in ev[0].detail
    ax0, ax1 = c.mc.by_name[A0], c.mc.by_name[A1]
    assert ax0.state == AxisState.ErrorStop and ax0.error_code == 0xFFFF
    assert first.CommandAborted  # the axis error aborts the running instruction (A-1 effect)

    # the kernel keeps stepping; A0 decelerates to standstill, A1 is untouched
    assert c.step(400) == 400
    i0 = ax0.i
    assert c.mc.cmd_vel[i0] == 0.0
    assert other.InVelocity and not other.Error and c.mc.cmd_vel[ax1.i] == pytest.approx(20.0)
    assert calls == [calls[0]]  # quarantined: no second call, no second event
    assert len([e for e in c.events.list() if e.code == "FFFF0000"]) == 1

    # MC_Reset releases the axis and the instance; without the fault it runs again on a new Execute edge
    del broken.__dict__["execute"]
    rs = c.fb("MC_Reset", Axis=A0, Execute=True)
    step_until(c, rs, "Done")
    c.step(1)
    assert ax0.state == AxisState.Standstill
    assert not broken.Error and broken.ErrorID == 0
    broken.Execute = False
    c.step(1)
    broken.Execute = True
    step_until(c, broken, "InVelocity")
    assert c.mc.cmd_vel[i0] == pytest.approx(30.0)


def test_exception_without_an_axis_is_an_mc_common_error() -> None:
    """MC_GenerateCamTable (no axis: an MC common instruction) faulting: Error FFFF, an MC common FFFF0000 event,
    no axis touched; ResetMCError releases the instance."""
    c = Controller(small_project(), cams={"Cam0": CamTable(100)})
    gen = c.fb("MC_GenerateCamTable", CamTable="Cam0", CamProperty={"CycleTime": 1.0},
               CamNodes=[{"Phase": 0.0, "Distance": 0.0}, {"Phase": 360.0, "Distance": 10.0}])

    def boom(*_: Any) -> None:
        raise ValueError("injected")

    gen.start = boom  # _CamTableFB: the edge calls start()
    gen.Execute = True
    c.step(2)
    assert gen.Error and gen.ErrorID == 0xFFFF
    ev = [e for e in c.events.list() if e.code == "FFFF0000"]
    assert len(ev) == 1 and ev[0].source_kind == "instruction" and "ValueError: injected" in ev[0].detail
    assert all(ax.state != AxisState.ErrorStop for ax in c.mc.axes if ax.used)
    c.step(10)
    del gen.__dict__["start"]
    c.mc.reset_mc_errors()
    c.step(1)
    assert not gen.Error and gen.ErrorID == 0


def test_runner_keeps_running_in_fast_mode() -> None:
    """The same injection under the runner thread in fast mode: cycles keep advancing (the runner would pause on
    an uncontained exception and log 00000000)."""
    from mcstudio.controller.runner import Runner

    c = Controller(small_project())
    mv = _mover(c, A0, 10.0)
    mv.execute = lambda axis: (_ for _ in ()).throw(KeyError("injected"))
    r = Runner(c, mode="paused")
    r.start()
    try:
        r.call(lambda ctl: setattr(mv, "Execute", True))
        r.set_mode("fast")
        start = r.call(lambda ctl: ctl.cycle)
        reached = r.call(lambda ctl: ctl.cycle, see_cycle=True)
        for _ in range(100):
            reached = r.call(lambda ctl: ctl.cycle, see_cycle=True)
            if reached > start + 1000:
                break
        assert reached > start + 1000 and r.mode == "fast"
        assert mv.Error and mv.ErrorID == 0xFFFF
        assert not any(e.code == "00000000" and e.level == "major fault" for e in c.events.list())
    finally:
        r.stop()
