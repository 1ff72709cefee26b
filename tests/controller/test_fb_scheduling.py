"""Skipping settled instances is invisible (kernel `skip_settled`, `FunctionBlock.sleep`).

The program calls every instance once per period (api.md "Function-block instances"). A settled instance — an
Execute-type instruction whose Execute and job have not changed, an MC_Power holding its axis — is not called until
an input, its job's status or its axis's servo state wakes it, because such a call would change nothing. These tests
run the same random command script with and without skipping and require identical outputs in every period.
"""

from __future__ import annotations

import random
from typing import Any

import pytest

from mcstudio.controller.kernel import Controller
from mcstudio.controller.mc.fb.base import FunctionBlock
from tests.conftest import small_project

AXES = ("MC_Axis000", "MC_Axis001", "MC_Axis002")


def _program(c: Controller) -> list[FunctionBlock]:
    fbs: list[FunctionBlock] = []
    for ax in AXES:
        fbs.append(c.fb("MC_Power", Axis=ax))
        fbs.append(c.fb("MC_MoveAbsolute", Axis=ax, Position=0.0, Velocity=60.0, Acceleration=600.0,
                        Deceleration=600.0))
        fbs.append(c.fb("MC_MoveRelative", Axis=ax, Distance=5.0, Velocity=40.0, Acceleration=800.0,
                        Deceleration=800.0, BufferMode="_mcBuffered"))
        fbs.append(c.fb("MC_MoveVelocity", Axis=ax, Velocity=20.0, Acceleration=300.0, Deceleration=300.0))
        fbs.append(c.fb("MC_Stop", Axis=ax, Deceleration=500.0))
        fbs.append(c.fb("MC_Reset", Axis=ax))
    return fbs


def _run(seed: int, *, skip: bool) -> list[Any]:
    c = Controller(small_project())
    c.skip_settled = skip
    fbs = _program(c)
    rng = random.Random(seed)
    trace: list[Any] = []
    for k in range(2500):
        if k % 7 == 0:
            fb = rng.choice(fbs)
            name = fb.DEF.name
            if name == "MC_Power":
                fb.Enable = rng.random() < 0.85 or not fb.Enable
            else:
                if name == "MC_MoveAbsolute" and rng.random() < 0.5:
                    fb.Position = rng.uniform(-50.0, 50.0)
                if name == "MC_MoveVelocity" and rng.random() < 0.5:
                    fb.Velocity = rng.uniform(5.0, 80.0)
                fb.Execute = not fb.Execute
        c.step(1, publish=False)
        trace.append((tuple(c.mc.cmd_pos.tolist()), tuple(tuple(fb.out.values()) for fb in fbs)))
    return trace


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_skipping_settled_instances_changes_no_output(seed: int) -> None:
    called_all = _run(seed, skip=False)
    skipping = _run(seed, skip=True)
    assert len({t[0] for t in called_all}) > 100, "the script really moved the axes"
    for k, (a, b) in enumerate(zip(called_all, skipping, strict=True)):
        assert a == b, f"period {k}: outputs differ when settled instances are skipped"


def test_settled_instances_sleep_and_wake() -> None:
    """A finished move with Execute held sleeps; a new Execute edge wakes it; MC_Power sleeps while the servo is ON
    and wakes when the drive leaves Operation enabled (an axis error with a free-run stop)."""
    c = Controller(small_project())
    pw = c.fb("MC_Power", Axis="MC_Axis000", Enable=True)
    c.step(5, publish=False)
    mv = c.fb("MC_MoveAbsolute", Axis="MC_Axis000", Execute=True, Position=1.0, Velocity=50.0,
              Acceleration=500.0, Deceleration=500.0)
    c.step(200, publish=False)
    assert mv.Done and mv._asleep and pw.Status and pw._asleep
    mv.Execute = False
    assert not mv._asleep
    c.step(2, publish=False)
    assert not mv.Done and mv._asleep
    mv.Position = 3.0
    mv.Execute = True
    c.step(1, publish=False)
    assert mv.Busy
    c.step(200, publish=False)
    assert mv.Done and c.mc.cmd_pos[0] == pytest.approx(3.0)
    c.network.drives.inject_fault(0, 0x2310)
    c.step(3, publish=False)
    assert not pw.Status and pw.Error is False, "MC_Power woke and shows the servo OFF"
