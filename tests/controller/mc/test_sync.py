"""Synchronized control: MC_CamIn / MC_CamOut, MC_GearIn / MC_GearOut, MC_GearInPos, MC_MoveLink, MC_CombineAxes.

Spec: omron-axis-instructions.md MC_CamIn (seed 000 line 6635: start sequence, absolute positions example with
StartPosition 60, InCam/InSync examples, Periodic, EndOfProfile, ReferenceType, re-execution, BufferMode),
MC_CamOut (line 8217), MC_GearIn (line 8324), MC_GearInPos (line 8880, sample program), MC_GearOut (line 9429),
MC_MoveLink (line 9537), MC_CombineAxes (line 10194); error codes omron-mc-basics.md A-1 (#23–27, #40, #84).

The rig: MC_Axis000 a virtual servo master in Rotary Mode 0–360°, MC_Axis001 the slave (linear, mm). The kernel is
stepped period by period (1 ms); positions are compared every period.
"""

from __future__ import annotations

import copy

import numpy as np
import pytest

from mcstudio.controller.kernel import Controller
from mcstudio.controller.mc.cam.table import CamTable
from mcstudio.controller.mc.enums import AxisState
from mcstudio.project.models import AxisConfig, Project
from tests.conftest import MM_AXIS, power_on, step_until

M, S = "MC_Axis000", "MC_Axis001"
# the manual's absolute-position example (MC_CamIn "Absolute positions"): StartPosition 60 on a 0–360° master
EXAMPLE = ([0.0, 60.0, 120.0, 180.0, 240.0, 300.0, 360.0], [0.0, 200.0, 100.0, 300.0, 100.0, 200.0, 0.0])
# the manual's InCam/InSync example table: straight segments (0,0) → (80,80) → (120,200) → (360,360)
STEPS = ([0.0, 80.0, 120.0, 360.0], [0.0, 80.0, 200.0, 360.0])


def _rig(*, slave_type: str = "_mcVirServo", slave_rotary: bool = False, master_number: int = 0,
         cams: dict[str, CamTable] | None = None) -> Controller:
    rot = copy.deepcopy(MM_AXIS)
    rot["UnitConversion"].update(UnitDisplay="_mcDeg", WorkTravelDistancePerMotorRotation=360.0)
    rot["Operation"].update(MaxVel=100000.0, MaxAcc=1e6, MaxDec=1e6)
    rot["PosCount"] = {"CountMode": "_mcCountModeRotary", "ModuloMinPosVal": 0.0, "ModuloMaxPosVal": 360.0}
    lin = copy.deepcopy(rot if slave_rotary else MM_AXIS)
    lin["Operation"].update(MaxVel=100000.0, MaxAcc=1e6, MaxDec=1e6)
    lin["Limit"] = {"PosiSwLimit": 1e7, "NegaSwLimit": -1e7}
    master = AxisConfig(name=M, number=master_number, type="_mcVirServo", parameters=rot)
    slave = AxisConfig(name=S, number=1 - master_number, type=slave_type,
                       node_address=1 if slave_type == "_mcServo" else None, parameters=lin)
    axes = [master, slave] if master_number == 0 else [slave, master]
    tables = {"CamProfile0": CamTable.from_points(*EXAMPLE), "Steps": CamTable.from_points(*STEPS)}
    tables.update(cams or {})
    c = Controller(Project(name="sync", axes=axes), cams=tables)
    power_on(c, M)
    power_on(c, S)
    return c


def _run_master(c: Controller, velocity: float = 360.0, acc: float = 0.0) -> object:
    mv = c.fb("MC_MoveVelocity", Axis=M, Execute=True, Velocity=velocity, Acceleration=acc, Deceleration=acc)
    step_until(c, mv, "InVelocity")
    return mv


def _pos(c: Controller, name: str) -> float:
    ax = c.mc.by_name[name]
    return float(c.mc.cmd_pos[ax.i])


def _ring(x: float) -> float:
    return x % 360.0


# ---------------------------------------------------------------------------------------------------- MC_CamIn
def test_periodic_cam_follows_the_rotary_master_every_period() -> None:
    """The manual's example: StartPosition 60, table (0,0)…(360,0). Master 60/120/180/240/300/360 ↔ slave
    0/200/100/300/100/200/0 + the slave position at the table start (MC_CamIn "Absolute positions"). With
    _mcLatestCommand the slave uses the master command of the same period, so the relation holds exactly, every
    period, over several master turns; EndOfProfile pulses for one period at each cycle end."""
    c = _rig()
    _run_master(c)  # 360°/s: 0.36° per period
    cam = c.fb("MC_CamIn", Master=M, Slave=S, CamTable="CamProfile0", Execute=True, Periodic=True,
               StartMode="_mcRelativePosition", StartPosition=60.0, ReferenceType="_mcLatestCommand")
    step_until(c, cam, "InSync")
    m0 = _pos(c, M)
    assert _ring(m0) == pytest.approx(60.0, abs=0.36 + 1e-9), "InSync when the master passes StartPosition (60°)"
    assert cam.InCam and cam.Active and c.mc.axes[1].state == AxisState.Synchronized
    p, d = np.array(EXAMPLE[0]), np.array(EXAMPLE[1])
    pulses, pulse_cycles, prev_eop = 0, [], False
    for _ in range(3 * 1000 + 10):  # three master turns
        c.step(1, publish=False)
        m = _pos(c, M)
        phase = (m - 60.0) % 360.0
        assert _pos(c, S) == pytest.approx(np.interp(phase, p, d), abs=1e-6), f"master {m}"
        if cam.EndOfProfile:
            assert not prev_eop, "EndOfProfile is a one-period pulse"
            pulses += 1
            pulse_cycles.append(c.cycle)
            assert phase < 0.36 + 1e-9, "EndOfProfile in the period the cycle end is output"
        prev_eop = cam.EndOfProfile
    assert pulses == 3
    assert np.diff(pulse_cycles).tolist() == [1000, 1000]
    assert cam.Busy and cam.Active and cam.InCam and cam.InSync and not cam.Error


@pytest.mark.parametrize(
    ("mode", "start", "msd", "in_cam", "in_sync"),
    [
        ("_mcRelativePosition", 0.0, 80.0, 0.0, 80.0),
        ("_mcRelativePosition", 40.0, 0.0, 40.0, 40.0),
        ("_mcRelativePosition", 40.0, 80.0, 40.0, 120.0),
        ("_mcAbsolutePosition", 40.0, 80.0, 40.0, 80.0),
    ],
)
def test_incam_and_insync_where_the_manual_draws_them(mode: str, start: float, msd: float, in_cam: float,
                                                      in_sync: float) -> None:
    """MC_CamIn InCam/InSync examples (table (0,0)→(80,80)→(120,200)→(360,360), Periodic): InCam when the master
    passes StartPosition, InSync when it passes the cam start position (absolute MSD, or StartPosition + MSD)."""
    c = _rig()
    move = c.fb("MC_MoveAbsolute", Axis=M, Execute=True, Position=300.0, Velocity=1000.0, Acceleration=0.0,
                Deceleration=0.0)
    step_until(c, move, "Done")
    _run_master(c)
    cam = c.fb("MC_CamIn", Master=M, Slave=S, CamTable="Steps", Execute=True, Periodic=True, StartMode=mode,
               StartPosition=start, MasterStartDistance=msd, ReferenceType="_mcLatestCommand")
    s0 = _pos(c, S)
    step_until(c, cam, "InCam")
    assert _ring(_pos(c, M) - in_cam + 180.0) - 180.0 == pytest.approx(0.0, abs=0.36 + 1e-9)
    if in_sync == in_cam:
        assert cam.InSync, "both in the same period"
    else:
        assert not cam.InSync
        step_until(c, cam, "InSync")
    assert _ring(_pos(c, M) - in_sync + 180.0) - 180.0 == pytest.approx(0.0, abs=0.36 + 1e-9)
    assert _pos(c, S) != s0 or in_sync == start, "the slave starts camming at InSync"


def test_slave_stays_stopped_until_insync() -> None:
    c = _rig()
    _run_master(c)
    s0 = _pos(c, S)
    cam = c.fb("MC_CamIn", Master=M, Slave=S, CamTable="Steps", Execute=True, Periodic=True,
               StartMode="_mcRelativePosition", StartPosition=40.0, MasterStartDistance=80.0)
    while not cam.InSync:
        c.step(1, publish=False)
        if not cam.InSync:
            assert _pos(c, S) == s0
    # starting mid-table: the slave jumps to the displacement of the phase (the manual's warning)
    assert _pos(c, S) - s0 == pytest.approx(np.interp(80.0, *STEPS), abs=1.0)


def test_scaling_and_offsets() -> None:
    """slave = reference + SlaveScaling · table((master − StartPosition − MasterOffset) / MasterScaling) +
    SlaveOffset (decision D38, the manual gives figures only)."""
    c = _rig()
    _run_master(c)
    cam = c.fb("MC_CamIn", Master=M, Slave=S, CamTable="Steps", Execute=True, Periodic=True,
               StartMode="_mcRelativePosition", StartPosition=10.0, MasterScaling=2.0, SlaveScaling=0.5,
               MasterOffset=0.0, SlaveOffset=3.0, ReferenceType="_mcLatestCommand")
    step_until(c, cam, "InSync")
    s_ref = _pos(c, S) - 3.0 - 0.5 * np.interp((_pos(c, M) - 10.0) / 2.0, *STEPS)
    for _ in range(500):
        c.step(1, publish=False)
        phase = (_pos(c, M) - 10.0) / 2.0
        assert phase < 360.0
        assert _pos(c, S) == pytest.approx(s_ref + 0.5 * np.interp(phase, *STEPS) + 3.0, abs=1e-6)


def test_feeding_cam_advances_by_the_end_distance_each_cycle() -> None:
    """Periodic with end distance ≠ start distance (a feeding cam): the slave advances by the end distance every
    cycle (MC_CamIn "Periodic", decision D38)."""
    c = _rig()
    _run_master(c)
    cam = c.fb("MC_CamIn", Master=M, Slave=S, CamTable="Steps", Execute=True, Periodic=True,
               ReferenceType="_mcLatestCommand")
    step_until(c, cam, "InSync")
    s0 = _pos(c, S) - np.interp(_ring(_pos(c, M)), *STEPS)
    base = 360.0 * np.floor(_pos(c, M) / 360.0)  # the StartPosition crossing the cam started from
    for _ in range(2500):
        c.step(1, publish=False)
        m = _pos(c, M)
        turns = np.floor((m - base) / 360.0)
        assert _pos(c, S) == pytest.approx(s0 + 360.0 * turns + np.interp(_ring(m), *STEPS), abs=1e-6)


def test_non_periodic_cam_ends_with_endofprofile_and_no_done() -> None:
    """Periodic FALSE: after the end point Busy, Active, InCam and InSync drop in the period EndOfProfile pulses;
    MC_CamIn has no Done; the slave stops (Standstill)."""
    c = _rig()
    _run_master(c)
    cam = c.fb("MC_CamIn", Master=M, Slave=S, CamTable="CamProfile0", Execute=True, Periodic=False,
               StartMode="_mcRelativePosition", StartPosition=60.0, ReferenceType="_mcLatestCommand")
    step_until(c, cam, "InSync")
    step_until(c, cam, "EndOfProfile")
    assert not (cam.Busy or cam.Active or cam.InCam or cam.InSync or cam.CommandAborted or cam.Error)
    assert "Done" not in cam.outputs_json()
    end = _pos(c, S)
    c.step(1)
    assert not cam.EndOfProfile
    assert c.mc.axes[1].state == AxisState.Standstill
    c.step(100)
    assert _pos(c, S) == end, "the slave no longer follows"


def test_camout_decelerates_the_slave_and_aborts_camin() -> None:
    """MC_CamOut: MC_CamIn CommandAborted, the slave decelerates with Deceleration from its velocity, Done at
    velocity 0 (Synchronized → Discrete → Standstill, A-3.4 *6); the master is not affected."""
    c = _rig()
    _run_master(c)
    cam = c.fb("MC_CamIn", Master=M, Slave=S, CamTable="Steps", Execute=True, Periodic=True,
               ReferenceType="_mcLatestCommand")
    step_until(c, cam, "InSync")
    c.step(10)
    v0 = float(c.mc.cmd_vel[1])
    assert v0 == pytest.approx(360.0, rel=1e-6)  # slope 1 in the first segment at 360°/s
    out = c.fb("MC_CamOut", Slave=S, Execute=True, Deceleration=3600.0)
    c.step(1)
    assert cam.CommandAborted and not cam.Busy and not cam.InSync
    assert out.Busy and not out.Done
    assert c.mc.axes[1].state == AxisState.Discrete
    n = step_until(c, out, "Done")
    assert n == pytest.approx(100, abs=2), "360 u/s at 3600 u/s² stops in 0.1 s"
    assert float(c.mc.cmd_vel[1]) == 0.0
    c.step(1)
    assert c.mc.axes[1].state == AxisState.Standstill
    assert float(c.mc.cmd_vel[0]) == pytest.approx(360.0), "the master keeps moving"


def test_camout_without_camin_is_synchronization_stopped() -> None:
    c = _rig()
    out = c.fb("MC_CamOut", Slave=S, Execute=True, Deceleration=100.0)
    c.step(1)
    assert out.Error and out.ErrorID == 0x543A
    assert c.mc.axes[1].state == AxisState.ErrorStop


def test_mc_stop_on_the_slave_aborts_the_cam_and_master_error_does_not() -> None:
    """MC_Stop on the slave ends the synchronization (CommandAborted); an error of the master does not: the cam
    keeps following the (stopping) master (MC_CamIn "Slave axis error / Master axis error")."""
    c = _rig()
    _run_master(c)
    cam = c.fb("MC_CamIn", Master=M, Slave=S, CamTable="Steps", Execute=True, Periodic=True,
               ReferenceType="_mcLatestCommand")
    step_until(c, cam, "InSync")
    stop = c.fb("MC_ImmediateStop", Axis=M, Execute=True)
    c.step(5)
    assert stop.Done and c.mc.axes[0].state == AxisState.ErrorStop
    assert cam.Busy and cam.InSync and not cam.CommandAborted, "a master error does not end camming"
    c.fb("MC_Stop", Axis=S, Execute=True, Deceleration=1000.0)
    c.step(1)
    assert cam.CommandAborted and not cam.Busy


def test_reexecution_switches_the_cam_table() -> None:
    """Re-execution only switches the cam table (InCam/InSync keep their states); another changed input is the
    manual's re-execution error (5463 SlaveOffset)."""
    c = _rig(cams={"Double": CamTable.from_points([0.0, 360.0], [0.0, 720.0])})
    _run_master(c)
    cam = c.fb("MC_CamIn", Master=M, Slave=S, CamTable="Steps", Execute=True, Periodic=True,
               ReferenceType="_mcLatestCommand")
    step_until(c, cam, "InSync")
    c.step(20)
    c.set_inputs(cam.id, {"Execute": False})
    c.step(1)
    c.set_inputs(cam.id, {"Execute": True, "CamTable": "Double"})
    c.step(1)
    assert cam.InCam and cam.InSync and cam.Busy and not cam.Error
    c.step(1)
    assert float(c.mc.cmd_vel[1]) == pytest.approx(720.0, rel=1e-6), "slope 2 of the new table"
    c.set_inputs(cam.id, {"Execute": False})
    c.step(1)
    c.set_inputs(cam.id, {"Execute": True, "SlaveOffset": 5.0})
    c.step(1)
    assert cam.Error and cam.ErrorID == 0x5463


def test_buffered_camin_takes_over_at_the_end_of_the_cycle() -> None:
    """Buffered onto a periodic MC_CamIn: the running cam finishes its cycle, then the buffered one waits for its
    StartPosition (slave stopped until InSync). Blending: it starts at once from where the first ended."""
    c = _rig()
    _run_master(c)
    cam1 = c.fb("MC_CamIn", Master=M, Slave=S, CamTable="Steps", Execute=True, Periodic=True,
                ReferenceType="_mcLatestCommand")
    step_until(c, cam1, "InSync")
    c.step(100)
    cam2 = c.fb("MC_CamIn", Master=M, Slave=S, CamTable="CamProfile0", Execute=True, Periodic=True,
                StartMode="_mcRelativePosition", StartPosition=60.0, BufferMode="_mcBuffered",
                ReferenceType="_mcLatestCommand")
    c.step(1)
    assert cam2.Busy and not cam2.Active and cam1.Active
    step_until(c, cam1, "EndOfProfile")
    assert not cam1.Busy and not cam1.CommandAborted
    assert cam2.Active and not cam2.InCam
    held = _pos(c, S)
    step_until(c, cam2, "InSync")
    assert _ring(_pos(c, M)) == pytest.approx(60.0, abs=0.36 + 1e-9)
    assert held == pytest.approx(_pos(c, S) - np.interp(_ring(_pos(c, M)) - 60.0, *EXAMPLE), abs=1e-6)

    c2 = _rig()
    _run_master(c2)
    a = c2.fb("MC_CamIn", Master=M, Slave=S, CamTable="Steps", Execute=True, Periodic=False,
              ReferenceType="_mcLatestCommand")
    step_until(c2, a, "InSync")
    b = c2.fb("MC_CamIn", Master=M, Slave=S, CamTable="Steps", Execute=True, Periodic=True,
              StartPosition=200.0, BufferMode="_mcBlendingLow", ReferenceType="_mcLatestCommand")
    step_until(c2, a, "EndOfProfile")
    end = _pos(c2, S)
    assert b.Active and b.InSync, "blending: InSync at once, StartPosition ignored"
    c2.step(1)
    assert _pos(c2, S) == pytest.approx(end + np.interp(0.36, *STEPS), abs=1e-6), "continues from the end point"


@pytest.mark.parametrize(
    ("inputs", "code"),
    [
        ({"Master": S}, 0x5436),
        ({"CamTable": "NoSuchTable"}, 0x5439),
        ({"MasterScaling": 0.0}, 0x5428),
        ({"SlaveScaling": -1.0}, 0x5429),
        ({"StartMode": 7}, 0x5471),
        ({"Direction": 1}, 0x542E),
        ({"CamTransition": 1}, 0x5490),
        ({"BufferMode": 9}, 0x542B),
        ({"ReferenceType": 5}, 0x5430),
    ],
)
def test_camin_input_errors(inputs: dict[str, object], code: int) -> None:
    c = _rig()
    args = {"Master": M, "Slave": S, "CamTable": "Steps", "Execute": True, **inputs}
    cam = c.fb("MC_CamIn", **args)
    c.step(1)
    assert cam.Error and cam.ErrorID == code
    assert not cam.Busy
    assert c.mc.axes[1].state == AxisState.ErrorStop
    assert any(e.code == f"{code:04X}0000" for e in c.events.list())


def test_latest_command_needs_ascending_axis_numbers() -> None:
    """_mcLatestCommand with the master's axis number above the slave's: 5438 (A-1 #25)."""
    c = _rig(master_number=1)
    cam = c.fb("MC_CamIn", Master=M, Slave=S, CamTable="Steps", Execute=True, ReferenceType="_mcLatestCommand")
    c.step(1)
    assert cam.Error and cam.ErrorID == 0x5438


def test_command_reference_uses_the_previous_period_and_the_drive_follows() -> None:
    """_mcCommand: the slave uses the master command position calculated in the previous period (MC_CamIn
    ReferenceType); a servo slave over EtherCAT follows its command through the drive model."""
    c = _rig(slave_type="_mcServo")
    _run_master(c)
    cam = c.fb("MC_CamIn", Master=M, Slave=S, CamTable="Steps", Execute=True, Periodic=True,
               ReferenceType="_mcCommand")
    step_until(c, cam, "InSync")

    def law(m: float) -> float:
        return 360.0 * np.floor(m / 360.0) + np.interp(_ring(m), *STEPS)

    m_prev = _pos(c, M)
    c.step(1, publish=False)
    s_ref = _pos(c, S) - law(m_prev)
    for _ in range(300):
        m_prev = _pos(c, M)
        c.step(1, publish=False)
        assert _pos(c, S) == pytest.approx(s_ref + law(m_prev), abs=1e-6)
        assert _pos(c, S) != pytest.approx(s_ref + law(_pos(c, M)), abs=1e-6), "not this period's master"
    assert abs(float(c.mc.act_pos[1]) - _pos(c, S)) < 5.0, "the drive follows the slave command"


# ---------------------------------------------------------------------------------------------------- gears
def test_gearin_catches_up_then_follows_the_master_increments() -> None:
    """MC_GearIn ratio 1:2 with Acceleration: Catching phase (ramp to master velocity × ratio), then InGear and the
    slave moves exactly ratio × the master's increments (MC_GearIn functional rules)."""
    c = _rig()
    _run_master(c, velocity=360.0)
    gear = c.fb("MC_GearIn", Master=M, Slave=S, Execute=True, RatioNumerator=1, RatioDenominator=2,
                Acceleration=1800.0, Deceleration=1800.0, ReferenceType="_mcLatestCommand")
    c.step(1)
    assert gear.Busy and not gear.Active and not gear.InGear
    n = step_until(c, gear, "InGear")
    assert n == pytest.approx(100, abs=2), "180 u/s at 1800 u/s²: 0.1 s of catching"
    assert float(c.mc.cmd_vel[1]) == pytest.approx(180.0, rel=1e-6)
    m0, s0 = _pos(c, M), _pos(c, S)
    for _ in range(300):
        c.step(1, publish=False)
        assert _pos(c, S) - s0 == pytest.approx(0.5 * (_pos(c, M) - m0), abs=1e-9)
    out = c.fb("MC_GearOut", Slave=S, Execute=True, Deceleration=1800.0)
    c.step(1)
    assert gear.CommandAborted and not gear.InGear and not gear.Busy
    step_until(c, out, "Done")
    assert float(c.mc.cmd_vel[1]) == 0.0


def test_gearin_negative_ratio_and_step_without_ramp() -> None:
    c = _rig()
    _run_master(c, velocity=360.0)
    gear = c.fb("MC_GearIn", Master=M, Slave=S, Execute=True, RatioNumerator=-2, RatioDenominator=1,
                ReferenceType="_mcLatestCommand")
    step_until(c, gear, "InGear")
    c.step(1)
    assert float(c.mc.cmd_vel[1]) == pytest.approx(-720.0, rel=1e-6)


def test_gearin_reexecution_changes_the_ratio() -> None:
    c = _rig()
    _run_master(c, velocity=360.0)
    gear = c.fb("MC_GearIn", Master=M, Slave=S, Execute=True, RatioNumerator=1, RatioDenominator=1,
                ReferenceType="_mcLatestCommand")
    step_until(c, gear, "InGear")
    c.set_inputs(gear.id, {"Execute": False})
    c.step(1)
    c.set_inputs(gear.id, {"Execute": True, "RatioNumerator": 3})
    c.step(2)
    assert gear.InGear and not gear.Error
    assert float(c.mc.cmd_vel[1]) == pytest.approx(1080.0, rel=1e-6)


def test_other_instructions_onto_gearin_only_aborting() -> None:
    """Other instructions onto MC_GearIn: Aborting only; Buffered → the other instruction errors (543C)."""
    c = _rig()
    _run_master(c)
    gear = c.fb("MC_GearIn", Master=M, Slave=S, Execute=True, ReferenceType="_mcLatestCommand")
    step_until(c, gear, "InGear")
    mv = c.fb("MC_MoveAbsolute", Axis=S, Execute=True, Position=0.0, Velocity=10.0, Acceleration=100.0,
              Deceleration=100.0, BufferMode="_mcBuffered")
    c.step(1)
    assert mv.Error and mv.ErrorID == 0x543C
    assert gear.CommandAborted, "the axis error-stops: the gear is aborted"


def test_gearinpos_sample_program_synchronizes_at_the_given_positions() -> None:
    """The manual's sample: master rotary 90°/s, ratio 1:2, MasterSyncPosition 300, SlaveSyncPosition 200,
    Velocity 180, Acc/Dec 180. StartSync at start, InSync when the master is at 300 and the slave at 200; then
    geared."""
    c = _rig(slave_rotary=True)
    _run_master(c, velocity=90.0)
    gp = c.fb("MC_GearInPos", Master=M, Slave=S, Execute=True, RatioNumerator=1, RatioDenominator=2,
              ReferenceType="_mcLatestCommand", MasterSyncPosition=300.0, SlaveSyncPosition=200.0, Velocity=180.0,
              Acceleration=180.0, Deceleration=180.0)
    c.step(2)
    assert gp.StartSync and gp.Active and not gp.InSync
    step_until(c, gp, "InSync")
    assert _ring(_pos(c, M)) == pytest.approx(300.0, abs=0.09 + 1e-9)
    # the slave is where the sync point puts it for this master position
    assert _ring(_pos(c, S)) == pytest.approx(200.0 + 0.5 * (_ring(_pos(c, M)) - 300.0), abs=1e-6)
    m0, s0 = _pos(c, M), _pos(c, S)
    for _ in range(200):
        c.step(1, publish=False)
        assert _pos(c, S) - s0 == pytest.approx(0.5 * (_pos(c, M) - m0), abs=1e-9)
    assert float(c.mc.cmd_vel[1]) == pytest.approx(45.0, rel=1e-6)


def test_gearinpos_refusals() -> None:
    """5476 master velocity 0 at start; 5447 Velocity not above master velocity × ratio (A-1 #84, #40)."""
    c = _rig()
    gp = c.fb("MC_GearInPos", Master=M, Slave=S, Execute=True, MasterSyncPosition=100.0, SlaveSyncPosition=10.0,
              Velocity=100.0, Acceleration=100.0, Deceleration=100.0)
    c.step(2)
    assert gp.Error and gp.ErrorID == 0x5476
    c2 = _rig()
    _run_master(c2, velocity=360.0)
    gp2 = c2.fb("MC_GearInPos", Master=M, Slave=S, Execute=True, MasterSyncPosition=100.0, SlaveSyncPosition=10.0,
                Velocity=300.0, Acceleration=100.0, Deceleration=100.0)
    c2.step(2)
    assert gp2.Error and gp2.ErrorID == 0x5447


def test_gearout_without_gear_is_synchronization_stopped() -> None:
    c = _rig()
    _run_master(c)
    cam = c.fb("MC_CamIn", Master=M, Slave=S, CamTable="Steps", Execute=True, Periodic=True)
    step_until(c, cam, "InSync")
    out = c.fb("MC_GearOut", Slave=S, Execute=True)
    c.step(1)
    assert out.Error and out.ErrorID == 0x543A


# ---------------------------------------------------------------------------------------------------- link, combine
def test_movelink_moves_the_slave_distance_over_the_master_distance() -> None:
    """MC_MoveLink: Ma = 100, Md = 100, M = 1000, S = 450: velocity ratio k = S / (Ma/2 + Mc + Md/2) = 0.5 in the
    constant section; Done when the master has travelled MasterDistance (MC_MoveLink table)."""
    c = _rig()
    _run_master(c, velocity=360.0)
    s0 = _pos(c, S)
    link = c.fb("MC_MoveLink", Master=M, Slave=S, Execute=True, SlaveDistance=450.0, MasterDistance=1000.0,
                MasterDistanceInACC=100.0, MasterDistanceInDEC=100.0, ReferenceType="_mcLatestCommand")
    c.step(1)
    m0 = _pos(c, M)
    assert link.InSync or link.Busy
    c.step(int(500 / 0.36))
    assert float(c.mc.cmd_vel[1]) == pytest.approx(180.0, rel=1e-6), "ratio 0.5 in the constant section"
    step_until(c, link, "Done")
    assert _pos(c, M) - m0 == pytest.approx(1000.0, abs=0.37)
    assert _pos(c, S) - s0 == pytest.approx(450.0, abs=1e-9)
    assert not link.InSync


def test_movelink_trigger_detection_in_controller_mode() -> None:
    """LinkOption _mcTriggerDetection with a controller-mode trigger: the slave waits (InSync FALSE) until the
    TriggerVariable rises, then links from the master position of that period (MC_MoveLink "LinkOption")."""
    c = _rig()
    _run_master(c, velocity=360.0)
    s0 = _pos(c, S)
    link = c.fb("MC_MoveLink", Master=M, Slave=S, Execute=True, SlaveDistance=100.0, MasterDistance=200.0,
                MasterDistanceInACC=50.0, MasterDistanceInDEC=50.0, LinkOption="_mcTriggerDetection",
                TriggerInput={"Mode": "_mcController", "LatchID": "_mcLatch1"}, ReferenceType="_mcLatestCommand")
    c.step(100)
    assert link.Active and not link.InSync and _pos(c, S) == s0, "waiting for the trigger"
    c.set_inputs(link.id, {"TriggerVariable": True})
    c.step(1)
    m0 = _pos(c, M)
    assert link.InSync
    step_until(c, link, "Done")
    assert _pos(c, S) - s0 == pytest.approx(100.0, abs=1e-9)
    assert _pos(c, M) - m0 == pytest.approx(200.0, abs=0.37)


def test_movelink_done_waits_for_in_position() -> None:
    """A servo slave with an in-position check time: the command arrives first, Done follows only when the feedback
    is within the in-position range (MC_MoveLink: "in-position check when the slave motion completes")."""
    c = _rig(slave_type="_mcServo")
    ax = c.mc.by_name[S]
    ax.params.Operation.InPosCheckTime = 500
    ax.params.Operation.InPosRange = 1e-4
    _run_master(c, velocity=360.0)
    s0 = _pos(c, S)
    link = c.fb("MC_MoveLink", Master=M, Slave=S, Execute=True, SlaveDistance=50.0, MasterDistance=100.0,
                ReferenceType="_mcLatestCommand")
    arrived = None
    for _ in range(2000):
        c.step(1, publish=False)
        if arrived is None and _pos(c, S) == pytest.approx(s0 + 50.0, abs=1e-12):
            arrived = c.cycle
            lag = abs(float(c.mc.act_pos[ax.i]) - _pos(c, S))
            assert lag > 1e-4 and not link.Done, "the feedback is still on its way"
        if link.Done:
            break
    assert arrived is not None and link.Done and c.cycle > arrived
    assert abs(float(c.mc.act_pos[ax.i]) - (s0 + 50.0)) <= 1e-4


def test_movelink_short_constant_section_is_5446() -> None:
    c = _rig()
    link = c.fb("MC_MoveLink", Master=M, Slave=S, Execute=True, SlaveDistance=10.0, MasterDistance=100.0,
                MasterDistanceInACC=60.0, MasterDistanceInDEC=60.0)
    c.step(1)
    assert link.Error and link.ErrorID == 0x5446


def test_combine_axes_adds_and_subtracts_the_relative_travel() -> None:
    p = copy.deepcopy(MM_AXIS)
    p["Limit"] = {"PosiSwLimit": 1e7, "NegaSwLimit": -1e7}
    axes = [AxisConfig(name=f"MC_Axis00{k}", number=k, type="_mcVirServo", parameters=p) for k in range(3)]
    c = Controller(Project(name="combine", axes=axes))
    for k in range(3):
        power_on(c, f"MC_Axis00{k}")
    comb = c.fb("MC_CombineAxes", Master="MC_Axis000", Auxiliary="MC_Axis001", Slave="MC_Axis002", Execute=True,
                CombineMode="_mcSubAxes")
    c.step(1)
    assert comb.InCombination and not comb.Active, "InCombination in the period output starts, Active next"
    c.step(1)
    assert comb.Active
    c.fb("MC_MoveRelative", Axis="MC_Axis000", Execute=True, Distance=30.0, Velocity=100.0, Acceleration=1000.0,
         Deceleration=1000.0)
    c.fb("MC_MoveRelative", Axis="MC_Axis001", Execute=True, Distance=12.0, Velocity=50.0, Acceleration=1000.0,
         Deceleration=1000.0)
    for _ in range(600):
        c.step(1, publish=False)
        assert c.mc.cmd_pos[2] == pytest.approx(c.mc.cmd_pos[0] - c.mc.cmd_pos[1], abs=1e-9)
    assert c.mc.cmd_pos[2] == pytest.approx(18.0)


def test_combine_axes_same_axis_errors() -> None:
    c = _rig()
    comb = c.fb("MC_CombineAxes", Master=M, Auxiliary=M, Slave=S, Execute=True, ReferenceTypeMaster="_mcFeedback",
                ReferenceTypeAuxiliary="_mcFeedback")
    c.step(1)
    assert comb.Error and comb.ErrorID == 0x5437


# ---------------------------------------------------------------------------------------------------- compensation
def test_phasing_shifts_the_master_phase_the_slave_sees() -> None:
    """MC_Phasing on a geared slave: the master does not move differently; the slave follows master + shift, the
    shift being a relative profile of PhaseShift at Velocity; Done when the whole shift is output (MC_Phasing)."""
    c = _rig()
    _run_master(c, velocity=360.0)
    gear = c.fb("MC_GearIn", Master=M, Slave=S, Execute=True, ReferenceType="_mcLatestCommand")
    step_until(c, gear, "InGear")
    m0, s0 = _pos(c, M), _pos(c, S)
    ph = c.fb("MC_Phasing", Master=M, Slave=S, Execute=True, PhaseShift=30.0, Velocity=100.0, Acceleration=1000.0,
              Deceleration=1000.0)
    c.step(1)
    assert ph.Busy and not ph.Done
    n = step_until(c, ph, "Done")
    assert n == pytest.approx(400, abs=3), "30 at 100 u/s with 1000 u/s² ramps: 0.4 s"
    assert float(c.mc.cmd_vel[0]) == pytest.approx(360.0), "the master is not affected"
    assert _pos(c, S) - s0 == pytest.approx(_pos(c, M) - m0 + 30.0, abs=1e-9)
    assert gear.InGear and gear.Busy and c.mc.axes[1].state == AxisState.Synchronized


def test_phasing_needs_a_running_synchronization_and_ends_with_it() -> None:
    c = _rig()
    ph = c.fb("MC_Phasing", Master=M, Slave=S, Execute=True, PhaseShift=5.0, Velocity=10.0)
    c.step(1)
    assert ph.Error and ph.ErrorID == 0x543A
    c2 = _rig()
    _run_master(c2)
    gear = c2.fb("MC_GearIn", Master=M, Slave=S, Execute=True)
    step_until(c2, gear, "InGear")
    ph2 = c2.fb("MC_Phasing", Master=M, Slave=S, Execute=True, PhaseShift=1000.0, Velocity=10.0)
    c2.step(5)
    assert ph2.Active
    c2.fb("MC_GearOut", Slave=S, Execute=True, Deceleration=1000.0)
    c2.step(1)
    assert ph2.CommandAborted and not ph2.Busy, "the synchronized instruction ended: CommandAborted"


def test_sync_offset_position_adds_the_offset_every_period() -> None:
    """MC_SyncOffsetPosition: the slave command = synchronized command + OffsetPosition (changed every period while
    Active); after the abort the last offset stays (MC_SyncOffsetPosition)."""
    c = _rig()
    _run_master(c, velocity=360.0)
    gear = c.fb("MC_GearIn", Master=M, Slave=S, Execute=True, ReferenceType="_mcLatestCommand")
    step_until(c, gear, "InGear")
    m0, s0 = _pos(c, M), _pos(c, S)
    off = c.fb("MC_SyncOffsetPosition", Axis=S, Execute=True, OffsetPosition=0.0)
    c.step(1)
    for k in range(1, 50):
        c.set_inputs(off.id, {"OffsetPosition": 0.1 * k})
        c.step(1, publish=False)
        assert _pos(c, S) - s0 == pytest.approx(_pos(c, M) - m0 + 0.1 * k, abs=1e-9)
        assert off.OutputtedOffsetPosition == pytest.approx(0.1 * k)
    assert off.Active
    second = c.fb("MC_SyncOffsetPosition", Axis=S, Execute=True, OffsetPosition=1.0)
    c.step(1)
    assert off.CommandAborted and second.Busy and not second.Active
    assert _pos(c, S) - s0 == pytest.approx(_pos(c, M) - m0 + 4.9 + 1.0, abs=1e-9), "the old offset stays"
    c.step(1)
    assert second.Active


# ---------------------------------------------------------------------------------------------------- cyclic
def test_sync_move_absolute_outputs_the_target_of_every_period() -> None:
    """MC_SyncMoveAbsolute: the target written in a period is the command of the next; a step beyond Maximum
    Velocity × period is saturated (the rest follows); InPosition when the feedback is within the in-position range
    of an unchanged target; Discrete; MC_Stop stops at once (MC_SyncMoveAbsolute rules)."""
    c = _rig()
    ax = c.mc.by_name[S]
    sm = c.fb("MC_SyncMoveAbsolute", Axis=S, Execute=True, Position=0.0)
    c.step(1)
    assert sm.Busy
    assert ax.state == AxisState.Discrete
    for k in range(1, 20):
        c.set_inputs(sm.id, {"Position": 0.5 * k})
        c.step(1, publish=False)
        assert _pos(c, S) == pytest.approx(0.5 * k)
    c.step(2)
    assert sm.InPosition and sm.Active
    vmax = ax.params.Operation.MaxVel  # 100000 u/s: 100 per period
    c.set_inputs(sm.id, {"Position": 1000.0})
    c.step(1)
    assert _pos(c, S) == pytest.approx(9.5 + vmax * 0.001), "velocity-saturated step"
    assert not sm.InPosition
    c.step(10)
    assert _pos(c, S) == pytest.approx(1000.0)
    c.fb("MC_Stop", Axis=S, Execute=True, Deceleration=10.0)
    c.step(1)
    assert sm.CommandAborted and float(c.mc.cmd_vel[1]) == 0.0


def test_sync_move_velocity_runs_the_drive_in_csv() -> None:
    """MC_SyncMoveVelocity on a servo axis over EtherCAT: the drive switches to CSV (6061h = 9), the target velocity
    of each period goes out in 60FFh (no ramp), the command position follows the feedback (`_mcCount`),
    InVelocity, Continuous; MC_Stop ends it back in CSP decelerating from the velocity (MC_SyncMoveVelocity, D47)."""
    c = _rig(slave_type="_mcServo")
    ax = c.mc.by_name[S]
    sv = c.fb("MC_SyncMoveVelocity", Axis=S, Execute=True, Velocity=50.0)
    step_until(c, sv, "InVelocity")
    assert ax.state == AxisState.Continuous and sv.Active
    assert int(c.mc.drv_mode[ax.i]) == 9, "the drive reports CSV"
    c.step(100)
    assert float(c.mc.act_vel[ax.i]) == pytest.approx(50.0, rel=1e-3)
    assert _pos(c, S) == pytest.approx(float(c.mc.act_pos[ax.i]) - 50.0 * 0.001, abs=1e-3), "Cmd = feedback"
    c.set_inputs(sv.id, {"Velocity": -20.0})
    c.step(3)
    assert float(c.mc.act_vel[ax.i]) == pytest.approx(-20.0, rel=1e-3), "a new value applies at once"
    stop = c.fb("MC_Stop", Axis=S, Execute=True, Deceleration=200.0)
    c.step(1)
    assert sv.CommandAborted and not sv.Busy
    n = step_until(c, stop, "Done")
    assert n == pytest.approx(100, abs=5), "from −20 u/s at 200 u/s²"
    c.step(5)
    assert int(c.mc.drv_mode[ax.i]) == 8, "back in CSP"


def test_sync_move_velocity_needs_60ffh() -> None:
    c = _rig(slave_type="_mcServo")
    ax = c.mc.by_name[S]
    c.mc.pdo_objects[ax.i] = set(c.mc.pdo_objects[ax.i]) - {0x60FF}
    sv = c.fb("MC_SyncMoveVelocity", Axis=S, Execute=True, Velocity=5.0)
    c.step(1)
    assert sv.Error and sv.ErrorID == 0x3461
