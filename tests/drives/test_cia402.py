"""CiA402 power drive system: state machine, statusword, faults, quick stop, communication loss, modes, inputs
(codesys-lc1200.md §B; CiA402-2 state machine and transitions 0–16)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mcstudio.drives.cia402 import (
    DI_EXT1,
    DI_HOME_SWITCH,
    DI_NEGATIVE_LIMIT,
    DI_POSITIVE_LIMIT,
    ERR_FOLLOWING,
    ERR_SYNC,
    PDS,
    TP1_CONTINUOUS,
    TP1_ENABLE,
    TP1_NEG_EDGE,
    TP1_POS_EDGE,
    TP1_SOURCE_Z,
    TP2_ENABLE,
    TP2_NEG_EDGE,
    TP2_POS_EDGE,
    TS1_ENABLED,
    TS1_NEG_STORED,
    TS1_STORED,
    TS2_NEG_STORED,
    TS2_STORED,
    Cia402Drives,
    SensorLayout,
    decode_command,
)
from mcstudio.plant.ideal import Mechanics
from tests.drives.rig import Rig

S = PDS
DV, QS, SD, SO, EO, RESET = 0x0000, 0x0002, 0x0006, 0x0007, 0x000F, 0x0080

# CiA402-2 figure "state machine": the state after one frame with the command, from each state (independent of the
# implementation's table). Quick stop option code 6 (stay in Quick stop active) so that QSA is stable.
EXPECTED = {
    S.NotReadyToSwitchOn: {DV: S.SwitchOnDisabled, QS: S.SwitchOnDisabled, SD: S.SwitchOnDisabled,
                           SO: S.SwitchOnDisabled, EO: S.SwitchOnDisabled, RESET: S.SwitchOnDisabled},  # 1
    S.SwitchOnDisabled: {DV: S.SwitchOnDisabled, QS: S.SwitchOnDisabled, SD: S.ReadyToSwitchOn,  # 2
                         SO: S.SwitchOnDisabled, EO: S.SwitchOnDisabled, RESET: S.SwitchOnDisabled},
    S.ReadyToSwitchOn: {DV: S.SwitchOnDisabled, QS: S.SwitchOnDisabled, SD: S.ReadyToSwitchOn,  # 7, 3, 3+4
                        SO: S.SwitchedOn, EO: S.OperationEnabled, RESET: S.SwitchOnDisabled},
    S.SwitchedOn: {DV: S.SwitchOnDisabled, QS: S.SwitchOnDisabled, SD: S.ReadyToSwitchOn,  # 10, 6, 4
                   SO: S.SwitchedOn, EO: S.OperationEnabled, RESET: S.SwitchOnDisabled},
    S.OperationEnabled: {DV: S.SwitchOnDisabled, QS: S.QuickStopActive, SD: S.ReadyToSwitchOn,  # 9, 11, 8, 5
                         SO: S.SwitchedOn, EO: S.OperationEnabled, RESET: S.SwitchOnDisabled},
    S.QuickStopActive: {DV: S.SwitchOnDisabled, QS: S.QuickStopActive, SD: S.QuickStopActive,  # 12, 16
                        SO: S.QuickStopActive, EO: S.OperationEnabled, RESET: S.SwitchOnDisabled},
    S.FaultReactionActive: {c: S.Fault for c in (DV, QS, SD, SO, EO, RESET)},  # 14
    S.Fault: {DV: S.Fault, QS: S.Fault, SD: S.Fault, SO: S.Fault, EO: S.Fault, RESET: S.SwitchOnDisabled},  # 15
}
_PATH = {S.SwitchOnDisabled: [], S.ReadyToSwitchOn: [SD], S.SwitchedOn: [SD, SO], S.OperationEnabled: [SD, SO, EO],
         S.QuickStopActive: [SD, SO, EO, QS]}


def _in_state(state: PDS) -> Rig:
    """A drive brought into `state` by commands (NotReadyToSwitchOn, FaultReactionActive: set directly; Fault: by an
    alarm)."""
    rig = Rig()
    rig.d.quick_stop_option[0] = 6
    if state in _PATH:
        for cw in _PATH[state]:
            rig.step(controlword=cw)
    elif state == S.Fault:
        rig.d.inject_fault(0, 0x2310)
        rig.step(2, controlword=DV)
    else:
        rig.d.state[0] = state
        rig.d.quick_stop_option[0] = 6
    assert rig.d.state[0] == state
    return rig


@pytest.mark.parametrize("state", list(EXPECTED))
@pytest.mark.parametrize("cw", [DV, QS, SD, SO, EO, RESET])
def test_transition_table(state: PDS, cw: int) -> None:
    rig = _in_state(state)
    if cw == RESET:
        rig.step(controlword=DV)  # a rising edge of bit 7 needs bit 7 = 0 before
        if state != S.Fault:
            rig = _in_state(state)
    rig.step(controlword=cw)
    assert PDS(int(rig.d.state[0])) == EXPECTED[state][cw]


def test_quick_stop_active_to_operation_enabled_needs_option_5_to_8() -> None:
    """Transition 16 exists only for 605Ah = 5–8; with the default 2 the drive finishes its quick stop (12)."""
    rig = Rig()
    rig.enable()
    rig.step(target_position=np.array([5000], dtype=np.int32))  # move so that the quick stop ramps
    rig.step(controlword=QS)
    assert rig.d.state[0] == S.QuickStopActive
    rig.step(controlword=EO)
    assert rig.d.state[0] != S.OperationEnabled


def test_statusword_patterns() -> None:
    """Statusword bits 0–6 per state (CiA402), bit 4 voltage enabled (main power), bit 9 remote."""
    expect = {S.SwitchOnDisabled: 0x40, S.ReadyToSwitchOn: 0x21, S.SwitchedOn: 0x23, S.OperationEnabled: 0x27,
              S.QuickStopActive: 0x07, S.Fault: 0x08}
    for state, pattern in expect.items():
        rig = _in_state(state)
        rig.step(controlword=rig.rx["controlword"][0])
        sw = rig.sw()
        assert PDS(int(rig.d.state[0])) == state
        assert sw & 0x6F == pattern, (state, hex(sw))
        assert sw & 0x10 and sw & 0x200
    rig = Rig()  # Fault reaction active: seen for one period when an alarm is raised
    rig.enable()
    rig.d.inject_fault(0, 0x3210)
    tx = rig.step()
    assert int(tx["statusword"][0]) & 0x6F == 0x0F and int(tx["error_code"][0]) == 0x3210


def test_warning_bit_7() -> None:
    rig = Rig()
    rig.enable()
    rig.d.warning[0] = True
    assert rig.step()["statusword"][0] & 0x80
    rig.d.warning[0] = False
    assert not rig.step()["statusword"][0] & 0x80


def test_power_up_sequence_and_csp_following() -> None:
    rig = Rig()
    rig.enable()
    assert rig.sw() & 0x6F == 0x27 and rig.sw() & 0x1000, "bit 12: the drive follows the command value"
    tx = rig.step(target_position=np.array([-5], dtype=np.int32))
    assert int(tx["position_actual"][0]) == -5 and int(tx["position_demand"][0]) == -5
    assert int(tx["following_error_actual"][0]) == 0 and int(tx["modes_display"][0]) == 8


def test_no_operation_without_main_power() -> None:
    rig = Rig()
    rig.d.main_power[0] = False
    for cw in (SD, SO, EO):
        rig.step(controlword=cw)
    assert rig.d.state[0] == S.ReadyToSwitchOn and rig.sw() & 0x10 == 0
    rig.d.main_power[0] = True
    rig.step(controlword=EO)
    assert rig.d.state[0] == S.OperationEnabled


def test_decode_command() -> None:
    cw = np.array([0x00, 0x02, 0x06, 0x07, 0x0F, 0x8F], dtype=np.uint16)
    assert decode_command(cw).tolist() == [0, 1, 2, 3, 4, 4]


# ------------------------------------------------------------------------------------------------ faults
def test_alarm_reaction_fault_and_reset() -> None:
    """inject_fault → Fault reaction active (603Fh set) → Fault → fault reset edge → Switch on disabled, 603Fh 0."""
    rig = Rig()
    rig.enable()
    rig.d.inject_fault(0, 0x2310)
    assert rig.step()["error_code"][0] == 0x2310 and rig.d.state[0] == S.FaultReactionActive
    rig.step()
    assert rig.d.state[0] == S.Fault and rig.sw() & 0x4F == 0x08
    rig.step(5, controlword=EO)
    assert rig.d.state[0] == S.Fault, "no command leaves Fault"
    tx = rig.step(controlword=RESET)
    assert rig.d.state[0] == S.SwitchOnDisabled and int(tx["error_code"][0]) == 0


def test_fault_reset_needs_a_rising_edge() -> None:
    rig = Rig()
    rig.d.inject_fault(0, 0x7305)
    rig.step(2, controlword=RESET)
    assert rig.d.state[0] == S.Fault, "bit 7 already set when the fault came: no edge"
    rig.step(controlword=DV)
    rig.step(controlword=RESET)
    assert rig.d.state[0] == S.SwitchOnDisabled


def test_persistent_alarm_survives_the_reset_until_its_cause_is_cleared() -> None:
    rig = Rig()
    rig.enable()
    rig.d.inject_fault(0, 0x7305, persistent=True)
    rig.step(2)
    for _ in range(3):
        rig.step(controlword=DV)
        rig.step(controlword=RESET)
        assert rig.d.state[0] == S.Fault and rig.field("error_code") == 0x7305
    rig.d.clear_fault_cause(0)
    rig.step(controlword=DV)
    rig.step(controlword=RESET)
    assert rig.d.state[0] == S.SwitchOnDisabled and rig.field("error_code") == 0


def _moving(rig: Rig, v_per_period: int, periods: int) -> None:
    rig.enable()
    for _ in range(periods):
        rig.step(target_position=rig.rx["target_position"] + v_per_period)


def test_fault_reaction_option_0_holds_at_once_and_2_ramps_with_6085() -> None:
    rig = Rig()
    _moving(rig, 100, 10)  # 100 000 pulse/s
    rig.d.inject_fault(0, 0x2310)
    p = rig.pos()
    rig.step(3)
    assert rig.pos() == p and rig.d.state[0] == S.Fault, "605Eh = 0 (default): disabled at once, the shaft holds"
    rig = Rig()
    rig.d.fault_reaction_option[0] = 2
    rig.rx["quick_stop_deceleration"] = 10_000_000
    _moving(rig, 100, 10)
    rig.d.inject_fault(0, 0x2310)
    p = rig.pos()
    n = rig.run_until(lambda tx: PDS(int(rig.d.state[0])) == S.Fault)
    assert 10 <= n <= 13, "100 000 pulse/s at 10^7 pulse/s² stops in 10 ms"
    assert rig.pos() - p == pytest.approx(100_000**2 / (2 * 10_000_000), abs=150)


def test_communication_loss_while_enabled_trips_the_watchdog() -> None:
    """No valid frame while Operation enabled: sync-manager watchdog → 603Fh 8700h, fault reaction, Fault; a drive
    that is not enabled just waits. Back online, a fault reset clears it."""
    rig = Rig(2)
    rig.enable()
    rig.step(controlword=np.array([EO, SD], dtype=np.uint16))
    rig.online[:] = False
    tx = rig.step()
    assert int(tx["error_code"][0]) == ERR_SYNC and rig.d.state[0] == S.FaultReactionActive
    rig.step(3)
    assert rig.d.state[0] == S.Fault
    assert rig.d.state[1] == S.ReadyToSwitchOn and int(rig.tx["error_code"][1]) == 0
    rig.online[:] = True
    rig.step(controlword=np.array([DV, SD], dtype=np.uint16))
    rig.step(controlword=np.array([RESET, SD], dtype=np.uint16))
    assert rig.d.state[0] == S.SwitchOnDisabled and rig.field("error_code") == 0


def test_offline_drive_takes_no_command_and_keeps_its_last_values() -> None:
    rig = Rig()
    rig.step(controlword=SD)
    rig.online[0] = False
    rig.step(3, controlword=SO)
    assert rig.d.state[0] == S.ReadyToSwitchOn
    rig.online[0] = True
    rig.step()
    assert rig.d.state[0] == S.SwitchedOn


def test_following_error_window_and_timeout() -> None:
    """|60F4h| > 6065h for longer than 6066h ms → 8611h; meanwhile CSP statusword bit 13."""
    m = Mechanics(1)
    m.model[0] = 1
    m.bandwidth_hz[0] = 10.0
    rig = Rig(mechanics=m)
    rig.rx["following_error_window"] = 1000
    rig.rx["following_error_timeout"] = 5
    rig.enable()
    tx = rig.step(target_position=np.array([100_000], dtype=np.int32))
    assert tx["following_error_actual"][0] > 1000 and rig.sw() & 0x2000 and rig.d.state[0] == S.OperationEnabled
    rig.step(4)
    assert rig.d.state[0] == S.OperationEnabled, "5 ms not exceeded yet"
    tx = rig.step(2)
    assert rig.d.state[0] in (S.FaultReactionActive, S.Fault) and int(tx["error_code"][0]) == ERR_FOLLOWING


def test_following_error_off_with_ffffffff() -> None:
    m = Mechanics(1)
    m.model[0] = 1
    rig = Rig(mechanics=m)
    rig.rx["following_error_window"] = 0xFFFFFFFF
    rig.enable()
    rig.step(50, target_position=np.array([2_000_000_000], dtype=np.int32))
    assert rig.d.state[0] == S.OperationEnabled


# ------------------------------------------------------------------------------------------------ quick stop
@pytest.mark.parametrize(("option", "dec_field", "end"), [
    (1, "profile_deceleration", S.SwitchOnDisabled), (2, "quick_stop_deceleration", S.SwitchOnDisabled),
    (5, "profile_deceleration", S.QuickStopActive), (6, "quick_stop_deceleration", S.QuickStopActive)])
def test_quick_stop_ramps(option: int, dec_field: str, end: PDS) -> None:
    rig = Rig()
    rig.d.quick_stop_option[0] = option
    rig.rx["profile_deceleration"] = 5_000_000
    rig.rx["quick_stop_deceleration"] = 20_000_000
    _moving(rig, 200, 10)  # 200 000 pulse/s
    p0 = rig.pos()
    rig.step(controlword=QS)
    assert rig.d.state[0] == S.QuickStopActive and rig.sw() & 0x6F == 0x07
    rig.run_until(lambda tx: int(tx["velocity_actual"][0]) == 0)
    dec = float(rig.rx[dec_field][0])
    assert rig.pos() - p0 == pytest.approx(200_000**2 / (2 * dec), rel=0.03)
    rig.step(2)
    assert PDS(int(rig.d.state[0])) == end
    if end == S.QuickStopActive:
        p = rig.pos()
        rig.step(5)
        assert rig.pos() == p, "stays stopped, enabled"
        rig.step(controlword=EO)
        assert rig.d.state[0] == S.OperationEnabled, "transition 16"


def test_quick_stop_option_0_disables_at_once() -> None:
    rig = Rig()
    rig.d.quick_stop_option[0] = 0
    _moving(rig, 100, 5)
    p = rig.pos()
    rig.step(controlword=QS)
    assert rig.d.state[0] == S.SwitchOnDisabled and rig.pos() == p


# ------------------------------------------------------------------------------------------------ modes
def test_unsupported_mode_is_ignored_and_6502h() -> None:
    rig = Rig()
    rig.enable()
    tx = rig.step(modes_of_operation=4)  # profile torque: not supported
    assert int(tx["modes_display"][0]) == 8
    assert int(tx["supported_drive_modes"][0]) == 0x3A5
    m = Mechanics(1)
    m.cst[0] = False
    rig = Rig(mechanics=m)
    tx = rig.step(modes_of_operation=10)
    assert int(tx["modes_display"][0]) == 8 and int(tx["supported_drive_modes"][0]) == 0x1A5
    for mode in (1, 3, 6, 9, 8):
        assert int(rig.step(modes_of_operation=mode)["modes_display"][0]) == mode


def test_halt_is_ignored_in_csp() -> None:
    rig = Rig()
    rig.enable()
    tx = rig.step(controlword=EO | 0x100, target_position=np.array([1234], dtype=np.int32))
    assert int(tx["position_actual"][0]) == 1234


# ------------------------------------------------------------------------------------------------ inputs
def _layout() -> SensorLayout:
    s = SensorLayout(1)
    s.pos_limit[0], s.neg_limit[0] = 1000.0, -1000.0
    s.prox[0] = (100.0, 200.0)
    s.ext1[0] = (300.0, 310.0)
    s.ext2[0] = (500.0, 520.0)
    s.z_offset[0], s.z_period[0] = 50.0, 400.0
    return s


def _moved_to(rig: Rig, positions: list[int], tp: int) -> list[np.ndarray]:
    out = []
    for p in positions:
        out.append(rig.step(target_position=np.array([p], dtype=np.int32), touch_probe_function=tp))
    return out


def test_digital_inputs_from_sensor_positions() -> None:
    """60FDh: bit 0 negative limit, bit 1 positive limit, bit 2 home switch (CiA402); bit 16 external input 1."""
    rig = Rig(sensors=_layout())
    rig.enable()
    rows = _moved_to(rig, [0, 150, 305, 1000, -1000], 0)
    assert [int(r["digital_inputs"][0]) for r in rows] == [0, DI_HOME_SWITCH, DI_EXT1, DI_POSITIVE_LIMIT,
                                                           DI_NEGATIVE_LIMIT]


def test_sensors_changed_in_place() -> None:
    rig = Rig()
    rig.enable()
    rig.d.sensors.pos_limit[0] = 10.0
    rig.d.sensors_changed()
    assert int(_moved_to(rig, [20], 0)[0]["digital_inputs"][0]) == DI_POSITIVE_LIMIT


def test_touch_probe_latches_the_exact_edge_position() -> None:
    """Touch probe 1 on the Z phase: armed by 60B8h bits 0+4 (+2 = Z source); the latched position is the pulse's
    position, not the sampled one; first-event mode keeps it until re-armed."""
    rig = Rig(sensors=_layout())
    rig.enable()
    fn = TP1_ENABLE | TP1_POS_EDGE | TP1_SOURCE_Z
    rows = _moved_to(rig, [0, 30, 437, 900], fn)
    assert int(rows[0]["touch_probe_status"][0]) == TS1_ENABLED
    assert int(rows[2]["touch_probe_status"][0]) == TS1_ENABLED | TS1_STORED
    assert int(rows[2]["touch_probe_pos1"][0]) == 50
    assert int(rows[3]["touch_probe_pos1"][0]) == 50, "first event kept (the Z pulse at 450 is not taken)"
    rows = _moved_to(rig, [950], 0)  # disable …
    assert int(rows[0]["touch_probe_status"][0]) == 0
    rows = _moved_to(rig, [1250, 1290], fn)  # … and re-arm
    assert int(rows[0]["touch_probe_pos1"][0]) == 1250 and int(rows[0]["touch_probe_status"][0]) & TS1_STORED


def test_touch_probe_on_external_input_moving_backwards() -> None:
    rig = Rig(sensors=_layout())
    rig.enable()
    _moved_to(rig, [400], 0)
    rows = _moved_to(rig, [360, 305, 200], TP1_ENABLE | TP1_POS_EDGE)
    assert int(rows[1]["touch_probe_status"][0]) & TS1_STORED
    assert int(rows[1]["touch_probe_pos1"][0]) == 310, "entering [300, 310] from above: the edge is at 310"


def test_touch_probe_negative_edges_and_continuous_mode() -> None:
    """60B8h bits 5/13 latch the falling edges into 60BBh/60BDh (60B9h bits 2/10); continuous mode (bit 1) takes
    every edge, first-event mode only the first."""
    rig = Rig(sensors=_layout())
    rig.enable()
    fn = TP1_ENABLE | TP1_POS_EDGE | TP1_NEG_EDGE | TP2_ENABLE | TP2_POS_EDGE | TP2_NEG_EDGE
    rows = _moved_to(rig, [0, 600], fn)  # across EXT1 [300, 310] and EXT2 [500, 520] in one period
    tx = rows[-1]
    st = int(tx["touch_probe_status"][0])
    assert st & (TS1_STORED | TS1_NEG_STORED | TS2_STORED | TS2_NEG_STORED) == \
        TS1_STORED | TS1_NEG_STORED | TS2_STORED | TS2_NEG_STORED
    assert [int(tx[f][0]) for f in ("touch_probe_pos1", "touch_probe_neg1", "touch_probe_pos2",
                                    "touch_probe_neg2")] == [300, 310, 500, 520]
    tx = _moved_to(rig, [0], fn)[-1]
    assert int(tx["touch_probe_neg1"][0]) == 310, "first event: the way back does not overwrite"
    tx = _moved_to(rig, [600, 0], fn | TP1_CONTINUOUS)[-1]
    assert int(tx["touch_probe_pos1"][0]) == 310 and int(tx["touch_probe_neg1"][0]) == 300, \
        "continuous: backwards the rising edge is at 310 and the falling one at 300"


def test_touch_probe_position_in_the_reported_frame_after_homing() -> None:
    """After homing (6064h = position + shift) latches report 6064h values."""
    rig = Rig(sensors=_layout())
    rig.enable(mode=6)
    rig.step(homing_method=35, home_offset=1000, controlword=EO)
    rig.step(controlword=EO | 0x10)
    assert rig.pos() == 1000
    rig.step(modes_of_operation=8, controlword=EO, target_position=np.array([1000], dtype=np.int32))
    tx = _moved_to(rig, [1400], TP1_ENABLE | TP1_POS_EDGE)[-1]
    assert int(tx["touch_probe_pos1"][0]) == 1300


def test_large_moves_wrap_32_bit_objects() -> None:
    rig = Rig()
    rig.enable()
    p = 2**31 - 100
    for target in (p, p + 200):
        t32 = np.array([target], dtype=np.int64).astype(np.int32)
        tx = rig.step(target_position=t32)
    assert int(rig.d.position[0]) == p + 200, "64-bit inside"
    assert int(tx["position_actual"][0]) == -(2**31) + 100
    assert int(tx["velocity_actual"][0]) == 200_000


def test_vectorised_drives_are_independent() -> None:
    rig = Rig(3)
    rig.enable()
    tx = rig.step(target_position=np.array([10, -20, 30], dtype=np.int32))
    assert tx["position_actual"].tolist() == [10, -20, 30]
    rig.d.inject_fault(1, 0x2310)
    rig.step(2, target_position=np.array([11, -21, 31], dtype=np.int32))
    assert rig.d.state.tolist() == [4, 7, 4] and rig.tx["position_actual"].tolist() == [11, -20, 31]


def test_velocity_and_torque_reported() -> None:
    """606Ch is the position change per period; 6077h the torque the ideal move takes (J·Δω/Δt)."""
    rig = Rig()
    rig.enable()
    tx = rig.step(target_position=np.array([100], dtype=np.int32))
    assert int(tx["velocity_actual"][0]) == 100_000
    j, rated = 2.7e-4, 1.27
    alpha = 100_000 * 2 * math.pi / 8192 / 0.001
    expect = j * alpha / rated * 1000  # ≈ (viscous friction is small)
    assert int(tx["torque_actual"][0]) == pytest.approx(expect, rel=0.02)
    assert int(tx["torque_demand"][0]) == int(tx["torque_actual"][0])


def test_drive_without_sensors_reports_no_inputs() -> None:
    d = Cia402Drives(2)
    assert not d._di.fitted
