"""MC_SetKinTransform and MC_InverseKin as timing charts on the paused controller.

Spec: omron-robot-delta3.md §9.1 MC_SetKinTransform (seed 003 L2735–2977: KinParam order Rf, Lf, Rm, Lm; θ in
ExpansionParam[0]; conditions 5706/543E/5466; parameter errors 5707–570A, 571E, 571F deleting the kinematics;
usable one period after Done), §9.7 MC_InverseKin (L4704–4902: Valid/OutWorkspace/AxesPosition, 5710, 570F), §3.3
restrictions, §11 error table. The demo robot MC_Group000 (MC_Axis004–006, degrees) with its project kinematics
removed, so the instruction registers them.
"""

from __future__ import annotations

from typing import Any

import pytest

from mcstudio.controller.kernel import Controller
from mcstudio.controller.mc.fb.base import FunctionBlock
from mcstudio.controller.mc.group import GroupState
from mcstudio.controller.mc.kinematics import Delta3Params, inverse_point
from mcstudio.project.io import load_project
from tests.conftest import DEMO
from tests.controller.mc.group_helpers import group_project

GRP = "MC_Group000"
KIN = {"KinType": "_mcDelta3Type1", "KinParam": [200.0, 350.0, 50.0, 800.0], "ExpansionParam": [30.0]}
WS = {"WorkspaceType": 100, "WorkspaceParam": [-50.0, 300.0, 250.0, 150.0, 150.0]}


def _robot(*, homed: bool = True) -> Controller:
    p = load_project(DEMO)
    p.groups[0].kinematics = None
    c = Controller(p)
    c.step(2)
    for a in c.mc.groups_by_name[GRP].axes:
        a.homed = homed
    return c


def _set(c: Controller, kin: dict[str, Any] | None = None, ws: dict[str, Any] | None = None, **inputs: Any
         ) -> FunctionBlock:
    return c.fb("MC_SetKinTransform", AxesGroup=GRP, Execute=True, KinTransform=kin or KIN, Workspace=ws or WS,
                **inputs)


def test_set_kin_transform_registers_rf_lf_rm_lm_theta() -> None:
    """§9.1: cycle 0 Execute↑ → Busy; cycle 1 Done. KinParam is [Rf, Lf, Rm, Lm], θ is ExpansionParam[0]."""
    c = _robot()
    g = c.mc.groups_by_name[GRP]
    fb = _set(c, EnableWorkspace=False)
    c.step(1)
    assert fb.Busy and not fb.Done
    c.step(1)
    assert fb.Done and not fb.Busy and not fb.Error
    k = g.kinematics
    assert k is not None
    assert (k.Rf, k.Lf, k.Rm, k.Lm, k.theta) == (200.0, 350.0, 50.0, 800.0, 30.0)
    assert (k.workspace.Zu, k.workspace.Rcy, k.workspace.Hcy, k.workspace.Rco, k.workspace.Hco) == (
        -50.0, 300.0, 250.0, 150.0, 150.0)
    assert g.workspace_check is False  # the workspace is stored even with EnableWorkspace FALSE
    assert g.state == GroupState.Disabled


def test_inverse_kin_is_usable_one_period_after_done() -> None:
    """§9.1: the robot instructions may be used one control cycle after Done (earlier: 5710, §11)."""
    c = _robot()
    fb = _set(c)
    ik = c.fb("MC_InverseKin", AxesGroup=GRP, Enable=True, Position=[10.0, -20.0, -150.0])
    c.step(1)  # execution cycle: no kinematics yet
    assert ik.Error and ik.ErrorID == 0x5710
    c2 = _robot()
    fb = _set(c2)
    c2.step(2)
    assert fb.Done
    ik = c2.fb("MC_InverseKin", AxesGroup=GRP, Enable=True, Position=[10.0, -20.0, -150.0])
    c2.step(1)
    assert ik.Valid and ik.Busy and not ik.OutWorkspace
    _, expected = inverse_point(Delta3Params(Rf=200, Lf=350, Rm=50, Lm=800, theta=30), 10.0, -20.0, -150.0)
    assert ik.AxesPosition[:3] == pytest.approx(list(expected)) and ik.AxesPosition[3:] == [0.0] * 3


def test_inverse_kin_out_of_workspace_and_enable_off() -> None:
    """§9.7: OutWorkspace ↑ outside the workspace (Valid ↓); back inside → Valid; Enable ↓ → Busy, Valid ↓."""
    c = Controller(load_project(DEMO))  # the project's kinematics: usable from cycle 0
    ik = c.fb("MC_InverseKin", AxesGroup=GRP, Enable=True, Position=[0.0, 0.0, -100.0])
    c.step(1)
    assert ik.Valid and ik.AxesPosition[:3] == pytest.approx([15.00688481] * 3)
    c.set_inputs(ik.id, {"Position": [0.0, 0.0, -10.0]})  # above Zu = -50 mm
    c.step(1)
    assert ik.OutWorkspace and not ik.Valid and not ik.Error
    c.set_inputs(ik.id, {"Position": [0.0, 0.0, -100.0]})
    c.step(1)
    assert ik.Valid and not ik.OutWorkspace
    c.set_inputs(ik.id, {"Enable": False})
    c.step(1)
    assert not (ik.Busy or ik.Valid or ik.OutWorkspace)


def test_inverse_kin_without_kinematics_is_5710() -> None:
    c = _robot()
    ik = c.fb("MC_InverseKin", AxesGroup=GRP, Enable=True, Position=[0.0, 0.0, -100.0])
    c.step(1)
    assert ik.Error and ik.ErrorID == 0x5710 and not ik.Valid
    assert c.mc.groups_by_name[GRP].state == GroupState.ErrorStop  # source group (§11)


@pytest.mark.parametrize(("kin", "ws", "code"), [
    ({**KIN, "KinType": 101}, WS, 0x5707),
    ({**KIN, "KinParam": [0.0, 350.0, 50.0, 800.0]}, WS, 0x5708),  # Rf must be positive
    ({**KIN, "KinParam": [200.0, 350.0, 250.0, 800.0]}, WS, 0x5708),  # restriction (3): Rm < Rf
    ({**KIN, "ExpansionParam": [400.0]}, WS, 0x5708),  # θ 0–360
    ({**KIN, "KinParam": "200"}, WS, 0x5708),  # not an array
    (KIN, {**WS, "WorkspaceType": 7}, 0x5709),
    (KIN, {**WS, "WorkspaceParam": [10.0, 300.0, 250.0, 150.0, 150.0]}, 0x570A),  # Zu ≤ 0
    ({**KIN, "KinParam": [200.0, 350.0, 50.0, 400.0]}, WS, 0x571F),  # Lm ≤ Rf − Rm + Lf: no zero pose
])
def test_parameter_errors(kin: dict[str, Any], ws: dict[str, Any], code: int) -> None:
    """§9.1 parameter errors in the [Emulator] order; the group gets the error (§11 source group)."""
    c = _robot()
    fb = _set(c, kin, ws)
    c.step(1)
    assert fb.Error and fb.ErrorID == code, f"{fb.ErrorID:04X}"
    assert c.mc.groups_by_name[GRP].state == GroupState.ErrorStop
    assert any(e.code == f"{code:04X}0000" for e in c.events.list())


def test_kinematics_error_571f_deletes_the_registered_kinematics() -> None:
    """§9.1: after 571F the previously registered kinematics are deleted."""
    c = Controller(load_project(DEMO))
    c.step(2)
    g = c.mc.groups_by_name[GRP]
    for a in g.axes:
        a.homed = True
    assert g.kinematics is not None
    fb = _set(c, {**KIN, "KinParam": [200.0, 350.0, 50.0, 400.0]})
    c.step(1)
    assert fb.ErrorID == 0x571F and g.kinematics is None


def test_conditions_home_and_enabled_group() -> None:
    """§9.1: all axes homed (5466); only on a disabled group (543E, §11 "MC_SetKinTransform executed while the
    group is enabled")."""
    c = _robot(homed=False)
    fb = _set(c)
    c.step(1)
    assert fb.ErrorID == 0x5466
    c = _robot()
    en = c.fb("MC_GroupEnable", AxesGroup=GRP, Execute=True)
    c.step(2)
    assert en.Done
    fb = _set(c)
    c.step(1)
    assert fb.ErrorID == 0x543E and c.mc.groups_by_name[GRP].state == GroupState.ErrorStop


def test_composition_mismatch_is_5706() -> None:
    """§9.1 / §11 5706: a Delta3 needs 3 axes in degrees with linear count mode (MC_Group000 of group_project is a
    2-axis _mcXY group in mm)."""
    c = Controller(group_project())
    c.step(1)
    fb = c.fb("MC_SetKinTransform", AxesGroup="MC_Group000", Execute=True, KinTransform=KIN, Workspace=WS)
    c.step(1)
    assert fb.Error and fb.ErrorID == 0x5706

