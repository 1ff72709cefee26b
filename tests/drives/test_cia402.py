"""CiA402 power drive system state machine (codesys-lc1200.md §B: controlword commands, statusword patterns)."""

from __future__ import annotations

import numpy as np
import pytest

from mcstudio.drives.cia402 import (
    DI_EXT1,
    DI_HOME_SWITCH,
    DI_NEGATIVE_LIMIT,
    DI_POSITIVE_LIMIT,
    PDS,
    TP1_ENABLE,
    TP1_POS_EDGE,
    TP1_SOURCE_Z,
    TS1_ENABLED,
    TS1_STORED,
    Cia402Drives,
    SensorLayout,
    decode_command,
)


def _run(d: Cia402Drives, *cws: int) -> list[int]:
    states = []
    for cw in cws:
        d.step(np.array([cw], dtype=np.uint16), np.array([8], dtype=np.int8))
        states.append(int(d.state[0]))
    return states


def test_power_up_sequence() -> None:
    d = Cia402Drives(1)
    assert _run(d, 0x0000, 0x0006, 0x0007, 0x000F) == [
        PDS.SwitchOnDisabled, PDS.ReadyToSwitchOn, PDS.SwitchedOn, PDS.OperationEnabled]
    assert int(d.statusword()[0]) & 0x6F == 0x27


@pytest.mark.parametrize(("cw", "expected"), [(0x0006, PDS.ReadyToSwitchOn), (0x0007, PDS.SwitchedOn),
                                              (0x0000, PDS.SwitchOnDisabled), (0x0002, PDS.QuickStopActive)])
def test_transitions_out_of_operation_enabled(cw: int, expected: PDS) -> None:
    d = Cia402Drives(1)
    _run(d, 0x0006, 0x0007, 0x000F)
    assert _run(d, cw)[-1] == expected


def test_statusword_patterns() -> None:
    """Statusword bits 0–6 per state (CiA402), bit 4 = main circuit powered, bit 9 remote."""
    d = Cia402Drives(1)
    expect = {PDS.SwitchOnDisabled: 0x40, PDS.ReadyToSwitchOn: 0x21, PDS.SwitchedOn: 0x23,
              PDS.OperationEnabled: 0x27, PDS.QuickStopActive: 0x07, PDS.Fault: 0x08}
    for state, pattern in expect.items():
        d.state[0] = state
        sw = int(d.statusword()[0])
        assert sw & 0x6F == pattern & 0x6F
        assert sw & 0x10 and sw & 0x200


def test_fault_reset_needs_a_rising_edge() -> None:
    d = Cia402Drives(1)
    d.state[0] = PDS.Fault
    assert _run(d, 0x0000)[-1] == PDS.Fault
    assert _run(d, 0x0080)[-1] == PDS.SwitchOnDisabled
    d.state[0] = PDS.Fault
    assert _run(d, 0x0080)[-1] == PDS.Fault, "bit 7 held: no new edge"


def test_no_operation_without_main_power() -> None:
    d = Cia402Drives(1)
    d.main_power[0] = False
    assert _run(d, 0x0006, 0x0007, 0x000F)[-1] == PDS.ReadyToSwitchOn
    assert int(d.statusword()[0]) & 0x10 == 0


def test_decode_command() -> None:
    cw = np.array([0x00, 0x02, 0x06, 0x07, 0x0F, 0x8F], dtype=np.uint16)
    assert decode_command(cw).tolist() == [0, 1, 2, 3, 4, 4]


def _layout() -> SensorLayout:
    s = SensorLayout(1)
    s.pos_limit[0], s.neg_limit[0] = 1000.0, -1000.0
    s.prox[0] = (100.0, 200.0)
    s.ext1[0] = (300.0, 310.0)
    s.z_offset[0], s.z_period[0] = 50.0, 400.0
    return s


def _drive_moving(d: Cia402Drives, positions: list[int], tp: int) -> list[tuple[int, int, int]]:
    out = []
    prev = d.position.copy()
    for p in positions:
        d.position[0] = p
        d.sense(prev, np.array([tp], dtype=np.uint16))
        prev = d.position.copy()
        out.append((int(d.digital_inputs[0]), int(d.probe_status[0]), int(d.probe_pos1[0])))
    return out


def test_digital_inputs_from_sensor_positions() -> None:
    """60FDh: bit 0 negative limit, bit 1 positive limit, bit 2 home switch (CiA402); bit 16 external input 1."""
    d = Cia402Drives(1, _layout())
    rows = _drive_moving(d, [0, 150, 305, 1000, -1000], 0)
    assert [r[0] for r in rows] == [0, DI_HOME_SWITCH, DI_EXT1, DI_POSITIVE_LIMIT, DI_NEGATIVE_LIMIT]


def test_touch_probe_latches_the_exact_edge_position() -> None:
    """Touch probe 1 on the Z phase: armed by 60B8h bits 0+4 (+2 = Z source); the latched position is the pulse's
    position, not the sampled one; first-event mode keeps it until re-armed."""
    d = Cia402Drives(1, _layout())
    fn = TP1_ENABLE | TP1_POS_EDGE | TP1_SOURCE_Z
    rows = _drive_moving(d, [0, 30, 437, 900], fn)
    assert rows[0][1] == TS1_ENABLED
    assert rows[2][1] == TS1_ENABLED | TS1_STORED and rows[2][2] == 50
    assert rows[3][2] == 50, "first event kept (the Z pulse at 450 is not taken)"
    rows = _drive_moving(d, [950], 0)  # disable …
    assert rows[0][1] == 0
    rows = _drive_moving(d, [1250, 1290], TP1_ENABLE | TP1_POS_EDGE | TP1_SOURCE_Z)  # … and re-arm
    assert rows[0][2] == 1250 and rows[0][1] & TS1_STORED


def test_touch_probe_on_external_input_moving_backwards() -> None:
    d = Cia402Drives(1, _layout())
    d.position[0] = 400
    rows = _drive_moving(d, [360, 305, 200], TP1_ENABLE | TP1_POS_EDGE)
    assert rows[1][1] & TS1_STORED and rows[1][2] == 310, "entering [300, 310] from above: the edge is at 310"
