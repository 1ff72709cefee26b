"""ErrorIDs of the interpolation instructions and MC_ChangeAxesInGroup (the group rows of docs/error-coverage.md).

Spec: omron-group-and-cam.md §4.3 MC_MoveLinear errors table (seed 000 line 14568; A-1 codes of the inputs,
lines 19141–19383), §4.5 (5479 instead of 5478), §4.6 MC_MoveCircular2D errors (547D, 5489, 548A, 544A; seed 000
lines 15714, 19283–19297), §4.11 MC_ChangeAxesInGroup (549D, seed 000 line 17004), §4.12 start conditions (linear
count mode, line 17153), the composition-axis start conditions of A-1 (543D line 19809, 5442 line 19876, 544A line
19977, 6443/6444 lines 21279/21292). An error of a group instruction is a group minor fault (A-1 source "Group"):
the instruction shows Error with the code in the period of its Execute edge (A-1 detection timing "at instruction
start") and the group goes to ErrorStop with MFaultLvl.Code = the code (decisions D50, D53); the composition axes
keep no error (§4.1).
"""

from __future__ import annotations

import copy
from typing import Any

import pytest

from mcstudio.controller.kernel import Controller
from mcstudio.controller.mc.enums import AxisState
from mcstudio.controller.mc.fb.base import FunctionBlock
from mcstudio.controller.mc.group import GroupState
from mcstudio.project.checks import check_groups
from mcstudio.project.io import ProjectError, parse_project
from mcstudio.project.models import AxisConfig, Project
from tests.conftest import MM_AXIS, step_until
from tests.controller.mc.group_helpers import group_project, ready

G0 = "MC_Group000"
G1 = "MC_Group001"
LINE = {"Position": [30.0, 40.0], "Velocity": 100.0, "Acceleration": 1000.0, "Deceleration": 1000.0}
ARC = {"Velocity": 10.0, "Acceleration": 100.0, "Deceleration": 100.0, "CircAxes": [0, 1]}


def _assert_group_error(c: Controller, fb: Any, code: int, group: str = G0) -> None:
    assert fb.Error and fb.ErrorID == code, f"{fb.ErrorID:04X}"
    g = c.mc.groups_by_name[group]
    assert g.state == GroupState.ErrorStop and g.capture()["MFaultLvl"] == {"Active": True, "Code": f"{code:04X}"}
    assert any(e.code == f"{code:04X}0000" for e in c.events.list())


def _attached_axis(c: Controller, code: int) -> str:
    """The latest event of `code`: its attached information (A-1: for a group source, the logical axis number of
    the composition axis concerned — basics L1199)."""
    return [e for e in c.events.list() if e.code == f"{code:04X}0000"][-1].detail


def _execute_edge(c: Controller, name: str, group: str = G0, **inputs: Any) -> FunctionBlock:
    """Timing chart of a start error: the instance runs one period with Execute FALSE (nothing happens), then
    Execute↑ — in that same period Error is TRUE; Busy and Active never were (the instruction did not start) and the
    composition axes' command positions did not move."""
    g = c.mc.groups_by_name[group]
    fb = c.fb(name, AxesGroup=group, Execute=False, **inputs)
    c.step(1)
    assert not fb.out["Busy"] and not fb.out["Error"]
    before = g.point()
    c.set_inputs(fb.id, {"Execute": True})
    c.step(1)
    assert fb.out["Error"] and not fb.out["Busy"] and not fb.out.get("Active", False), fb.out
    assert g.point() == before
    return fb


def _members_keep_no_error(c: Controller, group: str = G0) -> None:
    """A group error does not put the composition axes into error (§4.1): they stay Coordinated, no MFaultLvl."""
    for a in c.mc.groups_by_name[group].axes:
        assert a.state == AxisState.Coordinated and a.error_code == 0, (a.name, a.state, a.error_code)


def _group_reset(c: Controller, group: str = G0) -> None:
    rs = c.fb("MC_GroupReset", AxesGroup=group, Execute=True)
    step_until(c, rs, "Done", limit=100)


@pytest.mark.parametrize(("name", "inputs", "code"), [
    pytest.param("MC_MoveLinearAbsolute", {"Velocity": 0.0}, 0x5422, id="velocity-0-5422"),
    pytest.param("MC_MoveLinearAbsolute", {"Acceleration": -1.0}, 0x5423, id="acceleration-5423"),
    pytest.param("MC_MoveLinearAbsolute", {"Deceleration": -1.0}, 0x5424, id="deceleration-5424"),
    pytest.param("MC_MoveLinearAbsolute", {"Jerk": -1.0}, 0x5425, id="jerk-5425"),
    pytest.param("MC_MoveLinearAbsolute", {"BufferMode": 9}, 0x542B, id="buffermode-542b"),
    pytest.param("MC_MoveLinearAbsolute", {"CoordSystem": 1}, 0x542C, id="coordsystem-542c"),
    pytest.param("MC_MoveLinear", {"MoveMode": 2}, 0x5431, id="movemode-5431"),
    pytest.param("MC_MoveLinearAbsolute", {"TransitionMode": 10}, 0x5432, id="corner-with-aborting-5432"),
    pytest.param("MC_MoveLinearAbsolute", {"TransitionMode": 3}, 0x5432, id="transitionmode-5432"),
    pytest.param("MC_MoveLinearAbsolute", {"Position": [1e300, 0.0]}, 0x5478, id="position-5478"),
    pytest.param("MC_MoveLinearRelative", {"Distance": [1e300, 0.0]}, 0x5479, id="distance-5479"),
])
def test_interpolation_input_errors(name: str, inputs: dict[str, Any], code: int) -> None:
    """Inputs out of range (§4.3 errors table, A-1): Error with the code at the start, a group minor fault."""
    c = Controller(group_project())
    ready(c)
    args = {**LINE, **inputs}
    if name == "MC_MoveLinearRelative":
        args.pop("Position")
    fb = c.fb(name, AxesGroup=G0, Execute=True, **args)
    c.step(1)
    _assert_group_error(c, fb, code)


@pytest.mark.parametrize(("target", "code"), [(150.0, 0x6440), (-80.0, 0x6441)])
def test_target_beyond_a_software_limit(target: float, code: int) -> None:
    """§4.3 errors 6440/6441 (A-1): a target of a composition axis beyond its positive/negative software limit
    (SwLimitMode on, home defined) is refused at the start."""
    p = group_project()
    for a in p.axes:
        a.parameters.Limit.SwLimitMode = "_mcCmdDecelerationStop"  # type: ignore[assignment]
        a.parameters.Limit.PosiSwLimit = 100.0
        a.parameters.Limit.NegaSwLimit = -50.0
    c = Controller(p)
    ready(c)
    fb = c.fb("MC_MoveLinearAbsolute", AxesGroup=G0, Execute=True, **{**LINE, "Position": [target, 0.0]})
    c.step(1)
    _assert_group_error(c, fb, code)
    assert c.mc.groups_by_name[G0].point() == (0.0, 0.0)


def test_blending_that_cannot_reach_the_transit_velocity_is_5445_with_error_stop() -> None:
    """§4.3 BufferMode / A-1 5445: InterpolationAccDecOver = error stop; the running 10 mm move at 100 mm/s cannot
    reach the _mcBlendingNext transit velocity 400 mm/s in its remaining distance with 1000 mm/s² → 5445."""
    c = Controller(group_project(InterpolationAccDecOver="_mcAccDecOverErrorStop"))
    ready(c)
    mv1 = c.fb("MC_MoveLinearAbsolute", AxesGroup=G0, Execute=True, **{**LINE, "Position": [10.0, 0.0]})
    c.step(50)
    mv2 = c.fb("MC_MoveLinearAbsolute", AxesGroup=G0, Execute=True, BufferMode=4,
               **{**LINE, "Position": [10.0, 50.0], "Velocity": 400.0})
    c.step(1)
    _assert_group_error(c, mv2, 0x5445)
    assert mv1.CommandAborted


def test_blending_uses_the_reachable_transit_velocity_otherwise() -> None:
    """The same blend with the default InterpolationAccDecOver: no error, the reachable transit velocity is used
    (D54) and both moves complete."""
    c = Controller(group_project())
    ready(c)
    mv1 = c.fb("MC_MoveLinearAbsolute", AxesGroup=G0, Execute=True, **{**LINE, "Position": [10.0, 0.0]})
    c.step(50)
    mv2 = c.fb("MC_MoveLinearAbsolute", AxesGroup=G0, Execute=True, BufferMode=4,
               **{**LINE, "Position": [10.0, 50.0], "Velocity": 400.0})
    step_until(c, mv2, "Done", limit=2000)
    assert mv1.Done and not mv2.Error


@pytest.mark.parametrize("axes", [[0, 99], [0, 0], [0, 1, 2, 3]], ids=["unknown-axis", "duplicate", "count-ok"])
def test_change_axes_in_group_549d(axes: list[int]) -> None:
    """§4.11 (seed 000 line 17004, A-1 549D): an axis number that does not exist or is given twice → 549D, nothing
    written; only the first len(composition) entries count (a 2-axis group with [0, 1, 2, 3] is fine)."""
    c = Controller(group_project())
    ready(c, enable=False)
    g = c.mc.groups_by_name[G0]
    before = [a.number for a in g.axes]
    ch = c.fb("MC_ChangeAxesInGroup", AxesGroup=G0, Execute=True, Axes=axes + [0] * (4 - len(axes)))
    c.step(2)
    if axes == [0, 1, 2, 3]:
        assert ch.Done and [a.number for a in g.axes] == [0, 1]
        return
    assert ch.Error and ch.ErrorID == 0x549D
    assert [a.number for a in g.axes] == before


@pytest.mark.parametrize(("inputs", "code"), [
    pytest.param({"AccFactor": 500.1}, 0x5470, id="accfactor-5470"),
    pytest.param({"AccFactor": -1.0}, 0x5470, id="accfactor-negative-5470"),
    pytest.param({"JerkFactor": 600.0}, 0x546F, id="jerkfactor-546f"),
])
def test_group_set_override_reserved_factors_out_of_range(inputs: dict[str, Any], code: int) -> None:
    """§4.9 MC_GroupSetOverride (seed 000 line 16694) and A-1 5470 / 546F: AccFactor / JerkFactor (reserved) outside
    0–500 % is an error (Enabled stays FALSE)."""
    c = Controller(group_project())
    ready(c)
    ov = c.fb("MC_GroupSetOverride", AxesGroup=G0, Enable=True, VelFactor=50.0, **inputs)
    c.step(1)
    assert ov.Error and ov.ErrorID == code and not ov.Enabled, f"{ov.ErrorID:04X}"



# ------------------------------------------------------------------------------------------- composition-axis start
def _with_encoder_axis() -> Project:
    """The group fixture with A1 of MC_Group000 replaced by a virtual encoder axis MC_Axis005 (the demo and fixture
    projects have none: the project check refuses it, see below)."""
    p = group_project()
    p.axes.append(AxisConfig(name="MC_Axis005", number=5, type="_mcVirEncdr", parameters=copy.deepcopy(MM_AXIS)))
    p.groups[0].axes = ["MC_Axis000", "MC_Axis005"]
    return p


def test_encoder_axis_in_a_group_is_543d() -> None:
    """§0.3 / §4.3 (seed 000 line 14669: "a group containing an encoder or virtual encoder axis → 543D, the operation
    ends"), A-1 543D (line 19809). The product refuses such a project before it reaches the controller — the project
    check names the axis and 543D, and loading fails; a controller given it anyway refuses MC_GroupEnable with 543D
    in the period of Execute↑, as a group error (decision D131): the group is ErrorStop, the axes keep no error and
    are not Coordinated. A motion instruction then sees a group that was never enabled (CommandAborted in ErrorStop,
    543F once reset)."""
    p = _with_encoder_axis()
    issues = check_groups(p)
    assert [(i.path, i.code) for i in issues] == [("groups[0].axes[1]", "543D")]
    assert "_mcVirEncdr" in issues[0].message
    with pytest.raises(ProjectError) as err:
        parse_project(p.model_dump(mode="json"))
    assert [(i.path, i.code) for i in err.value.issues] == [("groups[0].axes[1]", "543D")]

    c = Controller(p)
    g = c.mc.groups_by_name[G0]
    en = _execute_edge(c, "MC_GroupEnable")
    _assert_group_error(c, en, 0x543D)
    assert not g.enabled
    for name in ("MC_Axis000", "MC_Axis005"):
        a = c.mc.by_name[name]
        assert a.state == AxisState.Disabled and a.error_code == 0 and a.group is None
    mv = c.fb("MC_MoveLinearAbsolute", AxesGroup=G0, Execute=True, **LINE)
    c.step(1)
    assert mv.CommandAborted and not mv.Error
    _group_reset(c)
    assert g.state == GroupState.Disabled and not en.Error
    mv = _execute_edge(c, "MC_MoveLinearAbsolute", **LINE)
    assert mv.ErrorID == 0x543F


def _rotary_a2() -> Controller:
    """MC_Group001 (virtual servo axes 002, 003, 004 as A0, A1, A2) with MC_Axis004 in Rotary Mode 0–360."""
    p = group_project()
    pc = p.axes[4].parameters.PosCount
    pc.CountMode = "_mcCountModeRotary"  # type: ignore[assignment]
    pc.ModuloMinPosVal, pc.ModuloMaxPosVal = 0.0, 360.0
    c = Controller(p)
    ready(c, G1)
    assert c.mc.by_name["MC_Axis004"].rotary
    return c


@pytest.mark.parametrize(("name", "inputs", "code"), [
    pytest.param("MC_MoveCircular2D", {**ARC, "CircAxes": [0, 2], "CircMode": 2, "AuxPoint": [10.0, 0.0],
                                       "EndPoint": [10.0, 10.0]}, 0x544A, id="circular-y-rotary-544a"),
    pytest.param("MC_MoveCircular2D", {**ARC, "CircAxes": [2, 1], "CircMode": 2, "AuxPoint": [10.0, 0.0],
                                       "EndPoint": [10.0, 10.0]}, 0x544A, id="circular-x-rotary-544a"),
    pytest.param("MC_GroupSyncMoveAbsolute", {"Position": [1.0, 1.0, 1.0]}, 0x544A, id="sync-move-544a"),
    pytest.param("MC_MoveCircular2D", {**ARC, "CircMode": 2, "AuxPoint": [10.0, 0.0], "EndPoint": [10.0, 10.0]}, 0,
                 id="circular-in-the-linear-plane-accepted"),
    pytest.param("MC_MoveLinearAbsolute", {**LINE, "Position": [1.0, 1.0, 370.0]}, 0, id="linear-accepted"),
])
def test_rotary_axis_is_544a(name: str, inputs: dict[str, Any], code: int) -> None:
    """§4.6 (seed 000 line 15714): the X and Y axes of MC_MoveCircular2D must be in Linear Mode, else 544A at the
    start; §4.12 start condition (line 17153): every composition axis of MC_GroupSyncMoveAbsolute in Linear Mode;
    A-1 544A (line 19977, source Group, "the group cannot operate"). Counter-cases: a circle in the plane of the two
    linear axes, and MC_MoveLinear (a rotary member is positioned as with _mcNoDirection, §4.3) start normally."""
    c = _rotary_a2()
    g = c.mc.groups_by_name[G1]
    if not code:
        fb = c.fb(name, AxesGroup=G1, Execute=True, **inputs)
        c.step(2)
        assert fb.Busy and fb.Active and not fb.Error and g.state == GroupState.Moving
        return
    fb = _execute_edge(c, name, G1, **inputs)
    _assert_group_error(c, fb, code, G1)
    _members_keep_no_error(c, G1)


@pytest.mark.parametrize(("name", "inputs"), [
    pytest.param("MC_MoveLinearAbsolute", LINE, id="linear"),
    pytest.param("MC_MoveCircular2D", {**ARC, "CircMode": 2, "AuxPoint": [10.0, 0.0], "EndPoint": [10.0, 10.0]},
                 id="circular"),
    pytest.param("MC_GroupSyncMoveAbsolute", {"Position": [1.0, 1.0]}, id="sync-move"),
])
def test_member_stopped_by_mc_stop_is_5442(name: str, inputs: dict[str, Any]) -> None:
    """A-1 5442 (seed 000 line 19876): a group motion instruction while MC_Stop is executing (Execute TRUE) on a
    composition axis → 5442 at the start, the group cannot operate; remedy: MC_Stop Execute FALSE, reset, retry.
    The condition arises when MC_Stop is held on a servo-OFF member (A-3: Disabled → Done, the axis stays Disabled)
    and the group is then enabled (§4.1 accepts Disabled members) and the servo switched on — MC_Stop on a member of
    an enabled group is 543E instead (A-3.4 column I, D70), and a member in Stopping cannot be enabled (5440)."""
    c = Controller(group_project())
    g = c.mc.groups_by_name[G0]
    st = c.fb("MC_Stop", Axis="MC_Axis001", Execute=True, Deceleration=1000.0)
    c.step(2)
    assert st.Done and c.mc.by_name["MC_Axis001"].state == AxisState.Disabled
    en = c.fb("MC_GroupEnable", AxesGroup=G0, Execute=True)  # the members are Disabled: accepted (§4.1)
    step_until(c, en, "Done", limit=10)
    ready(c, enable=False)  # then servo ON and home defined; MC_Axis001 stays Coordinated
    assert g.state == GroupState.Standby and not g.capture()["Status"]["Ready"]
    fb = _execute_edge(c, name, **inputs)
    _assert_group_error(c, fb, 0x5442)
    _members_keep_no_error(c)
    assert _attached_axis(c, 0x5442) == "attached information 1: 1 (logical axis A1, MC_Axis001)"
    assert st.Done and not st.Error
    # the manual's remedy: release MC_Stop, reset the error, execute again
    c.set_inputs(st.id, {"Execute": False})
    c.step(1)
    _group_reset(c)
    assert g.state == GroupState.Standby and g.capture()["Status"]["Ready"]
    again = c.fb(name, AxesGroup=G0, Execute=True, **inputs)
    c.step(2)
    assert again.Busy and again.Active and not again.Error and g.state == GroupState.Moving


@pytest.mark.parametrize(("inputs", "code"), [
    # border: start (0, 0), via 0.01 mm (≈ 1049 pulses, so not collinear) off the 2000 mm chord: R = 5e7 mm ≈ 5.2e12
    # pulses > 2^40
    pytest.param({"CircMode": 0, "AuxPoint": [1000.0, 0.01], "EndPoint": [2000.0, 0.0]}, 0x547D,
                 id="border-radius-overflow-547d"),
    pytest.param({"CircMode": 0, "AuxPoint": [6e6, 0.0], "EndPoint": [20.0, 0.0]}, 0x5489, id="border-aux-5489"),
    pytest.param({"CircMode": 1, "AuxPoint": [0.0, -6e6], "EndPoint": [20.0, 0.0]}, 0x5489, id="centre-aux-5489"),
    pytest.param({"CircMode": 2, "AuxPoint": [-1.1e7, 0.0], "EndPoint": [20.0, 0.0]}, 0x5489, id="radius-5489"),
    pytest.param({"CircMode": 2, "AuxPoint": [20.0, 0.0], "EndPoint": [20.0, 6e6]}, 0x548A, id="end-y-548a"),
    pytest.param({"CircMode": 1, "AuxPoint": [10.0, 0.0], "EndPoint": [-6e6, 0.0]}, 0x548A, id="end-x-548a"),
    # a radius is a magnitude: 6e6 mm is beyond the signed 40-bit position range but within 40 bits
    pytest.param({"CircMode": 2, "AuxPoint": [6e6, 0.0], "EndPoint": [20.0, 0.0]}, 0, id="radius-within-40-bits"),
])
def test_circular_radius_and_point_ranges(inputs: dict[str, Any], code: int) -> None:
    """§4.6 errors, A-1 (seed 000 lines 19283–19297, 20556–20691): 547D the radius of a border/centre-mode arc beyond
    40 bits in pulses; 5489 AuxPoint beyond signed 40 bits in pulses (border/centre), |AuxPoint[0]| beyond 40 bits
    (radius mode — its overflow is 5489, not 547D, note of line 20566); 548A EndPoint beyond signed 40 bits. The axes
    have 104857.6 pulses/mm: signed 40 bits = ±5,242,880 mm, 40 bits = 10,485,760 mm. At the start; group stops."""
    c = Controller(group_project())
    ready(c)
    g = c.mc.groups_by_name[G0]
    if not code:
        fb = c.fb("MC_MoveCircular2D", AxesGroup=G0, Execute=True, **ARC, **inputs)
        c.step(2)
        assert fb.Busy and fb.Active and not fb.Error and g.state == GroupState.Moving
        return
    fb = _execute_edge(c, "MC_MoveCircular2D", **ARC, **inputs)
    _assert_group_error(c, fb, code)
    _members_keep_no_error(c)
    _group_reset(c)
    assert g.state == GroupState.Standby and not fb.Error


def test_centre_mode_radius_overflow_is_547d() -> None:
    """547D in centre mode (A-1, seed 000 line 20556): start (5e6, 5e6) mm set by MC_SetPosition before the group is
    enabled, centre (−5e6, −5e6) mm — both within the signed 40-bit position range — give a radius of 1.41e7 mm
    ≈ 1.48e12 pulses > 2^40."""
    c = Controller(group_project())
    for ax in ("MC_Axis002", "MC_Axis003"):
        sp = c.fb("MC_SetPosition", Axis=ax, Execute=True, Position=5e6)
        step_until(c, sp, "Done", limit=10)
    ready(c, G1)
    assert c.mc.groups_by_name[G1].point() == (5e6, 5e6, 0.0)
    fb = _execute_edge(c, "MC_MoveCircular2D", G1, **ARC, CircMode=1, AuxPoint=[-5e6, -5e6], EndPoint=[5e6, 5e6])
    _assert_group_error(c, fb, 0x547D, G1)
    _members_keep_no_error(c, G1)


@pytest.mark.parametrize(("sensors", "name", "inputs", "code"), [
    # the positive limit input of A1 ON; the line moves A1 in the negative direction, away from it — still refused
    pytest.param({"PositiveLimit": -5.0}, "MC_MoveLinearAbsolute", {**LINE, "Position": [30.0, -40.0]}, 0x6443,
                 id="linear-6443"),
    pytest.param({"NegativeLimit": 5.0}, "MC_MoveLinearAbsolute", LINE, 0x6444, id="linear-6444"),
    pytest.param({"NegativeLimit": 5.0}, "MC_MoveCircular2D",
                 {**ARC, "CircMode": 2, "AuxPoint": [10.0, 0.0], "EndPoint": [10.0, 10.0]}, 0x6444,
                 id="circular-6444"),
    pytest.param({"PositiveLimit": -5.0}, "MC_GroupSyncMoveAbsolute", {"Position": [0.0, -1.0]}, 0x6443,
                 id="sync-move-6443"),
])
def test_limit_input_on_at_the_start(sensors: dict[str, float], name: str, inputs: dict[str, Any],
                                     code: int) -> None:
    """A-1 6443/6444 (seed 000 lines 21279/21292): "an axes group motion instruction executed while the positive /
    negative limit input is ON" — whatever the direction of the motion (unlike a single-axis instruction), and for
    MC_GroupSyncMoveAbsolute too (D130). Source Group: the group cannot operate, the axis keeps no error. The
    manual's remedy: reset, disable the group, move the axis off the limit, then the group moves again."""
    p = group_project()
    p.axes[1].sensors = sensors  # type: ignore[assignment]  # MC_Axis001 = A1 of MC_Group000 (servo, node 2)
    c = Controller(p)
    ready(c)
    g = c.mc.groups_by_name[G0]
    fb = _execute_edge(c, name, **inputs)
    _assert_group_error(c, fb, code)
    _members_keep_no_error(c)
    assert _attached_axis(c, code) == "attached information 1: 1 (logical axis A1, MC_Axis001)"
    _group_reset(c)
    assert g.state == GroupState.Standby and not fb.Error
    again = _execute_edge(c, name, **inputs)  # the input is still ON: refused again
    assert again.ErrorID == code
    _group_reset(c)
    dis = c.fb("MC_GroupDisable", AxesGroup=G0, Execute=True)
    step_until(c, dis, "Done", limit=10)
    off = c.fb("MC_MoveAbsolute", Axis="MC_Axis001", Execute=True, Position=-10.0 if code == 0x6443 else 10.0,
               Velocity=100.0, Acceleration=1000.0, Deceleration=1000.0)
    step_until(c, off, "Done", limit=1000)
    en = c.fb("MC_GroupEnable", AxesGroup=G0, Execute=True)
    step_until(c, en, "Done", limit=10)
    ok = c.fb(name, AxesGroup=G0, Execute=True, **inputs)
    c.step(2)
    assert ok.Busy and ok.Active and not ok.Error and g.state == GroupState.Moving
