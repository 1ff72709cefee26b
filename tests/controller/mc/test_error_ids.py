"""Every ErrorID condition the manual names for the single-axis and common instructions, as short timing charts.

The inventory (code, condition, spec line, test) is docs/error-coverage.md. References in ids and docstrings:
"ch3 L<n>" = line n of omron-axis-instructions.md, "A-1 #n" = row n of the error list in omron-mc-basics.md
(lines 1011–1171), "A-2.4" = its detail-code tables, "§5.x" = omron-group-and-cam.md. Each case checks the instance's
Error and exact ErrorID, the axis state afterwards — ErrorStop with MFaultLvl.Code for an axis minor fault, unchanged
for an error whose source is MC common — and the event with the 8-digit code in the event log.
"""

from __future__ import annotations

import copy
from typing import Any

import numpy as np
import pytest

from mcstudio.controller.kernel import Controller, Until
from mcstudio.controller.mc.enums import AxisState, _eMC_AXIS_USE
from mcstudio.controller.mc.fb.base import FunctionBlock
from mcstudio.project.models import Project
from tests.conftest import axis_project, power_on, run_into_overflow, small_project, step_until

AX = "MC_Axis000"
PPU = 104857.6  # pulses per mm of the fixtures (2^20 pulses per 10 mm)
OUT40 = 1e7  # mm: beyond signed 40 bits in pulses (2^39 / PPU ≈ 5.24e6 mm)
OUT40D = 2e7  # mm: a distance beyond 40 bits in pulses (2^40 / PPU ≈ 1.05e7 mm)
MOVE = {"Velocity": 10.0, "Acceleration": 100.0, "Deceleration": 100.0}
EXT1 = {"Mode": "_mcDrive", "LatchID": "_mcLatch1", "InputDrive": "_mcEXT"}
EXT2 = {"Mode": "_mcDrive", "LatchID": "_mcLatch2", "InputDrive": "_mcEXT"}
SW = {"SwLimitMode": "_mcCmdDecelerationStop", "PosiSwLimit": 100.0, "NegaSwLimit": -50.0}
S = AxisState


# ---------------------------------------------------------------------------------------------------- helpers
def _events(c: Controller, code: int) -> list[Any]:
    return [e for e in c.events.list() if e.code == f"{code:04X}0000"]


def _outputs(fb: FunctionBlock) -> str:
    return f"{fb.DEF.name} outputs {fb.outputs_json()}"


def assert_axis_fault(c: Controller, fb: FunctionBlock, code: int, axis: int = 0) -> None:
    """The instance shows Error/ErrorID; the code is an axis minor fault: MFaultLvl.Code, ErrorStop, event logged."""
    assert fb.out["Error"] and fb.out["ErrorID"] == code, _outputs(fb)
    ax = c.mc.axes[axis]
    assert ax.state == S.ErrorStop, f"{ax.name} is {ax.state.name}"
    assert ax.error_code == code, f"MFaultLvl.Code {ax.error_code:04X}"
    ev = _events(c, code)
    assert ev and ev[-1].level == "minor fault" and ev[-1].source.startswith(ax.name), [e.code for e in ev]


def assert_common_error(c: Controller, fb: FunctionBlock, code: int, states: dict[str, AxisState]) -> None:
    """The instance shows Error/ErrorID; the source is MC common: no axis changes state or gets a minor fault."""
    assert fb.out["Error"] and fb.out["ErrorID"] == code, _outputs(fb)
    for ax in c.mc.axes:
        assert ax.state == states[ax.name], f"{ax.name}: {states[ax.name].name} → {ax.state.name}"
        assert ax.error_code == 0
    ev = _events(c, code)
    assert ev and ev[-1].source.startswith("MC common"), [(e.code, e.source) for e in ev]


def _states(c: Controller) -> dict[str, AxisState]:
    return {a.name: a.state for a in c.mc.axes}


def _homed(**groups: Any) -> Controller:
    """MC_Axis000 servo ON and home defined (absolute encoder), MC_Axis001 virtual."""
    c = Controller(axis_project(encoder="absolute", **groups))
    power_on(c)
    return c


def _rotary(**groups: Any) -> Controller:
    c = Controller(axis_project(encoder="absolute", count_mode="_mcCountModeRotary", modulo=(0.0, 360.0), **groups))
    power_on(c)
    return c


def _with_encoder_axis() -> Controller:
    """MC_Axis000 servo (ON), MC_Axis001 an encoder axis on node 2 (Disabled, the only state besides ErrorStop)."""
    p = axis_project()
    p.axes[1].type = "_mcEncdr"  # type: ignore[assignment]
    p.axes[1].node_address = 2
    c = Controller(p)
    power_on(c)
    return c


def _with_unused_axis() -> Controller:
    """small_project with MC_Axis002 set to an unused axis; MC_Axis000 servo ON."""
    p: Project = small_project()
    p.axes[2] = p.axes[2].model_copy(update={"use": _eMC_AXIS_USE._mcUnusedAxis})
    c = Controller(p)
    power_on(c)
    return c


def _block_mechanism(c: Controller, at_mm: float) -> None:
    """A mechanical stop: the motor of MC_Axis000 cannot pass `at_mm` (positive side), whatever the drive commands."""
    plant = c.network.plant
    advance = plant.advance
    stop = int(at_mm * PPU)

    def blocked(position: np.ndarray, *args: Any, **kwargs: Any) -> Any:
        result = advance(position, *args, **kwargs)
        position[0] = min(int(position[0]), stop)
        return result

    plant.advance = blocked  # type: ignore[method-assign]
    # the drive's own following-error window (6065h, not mapped: its start-up value) is opened, as a start-up SDO
    # 6065h = FFFFFFFFh would: these tests are about the MC module's reaction, not the drive's 8611h
    c.network.drive_rx["following_error_window"][0] = 0xFFFFFFFF


def _retrigger(c: Controller, fb: FunctionBlock) -> None:
    """Execute↓ for one period, then Execute↑ again (a new rising edge on the same instance)."""
    fb.Execute = False
    c.step(1)
    fb.Execute = True
    c.step(1)


# ---------------------------------------------------------------------------------------------------- 5460 / 5462
# Every instruction in scope on an axis that does not exist for the MC module (an unused axis, or no axis given for
# the three instructions that work on unused axes): 5460 Illegal Axis Specification, source MC common, effect
# NOEXEC (A-1 #63, omron-mc-basics.md L1073; §5.3/§5.5/§5.6 for the common instructions).
UNUSED = "MC_Axis002"
ILLEGAL_AXIS_CASES: list[tuple[str, dict[str, Any]]] = [
    ("MC_Power", {"Axis": UNUSED, "Enable": True}),
    ("MC_Reset", {"Axis": UNUSED, "Execute": True}),
    ("MC_Stop", {"Axis": UNUSED, "Execute": True}),
    ("MC_ImmediateStop", {"Axis": UNUSED, "Execute": True}),
    ("MC_Move", {"Axis": UNUSED, "Execute": True, **MOVE}),
    ("MC_MoveAbsolute", {"Axis": UNUSED, "Execute": True, **MOVE}),
    ("MC_MoveRelative", {"Axis": UNUSED, "Execute": True, **MOVE}),
    ("MC_MoveVelocity", {"Axis": UNUSED, "Execute": True, **MOVE}),
    ("MC_MoveJog", {"Axis": UNUSED, "PositiveEnable": True, **MOVE}),
    ("MC_MoveFeed", {"Axis": UNUSED, "Execute": True, "TriggerInput": EXT1, **MOVE}),
    ("MC_MoveZeroPosition", {"Axis": UNUSED, "Execute": True, **MOVE}),
    ("MC_Home", {"Axis": UNUSED, "Execute": True}),
    ("MC_HomeWithParameter", {"Axis": UNUSED, "Execute": True}),
    ("MC_SetPosition", {"Axis": UNUSED, "Execute": True}),
    ("MC_SetOverride", {"Axis": UNUSED, "Enable": True}),
    ("MC_ResetFollowingError", {"Axis": UNUSED, "Execute": True}),
    ("MC_ZoneSwitch", {"Axis": UNUSED, "Enable": True}),
    ("MC_TouchProbe", {"Axis": UNUSED, "Execute": True, "TriggerInput": EXT1}),
    ("MC_AbortTrigger", {"Axis": UNUSED, "Execute": True, "TriggerInput": EXT1}),
    ("MC_AxesObserve", {"Master": AX, "Slave": UNUSED, "Enable": True}),
    ("MC_ChangeAxisUse", {"Execute": True, "AxisUse": "_mcUsedAxis"}),
    ("MC_Write", {"Target": UNUSED, "Execute": True, "ParameterNumber": "_mcChkVel", "SettingValue": 10}),
    ("MC_WriteAxisParameter", {"Execute": True, "AxisParameter": {}}),
    ("MC_ReadAxisParameter", {"Execute": True, "AxisParameter": {}}),
]


@pytest.mark.parametrize(("name", "inputs"), ILLEGAL_AXIS_CASES, ids=[f"{n}-A-1#63" for n, _ in ILLEGAL_AXIS_CASES])
def test_illegal_axis_is_5460(name: str, inputs: dict[str, Any]) -> None:
    c = _with_unused_axis()
    states = _states(c)
    fb = c.fb(name, **inputs)
    c.step(1)
    assert_common_error(c, fb, 0x5460, states)
    assert not fb.out["Busy"]


def test_axes_observe_illegal_master_is_5462() -> None:
    """MC_AxesObserve with a Master that does not exist: 5462 Illegal Master Axis Specification, MC common
    (A-1 #65 L1075; ch3 L1670-1673: errors of this instruction are MC common minor faults)."""
    c = _with_unused_axis()
    states = _states(c)
    ob = c.fb("MC_AxesObserve", Master=UNUSED, Slave=AX, Enable=True)
    c.step(1)
    assert_common_error(c, ob, 0x5462, states)


# ---------------------------------------------------------------------------------------------------- input ranges
# Input values outside the instruction's valid range, detected at start (omron-mc-basics.md §2.6, A-1). All these
# codes have the source Axis (A-1 "Source" column), so the axis gets the minor fault and error-stops.
INPUT_BASE: dict[str, dict[str, Any]] = {
    "MC_Move": {"Execute": True, "Position": 10.0, **MOVE},
    "MC_MoveAbsolute": {"Execute": True, "Position": 10.0, **MOVE},
    "MC_MoveRelative": {"Execute": True, "Distance": 10.0, **MOVE},
    "MC_MoveVelocity": {"Execute": True, **MOVE},
    "MC_MoveZeroPosition": {"Execute": True, **MOVE},
    "MC_MoveJog": {"PositiveEnable": True, **MOVE},
    "MC_MoveFeed": {"Execute": True, "TriggerInput": EXT1, "MoveMode": "_mcAbsolute", "Position": 10.0, **MOVE,
                    "FeedDistance": 1.0, "FeedVelocity": 5.0},
    "MC_Stop": {"Execute": True, "Deceleration": 100.0},
    "MC_ImmediateStop": {"Execute": True},
    "MC_SetPosition": {"Execute": True, "Position": 1.0},
    "MC_SetOverride": {"Enable": True},
    "MC_ResetFollowingError": {"Execute": True},
    "MC_ZoneSwitch": {"Enable": True, "FirstPosition": -1.0, "LastPosition": 1.0},
    "MC_TouchProbe": {"Execute": True, "TriggerInput": EXT1},
    "MC_AbortTrigger": {"Execute": True, "TriggerInput": EXT1},
}
WINDOW = {"WindowOnly": True, "FirstPosition": 20.0, "LastPosition": 30.0}
INPUT_CASES: list[Any] = [
    # MC_Move (ch3 L381–432)
    pytest.param("MC_Move", {"Velocity": 0.0}, 0x5422, id="Move-Velocity0-5422-ch3L392"),
    pytest.param("MC_Move", {"Acceleration": -1.0}, 0x5423, id="Move-Acc-5423-A-1#5"),
    pytest.param("MC_Move", {"Deceleration": -1.0}, 0x5424, id="Move-Dec-5424-A-1#6"),
    pytest.param("MC_Move", {"Jerk": -1.0}, 0x5425, id="Move-Jerk-5425-A-1#7"),
    pytest.param("MC_Move", {"Direction": 5}, 0x542E, id="Move-Direction-542E-A-1#15"),
    pytest.param("MC_Move", {"BufferMode": 6}, 0x542B, id="Move-BufferMode-542B-A-1#12"),
    pytest.param("MC_Move", {"MoveMode": 2}, 0x5431, id="Move-MoveMode-5431-A-1#18-ch3L398"),
    pytest.param("MC_Move", {"Position": OUT40}, 0x5478, id="Move-abs-40bit-5478-A-1#85"),
    pytest.param("MC_Move", {"MoveMode": 1, "Position": OUT40D}, 0x5479, id="Move-rel-40bit-5479-A-1#86"),
    # MC_MoveRelative (ch3 L489–527: "Velocity not set → error, presumably 5422")
    pytest.param("MC_MoveRelative", {"Velocity": 0.0}, 0x5422, id="MoveRelative-Velocity0-5422-ch3L525"),
    pytest.param("MC_MoveRelative", {"Acceleration": -1.0}, 0x5423, id="MoveRelative-Acc-5423-A-1#5"),
    pytest.param("MC_MoveRelative", {"Deceleration": -1.0}, 0x5424, id="MoveRelative-Dec-5424-A-1#6"),
    pytest.param("MC_MoveRelative", {"Jerk": -1.0}, 0x5425, id="MoveRelative-Jerk-5425-A-1#7"),
    pytest.param("MC_MoveRelative", {"BufferMode": 6}, 0x542B, id="MoveRelative-BufferMode-542B-A-1#12"),
    # MC_MoveVelocity (ch3 L529–576)
    pytest.param("MC_MoveVelocity", {"Acceleration": -1.0}, 0x5423, id="MoveVelocity-Acc-5423-A-1#5"),
    pytest.param("MC_MoveVelocity", {"Deceleration": -1.0}, 0x5424, id="MoveVelocity-Dec-5424-A-1#6"),
    pytest.param("MC_MoveVelocity", {"Jerk": -1.0}, 0x5425, id="MoveVelocity-Jerk-5425-A-1#7"),
    pytest.param("MC_MoveVelocity", {"Direction": 4}, 0x542E, id="MoveVelocity-NoDirection-542E-ch3L543"),
    pytest.param("MC_MoveVelocity", {"Continuous": True}, 0x5433, id="MoveVelocity-Continuous-5433-A-1#20"),
    # MC_MoveZeroPosition (ch3 L578–623: "Velocity must be set (error if not)", BufferMode 0/1)
    pytest.param("MC_MoveZeroPosition", {"Velocity": 0.0}, 0x5422, id="MoveZeroPosition-Velocity0-5422-ch3L588"),
    pytest.param("MC_MoveZeroPosition", {"Acceleration": -1.0}, 0x5423, id="MoveZeroPosition-Acc-5423-A-1#5"),
    pytest.param("MC_MoveZeroPosition", {"Deceleration": -1.0}, 0x5424, id="MoveZeroPosition-Dec-5424-A-1#6"),
    pytest.param("MC_MoveZeroPosition", {"Jerk": -1.0}, 0x5425, id="MoveZeroPosition-Jerk-5425-A-1#7"),
    pytest.param("MC_MoveZeroPosition", {"BufferMode": 2}, 0x542B, id="MoveZeroPosition-Blending-542B-ch3L592"),
    # MC_MoveJog (ch3 L117–161: Velocity/Acceleration/Deceleration "positive or 0")
    pytest.param("MC_MoveJog", {"Velocity": -1.0}, 0x5422, id="MoveJog-Velocity-5422-A-1#4"),
    pytest.param("MC_MoveJog", {"Acceleration": -1.0}, 0x5423, id="MoveJog-Acc-5423-A-1#5"),
    pytest.param("MC_MoveJog", {"Deceleration": -1.0}, 0x5424, id="MoveJog-Dec-5424-A-1#6"),
    # MC_MoveFeed (ch3 L625–703)
    pytest.param("MC_MoveFeed", {"Velocity": 0.0}, 0x5422, id="MoveFeed-Velocity0-5422-ch3L640"),
    pytest.param("MC_MoveFeed", {"Acceleration": -1.0}, 0x5423, id="MoveFeed-Acc-5423-A-1#5"),
    pytest.param("MC_MoveFeed", {"Deceleration": -1.0}, 0x5424, id="MoveFeed-Dec-5424-A-1#6"),
    pytest.param("MC_MoveFeed", {"Jerk": -1.0}, 0x5425, id="MoveFeed-Jerk-5425-A-1#7"),
    pytest.param("MC_MoveFeed", {"Direction": 5}, 0x542E, id="MoveFeed-Direction-542E-ch3L644"),
    pytest.param("MC_MoveFeed", {"BufferMode": 2}, 0x542B, id="MoveFeed-Blending-542B-ch3L648"),
    pytest.param("MC_MoveFeed", {"FeedDistance": OUT40D}, 0x548D, id="MoveFeed-FeedDistance-548D-A-1#104"),
    pytest.param("MC_MoveFeed", {"Position": OUT40}, 0x5478, id="MoveFeed-abs-40bit-5478-A-1#85"),
    pytest.param("MC_MoveFeed", {"MoveMode": "_mcRelative", "Position": OUT40D}, 0x5479,
                 id="MoveFeed-rel-40bit-5479-A-1#86"),
    pytest.param("MC_MoveFeed", {**WINDOW, "FirstPosition": OUT40}, 0x5469, id="MoveFeed-First-5469-ch3L687"),
    pytest.param("MC_MoveFeed", {**WINDOW, "LastPosition": OUT40}, 0x546A, id="MoveFeed-Last-546A-ch3L687"),
    pytest.param("MC_MoveFeed", {**WINDOW, "FirstPosition": 31.0}, 0x546B, id="MoveFeed-First>Last-546B-ch3L687"),
    pytest.param("MC_MoveFeed", {"TriggerInput": {**EXT1, "Mode": 5}}, 0x5450, id="MoveFeed-TriggerMode-5450-A-1#48"),
    pytest.param("MC_MoveFeed", {"TriggerInput": {**EXT1, "LatchID": 2}}, 0x544E, id="MoveFeed-LatchID-544E-A-1#46"),
    pytest.param("MC_MoveFeed", {"TriggerInput": {**EXT1, "InputDrive": 2}}, 0x5451,
                 id="MoveFeed-InputDrive-5451-A-1#49"),
    # MC_Stop (ch3 L706–752: BufferMode only _mcAborting)
    pytest.param("MC_Stop", {"Jerk": -1.0}, 0x5425, id="Stop-Jerk-5425-A-1#7"),
    pytest.param("MC_Stop", {"BufferMode": 1}, 0x542B, id="Stop-BufferMode-542B-ch3L718"),
    # MC_ImmediateStop (ch3 L754–792: StopMode 1–3)
    pytest.param("MC_ImmediateStop", {"StopMode": 4}, 0x544D, id="ImmediateStop-NonStop-544D-ch3L764"),
    pytest.param("MC_ImmediateStop", {"StopMode": 0}, 0x544D, id="ImmediateStop-DecelerationStop-544D-A-1#45"),
    # MC_SetPosition (ch3 L795–839)
    pytest.param("MC_SetPosition", {"ReferenceType": 1}, 0x5430, id="SetPosition-Feedback-on-servo-5430-ch3L822"),
    pytest.param("MC_SetPosition", {"ReferenceType": 2}, 0x5430, id="SetPosition-LatestCommand-5430-ch3L806"),
    pytest.param("MC_SetPosition", {"Relative": True}, 0x548F, id="SetPosition-Relative-548F-A-1#106"),
    pytest.param("MC_SetPosition", {"ExecutionMode": 1}, 0x5487, id="SetPosition-ExecutionMode-5487-A-1#98"),
    pytest.param("MC_SetPosition", {"Position": OUT40}, 0x5478, id="SetPosition-40bit-5478-A-1#85"),
    # MC_SetOverride (ch3 L841–880: AccFactor/JerkFactor reserved, 0–500)
    pytest.param("MC_SetOverride", {"AccFactor": 500.5}, 0x5470, id="SetOverride-AccFactor-5470-A-1#79"),
    pytest.param("MC_SetOverride", {"AccFactor": -1.0}, 0x5470, id="SetOverride-AccFactorNeg-5470-A-1#79"),
    pytest.param("MC_SetOverride", {"JerkFactor": 501.0}, 0x546F, id="SetOverride-JerkFactor-546F-A-1#78"),
    # MC_ResetFollowingError (ch3 L882–923: BufferMode only _mcAborting)
    pytest.param("MC_ResetFollowingError", {"BufferMode": 1}, 0x542B, id="ResetFollowingError-BufferMode-542B-ch3L892"),
    # MC_ZoneSwitch (ch3 L1504–1540)
    pytest.param("MC_ZoneSwitch", {"ReferenceType": 2}, 0x5430, id="ZoneSwitch-LatestCommand-5430-ch3L1516"),
    pytest.param("MC_ZoneSwitch", {"FirstPosition": -OUT40}, 0x5469, id="ZoneSwitch-First-5469-A-1#72"),
    pytest.param("MC_ZoneSwitch", {"LastPosition": OUT40}, 0x546A, id="ZoneSwitch-Last-546A-A-1#73"),
    # MC_TouchProbe (ch3 L1542–1602: StopMode 1/4, ReferenceType reserved _mcFeedback, window as MC_MoveFeed)
    pytest.param("MC_TouchProbe", {"StopMode": 2}, 0x544D, id="TouchProbe-StopMode-544D-ch3L1556"),
    pytest.param("MC_TouchProbe", {"ReferenceType": 0}, 0x5430, id="TouchProbe-ReferenceType-5430-ch3L1555"),
    pytest.param("MC_TouchProbe", {"TriggerInput": {**EXT1, "Mode": 5}}, 0x5450, id="TouchProbe-Mode-5450-A-1#48"),
    pytest.param("MC_TouchProbe", {"TriggerInput": {**EXT1, "LatchID": 7}}, 0x544E,
                 id="TouchProbe-LatchID-544E-A-1#46"),
    pytest.param("MC_TouchProbe", {"TriggerInput": {**EXT1, "InputDrive": 9}}, 0x5451,
                 id="TouchProbe-InputDrive-5451-A-1#49"),
    pytest.param("MC_TouchProbe", {**WINDOW, "FirstPosition": OUT40}, 0x5469, id="TouchProbe-First-5469-ch3L1583"),
    pytest.param("MC_TouchProbe", {**WINDOW, "LastPosition": -OUT40}, 0x546A, id="TouchProbe-Last-546A-ch3L1583"),
    pytest.param("MC_TouchProbe", {**WINDOW, "FirstPosition": 40.0}, 0x546B, id="TouchProbe-First>Last-546B-ch3L1583"),
    # MC_AbortTrigger (ch3 L1604–1639: TriggerInput selects the latch)
    pytest.param("MC_AbortTrigger", {"TriggerInput": {**EXT1, "Mode": 5}}, 0x5450, id="AbortTrigger-Mode-5450-A-1#48"),
    pytest.param("MC_AbortTrigger", {"TriggerInput": {**EXT1, "LatchID": 7}}, 0x544E,
                 id="AbortTrigger-LatchID-544E-A-1#46"),
    pytest.param("MC_AbortTrigger", {"TriggerInput": {**EXT1, "InputDrive": 9}}, 0x5451,
                 id="AbortTrigger-InputDrive-5451-A-1#49"),
]


@pytest.mark.parametrize(("name", "inputs", "code"), INPUT_CASES)
def test_input_out_of_range(name: str, inputs: dict[str, Any], code: int) -> None:
    c = _homed()
    fb = c.fb(name, Axis=AX, **{**INPUT_BASE[name], **inputs})
    c.step(1)
    assert_axis_fault(c, fb, code)
    assert not fb.out["Busy"]


@pytest.mark.parametrize("name", list(INPUT_BASE))
def test_input_base_is_accepted(name: str) -> None:
    """The valid inputs the cases above start from are accepted (so each case fails only by the input it changes)."""
    c = _homed()
    fb = c.fb(name, Axis=AX, **INPUT_BASE[name])
    c.step(1)
    assert not fb.out["Error"], _outputs(fb)


# Rotary Mode (ring counter 0–360): absolute targets and positions outside the ring.
ROTARY_CASES: list[Any] = [
    pytest.param("MC_Move", {"Position": 400.0}, 0x5478, id="Move-outside-ring-5478-ch3L416"),
    pytest.param("MC_MoveFeed", {"Position": -10.0}, 0x5478, id="MoveFeed-outside-ring-5478-A-1#85"),
    pytest.param("MC_SetPosition", {"Position": 360.5}, 0x5478, id="SetPosition-outside-ring-5478-ch3L823"),
    pytest.param("MC_ZoneSwitch", {"FirstPosition": -1.0}, 0x5469, id="ZoneSwitch-First-outside-ring-5469-ch3L1533"),
    pytest.param("MC_ZoneSwitch", {"FirstPosition": 10.0, "LastPosition": 361.0}, 0x546A,
                 id="ZoneSwitch-Last-outside-ring-546A-ch3L1533"),
    pytest.param("MC_TouchProbe", {**WINDOW, "FirstPosition": 400.0}, 0x5469,
                 id="TouchProbe-First-outside-ring-5469-ch3L1583"),
    pytest.param("MC_MoveFeed", {**WINDOW, "LastPosition": 400.0}, 0x546A,
                 id="MoveFeed-Last-outside-ring-546A-ch3L687"),
]


@pytest.mark.parametrize(("name", "inputs", "code"), ROTARY_CASES)
def test_rotary_range(name: str, inputs: dict[str, Any], code: int) -> None:
    c = _rotary()
    fb = c.fb(name, Axis=AX, **{**INPUT_BASE[name], **inputs})
    c.step(1)
    assert_axis_fault(c, fb, code)


def test_rotary_move_feed_no_direction_accepts_a_target_beyond_the_ring() -> None:
    """Counter-case of MoveFeed-outside-ring: with _mcNoDirection the absolute target may lie beyond the ring
    (MC_MoveAbsolute rules, ch3 L474, which MC_MoveFeed's absolute mode follows)."""
    c = _rotary()
    mf = c.fb("MC_MoveFeed", Axis=AX, **{**INPUT_BASE["MC_MoveFeed"], "Position": 400.0,
                                           "Direction": "_mcNoDirection"})
    c.step(2)
    assert mf.Busy and not mf.Error


# ---------------------------------------------------------------------------------------------------- re-execution
# A new Execute↑ on the same busy instance with an input changed that may not change (A-2.3, omron-mc-basics.md
# L1267–1294; A-1 #50–61, detection "re-exec", effect AX-D).
REEXEC_CASES: list[Any] = [
    pytest.param("MC_MoveAbsolute", {"BufferMode": "_mcBuffered"}, 0x5454, id="MoveAbsolute-BufferMode-5454-A-1#51"),
    pytest.param("MC_MoveAbsolute", {"Direction": "_mcNegativeDirection"}, 0x5455,
                 id="MoveAbsolute-Direction-5455-A-1#52"),
    pytest.param("MC_MoveAbsolute", {"Axis": "MC_Axis001"}, 0x5453, id="MoveAbsolute-Axis-5453-A-1#50"),
    pytest.param("MC_Move", {"MoveMode": "_mcRelative"}, 0x545E, id="Move-MoveMode-545E-A-1#61"),
    pytest.param("MC_Move", {"Jerk": 100.0}, 0x5458, id="Move-Jerk-5458-A-1#55"),
    pytest.param("MC_MoveRelative", {"Jerk": 100.0}, 0x5458, id="MoveRelative-Jerk-5458-A-1#55"),
    pytest.param("MC_MoveRelative", {"BufferMode": "_mcBlendingLow"}, 0x5454, id="MoveRelative-BufferMode-5454-A-1#51"),
    pytest.param("MC_MoveRelative", {"Velocity": 0.0}, 0x5422, id="MoveRelative-Velocity0-at-reexec-5422-A-1#4"),
    pytest.param("MC_MoveVelocity", {"Direction": "_mcNegativeDirection"}, 0x5455,
                 id="MoveVelocity-Direction-5455-A-1#52"),
    pytest.param("MC_MoveVelocity", {"Continuous": True}, 0x545D, id="MoveVelocity-Continuous-545D-A-1#60"),
    pytest.param("MC_MoveVelocity", {"Jerk": 100.0}, 0x5458, id="MoveVelocity-Jerk-5458-A-1#55"),
    pytest.param("MC_MoveVelocity", {"BufferMode": "_mcBuffered"}, 0x5454, id="MoveVelocity-BufferMode-5454-A-1#51"),
    pytest.param("MC_MoveVelocity", {"Acceleration": -1.0}, 0x5423, id="MoveVelocity-Acc-at-reexec-5423-A-1#5"),
]
REEXEC_BASE: dict[str, dict[str, Any]] = {
    "MC_MoveAbsolute": {"Position": 100.0, **MOVE},
    "MC_Move": {"Position": 100.0, **MOVE},
    "MC_MoveRelative": {"Distance": 100.0, **MOVE},
    "MC_MoveVelocity": MOVE,
}


@pytest.mark.parametrize(("name", "change", "code"), REEXEC_CASES)
def test_reexecution_with_a_forbidden_change(name: str, change: dict[str, Any], code: int) -> None:
    c = _homed()
    fb = c.fb(name, Axis=AX, Execute=True, **REEXEC_BASE[name])
    c.step(5)
    assert fb.Busy and fb.Active
    fb.Execute = False
    c.step(1)
    c.set_inputs(fb.id, change)
    fb.Execute = True
    c.step(1)
    assert_axis_fault(c, fb, code)  # on the axis the instruction was started on
    assert not fb.out["Busy"] and not fb.out["Active"]


def test_stop_reexecution_with_negative_deceleration_is_5424() -> None:
    """MC_Stop may be re-executed to change Deceleration (ch3 L737); a negative value is 5424 (A-1 #6)."""
    c = _homed()
    c.fb("MC_MoveVelocity", Axis=AX, Execute=True, Velocity=100.0, Acceleration=1000.0)
    c.step(200)
    st = c.fb("MC_Stop", Axis=AX, Execute=True, Deceleration=10.0)  # 10 s to stop
    c.step(5)
    assert st.Busy and c.mc.axes[0].state == S.Stopping
    st.Execute = False
    c.step(1)
    st.Deceleration = -1.0
    st.Execute = True
    c.step(1)
    assert_axis_fault(c, st, 0x5424)


def test_jog_restart_with_negative_velocity_is_5422() -> None:
    """MC_MoveJog latches Velocity at each enable edge (ch3 L148); re-enabling while it decelerates with a negative
    Velocity is 5422 (A-1 #4), the axis error-stops."""
    c = _homed()
    jog = c.fb("MC_MoveJog", Axis=AX, PositiveEnable=True, Velocity=50.0, Acceleration=100.0, Deceleration=10.0)
    c.step(100)
    jog.PositiveEnable = False
    c.step(2)
    assert jog.Busy, "decelerating"
    jog.Velocity = -1.0
    jog.PositiveEnable = True
    c.step(1)
    assert_axis_fault(c, jog, 0x5422)


# ---------------------------------------------------------------------------------------------------- 543B
def _long_homing() -> Controller:
    """Homing that keeps searching: dog and limits far away (the search at 10 mm/s lasts the whole test)."""
    sensors = {"PositiveLimit": 900.0, "NegativeLimit": -900.0, "HomeProximityStart": 500.0,
               "HomeProximityEnd": 510.0}
    c = Controller(axis_project(sensors=sensors))
    power_on(c)
    return c


HOMING_REF = {"HomingMode": "_mcHomeSwTurnHomeSwOff", "HomeInput": "_mcZPhase", "StartDir": "_mcPositiveDirection",
              "HomeDir": "_mcPositiveDirection", "PosiLmtMode": "_mcRevImmediateStop",
              "NegaLmtMode": "_mcRevImmediateStop", "Vel": 10.0, "ApproachVel": 1.0, "Acc": 1000.0, "Dec": 1000.0,
              "Jerk": 0.0, "Mask": 0.0, "Offset": 0.0, "PushTime": 0, "Compensation": 0.0, "CompensationVel": 5.0}


def test_home_with_parameter_is_not_reexecutable() -> None:
    """ch3 L374: re-execution of MC_HomeWithParameter → 543B (A-1 #28, effect AXG-D: the homing axis stops)."""
    c = _long_homing()
    h = c.fb("MC_HomeWithParameter", Axis=AX, Execute=True, HomingParameter=HOMING_REF)
    c.step(20)
    assert h.Busy and c.mc.axes[0].state == S.Homing
    _retrigger(c, h)
    assert_axis_fault(c, h, 0x543B)


def test_home_reexecution_error_stops_the_axis() -> None:
    """ch3 L320: MC_Home re-execution → 543B; the axis error-stops (test_homing checks only the ErrorID)."""
    c = _long_homing()
    h = c.fb("MC_Home", Axis=AX, Execute=True)
    c.step(20)
    _retrigger(c, h)
    assert_axis_fault(c, h, 0x543B)


def test_move_feed_is_not_reexecutable() -> None:
    """ch3 L688: MC_MoveFeed re-execution → 543B; the axis decelerates to an error stop."""
    c = _homed()
    mf = c.fb("MC_MoveFeed", Axis=AX, Execute=True, TriggerInput=EXT1, MoveMode="_mcVelocity", **MOVE,
              FeedDistance=5.0, FeedVelocity=10.0)
    c.step(20)
    assert mf.Busy and mf.Active
    _retrigger(c, mf)
    assert_axis_fault(c, mf, 0x543B)


def test_touch_probe_is_not_reexecutable() -> None:
    """ch3 L1590: MC_TouchProbe re-execution while it waits for the trigger → 543B; the axis error-stops."""
    c = _homed()
    tp = c.fb("MC_TouchProbe", Axis=AX, Execute=True, TriggerInput=EXT1)  # no sensor: waits for ever
    c.step(5)
    assert tp.Busy
    _retrigger(c, tp)
    assert_axis_fault(c, tp, 0x543B)


def test_reset_following_error_is_not_reexecutable() -> None:
    """ch3 L915: MC_ResetFollowingError re-execution → 543B. Pushing against a mechanical stop builds a following
    error of ~50 mm; its correction at Maximum Velocity (500 mm/s) lasts ~100 periods."""
    c = _homed()
    _block_mechanism(c, 5.0)
    c.fb("MC_MoveVelocity", Axis=AX, Execute=True, Velocity=50.0, Acceleration=1000.0, Deceleration=1000.0)
    c.step(1100)
    assert c.mc.cmd_pos[0] - c.mc.act_pos[0] > 40.0
    rfe = c.fb("MC_ResetFollowingError", Axis=AX, Execute=True)
    c.step(2)
    assert rfe.Busy and c.mc.axes[0].state == S.Stopping
    _retrigger(c, rfe)
    assert_axis_fault(c, rfe, 0x543B)


# ---------------------------------------------------------------------------------------------------- latches
def _move_feed_on_latch1(c: Controller) -> FunctionBlock:
    mf = c.fb("MC_MoveFeed", Axis=AX, Execute=True, TriggerInput=EXT1, MoveMode="_mcVelocity", **MOVE,
              FeedDistance=5.0, FeedVelocity=10.0)
    c.step(5)
    assert mf.Busy
    return mf


def test_touch_probe_on_the_latch_of_move_feed_is_546e() -> None:
    """A-1 #77 (L1087): the same LatchID used by MC_TouchProbe and MC_MoveFeed → 546E (effect AX-D): the axis
    error-stops and MC_MoveFeed is aborted."""
    c = _homed()
    mf = _move_feed_on_latch1(c)
    tp = c.fb("MC_TouchProbe", Axis=AX, Execute=True, TriggerInput=EXT1)
    c.step(1)
    assert_axis_fault(c, tp, 0x546E)
    assert mf.CommandAborted


def test_move_feed_on_the_latch_of_touch_probe_is_546e() -> None:
    """A-1 #77: MC_MoveFeed started on the LatchID a pending MC_TouchProbe uses → 546E."""
    c = _homed()
    tp = c.fb("MC_TouchProbe", Axis=AX, Execute=True, TriggerInput=EXT1)
    c.step(2)
    mf = c.fb("MC_MoveFeed", Axis=AX, Execute=True, TriggerInput=EXT1, MoveMode="_mcVelocity", **MOVE,
              FeedDistance=5.0, FeedVelocity=10.0)
    c.step(1)
    assert_axis_fault(c, mf, 0x546E)
    assert tp.Busy, "the earlier MC_TouchProbe keeps its latch"


def test_abort_trigger_on_the_latch_of_move_feed_is_546e() -> None:
    """A-3.4 footnote *9 (omron-mc-basics.md L1545) and A-1 #77: MC_AbortTrigger on the LatchID of an executing
    MC_MoveFeed → 546E, state H. On the other latch it ends normally (Done, ch3 L1631)."""
    c = _homed()
    mf = _move_feed_on_latch1(c)
    other = c.fb("MC_AbortTrigger", Axis=AX, Execute=True, TriggerInput=EXT2)
    c.step(2)
    assert other.Done and not other.Error and mf.Busy
    ab = c.fb("MC_AbortTrigger", Axis=AX, Execute=True, TriggerInput=EXT1)
    c.step(1)
    assert_axis_fault(c, ab, 0x546E)


@pytest.mark.parametrize("name", ["MC_TouchProbe", "MC_AbortTrigger"])
def test_latch_instructions_during_homing_are_546e(name: str) -> None:
    """A-1 #77: during MC_Home both latches count as in use → 546E for MC_TouchProbe; ch3 L1632 and A-1 #77 for
    MC_AbortTrigger ("a latch used by something other than MC_TouchProbe"). Decision D22."""
    c = _long_homing()
    h = c.fb("MC_Home", Axis=AX, Execute=True)
    c.step(20)
    fb = c.fb(name, Axis=AX, Execute=True, TriggerInput=EXT1)
    c.step(1)
    assert_axis_fault(c, fb, 0x546E)
    assert h.CommandAborted


def test_touch_probe_immediate_stop_on_an_encoder_axis_is_5492() -> None:
    """ch3 L1586/L1599, A-1 #109: StopMode _mcImmediateStop on an encoder axis → 5492; the encoder axis goes to
    ErrorStop (A-3.7). With _mcNonStop the same instruction is accepted."""
    c = _with_encoder_axis()
    ok = c.fb("MC_TouchProbe", Axis="MC_Axis001", Execute=True, TriggerInput=EXT1, StopMode="_mcNonStop")
    c.step(1)
    assert ok.Busy and not ok.Error
    ok.Execute = False
    c.delete_fb(ok.id)
    tp = c.fb("MC_TouchProbe", Axis="MC_Axis001", Execute=True, TriggerInput=EXT2, StopMode="_mcImmediateStop")
    c.step(1)
    assert_axis_fault(c, tp, 0x5492, axis=1)


# ---------------------------------------------------------------------------------------------------- 543C
def test_set_position_during_move_zero_position_is_543c() -> None:
    """ch3 L614 and L827, A-3.4 footnote *4: MC_SetPosition while MC_MoveZeroPosition runs → MC_SetPosition Error
    (543C, decision D6), MC_MoveZeroPosition decelerates to a stop with CommandAborted, home stays defined."""
    c = _homed()
    mv = c.fb("MC_MoveAbsolute", Axis=AX, Execute=True, Position=50.0, Velocity=100.0, Acceleration=1000.0,
              Deceleration=1000.0)
    step_until(c, mv, "Done")
    z = c.fb("MC_MoveZeroPosition", Axis=AX, Execute=True, Velocity=20.0, Acceleration=100.0, Deceleration=100.0)
    c.step(100)
    sp = c.fb("MC_SetPosition", Axis=AX, Execute=True, Position=7.0)
    c.step(1)
    assert_axis_fault(c, sp, 0x543C)
    assert z.CommandAborted and not z.Error
    assert c.mc.axes[0].homed, "the position was not changed, so home stays defined"
    assert c.mc.cmd_vel[0] < 0, "still moving towards 0 in the period of the error: a deceleration stop (D3)"


def test_blending_onto_move_zero_position_is_543c() -> None:
    """Others onto MC_MoveZeroPosition: Aborting or Buffered only, no blending (ch3 L613; summary table L2071):
    the blending instruction gets 543C (A-1 #29, decision D18) and the axis error-stops."""
    c = _homed()
    mv = c.fb("MC_MoveAbsolute", Axis=AX, Execute=True, Position=50.0, Velocity=100.0, Acceleration=1000.0,
              Deceleration=1000.0)
    step_until(c, mv, "Done")
    z = c.fb("MC_MoveZeroPosition", Axis=AX, Execute=True, **MOVE)
    c.step(5)
    b = c.fb("MC_MoveAbsolute", Axis=AX, Execute=True, Position=-10.0, **MOVE, BufferMode="_mcBlendingNext")
    c.step(1)
    assert_axis_fault(c, b, 0x543C)
    assert z.CommandAborted


# ---------------------------------------------------------------------------------------------------- software limits
# 6440/6441 "Target Position Positive/Negative Software Limit Exceeded" (A-1 #142/#143, L1152–1153): the target is
# beyond a software limit, or the axis starts beyond it and does not move back (Linear Mode, home defined).
SW_TARGET_CASES: list[Any] = [
    pytest.param("MC_MoveRelative", {"Distance": 120.0}, 0x6440, id="MoveRelative-6440-A-1#142"),
    pytest.param("MC_Move", {"MoveMode": "_mcRelative", "Position": -60.0}, 0x6441, id="Move-rel-6441-A-1#143"),
    pytest.param("MC_Move", {"Position": 101.0}, 0x6440, id="Move-abs-6440-A-1#142"),
    pytest.param("MC_MoveFeed", {"Position": 150.0}, 0x6440, id="MoveFeed-abs-6440-A-1#142"),
    pytest.param("MC_MoveFeed", {"MoveMode": "_mcRelative", "Position": -51.0}, 0x6441, id="MoveFeed-rel-6441-A-1#143"),
]


@pytest.mark.parametrize(("name", "inputs", "code"), SW_TARGET_CASES)
def test_target_beyond_software_limit(name: str, inputs: dict[str, Any], code: int) -> None:
    c = _homed(Limit=SW)
    fb = c.fb(name, Axis=AX, **{**INPUT_BASE[name], **inputs})
    c.step(1)
    assert_axis_fault(c, fb, code)


def _beyond_positive_limit() -> Controller:
    """Stand at 50 mm, then lower the positive software limit to 40 mm with MC_Write (§5.3): the axis is beyond it."""
    c = _homed(Limit=SW)
    mv = c.fb("MC_MoveAbsolute", Axis=AX, Execute=True, Position=50.0, Velocity=100.0, Acceleration=1000.0,
              Deceleration=1000.0)
    step_until(c, mv, "Done")
    wr = c.fb("MC_Write", Target=AX, Execute=True, ParameterNumber="_mcPosiSwLmt", SettingValue=40.0)
    step_until(c, wr, "Done")
    return c


@pytest.mark.parametrize(("name", "inputs"), [
    ("MC_MoveVelocity", {"Execute": True, **MOVE}),
    ("MC_MoveJog", {"PositiveEnable": True, **MOVE}),
    ("MC_MoveFeed", {**INPUT_BASE["MC_MoveFeed"], "MoveMode": "_mcVelocity"}),
], ids=["MoveVelocity-6440-A-1#142", "MoveJog-6440-A-1#142", "MoveFeed-velocity-6440-A-1#142"])
def test_start_beyond_software_limit_moving_further_is_6440(name: str, inputs: dict[str, Any]) -> None:
    c = _beyond_positive_limit()
    fb = c.fb(name, Axis=AX, **inputs)
    c.step(1)
    assert_axis_fault(c, fb, 0x6440)


def test_start_beyond_software_limit_moving_back_is_accepted() -> None:
    """Counter-case of A-1 #142: beyond the positive limit, motion back towards the range starts normally."""
    c = _beyond_positive_limit()
    mv = c.fb("MC_MoveVelocity", Axis=AX, Execute=True, **MOVE, Direction="_mcNegativeDirection")
    c.step(2)
    assert mv.Busy and mv.Active and not mv.Error


# ---------------------------------------------------------------------------------------------------- limit inputs
# 6443/6444 "Positive/Negative Limit Input" (A-1 #145/#146, L1155–1156): an instruction moving towards an active limit
# input is refused at start (effect AXG: the axis cannot operate).
NEG_ON = {"NegativeLimit": 5.0}  # negative limit input ON at positions ≤ 5 mm: ON where the axis stands (0)
POS_ON = {"PositiveLimit": -5.0}  # positive limit input ON at positions ≥ −5 mm


@pytest.mark.parametrize(("sensors", "name", "inputs", "code"), [
    pytest.param(NEG_ON, "MC_MoveAbsolute", {"Execute": True, "Position": -10.0, **MOVE}, 0x6444,
                 id="MoveAbsolute-6444-A-1#146"),
    pytest.param(NEG_ON, "MC_MoveVelocity", {"Execute": True, **MOVE, "Direction": "_mcNegativeDirection"}, 0x6444,
                 id="MoveVelocity-6444-A-1#146"),
    pytest.param(NEG_ON, "MC_MoveJog", {"NegativeEnable": True, **MOVE}, 0x6444, id="MoveJog-6444-A-1#146"),
    pytest.param(NEG_ON, "MC_MoveRelative", {"Execute": True, "Distance": -1.0, **MOVE}, 0x6444,
                 id="MoveRelative-6444-A-1#146"),
    pytest.param(POS_ON, "MC_MoveVelocity", {"Execute": True, **MOVE}, 0x6443, id="MoveVelocity-6443-A-1#145"),
    pytest.param(POS_ON, "MC_MoveFeed", {**INPUT_BASE["MC_MoveFeed"]}, 0x6443, id="MoveFeed-6443-A-1#145"),
    pytest.param(POS_ON, "MC_MoveJog", {"PositiveEnable": True, **MOVE}, 0x6443, id="MoveJog-6443-A-1#145"),
])
def test_limit_input_on_at_start(sensors: dict[str, float], name: str, inputs: dict[str, Any], code: int) -> None:
    c = Controller(axis_project(sensors=sensors))
    power_on(c)
    fb = c.fb(name, Axis=AX, **inputs)
    c.step(1)
    assert_axis_fault(c, fb, code)


def test_motion_away_from_an_active_limit_input_is_accepted() -> None:
    """Counter-case of A-1 #146: with the negative limit input ON, a positive motion starts normally."""
    c = Controller(axis_project(sensors=NEG_ON))
    power_on(c)
    mv = c.fb("MC_MoveRelative", Axis=AX, Execute=True, Distance=10.0, **MOVE)
    c.step(2)
    assert mv.Busy and mv.Active and not mv.Error


# ---------------------------------------------------------------------------------------------------- run-time faults
# Axis faults during motion. The instruction manual refers them to the Troubleshooting Manual (not in the seeds,
# omron-mc-basics.md L990); the codes 6450–6457 are MC Studio assignments (errors_table.py, decision D19). The
# running instruction is aborted by the error (CommandAborted, ch3 conventions L63), the axis error-stops.
def _run_fault(c: Controller, fb: FunctionBlock, code: int, limit: int = 5000) -> None:
    c.step(limit, Until(fb.id, "CommandAborted", True))
    assert fb.out["CommandAborted"] and not fb.out["Error"], _outputs(fb)
    ax = c.mc.axes[0]
    assert ax.state == S.ErrorStop and ax.error_code == code, f"{ax.state.name} {ax.error_code:04X}"
    ev = _events(c, code)
    assert ev and ev[-1].level == "minor fault" and ev[-1].source.startswith(AX)


@pytest.mark.parametrize(("mode", "direction", "code"), [
    pytest.param("_mcCmdDecelerationStop", "_mcNegativeDirection", 0x6451, id="cmd-decel-negative-6451"),
    pytest.param("_mcCmdImmediateStop", "_mcPositiveDirection", 0x6450, id="cmd-immediate-positive-6450"),
    pytest.param("_mcActDecelerationStop", "_mcNegativeDirection", 0x6451, id="act-decel-negative-6451"),
    pytest.param("_mcActImmediateStop", "_mcPositiveDirection", 0x6450, id="act-immediate-positive-6450"),
    pytest.param("_mcActImmediateStop", "_mcNegativeDirection", 0x6451, id="act-immediate-negative-6451"),
])
def test_software_limit_reached_during_motion(mode: str, direction: str, code: int) -> None:
    """SwLimitMode 1–4 (§5.5.5, omron-group-and-cam.md L1511): a velocity motion reaching a software limit."""
    c = _homed(Limit={**SW, "SwLimitMode": mode})
    mv = c.fb("MC_MoveVelocity", Axis=AX, Execute=True, Velocity=50.0, Acceleration=1000.0, Deceleration=1000.0,
              Direction=direction)
    _run_fault(c, mv, code)
    c.step(500)
    limit = SW["PosiSwLimit"] if code == 0x6450 else SW["NegaSwLimit"]
    # stopped at the limit; an actual-position deceleration stop passes it by the braking distance 50²/2000 mm plus
    # one period of travel (the actual position lags the command by one period)
    assert c.mc.cmd_vel[0] == 0.0 and abs(c.mc.cmd_pos[0] - limit) <= 1.25 + 0.05 + 1e-9, c.mc.cmd_pos[0]


def test_negative_limit_input_during_motion_is_6454() -> None:
    """The negative limit input turns ON while moving negative: 6454, stop by LimitInputStopMode (§5.5.4)."""
    c = Controller(axis_project(sensors={"NegativeLimit": -5.0}))
    power_on(c)
    mv = c.fb("MC_MoveVelocity", Axis=AX, Execute=True, Velocity=50.0, Acceleration=1000.0, Deceleration=1000.0,
              Direction="_mcNegativeDirection")
    _run_fault(c, mv, 0x6454)
    assert -5.5 < c.mc.act_pos[0] <= -5.0


def test_in_position_check_time_exceeded_is_6455() -> None:
    """In-position Check Time > 0 (§5.5.3, omron-group-and-cam.md L1487; decision D9): the command reached the
    target but a mechanical stop keeps the actual position 0.5 mm short; after the check time (5 ms) the axis errors
    with 6455 (D19)."""
    c = _homed(Operation={"InPosCheckTime": 5, "InPosRange": 0.01})
    _block_mechanism(c, 9.5)
    mv = c.fb("MC_MoveAbsolute", Axis=AX, Execute=True, Position=10.0, Velocity=100.0, Acceleration=1000.0,
              Deceleration=1000.0)
    ax = c.mc.axes[0]
    n = 0
    while not ax.in_pos_waiting and n < 400:  # the 0.2 s profile ends: waiting for in-position (InPosWaiting)
        c.step(1)
        n += 1
    assert mv.Busy and ax.in_pos_waiting and c.mc.cmd_pos[0] == 10.0
    waiting_from = c.cycle
    _run_fault(c, mv, 0x6455, limit=10)
    assert c.cycle - waiting_from >= 4, "not before the check time has run"


def test_homing_limit_in_detection_direction_at_approach_velocity_is_6456() -> None:
    """ch3 L227: even with "reverse" selected, the limit in the home input detection direction turning ON at the
    approach velocity error-stops the axis (6456, D19). Mode 0 with an external home input that never comes."""
    sensors = {"PositiveLimit": 40.0, "NegativeLimit": -60.0, "HomeProximityStart": 20.0, "HomeProximityEnd": 30.0}
    homing = {"Mode": "_mcHomeSwTurnHomeSwOff", "HomeInputSignal": "_mcExternalSignal", "Vel": 100.0,
              "ApproachVel": 10.0, "Acc": 2000.0, "Dec": 2000.0, "PosiLimitInputMode": "_mcRevImmediateStop",
              "NegaLimitInputMode": "_mcRevImmediateStop"}
    c = Controller(axis_project(sensors=sensors, Homing=homing))
    power_on(c)
    h = c.fb("MC_Home", Axis=AX, Execute=True)
    c.step(10_000, Until(h.id, "Busy", False))
    assert_axis_fault(c, h, 0x6456)  # the homing instruction's own processing failed: it shows the error
    assert not c.mc.axes[0].homed and 39.0 < c.mc.act_pos[0] < 41.0


# ---------------------------------------------------------------------------------------------------- 5485
@pytest.mark.parametrize("stop_mode", [1, 2, 3])
def test_immediate_stop_raises_5485_on_the_axis(stop_mode: int) -> None:
    """ch3 L779/L790: MC_ImmediateStop puts the axis in ErrorStop with the axis error 5485 (an intentional error);
    the instruction itself completes (Done, no Error) and MC_Reset is needed afterwards."""
    c = _homed()
    mv = c.fb("MC_MoveVelocity", Axis=AX, Execute=True, **MOVE)
    c.step(20)
    st = c.fb("MC_ImmediateStop", Axis=AX, Execute=True, StopMode=stop_mode)
    step_until(c, st, "Done", limit=3)
    assert not st.Error and mv.CommandAborted
    ax = c.mc.axes[0]
    assert ax.state == S.ErrorStop and ax.error_code == 0x5485
    ev = _events(c, 0x5485)
    assert ev and ev[-1].level == "minor fault" and ev[-1].source.startswith(AX)


# ---------------------------------------------------------------------------------------------------- MC_Power
def test_servo_on_without_main_circuit_power_is_7422() -> None:
    """A-1 #147 (L1157), decision D10: MC_Power Enable while the drive's main circuit is OFF → 7422, effect SVOFF:
    the servo stays OFF, the axis error-stops."""
    c = Controller(axis_project())
    c.network.drives.main_power[0] = False
    c.step(2)
    pw = c.fb("MC_Power", Axis=AX, Enable=True)
    c.step(20)
    assert_axis_fault(c, pw, 0x7422)
    assert not pw.Status and not c.mc.axes[0].servo_on


# ---------------------------------------------------------------------------------------------------- 5700
# MC_HomeWithParameter: a member of HomingParameter out of range → 5700 with the detail code of A-2.4 (omron-mc-
# basics.md L1298–1317) in the attached information; only members the selected mode uses are checked (ch3 L371).
# test_homing.py covers details 1, 7, 9, 106 and 108.
HOMING_DETAIL_CASES: list[Any] = [
    pytest.param({"HomeInput": 5}, 2, False, id="HomeInput-2"),
    pytest.param({"StartDir": "_mcShortestWay"}, 3, False, id="StartDir-3"),
    pytest.param({"HomeDir": "_mcCurrentDirection"}, 4, False, id="HomeDir-4"),
    pytest.param({"PosiLmtMode": 3}, 5, False, id="PosiLmtMode-5"),
    pytest.param({"NegaLmtMode": -1}, 6, False, id="NegaLmtMode-6"),
    pytest.param({"ApproachVel": 0.0}, 8, False, id="ApproachVel-8"),
    pytest.param({"Dec": -1.0}, 10, False, id="Dec-10"),
    pytest.param({"Jerk": -1.0}, 11, False, id="Jerk-11"),
    pytest.param({"HomingMode": "_mcHomeSwTurnHomeMask", "Mask": -1.0}, 12, False, id="Mask-12"),
    pytest.param({"Offset": "zero"}, 13, False, id="Offset-not-a-number-13"),
    pytest.param({"HomingMode": "_mcHomeSwTurnHoldingTime", "PushTime": 10001}, 14, False, id="PushTime-14"),
    pytest.param({"Compensation": True}, 15, False, id="Compensation-not-a-number-15"),
    pytest.param({"CompensationVel": 0.0}, 16, False, id="CompensationVel-16"),
    pytest.param({"HomingMode": "_mcHomeSwTurnHomeMask", "Mask": OUT40D}, 100, False, id="Mask-40bit-100"),
    pytest.param({"HomingMode": "_mcHomeSwTurnHomeMask", "Mask": 361.0}, 101, True, id="Mask-ring-101"),
    pytest.param({"Compensation": -OUT40D}, 102, False, id="Compensation-40bit-102"),
    pytest.param({"Compensation": 361.0}, 103, True, id="Compensation-ring-103"),
    pytest.param({"Offset": OUT40}, 104, False, id="Offset-40bit-104"),
    pytest.param({"Offset": 360.0}, 105, True, id="Offset-ring-105"),
    pytest.param({"ApproachVel": 600.0}, 107, False, id="ApproachVel-MaxVel-107"),
    pytest.param({"CompensationVel": 150.0}, 109, False, id="CompensationVel-Vel-109"),
    pytest.param({"Acc": 20000.0}, 110, False, id="Acc-MaxAcc-110"),
    pytest.param({"Dec": 20000.0}, 111, False, id="Dec-MaxDec-111"),
]


@pytest.mark.parametrize(("change", "detail", "rotary"), HOMING_DETAIL_CASES)
def test_homing_parameter_out_of_range_is_5700(change: dict[str, Any], detail: int, rotary: bool) -> None:
    """A-1 #122 (L1132): 5700, source Axis — an axis minor fault (ErrorStop, A-3.2 H; decision D23) — with the A-2.4
    detail code in the event; MC_Reset clears the axis and the instance's Error."""
    c = _rotary() if rotary else _homed()
    ref = {**HOMING_REF, "Vel": 100.0, "ApproachVel": 10.0, **change}
    h = c.fb("MC_HomeWithParameter", Axis=AX, Execute=True, HomingParameter=ref)
    c.step(1)
    assert_axis_fault(c, h, 0x5700)
    assert f"attached information {detail}:" in _events(c, 0x5700)[-1].detail
    rs = c.fb("MC_Reset", Axis=AX, Execute=True)
    step_until(c, rs, "Done")
    c.step(1)
    assert not h.Error and c.mc.axes[0].state == S.Standstill


def test_homing_parameter_unused_by_the_mode_is_not_checked() -> None:
    """ch3 L371: members the selected mode does not use are excluded from the checks (Mask outside mode 9)."""
    c = _homed()
    h = c.fb("MC_HomeWithParameter", Axis=AX, Execute=True,
             HomingParameter={**HOMING_REF, "HomingMode": "_mcHomePreset", "Mask": -1.0, "Vel": -1.0})
    step_until(c, h, "Done", limit=10)
    assert not h.Error


# ---------------------------------------------------------------------------------------------------- 573A / 573B
def _unused_axis_params(c: Controller) -> dict[str, Any]:
    return c.mc.by_name[UNUSED].params.model_dump(mode="json")


def _set(params: dict[str, Any], changes: dict[str, Any]) -> dict[str, Any]:
    out = copy.deepcopy(params)
    for path, value in changes.items():
        group, member = path.split(".")
        out[group][member] = value
    return out


# §5.5.9 (omron-group-and-cam.md L1590–1673): range checks (0xxx) …
RANGE_CASES = [
    ("UnitConversion.UnitDisplay", 9, 0x0000), ("UnitConversion.CmdPlsCountPerMotorRotation", 0, 0x0001),
    ("UnitConversion.WorkTravelDistancePerMotorRotation", 0.0, 0x0002),
    ("UnitConversion.WorkTravelDistancePerWorkSideRotation", 0.0, 0x0003),
    ("UnitConversion.WorkSideGearRatio", 0, 0x0004), ("UnitConversion.MotorSideGearRatio", 0, 0x0005),
    ("Operation.MaxVel", 0.0, 0x0100), ("Operation.StartVel", -1.0, 0x0101), ("Operation.MaxJogVel", 0.0, 0x0102),
    ("Operation.MaxAcc", -1.0, 0x0103), ("Operation.MaxDec", -1.0, 0x0104), ("Operation.AccDecOver", 3, 0x0105),
    ("Operation.ReverseMode", 2, 0x0106), ("Operation.VelWarningVal", 101, 0x0107),
    ("Operation.AccWarningVal", 101, 0x0108), ("Operation.DecWarningVal", 101, 0x0109),
    ("Operation.PosiTrqWarningVal", 1001, 0x010A), ("Operation.NegaTrqWarningVal", 1001, 0x010B),
    ("Operation.InPosRange", -1.0, 0x010C), ("Operation.InPosCheckTime", 10001, 0x010D),
    ("Operation.ActVelFilterTimeConstant", 101, 0x010E), ("Operation.ZeroPosRange", -1.0, 0x010F),
    ("OtherOperation.ImmediateStopInputStopMode", 0, 0x0200), ("OtherOperation.LimitInputStopMode", 4, 0x0201),
    ("OtherOperation.DriveErrorResetMonitoringTime", 0, 0x0202), ("OtherOperation.MaxPosiTrqLimit", 1000.5, 0x0203),
    ("OtherOperation.MaxNegaTrqLimit", -0.5, 0x0204), ("Limit.SwLimitMode", 5, 0x0300),
    ("Limit.PosiSwLimit", "x", 0x0301), ("Limit.NegaSwLimit", "x", 0x0302),
    ("Limit.FollowingErrorOverVal", -1.0, 0x0303), ("Limit.FollowingErrorWarningVal", -1.0, 0x0304),
    ("PosCount.CountMode", 2, 0x0400), ("PosCount.ModuloMaxPosVal", "x", 0x0401),
    ("PosCount.ModuloMinPosVal", "x", 0x0402), ("Homing.Mode", 2, 0x0500), ("Homing.HomeInputSignal", 2, 0x0501),
    ("Homing.StartDirection", 1, 0x0502), ("Homing.HomeInputDetectionDirection", 3, 0x0503),
    ("Homing.PosiLimitInputMode", 3, 0x0504), ("Homing.NegaLimitInputMode", 3, 0x0505), ("Homing.Vel", 0.0, 0x0506),
    ("Homing.ApproachVel", 0.0, 0x0507), ("Homing.Acc", -1.0, 0x0508), ("Homing.Dec", -1.0, 0x0509),
    ("Homing.Jerk", -1.0, 0x050A), ("Homing.HomeInputMaskDistance", -1.0, 0x050B), ("Homing.HomeOffset", "x", 0x050C),
    ("Homing.HoldingTime", 10001, 0x050D), ("Homing.CompensationVal", "x", 0x050E),
    ("Homing.CompensationVel", 0.0, 0x050F),
]
ROTARY = {"PosCount.CountMode": "_mcCountModeRotary", "PosCount.ModuloMinPosVal": 0.0,
          "PosCount.ModuloMaxPosVal": 360.0}
# … and consistency checks (1xxx), base: 10 mm/rev, 2^20 pulses/rev, MaxVel 500, MaxAcc/MaxDec 10000
CONSISTENCY_CASES: list[tuple[dict[str, Any], int]] = [
    ({"UnitConversion.ReducerUse": True, "UnitConversion.WorkTravelDistancePerWorkSideRotation": 1e-9}, 0x1000),
    ({"UnitConversion.ReducerUse": True, "UnitConversion.WorkTravelDistancePerWorkSideRotation": 10.0,
      "UnitConversion.MotorSideGearRatio": 1_000_000}, 0x1001),
    ({"Operation.MaxVel": 30000.0, "Operation.MaxJogVel": 100.0}, 0x1100),
    ({"Operation.StartVel": 501.0}, 0x1101),
    ({"Operation.MaxJogVel": 501.0}, 0x1102),
    ({"Operation.InPosRange": OUT40D}, 0x1103),
    ({"Operation.ZeroPosRange": OUT40D}, 0x1104),
    ({"Limit.PosiSwLimit": OUT40}, 0x1300),
    ({"Limit.NegaSwLimit": -OUT40}, 0x1301),
    ({"Limit.PosiSwLimit": -10.0, "Limit.NegaSwLimit": 10.0}, 0x1302),
    ({"Limit.FollowingErrorOverVal": OUT40D}, 0x1303),
    ({"Limit.FollowingErrorOverVal": 1.0, "Limit.FollowingErrorWarningVal": 2.0}, 0x1304),
    ({**ROTARY, "PosCount.ModuloMaxPosVal": OUT40}, 0x1400),
    ({**ROTARY, "PosCount.ModuloMinPosVal": -OUT40}, 0x1401),
    ({**ROTARY, "PosCount.ModuloMaxPosVal": -1.0}, 0x1402),
    ({**ROTARY, "PosCount.ModuloMaxPosVal": 1e-6}, 0x1403),
    ({"Homing.Vel": 501.0}, 0x1500),
    ({"Homing.Vel": 50.0, "Homing.ApproachVel": 60.0}, 0x1501),
    ({"Homing.Acc": 10001.0}, 0x1502),
    ({"Homing.Dec": 10001.0}, 0x1503),
    ({"Homing.HomeInputMaskDistance": OUT40D}, 0x1504),
    ({**ROTARY, "Homing.HomeInputMaskDistance": 361.0}, 0x1505),
    ({"Homing.HomeOffset": OUT40}, 0x1506),
    ({**ROTARY, "Homing.HomeOffset": 361.0}, 0x1507),
    ({"Homing.CompensationVal": -OUT40D}, 0x1508),
    ({**ROTARY, "Homing.CompensationVal": -361.0}, 0x1509),
    ({"Homing.CompensationVel": 501.0}, 0x150A),
]
PARAM_CASES: list[Any] = [
    *(pytest.param({path: value}, code, id=f"{path}-{code:04X}") for path, value, code in RANGE_CASES),
    *(pytest.param(changes, code, id=f"consistency-{code:04X}") for changes, code in CONSISTENCY_CASES),
    # range checks are reported before consistency checks; only one code is shown (A-2.4, omron-mc-basics.md L1319)
    pytest.param({"Operation.MaxJogVel": 501.0, "Homing.Vel": 0.0}, 0x0506, id="range-before-consistency-0506"),
]


@pytest.mark.parametrize(("changes", "parameter_code"), PARAM_CASES)
def test_write_axis_parameter_out_of_range_is_573b(changes: dict[str, Any], parameter_code: int) -> None:
    """MC_WriteAxisParameter (§5.5, A-1 #130 L1140): 573B with ErrorParameterCode; source MC common (no axis state
    changes), nothing is written."""
    c = _with_unused_axis()
    before = _unused_axis_params(c)
    states = _states(c)
    wr = c.fb("MC_WriteAxisParameter", Axis=UNUSED, Execute=True, AxisParameter=_set(before, changes))
    c.step(1)
    assert_common_error(c, wr, 0x573B, states)
    assert wr.ErrorParameterCode == parameter_code, f"{wr.ErrorParameterCode:04X}"
    assert f"ErrorParameterCode {parameter_code:04X}" in _events(c, 0x573B)[-1].detail
    assert _unused_axis_params(c) == before, "nothing is written"


def test_write_axis_parameter_base_is_accepted() -> None:
    """The unchanged parameters the cases above start from are written without error (Done)."""
    c = _with_unused_axis()
    wr = c.fb("MC_WriteAxisParameter", Axis=UNUSED, Execute=True, AxisParameter=_unused_axis_params(c))
    step_until(c, wr, "Done", limit=5)
    assert not wr.Error and wr.ErrorParameterCode == 0


def test_write_axis_parameter_on_a_used_axis_is_573a() -> None:
    """§5.5 (omron-group-and-cam.md L1411) / A-1 #129: only an unused axis may be written; a used one → 573A,
    MC common, nothing written."""
    c = _with_unused_axis()
    states = _states(c)
    params = c.mc.axes[0].params.model_dump(mode="json")
    wr = c.fb("MC_WriteAxisParameter", Axis=AX, Execute=True,
              AxisParameter=_set(params, {"Operation.MaxJogVel": 50.0}))
    c.step(1)
    assert_common_error(c, wr, 0x573A, states)
    assert c.mc.axes[0].params.Operation.MaxJogVel == 100.0


# ---------------------------------------------------------------------------------------------------- MC_Write
@pytest.mark.parametrize(("number", "value", "code"), [
    pytest.param(13, 1, 0x544C, id="ParameterNumber-544C-A-1#44"),
    pytest.param(-1, 1, 0x544C, id="ParameterNumber-negative-544C-A-1#44"),
    pytest.param("_mcChkVel", 101, 0x544F, id="ChkVel-0..100-544F"),
    pytest.param("_mcChkAcc", 10.5, 0x544F, id="ChkAcc-UINT-544F"),
    pytest.param("_mcNegaChkTrq", 1001, 0x544F, id="NegaChkTrq-0..1000-544F"),
    pytest.param("_mcFELmt", 0.0, 0x544F, id="FELmt-positive-544F"),
    pytest.param("_mcChkFELmt", 5.0, 0x544F, id="ChkFELmt-above-FELmt-544F"),
    pytest.param("_mcSwLmtMode", 5, 0x544F, id="SwLmtMode-enum-544F"),
    pytest.param("_mcSwLmtMode", "_mcDrive", 0x544F, id="SwLmtMode-wrong-enum-544F"),
    pytest.param("_mcPosiSwLmt", "_mcNonSwLmt", 0x544F, id="PosiSwLmt-type-544F"),
    pytest.param("_mcNegaSwLmt", 200000.0, 0x544F, id="NegaSwLmt-above-Posi-544F"),
    pytest.param("_mcInPosTime", 10001, 0x544F, id="InPosTime-0..10000-544F"),
    pytest.param("_mcInPosRange", -0.1, 0x544F, id="InPosRange-negative-544F"),
    pytest.param("_mcStartVel", -1.0, 0x544F, id="StartVel-negative-544F"),
])
def test_mc_write_errors(number: Any, value: Any, code: int) -> None:
    """MC_Write (§5.3, omron-group-and-cam.md L1073–1136): 544C ParameterNumber out of range (A-1 #44), 544F
    SettingValue out of range or of the wrong type (A-1 #47); source MC common, effect NOEXEC: nothing written."""
    c = _homed(Limit={"FollowingErrorOverVal": 1.0})
    before = c.mc.axes[0].params.model_dump()
    states = _states(c)
    wr = c.fb("MC_Write", Target=AX, Execute=True, ParameterNumber=number, SettingValue=value)
    c.step(1)
    assert_common_error(c, wr, code, states)
    assert c.mc.axes[0].params.model_dump() == before


# ---------------------------------------------------------------------------------------------------- axis use
def test_change_axis_use_out_of_range_on_a_used_axis_is_an_axis_error() -> None:
    """AxisUse out of range → 549E (A-1 #121, source "MC common/Axis"); on a used axis errors are axis errors
    (ch3 L1858): the axis error-stops and stays used (on error the axis use is not changed, L1859)."""
    c = _homed()
    cu = c.fb("MC_ChangeAxisUse", Axis=AX, Execute=True, AxisUse=3)
    c.step(1)
    assert_axis_fault(c, cu, 0x549E)
    assert c.mc.axes[0].used


def test_change_axis_use_out_of_range_on_an_unused_axis_is_mc_common() -> None:
    """549E on an unused axis: an MC common error (ch3 L1858); the axis stays unused."""
    c = _with_unused_axis()
    states = _states(c)
    cu = c.fb("MC_ChangeAxisUse", Axis=UNUSED, Execute=True, AxisUse=0)
    c.step(1)
    assert_common_error(c, cu, 0x549E, states)
    assert not c.mc.by_name[UNUSED].used


# ---------------------------------------------------------------------------------------------------- 5430 by axis type
@pytest.mark.parametrize(("name", "inputs"), [
    pytest.param("MC_SetPosition", {"Execute": True, "Position": 1.0}, id="SetPosition-ch3L822"),
    pytest.param("MC_ZoneSwitch", {"Enable": True, "FirstPosition": -1.0, "LastPosition": 1.0},
                 id="ZoneSwitch-ch3L1530"),
])
def test_command_position_on_an_encoder_axis_is_5430(name: str, inputs: dict[str, Any]) -> None:
    """ReferenceType _mcCommand on an encoder axis (it has no command position) → 5430 (A-1 #17); the encoder
    axis goes to ErrorStop (A-3.7)."""
    c = _with_encoder_axis()
    fb = c.fb(name, Axis="MC_Axis001", ReferenceType="_mcCommand", **inputs)
    c.step(1)
    assert_axis_fault(c, fb, 0x5430, axis=1)


@pytest.mark.parametrize(("master", "slave", "ref"), [
    pytest.param("MC_Axis001", AX, "_mcCommand", id="encoder-master-ch3L1671"),
    pytest.param(AX, "MC_Axis001", "_mcCommand", id="encoder-slave-ch3L1671"),
    pytest.param(AX, "MC_Axis001", 2, id="LatestCommand-out-of-range-ch3L1651"),
])
def test_axes_observe_reference_type_is_5430_mc_common(master: str, slave: str, ref: Any) -> None:
    """MC_AxesObserve: encoder axes only with _mcFeedback, ReferenceType 0/1 → else 5430; its errors do not
    affect the axes, they are MC common minor faults (ch3 L1673)."""
    c = _with_encoder_axis()
    states = _states(c)
    ob = c.fb("MC_AxesObserve", Master=master, Slave=slave, Enable=True, ReferenceType=ref)
    c.step(1)
    assert_common_error(c, ob, 0x5430, states)


@pytest.mark.parametrize(("code", "stop"), [pytest.param(0x6462, False, id="acceleration-6462"),
                                            pytest.param(0x6463, True, id="deceleration-6463")])
def test_acceleration_and_deceleration_warnings_are_observations(code: int, stop: bool) -> None:
    """Acceleration/Deceleration Warning Value (% of MaxAcc/MaxDec, §5.5.3 L1482–1483): exceeding it is an
    observation (Obsr, code assigned by MC Studio, D19) — no Error, the axis keeps its state."""
    c = _homed(Operation={"AccWarningVal": 50, "DecWarningVal": 50})  # 5000 mm/s² of 10000
    mv = c.fb("MC_MoveVelocity", Axis=AX, Execute=True, Velocity=100.0, Acceleration=1000.0 if stop else 8000.0,
              Deceleration=1000.0)
    c.step(5)
    if stop:
        step_until(c, mv, "InVelocity")
        c.fb("MC_Stop", Axis=AX, Execute=True, Deceleration=8000.0)
        c.step(5)
    ax = c.mc.axes[0]
    assert ax.obsr_code == code and ax.error_code == 0
    assert ax.state == (S.Stopping if stop else S.Continuous)
    ev = _events(c, code)
    assert ev and ev[-1].level == "observation"


# ---------------------------------------------------------------------------------------------------- 3461
@pytest.mark.parametrize(
    ("name", "inputs", "removed"),
    [
        pytest.param("MC_Home", {"Execute": True}, 0x60BA, id="MC_Home-latch1-ch3 L190"),
        pytest.param("MC_TouchProbe", {"Execute": True, "TriggerInput": EXT1}, 0x60B9, id="MC_TouchProbe-ch3 L1575"),
        pytest.param("MC_TouchProbe", {"Execute": True, "TriggerInput": EXT2}, 0x60BC, id="MC_TouchProbe-latch2"),
        pytest.param("MC_MoveFeed", {"Execute": True, "TriggerInput": EXT1, "Position": 50.0, "MoveMode": "_mcRelative",
                                     "FeedDistance": 5.0, "FeedVelocity": 10.0, **MOVE}, 0x60B8,
                     id="MC_MoveFeed-ch3 L685"),
    ],
)
def test_latch_objects_not_mapped_is_3461(name: str, inputs: dict[str, Any], removed: int) -> None:
    """Instructions that use the drive's touch probe need 60B8h (function), 60B9h (status) and the latch position
    (60BAh latch 1 / 60BCh latch 2) in the slave's PDO mapping (omron-mc-basics.md §2.11, A-1 3461). The
    axis's mapped objects stand in for a mapping without one of them."""
    c = Controller(axis_project(sensors={"HomeProximityStart": 20.0, "HomeProximityEnd": 30.0}))
    power_on(c)
    c.mc.pdo_objects[0] = c.mc.pdo_objects[0] - {removed}  # type: ignore[operator]
    fb = c.fb(name, Axis=AX, **inputs)
    c.step(1)
    assert_axis_fault(c, fb, 0x3461)


def test_latch_objects_not_needed_by_controller_mode_or_preset() -> None:
    """A controller-mode trigger (MC_TouchProbe, Mode _mcController) and homing mode 14 (preset) use no drive latch:
    no 3461 without the touch-probe objects."""
    c = Controller(axis_project(Homing={"Mode": "_mcHomePreset"}))
    power_on(c)
    c.mc.pdo_objects[0] = c.mc.pdo_objects[0] - {0x60B8, 0x60B9, 0x60BA, 0x60BC}  # type: ignore[operator]
    tp = c.fb("MC_TouchProbe", Axis=AX, Execute=True, TriggerInput={"Mode": "_mcController", "LatchID": "_mcLatch1"})
    h = c.fb("MC_Home", Axis=AX, Execute=True)
    c.step(1)
    assert not tp.Error and tp.Busy
    step_until(c, h, "Done")


# ---------------------------------------------------------------------------------------------------- 6442
def _overflowed(sign: int = 1) -> Controller:
    """An axis run into the end of the 40-bit range in Linear Mode: preset near Scale.MaxPos (or MinPos), then a
    velocity move toward it (decision D28)."""
    c = Controller(axis_project())
    power_on(c)
    edge = run_into_overflow(c, AX, sign, PPU)
    ax = c.mc.axes[0]
    assert ax.state == S.Standstill and not ax.error_code, "overflow itself is not an error"
    assert c.mc.cmd_pos[0] == pytest.approx(edge)
    assert c.mc.ovf[0] == sign
    return c


@pytest.mark.parametrize("sign", [1, -1], ids=["overflow", "underflow"])
@pytest.mark.parametrize(
    ("name", "inputs"),
    [
        pytest.param("MC_MoveAbsolute", {"Position": 0.0, **MOVE}, id="positioning"),
        pytest.param("MC_MoveRelative", {"Distance": "away", **MOVE}, id="positioning-relative-away"),
        pytest.param("MC_MoveVelocity", {"Direction": "toward", **MOVE}, id="continuous-toward"),
        pytest.param("MC_TorqueControl", {"Torque": 10.0, "TorqueRamp": 0.0, "Velocity": 10.0}, id="torque"),
    ],
)
def test_command_position_overflow_is_6442(sign: int, name: str, inputs: dict[str, Any]) -> None:
    """A-1 #144 (basics L1154): while the command position is in overflow/underflow, a positioning instruction, a
    continuous instruction toward the overflow direction or a direction-less one (torque control) → 6442, an axis
    minor fault."""
    c = _overflowed(sign)
    if inputs.get("Direction") == "toward":
        inputs = {**inputs, "Direction": "_mcPositiveDirection" if sign > 0 else "_mcNegativeDirection"}
    if inputs.get("Distance") == "away":  # even back into the range: any positioning is refused
        inputs = {**inputs, "Distance": -sign * 1.0}
    fb = c.fb(name, Axis=AX, Execute=True, **inputs)
    c.step(1)
    assert_axis_fault(c, fb, 0x6442)


def test_overflow_allows_motion_away_and_is_cleared_by_set_position() -> None:
    """Continuous motion away from the overflow side is allowed; MC_Reset does not end the overflow, a preset does
    (A-1 #144: "clear with reset + homing or position preset")."""
    c = _overflowed(1)
    away = c.fb("MC_MoveVelocity", Axis=AX, Execute=True, Velocity=10.0, Acceleration=1000.0,
                Direction="_mcNegativeDirection")
    c.step(50)
    assert not away.Error and away.Busy and c.mc.cmd_vel[0] < 0
    stop = c.fb("MC_Stop", Axis=AX, Execute=True, Deceleration=1000.0)
    step_until(c, stop, "Done")
    c.set_inputs(stop.id, {"Execute": False})
    c.step(1)
    assert c.mc.ovf[0] == 1
    sp = c.fb("MC_SetPosition", Axis=AX, Execute=True, Position=0.0)
    step_until(c, sp, "Done")
    mv = c.fb("MC_MoveAbsolute", Axis=AX, Execute=True, Position=5.0, **MOVE)
    step_until(c, mv, "Done")
    assert c.mc.act_pos[0] == pytest.approx(5.0, abs=0.5 / PPU)  # within a pulse: large offsets round


def test_scale_max_and_min_pos_in_linear_mode() -> None:
    """_sAXIS_REF.Scale.MaxPos/MinPos: in Linear Mode the positions just before overflow/underflow (basics L354)."""
    from mcstudio.controller.mc.axis import axis_variables

    c = Controller(axis_project())
    c.step(1)
    ax = c.mc.axes[0]
    v = axis_variables(ax, c.publish().mc["discrete"][0], {"cmd_pos": 0.0, "cmd_vel": 0.0, "cmd_accdec": 0.0,
                                                          "cmd_jerk": 0.0, "act_pos": 0.0, "act_vel": 0.0,
                                                          "drv": {}})
    assert v["Scale"]["MaxPos"] == pytest.approx((2**39 - 1) / PPU)
    assert v["Scale"]["MinPos"] == pytest.approx(-(2**39) / PPU)


def test_move_feed_beyond_the_range_is_6442_at_the_interrupt() -> None:
    """ch3 L684: an interrupt feed whose position would overflow → error at the interrupt input (6442)."""
    c = Controller(axis_project(sensors={"ExternalHomeStart": 2.0, "ExternalHomeEnd": 3.0}))
    power_on(c)
    edge = (2**39 - 1) / PPU
    sp = c.fb("MC_SetPosition", Axis=AX, Execute=True, Position=edge - 10.0)  # the sensor is now at edge − 8
    step_until(c, sp, "Done")
    mf = c.fb("MC_MoveFeed", Axis=AX, Execute=True, TriggerInput=EXT1, MoveMode="_mcVelocity", Velocity=10.0,
              Acceleration=1000.0, Deceleration=1000.0, FeedDistance=20.0, FeedVelocity=10.0)
    step_until(c, mf, "Error", limit=2000)
    assert_axis_fault(c, mf, 0x6442)
    assert float(c.mc.cmd_pos[0]) < edge
