"""Modes of operation of the emulated CiA402 drive: CSV, CST, PP, PV (codesys-lc1200.md §B; CiA402-2)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mcstudio.drives.cia402 import PDS
from mcstudio.plant.ideal import Mechanics
from tests.drives.rig import Rig

EO = 0x000F
NEW_SET_POINT, IMMEDIATE, RELATIVE, HALT = 0x10, 0x20, 0x40, 0x100


def _second_order(bandwidth: float = 50.0, damping: float = 0.7, ff: float = 0.0) -> Mechanics:
    m = Mechanics(1)
    m.model[0] = 1
    m.bandwidth_hz[0] = bandwidth
    m.damping[0] = damping
    m.feedforward[0] = ff
    return m


# ------------------------------------------------------------------------------------------------ CSV
def test_csv_ideal_turns_at_the_command_velocity_plus_offset() -> None:
    rig = Rig()
    rig.enable(mode=9)
    tx = rig.step(10, target_velocity=50_000, velocity_offset=-10_000)
    assert int(tx["velocity_actual"][0]) == 40_000 and rig.pos() == 400
    assert rig.sw() & 0x1000 and int(tx["modes_display"][0]) == 9
    assert int(tx["following_error_actual"][0]) == 0


def test_csv_second_order_is_a_first_order_velocity_loop() -> None:
    """ω̇ = ωn(ω_cmd − ω): after t the velocity is ω_cmd·(1 − exp(−ωn·t))."""
    rig = Rig(mechanics=_second_order(bandwidth=20.0))
    rig.enable(mode=9)
    rig.step(25, target_velocity=100_000)
    wn = 2 * math.pi * 20.0
    assert rig.d.plant.velocity[0] == pytest.approx(100_000 * (1 - math.exp(-wn * 0.025)), rel=1e-9)
    rig.step(500)
    assert rig.field("velocity_actual") == pytest.approx(100_000, abs=1)


# ------------------------------------------------------------------------------------------------ CST
def test_cst_accelerates_the_inertia_within_the_torque_limits() -> None:
    m = Mechanics(1)
    m.viscous[0] = 0.0
    rig = Rig(mechanics=m)
    rig.enable(mode=10)
    rig.step(100, target_torque=100, torque_offset=50, max_profile_velocity=10**9)
    alpha = 0.15 * 1.27 / 2.7e-4  # rad/s² at 15 %
    assert rig.d.plant.velocity[0] == pytest.approx(alpha * 0.1 * 8192 / (2 * math.pi), rel=1e-9)
    assert rig.field("torque_actual") == 150 and rig.field("torque_demand") == 150 and not rig.sw() & 0x800
    tx = rig.step(target_torque=1000, positive_torque_limit=400)
    assert int(tx["torque_actual"][0]) == 400 and rig.sw() & 0x800, "60E0h limits, bit 11"
    tx = rig.step(positive_torque_limit=3000, max_torque=250)
    assert int(tx["torque_actual"][0]) == 250 and int(tx["torque_demand"][0]) == 1050, "6072h limits too"


# ------------------------------------------------------------------------------------------------ PP
def _pp(rig: Rig, target: int, cw: int = EO) -> None:
    """One set-point handshake: target + bit 4 until acknowledged (bit 12), then bit 4 cleared."""
    rig.step(target_position=np.array([target], dtype=np.int32), controlword=cw | NEW_SET_POINT)
    assert rig.sw() & 0x1000, "set-point acknowledge"
    rig.step(controlword=cw)


def test_pp_absolute_move_reaches_the_target_with_the_profile() -> None:
    rig = Rig()
    rig.rx["profile_velocity"] = 100_000
    rig.rx["profile_acceleration"] = 1_000_000
    rig.rx["profile_deceleration"] = 2_000_000
    rig.enable(mode=1)
    assert rig.sw() & 0x400, "at rest: target reached"
    _pp(rig, 50_000)
    assert not rig.sw() & 0x1000 and not rig.sw() & 0x400
    n = rig.run_until(lambda tx: int(tx["statusword"][0]) & 0x400)
    # trapezoid: 0.1 s up, 0.05 s down, cruise (50 000 − 5 000 − 2 500)/100 000 s
    assert n + 2 == pytest.approx(1000 * (0.1 + 0.05 + 0.425), abs=3)
    assert rig.pos() == 50_000 and max(int(t["velocity_actual"][0]) for t in rig.history) <= 100_000
    v = np.array([int(t["velocity_actual"][0]) for t in rig.history])
    assert np.max(np.abs(np.diff(v))) <= 2_000_000 * 0.001 * 2 + 1, "accelerations within the profile"


def test_pp_relative_buffered_and_immediate_set_points() -> None:
    rig = Rig()
    rig.rx["profile_velocity"] = 1_000_000
    rig.rx["profile_acceleration"] = 10_000_000
    rig.rx["profile_deceleration"] = 10_000_000
    rig.enable(mode=1)
    _pp(rig, 10_000)
    _pp(rig, 5_000, EO | RELATIVE)  # buffered: starts after the first one, relative to it
    assert rig.sw() & 0x1000, "the buffer is full: acknowledge stays until the buffered set-point starts"
    rig.run_until(lambda tx: int(tx["statusword"][0]) & 0x400)
    assert rig.pos() == 15_000
    _pp(rig, 100_000)
    rig.step(20)
    _pp(rig, 0, EO | IMMEDIATE)  # change set immediately: reverses towards 0
    rig.run_until(lambda tx: int(tx["statusword"][0]) & 0x400)
    assert rig.pos() == 0
    assert max(int(t["position_actual"][0]) for t in rig.history) < 100_000


def test_pp_new_set_point_is_ignored_while_acknowledged() -> None:
    rig = Rig()
    rig.enable(mode=1)
    rig.step(target_position=np.array([1000], dtype=np.int32), controlword=EO | NEW_SET_POINT)
    rig.step(target_position=np.array([9999], dtype=np.int32), controlword=EO | NEW_SET_POINT)
    rig.step(controlword=EO)
    rig.run_until(lambda tx: int(tx["statusword"][0]) & 0x400)
    assert rig.pos() == 1000


def test_pp_halt_pauses_and_resumes() -> None:
    rig = Rig()
    rig.rx["profile_velocity"] = 100_000
    rig.enable(mode=1)
    _pp(rig, 100_000)
    rig.step(300)
    rig.run_until(lambda tx: int(tx["velocity_actual"][0]) == 0, controlword=EO | HALT)
    rig.step()
    p = rig.pos()
    assert 0 < p < 100_000 and rig.sw() & 0x400, "halted and stopped: target reached"
    rig.step(5)
    assert rig.pos() == p
    rig.run_until(lambda tx: int(tx["statusword"][0]) & 0x400, controlword=EO)
    assert rig.pos() == 100_000


def test_pp_following_error_in_bit_13() -> None:
    rig = Rig(mechanics=_second_order(bandwidth=5.0))
    rig.rx["following_error_window"] = 100
    rig.rx["following_error_timeout"] = 10_000
    rig.rx["profile_velocity"] = 1_000_000
    rig.enable(mode=1)
    _pp(rig, 1_000_000)
    rig.step(50)
    assert rig.sw() & 0x2000 and rig.field("following_error_actual") > 100


# ------------------------------------------------------------------------------------------------ PV
def test_pv_ramps_to_the_target_velocity_and_halts() -> None:
    rig = Rig()
    rig.rx["profile_acceleration"] = 1_000_000
    rig.rx["profile_deceleration"] = 500_000
    rig.enable(mode=3)
    assert rig.sw() & 0x1000, "speed zero"
    rig.step(50, target_velocity=100_000)
    assert rig.field("velocity_actual") == pytest.approx(50_000, abs=1_000) and not rig.sw() & 0x400
    n = rig.run_until(lambda tx: int(tx["statusword"][0]) & 0x400)
    assert 49 <= n <= 52 and rig.field("velocity_actual") == pytest.approx(100_000, abs=100)
    assert not rig.sw() & 0x1000
    n = rig.run_until(lambda tx: int(tx["statusword"][0]) & 0x1000, controlword=EO | HALT)
    assert 199 <= n <= 202, "6084h: 0.2 s to stop"
    assert rig.sw() & 0x400 and rig.d.state[0] == PDS.OperationEnabled


# ------------------------------------------------------------------------------------------------ limits
def test_low_torque_limit_makes_the_second_order_drive_lag_with_bit_11() -> None:
    """A fast CSP ramp with 60E0h/60E1h at 5 %: the drive cannot accelerate the inertia as commanded — statusword
    bit 11 while the limit bites, the following error grows far beyond the unlimited drive's."""
    v = 50  # pulses per period: 50 000 pulse/s (38 rad/s: about 80 % torque to follow at 50 Hz)
    free, lim = Rig(mechanics=_second_order()), Rig(mechanics=_second_order())
    lim.rx["positive_torque_limit"] = 50
    lim.rx["negative_torque_limit"] = 50
    fe = {}
    for name, rig in (("free", free), ("lim", lim)):
        rig.enable()
        bit11 = 0
        for k in range(1, 60):
            tx = rig.step(target_position=np.array([k * v], dtype=np.int32))
            bit11 |= int(tx["statusword"][0]) & 0x800
            assert abs(int(tx["torque_actual"][0])) <= 3000
        fe[name] = int(tx["following_error_actual"][0])
        if name == "lim":
            assert bit11 and abs(int(tx["torque_actual"][0])) <= 50
        else:
            assert not bit11
    assert fe["lim"] > 3 * fe["free"] > 0
