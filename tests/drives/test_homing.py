"""Drive-side homing, CiA402 homing mode 6 (codesys-lc1200.md §A): methods, home point, status bits 13/12/10."""

from __future__ import annotations

import numpy as np
import pytest

from mcstudio.drives.cia402 import SensorLayout
from mcstudio.drives.homing import homing_phases
from mcstudio.plant.ideal import Mechanics
from tests.drives.rig import Rig

EO, START, HALT = 0x000F, 0x0010, 0x0100
ATTAINED, ERROR, REACHED = 0x1000, 0x2000, 0x0400
OFFSET = 7777


def _layout(hs: bool = True, nls: bool = True, pls: bool = True, z: bool = True) -> SensorLayout:
    s = SensorLayout(1)
    if nls:
        s.neg_limit[0] = -10_000.0
    if pls:
        s.pos_limit[0] = 10_000.0
    if hs:
        s.prox[0] = (2000.0, 3000.0)
    if z:
        s.z_offset[0], s.z_period[0] = 100.0, 1000.0
    return s


def _rig(start: int = 0, mechanics: Mechanics | None = None, **layout: bool) -> Rig:
    rig = Rig(sensors=_layout(**layout), mechanics=mechanics)
    rig.rx["homing_speed_fast"] = 100_000
    rig.rx["homing_speed_slow"] = 10_000
    rig.rx["homing_acceleration"] = 2_000_000
    rig.rx["home_offset"] = OFFSET
    rig.enable()
    rig.step(3, target_position=np.array([start], dtype=np.int32))
    rig.step(modes_of_operation=6)
    return rig


def _home(rig: Rig, method: int, limit: int = 20_000) -> int:
    rig.step(homing_method=method, controlword=EO)
    return rig.run_until(lambda tx: int(tx["statusword"][0]) & REACHED, limit=limit, controlword=EO | START)


def _hm_bits(rig: Rig) -> int:
    return rig.sw() & (ERROR | ATTAINED | REACHED)


@pytest.mark.parametrize(("method", "start", "home"), [
    (17, 0, -10_000), (18, 0, 10_000),
    (19, 0, 2000), (19, 2500, 2000), (20, 0, 2000), (20, 2500, 2000),
    (21, 5000, 3000), (21, 2500, 3000), (22, 5000, 3000), (22, 2500, 3000),
    (1, 0, -9900), (2, 0, 9100), (3, 0, 1100), (4, 0, 2100), (5, 5000, 3100), (6, 5000, 2100),
    (33, 0, -900), (34, 0, 100),
])
def test_homing_method_finds_its_home_point(method: int, start: int, home: int) -> None:
    """At the home point (switch edge or the first Z pulse after it) 6064h becomes the home offset 607Ch; the drive
    then stops (with 609Ah) and reports homing attained + target reached."""
    rig = _rig(start)
    _home(rig, method)
    assert _hm_bits(rig) == ATTAINED | REACHED
    mech = int(rig.d.position[0])
    assert rig.pos() == OFFSET + (mech - home)
    phases = homing_phases(method, 0x4 if 2000 <= start <= 3000 else 0) or ()
    # approach speed of the home point: speed 1 if the home phase or the one before it in the same direction is
    # fast (the ramp from speed 1 to speed 2 may not have ended)
    fast = phases[-1].fast or (len(phases) > 1 and phases[-2].fast and phases[-2].direction == phases[-1].direction)
    v = 100_000 if fast else 10_000
    assert abs(mech - home) <= v**2 / (2 * 2_000_000) + v * 0.001 + 1, "stopped within the deceleration distance"
    assert int(rig.step(controlword=EO)["velocity_actual"][0]) == 0 and _hm_bits(rig) == ATTAINED | REACHED


@pytest.mark.parametrize("method", [35, 37])
def test_homing_on_the_current_position(method: int) -> None:
    rig = _rig(1234)
    n = _home(rig, method)
    assert n == 1 and _hm_bits(rig) == ATTAINED | REACHED
    assert rig.pos() == OFFSET and int(rig.d.position[0]) == 1234, "no motion: only the coordinate changes"
    rig.step(modes_of_operation=8, controlword=EO, target_position=np.array([OFFSET + 10], dtype=np.int32))
    assert rig.pos() == OFFSET + 10 and int(rig.d.position[0]) == 1244, "CSP targets in the new frame"


def test_homing_status_while_running_and_before() -> None:
    rig = _rig()
    assert _hm_bits(rig) == REACHED, "not started: 13/12/10 = 0/0/1"
    rig.step(homing_method=19, controlword=EO)
    rig.step(controlword=EO | START)
    assert _hm_bits(rig) == 0, "in progress"
    assert rig.d.position[0] > 0, "searching forward"


def test_home_switch_method_with_the_switch_missing_hits_the_limit() -> None:
    """Method 19 without a home switch: the search reaches the positive limit switch → homing error (bit 13), the
    drive stops (then bit 10 too)."""
    rig = _rig(hs=False)
    _home(rig, 19)
    assert _hm_bits(rig) == ERROR | REACHED
    assert rig.d.position[0] >= 10_000 and rig.step(controlword=EO)["velocity_actual"][0] == 0


def test_limit_method_without_the_switch_times_out() -> None:
    rig = _rig(nls=False, pls=False)
    rig.d.homing_timeout_s[0] = 0.3
    n = _home(rig, 17)
    assert _hm_bits(rig) == ERROR | REACHED and 300 <= n <= 400


def test_z_method_without_z_pulse_times_out() -> None:
    rig = _rig(z=False)
    rig.d.homing_timeout_s[0] = 0.1
    _home(rig, 34)
    assert _hm_bits(rig) == ERROR | REACHED


@pytest.mark.parametrize("method", [0, 7, 14, 23, 30, 36, -1])
def test_unsupported_methods_are_a_homing_error(method: int) -> None:
    assert homing_phases(method, 0) is None
    rig = _rig()
    assert _home(rig, method) == 1
    assert _hm_bits(rig) == ERROR | REACHED and rig.d.position[0] == 0


def test_halt_interrupts_homing() -> None:
    rig = _rig()
    rig.step(homing_method=19, controlword=EO)
    rig.step(20, controlword=EO | START)
    rig.run_until(lambda tx: int(tx["statusword"][0]) & REACHED, controlword=EO | START | HALT)
    assert _hm_bits(rig) == REACHED, "interrupted: not attained, no error"
    p = int(rig.d.position[0])
    rig.step(10, controlword=EO | START)
    assert int(rig.d.position[0]) == p, "no restart without a new rising edge of bit 4"
    rig.step(controlword=EO)
    _home(rig, 19)
    assert _hm_bits(rig) == ATTAINED | REACHED


def test_homing_with_the_second_order_loop() -> None:
    """The home point is the mechanism's real edge position, whatever the lag of the position loop."""
    m = Mechanics(1)
    m.model[0] = 1
    m.bandwidth_hz[0] = 20.0
    rig = _rig(mechanics=m)
    _home(rig, 19)
    assert _hm_bits(rig) == ATTAINED | REACHED
    assert rig.pos() == OFFSET + int(rig.d.position[0]) - 2000


def test_homing_phases_start_branch() -> None:
    assert [p.direction for p in homing_phases(19, 0) or ()] == [1, -1]
    assert [p.direction for p in homing_phases(19, 0x4) or ()] == [-1]
    three = homing_phases(3, 0) or ()
    assert [p.signal for p in three] == [2, 2, 3] and three[-1].home and not three[1].home
