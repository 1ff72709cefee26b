"""6443/6444 at the start of the single-axis instructions that specify no direction of motion (decision D132).

Spec: A-1 64430000 Hex / 64440000 Hex (seed 000 lines 21279–21300; omron-mc-basics.md L1155–1156, L1262–1263): the
error occurs, detected at the instruction's start, when with the positive (negative) limit input ON "an instruction
moving in the + (−) direction" or "an instruction whose direction of motion is not specified" (未指定移动方向的指令)
is executed; effect: the axis cannot operate (minor fault). The 6442 row two entries above (seed 000 line 21275)
names the direction-indeterminate instructions: the synchronization functions (同步功能) and torque control.

D132 reads "direction not specified" as: MC_CamIn, MC_GearIn, MC_GearInPos, MC_MoveLink, MC_CombineAxes (single-axis
synchronized control: the slave's motion is the master's, whatever sign an input has) and the cyclic synchronous
MC_SyncMoveAbsolute / MC_SyncMoveVelocity (the program gives a new target every period). Such an instruction is
refused with either limit input ON — 6443 when the positive one is ON, else 6444 — in the period of Execute↑, after
its input and state checks; a re-execution of the running instance is not a new start; a second instance started
onto a running instruction (multi-execution, any BufferMode) is.

Rig: MC_Axis000 virtual master, MC_Axis001 virtual auxiliary (MC_CombineAxes), MC_Axis002 the slave, a servo axis on
node 1 whose drive reads the limit switches of the simulated mechanism (`sensors`, mm). The kernel is stepped
period by period (1 ms).
"""

from __future__ import annotations

import copy
from typing import Any

import pytest

from mcstudio.controller.kernel import Controller
from mcstudio.controller.mc.cam.table import CamTable
from mcstudio.controller.mc.enums import AxisState
from mcstudio.controller.mc.fb.base import FunctionBlock
from mcstudio.project.models import AxisConfig, Project
from tests.conftest import MM_AXIS, power_on, run_into_overflow, step_until

M, A, S = "MC_Axis000", "MC_Axis001", "MC_Axis002"
PPU = 104857.6  # pulses per mm (2^20 pulses per 10 mm)
NEG_ON = {"NegativeLimit": 5.0}  # negative limit switch ON at positions ≤ 5 mm: ON where the slave stands (0)
POS_ON = {"PositiveLimit": -5.0}  # positive limit switch ON at positions ≥ −5 mm
BOTH_OFF = {"NegativeLimit": -500.0, "PositiveLimit": 500.0}  # both switches fitted, both OFF at 0
STEPS = ([0.0, 80.0, 120.0, 360.0], [0.0, 80.0, 200.0, 360.0])
MASTER_VEL = 10.0  # mm/s
MOVE = {"Velocity": 5.0, "Acceleration": 100.0, "Deceleration": 100.0}

# the instructions without a direction of motion (D132), with inputs that start normally when no limit is ON; where
# an input has a sign it points away from the negative limit (+), to show that the sign does not give a direction
DIRECTIONLESS: dict[str, dict[str, Any]] = {
    "MC_CamIn": {"Master": M, "Slave": S, "CamTable": "Steps"},
    "MC_GearIn": {"Master": M, "Slave": S, "Acceleration": 100.0, "Deceleration": 100.0},
    "MC_GearInPos": {"Master": M, "Slave": S, "MasterSyncPosition": 100.0, "SlaveSyncPosition": 10.0,
                     "Velocity": 50.0, "Acceleration": 100.0, "Deceleration": 100.0},
    "MC_MoveLink": {"Master": M, "Slave": S, "SlaveDistance": 10.0, "MasterDistance": 100.0},
    "MC_CombineAxes": {"Master": M, "Auxiliary": A, "Slave": S},
    "MC_SyncMoveAbsolute": {"Axis": S, "Position": 10.0},
    "MC_SyncMoveVelocity": {"Axis": S, "Velocity": 5.0},
}
STARTED_STATE = {"MC_SyncMoveAbsolute": AxisState.Discrete, "MC_SyncMoveVelocity": AxisState.Continuous}


def _rig(sensors: dict[str, float], **slave_groups: dict[str, Any]) -> Controller:
    """Master and auxiliary virtual, the slave a servo with `sensors` (and parameter groups updated from
    `slave_groups`); all servo ON, the master moving + at MASTER_VEL (so MC_GearInPos has a master velocity and the
    synchronized instructions a master that moves)."""
    p = copy.deepcopy(MM_AXIS)
    sp = copy.deepcopy(p)
    for group, values in slave_groups.items():
        sp.setdefault(group, {}).update(values)
    axes = [AxisConfig(name=M, number=0, type="_mcVirServo", parameters=copy.deepcopy(p)),
            AxisConfig(name=A, number=1, type="_mcVirServo", parameters=copy.deepcopy(p)),
            AxisConfig(name=S, number=2, type="_mcServo", node_address=1, parameters=sp, sensors=sensors)]
    c = Controller(Project(name="limit-sync", axes=axes), cams={"Steps": CamTable.from_points(*STEPS)})
    for name in (M, A, S):
        power_on(c, name)
    mv = c.fb("MC_MoveVelocity", Axis=M, Execute=True, Velocity=MASTER_VEL, Acceleration=0.0, Deceleration=0.0)
    step_until(c, mv, "InVelocity")
    return c


def _slave(c: Controller) -> Any:
    return c.mc.by_name[S]


def _events(c: Controller, code: int) -> list[Any]:
    return [e for e in c.events.list() if e.code == f"{code:04X}0000"]


def _assert_refused_at_the_edge(c: Controller, fb: FunctionBlock, code: int) -> None:
    """Timing chart: Execute↑ in period k → Error/ErrorID in period k (Busy never TRUE), the slave ErrorStop with
    MFaultLvl.Code = ErrorID and a minor-fault event whose source is the slave; nothing moves afterwards."""
    i = _slave(c).i
    pos0 = float(c.mc.cmd_pos[i])
    c.step(1)  # period k-1: Execute FALSE
    assert not (fb.out["Busy"] or fb.out["Error"]), fb.outputs_json()
    c.set_inputs(fb.id, {"Execute": True})
    c.step(1)  # period k: Execute↑
    o = fb.out
    assert o["Error"] and o["ErrorID"] == code, f"{fb.DEF.name}: {fb.outputs_json()}"
    assert not (o["Busy"] or o["Active"] or o["CommandAborted"])
    ax = _slave(c)
    assert ax.state == AxisState.ErrorStop and ax.error_code == code, f"{ax.state.name} {ax.error_code:04X}"
    ev = _events(c, code)
    assert ev and ev[-1].level == "minor fault" and ev[-1].source.startswith(S), [(e.code, e.source) for e in ev]
    for _ in range(20):
        c.step(1)
        assert float(c.mc.cmd_pos[i]) == pos0 and float(c.mc.cmd_vel[i]) == 0.0, "the slave must not move"
    assert fb.out["Error"] and not fb.out["Busy"]
    master = c.mc.by_name[M]
    assert master.error_code == 0 and float(c.mc.cmd_vel[master.i]) == pytest.approx(MASTER_VEL), \
        "the master is not affected"


# ---------------------------------------------------------------------------------------------------- (b) refused
@pytest.mark.parametrize("name", list(DIRECTIONLESS))
@pytest.mark.parametrize(("sensors", "code"), [
    pytest.param(POS_ON, 0x6443, id="6443-seed-L21279"),
    pytest.param(NEG_ON, 0x6444, id="6444-seed-L21292"),
])
def test_directionless_instruction_is_refused_with_a_limit_input_on(sensors: dict[str, float], code: int,
                                                                     name: str) -> None:
    """A-1 6443/6444 (seed 000 lines 21288 / 21301): "an instruction whose direction of motion is not specified,
    executed while the limit input is ON" — either limit, whatever sign SlaveDistance/Position/Velocity has (D132)."""
    c = _rig(sensors)
    fb = c.fb(name, Execute=False, **DIRECTIONLESS[name])
    _assert_refused_at_the_edge(c, fb, code)


def test_both_limits_on_is_6443() -> None:
    """Both inputs ON — the negative switch pressed, the positive one read through a wrong logic setting (the
    manual's "check the logic setting"): the positive one is reported, as by every start check (start_limit_error)."""
    c = _rig({"NegativeLimit": 5.0, "PositiveLimit": 500.0}, OtherOperation={"PosiLimitInputLogicInversion": True})
    fb = c.fb("MC_GearIn", Execute=False, **DIRECTIONLESS["MC_GearIn"])
    _assert_refused_at_the_edge(c, fb, 0x6443)


def test_input_error_comes_before_the_limit_input() -> None:
    """Order (D132, as D2 for the direction-defined instructions): the instruction's input checks come first — a
    RatioNumerator of 0 with the negative limit ON is 5420, not 6444."""
    c = _rig(NEG_ON)
    fb = c.fb("MC_GearIn", Execute=False, **{**DIRECTIONLESS["MC_GearIn"], "RatioNumerator": 0})
    _assert_refused_at_the_edge(c, fb, 0x5420)


def test_reset_move_off_the_limit_then_the_gear_starts() -> None:
    """The manual's remedy (seed 000 line 21301): reset the error, move in the positive direction off the negative
    limit; then MC_GearIn starts."""
    c = _rig(NEG_ON)
    gear = c.fb("MC_GearIn", Execute=False, **DIRECTIONLESS["MC_GearIn"])
    _assert_refused_at_the_edge(c, gear, 0x6444)
    rs = c.fb("MC_Reset", Axis=S, Execute=True)
    step_until(c, rs, "Done")
    assert _slave(c).state == AxisState.Standstill
    off = c.fb("MC_MoveRelative", Axis=S, Execute=True, Distance=10.0, Velocity=50.0, Acceleration=1000.0,
               Deceleration=1000.0)
    step_until(c, off, "Done", limit=2000)
    assert not c.publish().mc["drv"][_slave(c).i] & (1 << 4), "DrvStatus.N_OT is OFF at 10 mm"
    c.set_inputs(gear.id, {"Execute": False})
    c.step(1)
    c.set_inputs(gear.id, {"Execute": True})
    c.step(1)
    assert gear.Busy and not gear.Error
    step_until(c, gear, "InGear", limit=2000)
    assert _slave(c).state == AxisState.Synchronized


# ---------------------------------------------------------------------------------------------------- counter-cases
@pytest.mark.parametrize("name", list(DIRECTIONLESS))
def test_directionless_instruction_starts_with_the_limit_inputs_off(name: str) -> None:
    """Counter-case: both limit switches fitted but OFF → Execute↑ in period k gives Busy in period k, no error, the
    instruction becomes Active and the slave takes the instruction's state."""
    c = _rig(BOTH_OFF)
    fb = c.fb(name, Execute=False, **DIRECTIONLESS[name])
    c.step(1)
    c.set_inputs(fb.id, {"Execute": True})
    c.step(1)
    assert fb.Busy and not fb.Error, fb.outputs_json()
    step_until(c, fb, "Active", limit=10)
    assert not fb.Error and _slave(c).error_code == 0
    assert _slave(c).state == STARTED_STATE.get(name, AxisState.Synchronized)


@pytest.mark.parametrize(("sensors", "name", "inputs", "code"), [
    pytest.param(NEG_ON, "MC_MoveVelocity", {**MOVE, "Direction": "_mcPositiveDirection"}, 0,
                 id="MoveVelocity-away-from-negative-starts"),
    pytest.param(NEG_ON, "MC_MoveRelative", {**MOVE, "Distance": 10.0}, 0,
                 id="MoveRelative-away-from-negative-starts"),
    pytest.param(NEG_ON, "MC_TorqueControl", {"Torque": 10.0, "Velocity": 5.0, "Direction": "_mcPositiveDirection"},
                 0, id="TorqueControl-positive-with-negative-on-starts"),
    pytest.param(NEG_ON, "MC_MoveRelative", {**MOVE, "Distance": -1.0}, 0x6444,
                 id="MoveRelative-towards-negative-6444"),
    pytest.param(NEG_ON, "MC_TorqueControl", {"Torque": 10.0, "Velocity": 5.0, "Direction": "_mcNegativeDirection"},
                 0x6444, id="TorqueControl-negative-6444"),
    pytest.param(POS_ON, "MC_MoveVelocity", {**MOVE, "Direction": "_mcNegativeDirection"}, 0,
                 id="MoveVelocity-away-from-positive-starts"),
    pytest.param(POS_ON, "MC_MoveVelocity", {**MOVE, "Direction": "_mcPositiveDirection"}, 0x6443,
                 id="MoveVelocity-towards-positive-6443"),
])
def test_direction_defined_instructions_are_unchanged(sensors: dict[str, float], name: str, inputs: dict[str, Any],
                                                      code: int) -> None:
    """Counter-case: an instruction with a direction (A-1 6443/6444 first clause) is refused only towards the active
    limit; away from it it starts (MC_TorqueControl keeps its Direction input, D132)."""
    c = _rig(sensors)
    fb = c.fb(name, Axis=S, Execute=False, **inputs)
    if code:
        _assert_refused_at_the_edge(c, fb, code)
        return
    c.step(1)
    c.set_inputs(fb.id, {"Execute": True})
    c.step(1)
    assert fb.Busy and not fb.Error, fb.outputs_json()
    assert _slave(c).error_code == 0


# ---------------------------------------------------------------------------------------------------- multi-execution
@pytest.mark.parametrize("buffer_mode", [
    pytest.param("_mcAborting", id="aborting"),
    pytest.param("_mcBuffered", id="buffered"),
])
def test_gear_started_onto_a_motion_away_from_the_limit_is_6444(buffer_mode: str) -> None:
    """Multi-execution is a new start: with the negative limit ON the slave moves away from it (MC_MoveVelocity +,
    1 mm/s: still on the switch for ~5 s); MC_GearIn started onto it, Aborting or Buffered, is 6444 in the period
    of its Execute↑, and the error stop aborts the running MC_MoveVelocity (D132)."""
    c = _rig(NEG_ON)
    away = c.fb("MC_MoveVelocity", Axis=S, Execute=True, Velocity=1.0, Acceleration=100.0, Deceleration=100.0)
    step_until(c, away, "InVelocity", limit=100)
    assert _slave(c).state == AxisState.Continuous and not away.Error
    gear = c.fb("MC_GearIn", Execute=False, BufferMode=buffer_mode, **DIRECTIONLESS["MC_GearIn"])
    c.step(1)
    c.set_inputs(gear.id, {"Execute": True})
    c.step(1)
    assert gear.Error and gear.ErrorID == 0x6444 and not gear.Busy, gear.outputs_json()
    assert _slave(c).state == AxisState.ErrorStop and _slave(c).error_code == 0x6444
    assert away.CommandAborted and not away.Error


def _actuate_negative_limit(c: Controller) -> None:
    """The negative limit switch of the slave's mechanism turns ON where the slave is (the switch is moved beyond
    it, as an obstacle pressing it would): the drive reports N_OT from the next period."""
    drives = c.network.drives
    _, row = c.network.device_model(1)
    drives.sensors.neg_limit[row] = (float(c.mc.cmd_pos[_slave(c).i]) + 100.0) * PPU
    drives.sensors_changed()
    c.step(2)
    assert c.publish().mc["drv"][_slave(c).i] & (1 << 4), "DrvStatus.N_OT"


def test_reexecution_is_not_a_new_start_but_a_second_instance_is() -> None:
    """MC_GearIn runs (slave moving + with the master); the negative limit input turns ON. The slave moves away from
    it, so no 6454. Re-executing the running instance (new ratio) is not a start: no error, the new ratio applies.
    A second MC_GearIn instance is a start: 6444 in its Execute↑ period, the first ends CommandAborted (D132)."""
    c = _rig(BOTH_OFF)
    gear = c.fb("MC_GearIn", Execute=True, **DIRECTIONLESS["MC_GearIn"])
    step_until(c, gear, "InGear", limit=2000)
    _actuate_negative_limit(c)
    assert gear.Active and not gear.Error and _slave(c).error_code == 0
    c.set_inputs(gear.id, {"Execute": False})
    c.step(1)
    c.set_inputs(gear.id, {"Execute": True, "RatioNumerator": 20000})
    c.step(1)
    assert gear.Active and not gear.Error, gear.outputs_json()
    step_until(c, gear, "InGear", limit=2000)
    assert float(c.mc.cmd_vel[_slave(c).i]) == pytest.approx(2 * MASTER_VEL)
    assert _slave(c).error_code == 0 and _slave(c).state == AxisState.Synchronized
    second = c.fb("MC_GearIn", Execute=False, **DIRECTIONLESS["MC_GearIn"])
    c.step(1)
    c.set_inputs(second.id, {"Execute": True})
    c.step(1)
    assert second.Error and second.ErrorID == 0x6444 and not second.Busy, second.outputs_json()
    assert gear.CommandAborted and not gear.Active
    assert _slave(c).state == AxisState.ErrorStop and _slave(c).error_code == 0x6444


def test_cam_buffered_onto_a_running_cam_is_6444() -> None:
    """MC_CamIn Buffered onto a running MC_CamIn (the only Buffered onto synchronized control) with the negative
    limit input ON is refused at its Execute↑ — not when it would take over at EndOfProfile (D132)."""
    c = _rig(BOTH_OFF)
    cam = c.fb("MC_CamIn", Execute=True, StartPosition=1.0, MasterStartDistance=1.0, **DIRECTIONLESS["MC_CamIn"])
    step_until(c, cam, "InSync", limit=2000)  # the master passes 1 mm: the slave cams (moving +)
    _actuate_negative_limit(c)
    assert cam.Active and not cam.Error
    nxt = c.fb("MC_CamIn", Execute=False, BufferMode="_mcBuffered", **DIRECTIONLESS["MC_CamIn"])
    c.step(1)
    c.set_inputs(nxt.id, {"Execute": True})
    c.step(1)
    assert nxt.Error and nxt.ErrorID == 0x6444 and not nxt.Busy, nxt.outputs_json()
    assert cam.CommandAborted and _slave(c).state == AxisState.ErrorStop


# ------------------------------------------------------------------------------------- 6442 (position overflow)
@pytest.mark.parametrize("sign", [1, -1], ids=["overflow", "underflow"])
@pytest.mark.parametrize("name", list(DIRECTIONLESS))
def test_direction_less_instruction_in_position_overflow_is_6442(name: str, sign: int) -> None:
    """A-1 #144 (seed 000 line 21275, basics L1154): 6442 when, while the command position is in overflow/underflow,
    "an instruction of indeterminate direction (synchronization functions, torque control)" is executed — the same
    instructions D132 counts as direction-less. The slave is driven to the edge of the 40-bit pulse range by a
    velocity move (overflow itself is no error), then the instruction's Execute↑ gives 6442 in that period."""
    c = _rig({})
    run_into_overflow(c, S, sign, PPU)
    slave = _slave(c)
    assert slave.state == AxisState.Standstill and not slave.error_code
    assert c.mc.ovf[slave.i] == sign
    fb = c.fb(name, Execute=False, **DIRECTIONLESS[name])
    c.step(1)
    c.set_inputs(fb.id, {"Execute": True})
    c.step(1)
    assert fb.Error and fb.ErrorID == 0x6442 and not fb.Busy, (fb.ErrorID, fb.Busy)
    assert slave.state == AxisState.ErrorStop and slave.error_code == 0x6442
