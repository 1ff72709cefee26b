"""ErrorIDs of the interpolation instructions and MC_ChangeAxesInGroup (the group rows of docs/error-coverage.md).

Spec: omron-group-and-cam.md §4.3 MC_MoveLinear errors table (seed 000 line 14568; A-1 codes of the inputs,
lines 19141–19383), §4.5 (5479 instead of 5478), §4.11 MC_ChangeAxesInGroup (549D, seed 000 line 17004). An input
error of a group instruction is a group minor fault (A-1 source "Group"): the instruction shows Error with the code
and the group goes to ErrorStop with MFaultLvl.Code = the code (decisions D50, D53).
"""

from __future__ import annotations

from typing import Any

import pytest

from mcstudio.controller.kernel import Controller
from mcstudio.controller.mc.group import GroupState
from tests.conftest import step_until
from tests.controller.mc.group_helpers import group_project, ready

G0 = "MC_Group000"
LINE = {"Position": [30.0, 40.0], "Velocity": 100.0, "Acceleration": 1000.0, "Deceleration": 1000.0}


def _assert_group_error(c: Controller, fb: Any, code: int) -> None:
    assert fb.Error and fb.ErrorID == code, f"{fb.ErrorID:04X}"
    g = c.mc.groups_by_name[G0]
    assert g.state == GroupState.ErrorStop and g.capture()["MFaultLvl"] == {"Active": True, "Code": f"{code:04X}"}
    assert any(e.code == f"{code:04X}0000" for e in c.events.list())


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

