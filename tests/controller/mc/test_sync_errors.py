"""ErrorIDs of the synchronized-control instructions, one case per condition the manual names.

Spec: omron-axis-instructions.md MC_CamIn … MC_SyncMoveVelocity ("Error codes named in text"), omron-mc-basics.md
A-1 (#2–3 ratio, #9–10 scaling, #21–27, #56–67 re-execution, #65, #83–84, #88, #92, #95–97, #102, #105, #108,
#113–118). Each case checks Error, the exact ErrorID, and the event with the 8-digit code; input errors error-stop
the slave (minor fault, source axis).
"""

from __future__ import annotations

from typing import Any

import pytest

from mcstudio.controller.kernel import Controller
from mcstudio.controller.mc.enums import AxisState
from tests.conftest import step_until
from tests.controller.mc.test_sync import M, S, _rig, _run_master

GEAR = {"Master": M, "Slave": S, "Execute": True}
LINK = {"Master": M, "Slave": S, "Execute": True, "SlaveDistance": 10.0, "MasterDistance": 100.0}


@pytest.mark.parametrize(
    ("fb", "inputs", "code"),
    [
        ("MC_GearIn", {**GEAR, "RatioNumerator": 0}, 0x5420),
        ("MC_GearIn", {**GEAR, "RatioDenominator": 0}, 0x5421),
        ("MC_GearIn", {**GEAR, "Acceleration": -1.0}, 0x5423),
        ("MC_GearIn", {**GEAR, "Deceleration": -1.0}, 0x5424),
        ("MC_GearIn", {**GEAR, "Jerk": -1.0}, 0x5425),
        ("MC_GearIn", {**GEAR, "BufferMode": 3}, 0x542B),
        ("MC_GearIn", {**GEAR, "Master": S}, 0x5436),
        ("MC_GearInPos", {**GEAR, "Velocity": 0.0}, 0x5422),
        ("MC_GearInPos", {**GEAR, "Velocity": 10.0, "BufferMode": 1}, 0x542B),
        ("MC_GearInPos", {**GEAR, "Velocity": 10.0, "MasterSyncPosition": 1e15}, 0x546C),
        ("MC_GearInPos", {**GEAR, "Velocity": 10.0, "SlaveSyncPosition": 1e15}, 0x546D),
        ("MC_MoveLink", {**LINK, "LinkOption": 7}, 0x5435),
        ("MC_MoveLink", {**LINK, "MasterDistance": -1.0}, 0x5482),
        ("MC_MoveLink", {**LINK, "MasterDistanceInACC": -1.0}, 0x5483),
        ("MC_MoveLink", {**LINK, "MasterDistanceInDEC": -1.0}, 0x5484),
        ("MC_MoveLink", {**LINK, "SlaveDistance": 1e15}, 0x548B),
        ("MC_MoveLink", {**LINK, "LinkOption": 1, "TriggerInput": {"Mode": 9}}, 0x5450),
        ("MC_CamIn", {"Master": M, "Slave": S, "CamTable": "Steps", "Execute": True, "StartPosition": 1e15},
         0x547A),
        ("MC_CamIn", {"Master": M, "Slave": S, "CamTable": "Steps", "Execute": True, "MasterStartDistance": 1e15},
         0x547B),
        ("MC_CamIn", {"Master": M, "Slave": S, "CamTable": "Steps", "Execute": True, "MasterOffset": 1e15}, 0x5493),
        ("MC_CamIn", {"Master": M, "Slave": S, "CamTable": "Steps", "Execute": True, "SlaveOffset": 1e15}, 0x5494),
        ("MC_CamOut", {"Slave": S, "Execute": True, "OutMode": 3}, 0x5491),
        ("MC_CamOut", {"Slave": S, "Execute": True, "Deceleration": -1.0}, 0x5424),
        ("MC_SyncMoveVelocity", {"Axis": S, "Execute": True, "CmdPosMode": 1}, 0x5495),
        ("MC_SyncMoveAbsolute", {"Axis": S, "Execute": True, "Position": 1e15}, 0x5478),
    ],
)
def test_input_errors(fb: str, inputs: dict[str, Any], code: int) -> None:
    c = _rig()
    inst = c.fb(fb, **inputs)
    c.step(1)
    _assert_error(c, inst, code)


def _assert_error(c: Controller, inst: Any, code: int, *, axis: str = S) -> None:
    assert inst.Error and inst.ErrorID == code, f"{inst.DEF.name}: ErrorID {inst.ErrorID:04X}, expected {code:04X}"
    assert any(e.code == f"{code:04X}0000" for e in c.events.list()), f"no event {code:04X}0000"
    assert c.mc.by_name[axis].state == AxisState.ErrorStop


def test_combine_axes_errors() -> None:
    """5434 CombineMode, 548E auxiliary = slave, 549A/549B position types, 547F auxiliary number above the slave's
    with _mcLatestCommand (A-1 #21, #105, #117, #118, #92)."""
    import copy

    from mcstudio.project.models import AxisConfig, Project
    from tests.conftest import MM_AXIS, power_on

    p = copy.deepcopy(MM_AXIS)
    axes = [AxisConfig(name=f"MC_Axis00{k}", number=k, type="_mcVirServo", parameters=p) for k in range(3)]
    base = {"Master": "MC_Axis000", "Auxiliary": "MC_Axis001", "Slave": "MC_Axis002", "Execute": True}
    cases = [
        ({**base, "CombineMode": 5}, 0x5434),
        ({**base, "Auxiliary": "MC_Axis002", "ReferenceTypeAuxiliary": "_mcFeedback"}, 0x548E),
        ({**base, "ReferenceTypeMaster": 0}, 0x549A),
        ({**base, "ReferenceTypeAuxiliary": 0}, 0x549B),
        ({**base, "Slave": "MC_Axis001", "Auxiliary": "MC_Axis002"}, 0x547F),
    ]
    for inputs, code in cases:
        c = Controller(Project(name="combine", axes=axes))
        for k in range(3):
            power_on(c, f"MC_Axis00{k}")
        inst = c.fb("MC_CombineAxes", **inputs)
        c.step(1)
        _assert_error(c, inst, code, axis=inputs["Slave"])


@pytest.mark.parametrize(
    ("change", "code"),
    [
        ({"Master": S}, 0x5459),
        ({"MasterOffset": 1.0}, 0x545A),
        ({"MasterScaling": 2.0}, 0x545B),
        ({"MasterStartDistance": 1.0}, 0x545C),
        ({"SlaveScaling": 2.0}, 0x5464),
        ({"StartMode": "_mcRelativePosition"}, 0x5472),
    ],
)
def test_camin_reexecution_errors(change: dict[str, Any], code: int) -> None:
    """Re-execution may only switch the table (MC_CamIn re-execution; A-1 #56–67)."""
    c = _rig()
    _run_master(c)
    cam = c.fb("MC_CamIn", Master=M, Slave=S, CamTable="Steps", Execute=True, Periodic=True)
    step_until(c, cam, "InSync")
    c.set_inputs(cam.id, {"Execute": False})
    c.step(1)
    c.set_inputs(cam.id, {"Execute": True, **change})
    c.step(1)
    assert cam.Error and cam.ErrorID == code


def test_reexecution_disabled_543b() -> None:
    """MC_CamOut, MC_GearOut, MC_GearInPos, MC_MoveLink, MC_CombineAxes, MC_SyncMoveVelocity, MC_SyncMoveAbsolute:
    re-execution is 543B (their rules)."""
    c = _rig()
    _run_master(c)
    link = c.fb("MC_MoveLink", **{**LINK, "SlaveDistance": 1000.0, "MasterDistance": 100000.0})
    c.step(2)
    c.set_inputs(link.id, {"Execute": False})
    c.step(1)
    c.set_inputs(link.id, {"Execute": True})
    c.step(1)
    assert link.Error and link.ErrorID == 0x543B


def test_phasing_velocity_must_be_set() -> None:
    """MC_Phasing with Velocity 0: 5422, an error of the synchronized slave (MC_Phasing rules)."""
    c = _rig()
    _run_master(c)
    gear = c.fb("MC_GearIn", Master=M, Slave=S, Execute=True)
    step_until(c, gear, "InGear")
    ph = c.fb("MC_Phasing", Master=M, Slave=S, Execute=True, PhaseShift=1.0, Velocity=0.0)
    c.step(1)
    _assert_error(c, ph, 0x5422)
    assert gear.CommandAborted, "the slave error-stops: the gear ends"


def test_gearinpos_impossible_catch_up_is_5475() -> None:
    """The slave cannot reach SlaveSyncPosition when the master reaches MasterSyncPosition with the given
    Velocity/Acceleration/Deceleration (A-1 #83)."""
    c = _rig()
    _run_master(c, velocity=360.0)
    gp = c.fb("MC_GearInPos", Master=M, Slave=S, Execute=True, MasterSyncPosition=20.0, SlaveSyncPosition=5000.0,
              Velocity=400.0, Acceleration=100.0, Deceleration=100.0)
    c.step(2)
    assert gp.Error and gp.ErrorID == 0x5475


def test_aborted_generation_table_is_5743() -> None:
    """A table whose generation ended in 5742 (REAL overflow) is in an error state: MC_CamIn gives 5743."""
    c = _rig()
    c.mc.cam_tables["Steps"].generation_aborted = True
    cam = c.fb("MC_CamIn", Master=M, Slave=S, CamTable="Steps", Execute=True)
    c.step(1)
    assert cam.Error and cam.ErrorID == 0x5743
