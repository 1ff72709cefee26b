"""Faults (issue 9): slave disconnect, drive fault, following-error overflow, limit switch hit (software and
hardware limit) and kernel overrun, each while a second axis moves. Each ends in the manual's axis state and event,
the other axis is unaffected (the errors are axis-source errors: A-1 legend, omron-mc-basics.md §A-1; drop-out
isolation invt-ivc5.md §11 R2), and MC_Reset recovers (omron-axis-instructions.md MC_Reset).

Codes: 3003 slave drop-out, 3002 drive alarm (decision D29), 6452 following error, 6450 positive software limit,
6453 positive limit input (run-time codes D19), 6001 task period exceeded (seed 000 line 17849; D123).
The existing per-fault tests (tests/controller/mc/test_network_faults.py, test_limits.py, test_drive_model.py,
tests/controller/test_runner.py) check each fault's details; this file checks the same matrix for all of them.
"""

from __future__ import annotations

import copy
from collections.abc import Callable
from typing import Any

import pytest

from mcstudio.controller.kernel import Controller
from mcstudio.controller.mc.enums import AxisState
from mcstudio.controller.runner import OVERRUN_EVENT_INTERVAL_S, TASK_PERIOD_EXCEEDED, Runner
from mcstudio.project.models import AxisConfig, Project
from tests.conftest import MM_AXIS, power_on, step_until

A0, A1 = "MC_Axis000", "MC_Axis001"
V1 = 40.0  # the witness axis's velocity


def _project(*, limit: dict[str, Any] | None = None, sensors: dict[str, Any] | None = None) -> Project:
    """Two servo axes (nodes 1, 2; mm); MC_Axis000 with an absolute encoder (home defined at servo ON, so the
    software limits apply), optional Limit settings and limit switches."""
    p0 = copy.deepcopy(MM_AXIS)
    p0["Limit"].update(limit or {})
    return Project(name="faults", axes=[
        AxisConfig(name=A0, number=0, type="_mcServo", node_address=1, parameters=p0, sensors=sensors or {},
                   drive={"EncoderType": "absolute"}),
        AxisConfig(name=A1, number=1, type="_mcServo", node_address=2, parameters=copy.deepcopy(MM_AXIS)),
    ])


def _start(c: Controller) -> tuple[Any, Any]:
    """Both axes powered; A1 moving at V1 (the witness), A0 moving at 100 mm/s towards +."""
    power_on(c, A0)
    power_on(c, A1)
    w = c.fb("MC_MoveVelocity", Axis=A1, Execute=True, Velocity=V1, Acceleration=1000.0, Deceleration=1000.0)
    m = c.fb("MC_MoveVelocity", Axis=A0, Execute=True, Velocity=100.0, Acceleration=1000.0, Deceleration=1000.0)
    step_until(c, w, "InVelocity")
    step_until(c, m, "InVelocity")
    return m, w


def _witness_unaffected(c: Controller, w: Any) -> None:
    ax = c.mc.by_name[A1]
    assert w.InVelocity and not w.Error and not w.CommandAborted
    assert ax.state == AxisState.Continuous and ax.error_code == 0
    assert c.mc.cmd_vel[ax.i] == pytest.approx(V1)


def _disconnect(c: Controller) -> None:
    c.network.disconnect(1)


def _drive_fault(c: Controller) -> None:
    c.network.drives.inject_fault(0, 0x2310)  # overcurrent


FAULTS: dict[str, tuple[Callable[[], Project], Callable[[Controller], None] | None, int, str]] = {
    # name: (project, injection (None: the motion runs into it), axis ErrorID, event code)
    "slave disconnect": (_project, _disconnect, 0x3003, "30030000"),
    "drive fault": (_project, _drive_fault, 0x3002, "30020000"),
    "following-error overflow": (lambda: _project(limit={"FollowingErrorOverVal": 0.05}), None, 0x6452, "64520000"),
    "software limit": (lambda: _project(limit={"SwLimitMode": "_mcCmdDecelerationStop", "PosiSwLimit": 30.0,
                                               "NegaSwLimit": -30.0}), None, 0x6450, "64500000"),
    "hardware limit": (lambda: _project(sensors={"PositiveLimit": 30.0, "NegativeLimit": -30.0}), None, 0x6453,
                       "64530000"),
}


@pytest.mark.parametrize("fault", list(FAULTS))
def test_fault_matrix(fault: str) -> None:
    make, inject, code, event = FAULTS[fault]
    c = Controller(make())
    if fault == "following-error overflow":
        # a following error of 0.05 mm is exceeded at 100 mm/s (one period of lag = 0.1 mm): start A1 first
        power_on(c, A1)
        w = c.fb("MC_MoveVelocity", Axis=A1, Execute=True, Velocity=V1, Acceleration=1000.0, Deceleration=1000.0)
        step_until(c, w, "InVelocity")
        power_on(c, A0)
        m = c.fb("MC_MoveVelocity", Axis=A0, Execute=True, Velocity=100.0, Acceleration=1000.0,
                 Deceleration=1000.0)
    else:
        m, w = _start(c)
    if inject is not None:
        inject(c)
    step_until(c, m, "CommandAborted", limit=5000)
    ax = c.mc.by_name[A0]
    assert ax.state == AxisState.ErrorStop and ax.error_code == code, (ax.state, hex(ax.error_code))
    assert [e for e in c.events.list() if e.code == event], f"no {event} event"
    c.step(300)  # A0 comes to a stop (or stays without servo); A1 goes on
    assert c.mc.cmd_vel[ax.i] == 0.0 or not c.mc.servo_on[ax.i]
    _witness_unaffected(c, w)

    # recovery: undo the cause where there is one, MC_Reset, power, move back
    if fault == "slave disconnect":
        c.network.reconnect(1)
        c.step(5)
    rs = c.fb("MC_Reset", Axis=A0, Execute=True)
    step_until(c, rs, "Done", limit=2000)
    assert ax.error_code == 0 and ax.state in (AxisState.Standstill, AxisState.Disabled)
    pw = c.fb("MC_Power", Axis=A0, Enable=True)
    step_until(c, pw, "Status", limit=100)
    back = c.fb("MC_MoveRelative", Axis=A0, Execute=True, Distance=-2.0, Velocity=1.0, Acceleration=100.0,
                Deceleration=100.0)
    step_until(c, back, "Done", limit=5000)
    assert ax.state == AxisState.Standstill
    _witness_unaffected(c, w)


class _Clock:
    def __init__(self) -> None:
        self.t = 1000.0

    def __call__(self) -> float:
        return self.t


def test_kernel_overrun_is_task_period_exceeded_and_the_control_goes_on() -> None:
    """Realtime mode driven by an injected clock (no thread): periods that take 3 periods to compute are overruns;
    the first one logs 60010000 Task Period Exceeded (observation), later ones within OVERRUN_EVENT_INTERVAL_S are
    counted into the next event; the moving axes neither stop nor error; MC_Reset is not needed (D123)."""
    c = Controller(_project())
    m, w = _start(c)
    r = Runner(c, mode="realtime")
    clock = r.clock = _Clock()
    run = c.run_cycle
    slow = {"s": 0.0}

    def timed_cycle() -> None:
        run()
        clock.t += slow["s"]

    c.run_cycle = timed_cycle  # type: ignore[method-assign]
    T = c.period_s
    for _ in range(200):  # on time: no overrun
        clock.t += T
        r._realtime_cycle(c)
    assert r.overruns == 0 and not [e for e in c.events.list() if e.code == TASK_PERIOD_EXCEEDED]
    slow["s"] = 3 * T
    cycles = 0
    while r.overruns < 20:
        clock.t += T  # wall time goes on by a period between two computations, each of which takes 3 periods
        r._realtime_cycle(c)
        cycles += 1
        assert cycles < 1000
    ev = [e for e in c.events.list() if e.code == TASK_PERIOD_EXCEEDED]
    counted = int(ev[0].detail.split()[0])
    assert len(ev) == 1 and ev[0].level == "observation" and ev[0].message == "Task Period Exceeded"
    assert r.status().overruns == r.overruns
    # after the interval, the next overrun reports the ones counted meanwhile
    clock.t += OVERRUN_EVENT_INTERVAL_S
    r._realtime_cycle(c)
    ev = [e for e in c.events.list() if e.code == TASK_PERIOD_EXCEEDED]
    assert len(ev) == 2 and ev[1].detail.startswith(f"{r.overruns - counted} period(s)"), ev[1].detail
    # the control carried on: both axes still move, no error
    assert m.InVelocity and not m.Error and c.mc.by_name[A0].error_code == 0
    _witness_unaffected(c, w)
