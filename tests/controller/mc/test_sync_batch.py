"""The batch of steady cam followers (sync_batch.py) computes exactly what the per-law path computes.

Differential test: the same program runs twice, once with the batch and once with every follower on the per-law path
(`MotionModule.batch_enabled = False`); command positions and the outputs of every instance must agree every period,
through wraps in both directions, EndOfProfile pulses, Index changes, feeding cams, the three ReferenceTypes, a
re-execution switching the table, an MC_Phasing (the follower leaves the batch), a stopped follower and a follower
of a follower (kept on the per-law path).
"""

from __future__ import annotations

import copy

import numpy as np

from mcstudio.controller.kernel import Controller
from mcstudio.controller.mc.cam.table import CamTable
from mcstudio.project.models import AxisConfig, Project
from tests.conftest import MM_AXIS, power_on

N_MASTERS = 2
N_SLAVES = 6


def _controller(batch: bool) -> Controller:
    p = copy.deepcopy(MM_AXIS)
    p["Operation"].update(MaxVel=100000.0, MaxAcc=1e6, MaxDec=1e6)
    p["Limit"] = {"PosiSwLimit": 1e9, "NegaSwLimit": -1e9}
    axes = [AxisConfig(name=f"MC_Axis{k:03d}", number=k, type="_mcVirServo", parameters=p)
            for k in range(N_MASTERS + N_SLAVES)]
    x = np.linspace(0.0, 360.0, 121)
    tables = {
        "Rise": CamTable.from_points(x, 20.0 * (x / 360.0 - np.sin(2 * np.pi * x / 360.0) / (2 * np.pi))),  # feeding
        "Wave": CamTable.from_points(x, 5.0 * np.sin(2 * np.pi * x / 360.0)),  # reciprocating
        "Line": CamTable.from_points([0.0, 100.0], [0.0, 50.0]),
    }
    c = Controller(Project(name="batch", axes=axes), cams=tables)
    c.mc.batch_enabled = batch
    c.mc.batch_min = 1  # batch even these few followers
    for k in range(N_MASTERS + N_SLAVES):
        power_on(c, f"MC_Axis{k:03d}")
    return c


def _program(c: Controller) -> list:
    fbs = [
        c.fb("MC_MoveVelocity", Axis="MC_Axis000", Execute=True, Velocity=400.0, Acceleration=2000.0,
             Deceleration=2000.0),
        c.fb("MC_MoveVelocity", Axis="MC_Axis001", Execute=True, Velocity=250.0, Acceleration=0.0,
             Deceleration=0.0, Direction="_mcNegativeDirection"),
    ]
    specs = [
        ("MC_Axis000", "Rise", "_mcLatestCommand", {}),
        ("MC_Axis000", "Wave", "_mcCommand", {"MasterScaling": 2.0, "SlaveScaling": 0.5, "SlaveOffset": 1.0}),
        ("MC_Axis001", "Rise", "_mcFeedback", {"StartPosition": -30.0}),
        ("MC_Axis001", "Line", "_mcLatestCommand", {"MasterOffset": 10.0}),
        ("MC_Axis000", "Wave", "_mcLatestCommand", {"StartMode": "_mcRelativePosition", "StartPosition": 50.0,
                                                     "MasterStartDistance": 20.0}),
        ("MC_Axis002", "Wave", "_mcLatestCommand", {}),  # follows a follower: per-law path
    ]
    for k, (master, table, ref, extra) in enumerate(specs):
        fbs.append(c.fb("MC_CamIn", Master=master, Slave=f"MC_Axis{N_MASTERS + k:03d}", CamTable=table,
                        Execute=True, Periodic=True, ReferenceType=ref, **extra))
    return fbs


def _run(batch: bool) -> tuple[np.ndarray, list[list[dict]]]:
    c = _controller(batch)
    fbs = _program(c)
    positions, outputs = [], []
    for k in range(4000):
        if k == 1200:  # re-execution: the first follower switches to another table
            c.set_inputs(fbs[2].id, {"Execute": False})
        if k == 1201:
            c.set_inputs(fbs[2].id, {"Execute": True, "CamTable": "Wave"})
        if k == 1500:
            fbs.append(c.fb("MC_Phasing", Master="MC_Axis000", Slave="MC_Axis003", Execute=True, PhaseShift=20.0,
                            Velocity=100.0, Acceleration=1000.0, Deceleration=1000.0))
        if k == 2000:
            fbs.append(c.fb("MC_Stop", Axis="MC_Axis005", Execute=True, Deceleration=5000.0))
        if k == 2500:  # the master reverses: wraps backwards
            c.set_inputs(fbs[0].id, {"Execute": False})
        if k == 2501:
            c.set_inputs(fbs[0].id, {"Execute": True, "Direction": "_mcNegativeDirection"})
        c.step(1, publish=False)
        positions.append(c.mc.cmd_pos.copy())
        outputs.append([dict(fb.out) for fb in fbs])
    return np.array(positions), outputs


def test_batch_equals_the_per_law_path() -> None:
    pos_b, out_b = _run(batch=True)
    pos_s, out_s = _run(batch=False)
    assert pos_b.shape == pos_s.shape
    np.testing.assert_allclose(pos_b, pos_s, rtol=0, atol=1e-9)
    for k, (ob, os_) in enumerate(zip(out_b, out_s, strict=True)):
        assert ob == os_, f"period {k}"
    eops = sum(o[k]["EndOfProfile"] for o in out_b for k in range(2, 8))
    assert eops >= 4, "the test passes through wraps (forward ones pulse EndOfProfile)"
    indexes = {o[4]["Index"] for o in out_b}
    assert len(indexes) > 50, "and through many Index changes"


def test_steady_followers_run_in_the_batch() -> None:
    c = _controller(batch=True)
    _program(c)
    c.step(1500)
    batch = c.mc._batch
    assert batch is not None
    in_batch = sorted(int(i) for i in batch.slave)
    assert in_batch == [2, 3, 4, 5, 6], "every steady follower except the follower of a follower"
    assert c.mc._sync_order == [7]


def test_batch_handles_an_empty_set() -> None:
    c = _controller(batch=True)
    c.step(10)
    assert c.mc._batch is None
