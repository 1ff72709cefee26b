"""CiA402 power drive system state machine (codesys-lc1200.md §B: controlword commands, statusword patterns)."""

from __future__ import annotations

import numpy as np
import pytest

from mcstudio.drives.cia402 import PDS, Cia402Drives, decode_command


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
