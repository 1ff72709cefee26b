"""The A-3 multi-execution table for axis instructions, cell by cell.

Spec: omron-mc-basics.md §A-3.4 "Axis instructions on servo axes and virtual servo axes" (seed 000 lines
21576–21675: the state *after* executing each instruction, per state before) with the acceptance of each cell from
§A-3.8 (reconstructed: ✔ accepted, ✖ error and the axis error-stops, ⊘ CommandAborted and ignored) and §A-3.7
(encoder axes). Error codes of refused cells: 5441 on a servo-OFF axis (A-1 #34), 543C "multi-execution
disabled" (A-1 #29, decision D6), 543D "axis type mismatch" on encoder axes (A-1 #30).

Each case brings MC_Axis000 into the state of a column, executes the instruction once and checks the instance's
outputs, its ErrorID and the axis state one period later against the table cell. Column E (Synchronized) runs
with MC_Axis000 geared to a moving MC_Axis001 (MC_GearIn); column I (Coordinated) with MC_Axis000 in the enabled
MC_Group000 (MC_Axis000 + MC_Axis002, MC_GroupEnable): there the table's group columns (b Standby → b or e) are
checked too, and a refused instruction is 543E, a group error (A-1 #31, decision D70). Rows of instructions not
registered yet are skipped.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import pytest

from mcstudio.controller.kernel import Controller, Until
from mcstudio.controller.mc.cam.table import CamTable
from mcstudio.controller.mc.enums import AxisState
from mcstudio.controller.mc.fb.base import FunctionBlock
from mcstudio.controller.mc.fb.registry import FB_TYPES
from mcstudio.controller.mc.group import GroupState
from mcstudio.project.models import AxesGroupConfig
from tests.conftest import axis_project, power_on

AX = "MC_Axis000"
# dog and limits far away: homing started at 0 keeps searching at 10 mm/s for the whole test
SENSORS = {"PositiveLimit": 900.0, "NegativeLimit": -900.0, "HomeProximityStart": 500.0, "HomeProximityEnd": 510.0}
HOMING = {"Mode": "_mcHomeSwTurnHomeSwOff", "Vel": 10.0, "ApproachVel": 1.0, "Acc": 1000.0, "Dec": 1000.0}
EXT1 = {"Mode": "_mcDrive", "LatchID": "_mcLatch1", "InputDrive": "_mcEXT"}
HOMING_REF = {"HomingMode": "_mcHomeSwTurnHomeSwOff", "HomeInput": "_mcZPhase", "StartDir": "_mcPositiveDirection",
              "HomeDir": "_mcPositiveDirection", "PosiLmtMode": "_mcRevImmediateStop",
              "NegaLmtMode": "_mcRevImmediateStop", "Vel": 10.0, "ApproachVel": 1.0, "Acc": 1000.0, "Dec": 1000.0,
              "Jerk": 0.0, "Mask": 0.0, "Offset": 0.0, "PushTime": 0, "Compensation": 0.0, "CompensationVel": 5.0}

SV, MX, AT = 0x5441, 0x543C, 0x543D
LETTER = {"A": AxisState.Disabled, "B": AxisState.Standstill, "C": AxisState.Discrete, "D": AxisState.Continuous,
          "E": AxisState.Synchronized, "F": AxisState.Homing, "G": AxisState.Stopping, "H": AxisState.ErrorStop,
          "I": AxisState.Coordinated}


# ---------------------------------------------------------------------- bringing the axis into a state

@dataclass
class Rig:
    c: Controller
    power: FunctionBlock | None
    running: FunctionBlock | None  # the instruction that holds the state (moving, homing, MC_Stop)


def _controller(encoder_axis: bool = False) -> Controller:
    p = axis_project(sensors=SENSORS, encoder="absolute", Homing=HOMING)  # absolute: home defined at servo ON
    third = p.axes[1].model_copy(deep=True)
    third.name, third.number = "MC_Axis002", 2
    p.axes.append(third)  # the auxiliary axis of MC_CombineAxes
    # column I: MC_Axis000 coordinated in MC_Group000 (enabled only there; a disabled group changes nothing)
    p.groups.append(AxesGroupConfig(name="MC_Group000", number=0, composition="_mcXY",
                                    axes=["MC_Axis000", "MC_Axis002"]))
    if encoder_axis:
        p.axes[1].type = "_mcEncdr"  # type: ignore[assignment]
        p.axes[1].node_address = 2
    return Controller(p, cams={"Cam": CamTable.from_points([0.0, 100.0], [0.0, 50.0])})


def _move_master(c: Controller) -> None:
    """MC_Axis001 (virtual) moving at 10 u/s: the master of the synchronized instructions."""
    if not c.mc.axes[1].servo_on:
        power_on(c, "MC_Axis001")
    c.fb("MC_MoveVelocity", Axis="MC_Axis001", Execute=True, Velocity=10.0, Acceleration=0.0, Deceleration=0.0)
    c.step(3)


def _state(col: str) -> Rig:
    c = _controller()
    if col == "A":
        c.step(2)
        return Rig(c, None, None)
    pw = power_on(c)
    run: FunctionBlock | None = None
    if col == "C":
        run = c.fb("MC_MoveAbsolute", Axis=AX, Execute=True, Position=400.0, Velocity=10.0, Acceleration=1000.0,
                   Deceleration=1000.0)
    elif col == "D":
        run = c.fb("MC_MoveVelocity", Axis=AX, Execute=True, Velocity=10.0, Acceleration=1000.0,
                   Deceleration=1000.0)
    elif col == "E":
        _move_master(c)
        run = c.fb("MC_GearIn", Master="MC_Axis001", Slave=AX, Execute=True)
    elif col == "F":
        run = c.fb("MC_Home", Axis=AX, Execute=True)
    elif col == "G":
        run = c.fb("MC_Stop", Axis=AX, Execute=True, Deceleration=1000.0)  # Stopping while Execute stays TRUE
    elif col == "H":
        run = c.fb("MC_ImmediateStop", Axis=AX, Execute=True)  # ErrorStop (5485), servo stays ON
    elif col == "I":
        run = c.fb("MC_GroupEnable", AxesGroup="MC_Group000", Execute=True)  # Standstill → Coordinated
    c.step(20)
    assert c.mc.axes[0].state == LETTER[col], f"could not reach state {col}"
    return Rig(c, pw, run)


# ---------------------------------------------------------------------- executing an instruction

def _execute(name: str, **inputs: Any) -> Callable[[Rig, str], FunctionBlock]:
    def run(rig: Rig, axis: str = AX) -> FunctionBlock:
        return rig.c.fb(name, Axis=axis, **inputs)
    return run


MOVE = {"Velocity": 20.0, "Acceleration": 1000.0, "Deceleration": 1000.0}


def _power_off(rig: Rig, axis: str = AX) -> FunctionBlock:
    if rig.power is None:  # Disabled: an instance with Enable FALSE
        return rig.c.fb("MC_Power", Axis=axis, Enable=False)
    rig.c.set_inputs(rig.power.id, {"Enable": False})
    return rig.power


def _abort_trigger(rig: Rig, axis: str = AX) -> FunctionBlock:
    # MC_AbortTrigger aborts a latch owned by MC_TouchProbe: start one first where MC_TouchProbe is accepted
    if rig.c.mc.axes[0].state not in (AxisState.Homing, AxisState.Coordinated):  # I: no latch owner (5440)
        rig.c.fb("MC_TouchProbe", Axis=axis, Execute=True, TriggerInput=EXT1)
        rig.c.step(1)
    return rig.c.fb("MC_AbortTrigger", Axis=axis, Execute=True, TriggerInput=EXT1)


def _gear_in_pos(rig: Rig, axis: str = AX) -> FunctionBlock:
    # MC_GearInPos needs a moving master (5476 otherwise): start it, then execute
    _move_master(rig.c)
    return rig.c.fb("MC_GearInPos", Master="MC_Axis001", Slave=axis, Execute=True, MasterSyncPosition=1000.0,
                    SlaveSyncPosition=10.0, Velocity=100.0, Acceleration=1000.0, Deceleration=1000.0)


ROWS: dict[str, Callable[..., FunctionBlock]] = {
    "MC_Power(Enable=TRUE)": _execute("MC_Power", Enable=True),
    "MC_Power(Enable=FALSE)": _power_off,
    "MC_MoveJog": _execute("MC_MoveJog", PositiveEnable=True, **MOVE),
    "MC_Home": _execute("MC_Home", Execute=True),
    "MC_HomeWithParameter": _execute("MC_HomeWithParameter", Execute=True, HomingParameter=HOMING_REF),
    "MC_Move": _execute("MC_Move", Execute=True, Position=50.0, MoveMode="_mcAbsolute", **MOVE),
    "MC_MoveAbsolute": _execute("MC_MoveAbsolute", Execute=True, Position=50.0, **MOVE),
    "MC_MoveRelative": _execute("MC_MoveRelative", Execute=True, Distance=50.0, **MOVE),
    "MC_MoveVelocity": _execute("MC_MoveVelocity", Execute=True, **MOVE),
    "MC_MoveZeroPosition": _execute("MC_MoveZeroPosition", Execute=True, **MOVE),
    "MC_MoveFeed": _execute("MC_MoveFeed", Execute=True, TriggerInput=EXT1, Position=50.0,
                            MoveMode="_mcRelative", FeedDistance=5.0, FeedVelocity=10.0, **MOVE),
    "MC_Stop": _execute("MC_Stop", Execute=True, Deceleration=1000.0),
    "MC_ImmediateStop": _execute("MC_ImmediateStop", Execute=True),
    "MC_SetPosition": _execute("MC_SetPosition", Execute=True, Position=7.0),
    "MC_SetOverride": _execute("MC_SetOverride", Enable=True, VelFactor=100.0),
    "MC_ResetFollowingError": _execute("MC_ResetFollowingError", Execute=True),
    "MC_TorqueControl": _execute("MC_TorqueControl", Execute=True, Torque=10.0, TorqueRamp=1000.0, Velocity=10.0),
    "MC_SetTorqueLimit": _execute("MC_SetTorqueLimit", Enable=True, PositiveEnable=True, PositiveValue=50.0,
                                  NegativeEnable=True, NegativeValue=50.0),
    "MC_ZoneSwitch": _execute("MC_ZoneSwitch", Enable=True, FirstPosition=-1.0, LastPosition=1.0),
    "MC_TouchProbe": _execute("MC_TouchProbe", Execute=True, TriggerInput=EXT1),
    "MC_AbortTrigger": _abort_trigger,
    "MC_AxesObserve": lambda rig, axis=AX: rig.c.fb("MC_AxesObserve", Master="MC_Axis001", Slave=axis, Enable=True,
                                                    PermittedDeviation=1.0),
    "MC_Reset": _execute("MC_Reset", Execute=True),
    "MC_CamIn": lambda rig, axis=AX: rig.c.fb("MC_CamIn", Master="MC_Axis001", Slave=axis, CamTable="Cam",
                                              Execute=True, Periodic=True),
    "MC_CamOut": lambda rig, axis=AX: rig.c.fb("MC_CamOut", Slave=axis, Execute=True, Deceleration=100.0),
    "MC_GearIn": lambda rig, axis=AX: rig.c.fb("MC_GearIn", Master="MC_Axis001", Slave=axis, Execute=True),
    "MC_GearInPos": _gear_in_pos,
    "MC_GearOut": lambda rig, axis=AX: rig.c.fb("MC_GearOut", Slave=axis, Execute=True, Deceleration=100.0),
    "MC_MoveLink": lambda rig, axis=AX: rig.c.fb("MC_MoveLink", Master="MC_Axis001", Slave=axis, Execute=True,
                                                 SlaveDistance=5.0, MasterDistance=10.0),
    "MC_CombineAxes": lambda rig, axis=AX: rig.c.fb("MC_CombineAxes", Master="MC_Axis001", Auxiliary="MC_Axis002",
                                                    Slave=axis, Execute=True, ReferenceTypeMaster="_mcFeedback",
                                                    ReferenceTypeAuxiliary="_mcFeedback"),
    "MC_ChangeAxisUse(used→unused)": _execute("MC_ChangeAxisUse", Execute=True, AxisUse="_mcUnusedAxis"),
    "MC_SyncMoveVelocity": _execute("MC_SyncMoveVelocity", Execute=True, Velocity=5.0),
    "MC_SyncMoveAbsolute": _execute("MC_SyncMoveAbsolute", Execute=True, Position=5.0),
}

# cells (state after) for columns A B C D F G H, with the verdict: "ok", "abort" or an ErrorID.
# "-" after = the axis becomes unused (no state).
MOTION = {"A": ("H", SV), "F": ("H", MX), "G": ("G", "abort"), "H": ("H", "abort")}
TABLE: dict[str, dict[str, tuple[str, Any]]] = {
    "MC_Power(Enable=TRUE)": {"A": ("B", "ok"), "B": ("B", "ok"), "C": ("C", "ok"), "D": ("D", "ok"),
                              "F": ("F", "ok"), "G": ("G", "ok"), "H": ("H", "ok")},
    "MC_Power(Enable=FALSE)": {"A": ("A", "ok"), "B": ("A", "ok"), "C": ("A", "ok"), "D": ("A", "ok"),
                               "F": ("A", "ok"), "G": ("A", "ok"), "H": ("H", "ok")},
    **{n: {**MOTION, "B": (after, "ok"), "C": ("H", MX), "D": ("H", MX)}
       for n, after in (("MC_MoveJog", "D"), ("MC_Home", "F"), ("MC_HomeWithParameter", "F"))},
    **{n: {**MOTION, "B": (after, "ok"), "C": (after, "ok"), "D": (after, "ok")}
       for n, after in (("MC_Move", "C"), ("MC_MoveAbsolute", "C"), ("MC_MoveRelative", "C"),
                        ("MC_MoveVelocity", "D"), ("MC_MoveZeroPosition", "C"), ("MC_MoveFeed", "C"),
                        ("MC_TorqueControl", "D"))},
    "MC_Stop": {"A": ("A", "ok"), "B": ("G", "ok"), "C": ("G", "ok"), "D": ("G", "ok"), "F": ("G", "ok"),
                "G": ("G", "ok"), "H": ("H", "abort")},
    "MC_ImmediateStop": {col: ("H", "ok") for col in "ABCDFGH"},
    # C: printed F*4, read as C*4 (A-3.4 footnote *4, decision D6); C*4/D*5 errors apply only while
    # MC_MoveZeroPosition / MC_TorqueControl run (tested in test_admin.py)
    "MC_SetPosition": {"A": ("A", "ok"), "B": ("B", "ok"), "C": ("C", "ok"), "D": ("D", "ok"), "F": ("H", MX),
                       "G": ("G", "ok"), "H": ("H", "ok")},
    "MC_ResetFollowingError": {"A": ("H", SV), "B": ("B", "ok"), "C": ("G", "ok"), "D": ("G", "ok"),
                               "F": ("H", MX), "G": ("G", "ok"), "H": ("H", "abort")},
    **{n: {col: (col, "ok") for col in "ABCDFGH"}
       for n in ("MC_SetOverride", "MC_SetTorqueLimit", "MC_ZoneSwitch", "MC_AxesObserve", "MC_Reset")},
    # F: both latches are in use during homing — 546E Duplicate Latch ID (A-1 #77, decision D22)
    "MC_TouchProbe": {**{col: (col, "ok") for col in "ABCDGH"}, "F": ("H", 0x546E)},
    "MC_AbortTrigger": {**{col: (col, "ok") for col in "ABCDGH"}, "F": ("H", 0x546E)},
    "MC_ChangeAxisUse(used→unused)": {"A": ("-", "ok"), "B": ("-", "ok"),
                                      **{col: ("H", 0x5702) for col in "CDFGH"}},
}
TABLE["MC_Reset"]["H"] = ("B", "ok")  # *10: the reset succeeds with the servo ON → Standstill
# synchronized control (A-3.4 rows MC_CamIn … MC_CombineAxes): like the other motion instructions; MC_GearInPos only
# from Standstill; MC_CamOut/MC_GearOut only while their instruction runs (*6/*7), else 543A Synchronization Stopped
SYNC_STOPPED = 0x543A
for _n in ("MC_CamIn", "MC_GearIn", "MC_MoveLink", "MC_CombineAxes"):
    TABLE[_n] = {**MOTION, "B": ("E", "ok"), "C": ("E", "ok"), "D": ("E", "ok")}
TABLE["MC_GearInPos"] = {**MOTION, "B": ("E", "ok"), "C": ("H", MX), "D": ("H", MX)}
for _n in ("MC_CamOut", "MC_GearOut"):
    TABLE[_n] = {**MOTION, **{col: ("H", SYNC_STOPPED) for col in "BCDF"}}
TABLE["MC_SyncMoveVelocity"] = {**MOTION, "B": ("D", "ok"), "C": ("D", "ok"), "D": ("D", "ok")}
TABLE["MC_SyncMoveAbsolute"] = {**MOTION, "B": ("C", "ok"), "C": ("C", "ok"), "D": ("C", "ok")}
# column E (Synchronized: MC_GearIn running), A-3.4 column E
COLUMN_E: dict[str, tuple[str, Any]] = {
    "MC_Power(Enable=TRUE)": ("E", "ok"), "MC_Power(Enable=FALSE)": ("A", "ok"),
    "MC_MoveJog": ("H", MX), "MC_Home": ("H", MX), "MC_HomeWithParameter": ("H", MX),
    "MC_Move": ("C", "ok"), "MC_MoveAbsolute": ("C", "ok"), "MC_MoveRelative": ("C", "ok"),
    "MC_MoveVelocity": ("D", "ok"), "MC_MoveZeroPosition": ("C", "ok"), "MC_MoveFeed": ("C", "ok"),  # *3: target
    "MC_TorqueControl": ("D", "ok"), "MC_Stop": ("G", "ok"), "MC_ImmediateStop": ("H", "ok"),
    "MC_SetPosition": ("H", MX), "MC_ResetFollowingError": ("G", "ok"),
    **{n: ("E", "ok") for n in ("MC_SetOverride", "MC_SetTorqueLimit", "MC_ZoneSwitch", "MC_AxesObserve", "MC_Reset",
                                "MC_TouchProbe", "MC_AbortTrigger", "MC_CamIn", "MC_GearIn", "MC_MoveLink",
                                "MC_CombineAxes")},
    "MC_GearInPos": ("H", MX),
    "MC_CamOut": ("H", SYNC_STOPPED),  # *6: MC_GearIn, not MC_CamIn, is running
    "MC_GearOut": ("C", "ok"),  # *7
    "MC_SyncMoveVelocity": ("D", "ok"), "MC_SyncMoveAbsolute": ("C", "ok"),
    "MC_ChangeAxisUse(used→unused)": ("H", 0x5702),
}
for _row, _cell in COLUMN_E.items():
    TABLE[_row]["E"] = _cell
# column I (Coordinated: MC_Group000 enabled, group Standby), A-3.4 columns I and b with rule 5: the axis stays
# Coordinated; an instruction that drives the group to e (ErrorStop) is refused with 543E, a group error (D70).
# MC_ChangeAxisUse is printed I → H with the group staying b: 5702, an axis error (D70).
CO = 0x543E
COLUMN_I_OK = {"MC_Power(Enable=TRUE)", "MC_Power(Enable=FALSE)", "MC_SetOverride", "MC_SetTorqueLimit",
               "MC_ZoneSwitch", "MC_AxesObserve", "MC_Reset"}
for _row in TABLE:
    TABLE[_row]["I"] = ("I", "ok") if _row in COLUMN_I_OK else ("I", CO)
TABLE["MC_ChangeAxisUse(used→unused)"]["I"] = ("H", 0x5702)
GROUP_AFTER = {"ok": GroupState.Standby, CO: GroupState.ErrorStop, 0x5702: GroupState.Standby}

_ENABLE_TYPE = {"MC_Power", "MC_MoveJog", "MC_SetOverride", "MC_SetTorqueLimit", "MC_ZoneSwitch", "MC_AxesObserve"}


def _cases() -> list[Any]:
    out = []
    for row, cells in TABLE.items():
        for col in "ABCDEFGHI":
            out.append(pytest.param(row, col, cells[col], id=f"{row}-{col}"))
    return out


@pytest.mark.parametrize(("row", "col", "cell"), _cases())
def test_a3_cell(row: str, col: str, cell: tuple[str, Any]) -> None:
    name = row.split("(")[0]
    if name not in FB_TYPES:
        pytest.skip(f"{name} is not implemented yet")
    after, verdict = cell
    rig = _state(col)
    c = rig.c
    before_events = len(c.events.list())
    fb = ROWS[row](rig)
    c.step(1)
    out = fb.out
    ax = c.mc.axes[0]
    if verdict == "ok":
        assert not out.get("Error"), f"{row} in {col}: Error {out.get('ErrorID', 0):04X}"
        assert not out.get("CommandAborted"), f"{row} in {col}: CommandAborted"
        if name not in _ENABLE_TYPE:
            assert out["Busy"] or out["Done"], f"{row} in {col} was not accepted: {out}"
    elif verdict == "abort":
        assert out["CommandAborted"] and not out["Error"], f"{row} in {col}: {out}"
        assert not out["Busy"]
    else:
        assert out["Error"] and out["ErrorID"] == verdict, f"{row} in {col}: ErrorID {out['ErrorID']:04X}"
        code = f"{verdict:04X}0000"
        assert any(e.code == code for e in c.events.list()[before_events:]), f"no event {code}"
    if col == "I":  # group column b (Standby): b for the administrative instructions, e for the refused ones
        grp = c.mc.groups_by_name["MC_Group000"]
        assert grp.state == GROUP_AFTER[verdict], f"{row} in I: group {grp.state.name}"
    if name == "MC_Power" and not out.get("Error"):
        c.step(50, Until(fb.id, "Status", after != "A" and (after != "H" or ax.servo_on)))
    if after == "-":
        assert not ax.used, "the axis should be unused"
    else:
        assert ax.state == LETTER[after], f"{row} in {col}: state {ax.state.name}, table says {LETTER[after].name}"


# ---------------------------------------------------------------------- encoder axes

ENCODER_OK = {"MC_SetPosition", "MC_ZoneSwitch", "MC_TouchProbe", "MC_AbortTrigger", "MC_AxesObserve", "MC_Reset"}
FEEDBACK = {"ReferenceType": "_mcFeedback"}
ENCODER_ROWS: dict[str, Callable[..., FunctionBlock]] = {
    **{r: ROWS[r] for r in ("MC_Power(Enable=TRUE)", "MC_MoveJog", "MC_Home", "MC_Move", "MC_MoveAbsolute",
                            "MC_MoveRelative", "MC_MoveVelocity", "MC_MoveZeroPosition", "MC_MoveFeed", "MC_Stop",
                            "MC_ImmediateStop", "MC_SetOverride", "MC_ResetFollowingError", "MC_TorqueControl",
                            "MC_SetTorqueLimit", "MC_TouchProbe", "MC_AbortTrigger", "MC_Reset")},
    "MC_SetPosition": _execute("MC_SetPosition", Execute=True, Position=7.0, **FEEDBACK),
    "MC_ZoneSwitch": _execute("MC_ZoneSwitch", Enable=True, FirstPosition=-1.0, LastPosition=1.0, **FEEDBACK),
    "MC_AxesObserve": lambda rig, axis: rig.c.fb("MC_AxesObserve", Master=axis, Slave="MC_Axis000", Enable=True,
                                                 PermittedDeviation=1.0, **FEEDBACK),
}


@pytest.mark.parametrize("row", list(ENCODER_ROWS))
def test_a3_7_encoder_axis_in_disabled(row: str) -> None:
    """A-3.7: on an encoder axis (always state A or H) only the administrative instructions run (A → A); the
    others are errors — 543D Axis Type Mismatch (A-1 #30) — and the encoder axis goes to H."""
    name = row.split("(")[0]
    if name not in FB_TYPES:
        pytest.skip(f"{name} is not implemented yet")
    c = _controller(encoder_axis=True)
    c.step(2)
    enc = c.mc.axes[1]
    assert enc.encoder and enc.state == AxisState.Disabled
    fb = ENCODER_ROWS[row](Rig(c, None, None), "MC_Axis001")
    c.step(1)
    if name in ENCODER_OK:
        assert not fb.out.get("Error"), f"{row}: {fb.out.get('ErrorID', 0):04X}"
        assert enc.state == AxisState.Disabled
    else:
        assert fb.out["Error"] and fb.out["ErrorID"] == AT, f"{row}: {fb.out['ErrorID']:04X}"
        assert enc.state == AxisState.ErrorStop
