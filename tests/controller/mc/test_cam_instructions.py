"""Cam table instructions: MC_SetCamTableProperty, MC_SaveCamTable, MC_GenerateCamTable.

Spec: omron-group-and-cam.md §5.0.3 (mutual exclusion), §5.1 (worked examples with MyCam1 : ARRAY[0..4999]),
§5.2, §5.4.5 (GenerateCamBusy one period after Busy, errors with ErrorParameterCode / ErrorNodePointIndex, the
sample program's Tcd = 36001), decision D44 (generation in the period after Busy).
"""

from __future__ import annotations

import copy
import threading
from typing import Any

import numpy as np
import pytest

from mcstudio.controller.kernel import Controller
from mcstudio.controller.mc.cam.table import CamTable
from mcstudio.project.models import AxisConfig, Project
from tests.conftest import MM_AXIS, power_on, step_until


def _ctrl(**tables: CamTable) -> Controller:
    p = copy.deepcopy(MM_AXIS)
    axes = [AxisConfig(name=f"MC_Axis00{k}", number=k, type="_mcVirServo", parameters=p) for k in range(2)]
    return Controller(Project(name="cams", axes=axes), cams=tables)


def _mycam1() -> CamTable:
    """§5.1 worked example: MyCam1 : ARRAY[0..4999], end point [999] = (360, 0)."""
    t = CamTable(5000)
    t.phase[1:1000] = np.linspace(0.36, 360.0, 999)
    t.distance[:1000] = np.linspace(0.0, 1.0, 1000)
    t.distance[999] = 0.0
    t.set_cam_table_property()
    return t


def test_set_cam_table_property_worked_examples() -> None:
    """§5.1: initial table → EndPointIndex 999; after the program writes more ascending points up to [4997]
    without executing the instruction the cam still uses [0]…[999]; after executing it, 4997."""
    t = _mycam1()
    c = _ctrl(MyCam1=t)
    rt = c.mc.cam_tables["MyCam1"]
    fb = c.fb("MC_SetCamTableProperty", CamTable="MyCam1", Execute=True)
    c.step(1)
    assert fb.Busy and not fb.Done
    c.step(1)
    assert fb.Done and fb.EndPointIndex == 999 and fb.MaxDataNumber == 5000
    rt.phase[1000:4998] = np.linspace(360.5, 2000.0, 3998)
    assert rt.end_point_index == 999, "writing data alone does not move the end point"
    c.set_inputs(fb.id, {"Execute": False})
    c.step(1)
    c.set_inputs(fb.id, {"Execute": True})
    step_until(c, fb, "Done")
    assert fb.EndPointIndex == 4997
    assert rt.end_point_index == 4997


def test_set_cam_table_property_errors() -> None:
    """5480: phases not ascending before the first Phase 0 (an MC common minor fault); 5439: not a cam table."""
    t = _mycam1()
    c = _ctrl(MyCam1=t)
    c.mc.cam_tables["MyCam1"].phase[500] = 1.0
    fb = c.fb("MC_SetCamTableProperty", CamTable="MyCam1", Execute=True)
    c.step(1)
    assert fb.Error and fb.ErrorID == 0x5480
    assert any(e.code == "54800000" for e in c.events.list())
    bad = c.fb("MC_SetCamTableProperty", CamTable="Nope", Execute=True)
    c.step(1)
    assert bad.Error and bad.ErrorID == 0x5439


SAMPLE_NODES: list[dict[str, Any]] = [
    {"Phase": 180.0, "Distance": -100.0, "Curve": "_mcPolynomic5", "PhasePitch": 0.01},
    {"Phase": 200.0, "Distance": -102.0, "Curve": "_mcStraightLine", "PhasePitch": 0.01},
    {"Phase": 360.0, "Distance": 0.0, "Curve": "_mcPolynomic5", "PhasePitch": 0.01},
    {"Phase": 0.0},
]


def test_generate_cam_table_sample_program() -> None:
    """§5.4 sample program: CamProfile0 : ARRAY[0..36000], CycleTime 0.8, nodes (180, −100, quintic),
    (200, −102, straight line), (360, 0, quintic), pitch 0.01 → Tcd = 36001, EndPointIndex 36000.
    GenerateCamBusy turns TRUE the period after Busy; Done follows."""
    c = _ctrl(CamProfile0=CamTable(36001))
    gen = c.fb("MC_GenerateCamTable", CamTable="CamProfile0", CamProperty={"CycleTime": 0.8},
               CamNodes=SAMPLE_NODES, Execute=True)
    c.step(1)
    assert gen.Busy and not gen.Done and c.mc.generate_cam_busy is None
    c.step(1)
    assert c.mc.generate_cam_busy is gen, "GenerateCamBusy one period after Busy"
    assert gen.Busy and not gen.Done
    c.step(1)
    assert gen.Done and not gen.Busy and gen.EndPointIndex == 36000
    assert c.mc.generate_cam_busy is None
    t = c.mc.cam_tables["CamProfile0"]
    p, d = t.valid()
    assert p[18000] == pytest.approx(180.0) and d[18000] == pytest.approx(-100.0)
    assert d[-1] == pytest.approx(0.0)
    slope = (d[19000] - d[18999]) / (p[19000] - p[18999])
    assert slope == pytest.approx(-0.1, rel=1e-3), "the straight line between (180, −100) and (200, −102)"


def test_generate_errors_carry_the_parameter_and_node() -> None:
    c = _ctrl(T=CamTable(1000))
    gen = c.fb("MC_GenerateCamTable", CamTable="T", CamProperty={"CycleTime": 1.0}, Execute=True,
               CamNodes=[{"Phase": 90.0, "Distance": 1.0, "Curve": 1, "PhasePitch": 1.0},
                         {"Phase": 80.0, "Distance": 2.0, "Curve": 1, "PhasePitch": 1.0}])
    c.step(2)
    assert gen.Error and gen.ErrorID == 0x5740 and gen.ErrorNodePointIndex == 1
    assert c.mc.generate_cam_busy is None
    too_big = c.fb("MC_GenerateCamTable", CamTable="T", CamProperty={"CycleTime": 1.0}, Execute=True,
                   CamNodes=[{"Phase": 360.0, "Distance": 1.0, "Curve": 1, "PhasePitch": 0.01}])
    c.step(2)
    assert too_big.Error and too_big.ErrorID == 0x5741


def test_generate_is_exclusive_with_camin_on_the_same_table() -> None:
    """§5.0.3: MC_GenerateCamTable cannot start on a table an MC_CamIn uses (543C), and only one generation runs
    at a time."""
    c = _ctrl(T=CamTable.from_points([0.0, 360.0], [0.0, 10.0]), U=CamTable(1000))
    power_on(c, "MC_Axis000")
    power_on(c, "MC_Axis001")
    cam = c.fb("MC_CamIn", Master="MC_Axis000", Slave="MC_Axis001", CamTable="T", Execute=True)
    c.step(2)
    assert cam.Busy
    gen = c.fb("MC_GenerateCamTable", CamTable="T", CamProperty={"CycleTime": 1.0}, Execute=True,
               CamNodes=[{"Phase": 360.0, "Distance": 1.0, "Curve": 1, "PhasePitch": 1.0}])
    c.step(1)
    assert gen.Error and gen.ErrorID == 0x543C
    g1 = c.fb("MC_GenerateCamTable", CamTable="U", CamProperty={"CycleTime": 1.0}, Execute=True,
              CamNodes=[{"Phase": 360.0, "Distance": 1.0, "Curve": 1, "PhasePitch": 1.0}])
    c.step(1)
    assert g1.Busy and c.mc.generate_cam_busy is None
    # executed in the period g1 generates (GenerateCamBusy TRUE when g2 is called, after g1 in program order)
    g2 = c.fb("MC_GenerateCamTable", CamTable="U", CamProperty={"CycleTime": 1.0}, Execute=True,
              CamNodes=[{"Phase": 360.0, "Distance": 1.0, "Curve": 1, "PhasePitch": 1.0}])
    c.step(1)
    assert c.mc.generate_cam_busy is g1
    assert g2.Error and g2.ErrorID == 0x543C
    c.step(1)
    assert g1.Done


def test_cam_in_on_a_generated_table_follows_it() -> None:
    c = _ctrl(T=CamTable(400))
    gen = c.fb("MC_GenerateCamTable", CamTable="T", CamProperty={"CycleTime": 1.0}, Execute=True,
               CamNodes=[{"Phase": 360.0, "Distance": 36.0, "Curve": "_mcStraightLine", "PhasePitch": 1.0}])
    step_until(c, gen, "Done")
    assert gen.EndPointIndex == 360
    power_on(c, "MC_Axis000")
    power_on(c, "MC_Axis001")
    cam = c.fb("MC_CamIn", Master="MC_Axis000", Slave="MC_Axis001", CamTable="T", Execute=True,
               ReferenceType="_mcLatestCommand")
    c.step(2)
    assert cam.InSync, "the master stands at StartPosition 0"
    c.fb("MC_MoveAbsolute", Axis="MC_Axis000", Execute=True, Position=100.0, Velocity=100.0, Acceleration=1000.0,
         Deceleration=1000.0)
    c.step(1500)
    assert c.mc.cmd_pos[1] == pytest.approx(10.0, abs=1e-4)


def test_save_cam_table_writes_through_the_saver_in_the_background() -> None:
    """MC_SaveCamTable: CamTableBusy while the save runs (a background thread: the period goes on); Done when the
    file is written; only one save at a time (543C)."""
    c = _ctrl(T=CamTable.from_points([0.0, 360.0], [0.0, 10.0]), U=CamTable.from_points([0.0, 1.0], [0.0, 1.0]))
    release = threading.Event()
    saved: list[tuple[str, list[float]]] = []

    def saver(name: str, table: CamTable) -> None:
        release.wait(10.0)
        saved.append((name, table.valid()[1].tolist()))

    c.mc.cam_saver = saver
    fb = c.fb("MC_SaveCamTable", CamTable="T", Execute=True)
    c.step(3)
    assert fb.Busy and not fb.Done and c.mc.cam_saving is fb
    other = c.fb("MC_SaveCamTable", CamTable="U", Execute=True)
    c.step(1)
    assert other.Error and other.ErrorID == 0x543C
    release.set()
    for _ in range(10_000):  # the kernel steps until the save thread has finished (no sleeping)
        c.step(1, publish=False)
        if fb.Done:
            break
    assert fb.Done and c.mc.cam_saving is None
    assert saved == [("T", [0.0, 10.0])]


def test_save_failure_is_743c() -> None:
    c = _ctrl(T=CamTable.from_points([0.0, 360.0], [0.0, 10.0]))

    def saver(name: str, table: CamTable) -> None:
        raise OSError("disk full")

    c.mc.cam_saver = saver
    fb = c.fb("MC_SaveCamTable", CamTable="T", Execute=True)
    for _ in range(10_000):
        c.step(1, publish=False)
        if fb.Error:
            break
    assert fb.ErrorID == 0x743C
