"""What the cam editor shows (docs/cams.md "Characteristics and continuity"): v, a, j in user units from the
analytic derivatives (A.2 of the spec: v = h/T·f', a = h/T²·f''), segment and table maxima, and jumps at segment
boundaries with their index and size."""

from __future__ import annotations

import numpy as np
import pytest

from mcstudio.controller.mc.cam.analysis import continuity, kinematics, profile_characteristics
from mcstudio.controller.mc.cam.curves import characteristics
from mcstudio.controller.mc.cam.generate import CamProfile, generate, plan
from mcstudio.controller.mc.cam.generate import _sMC_CAM_NODE as Node
from mcstudio.controller.mc.cam.generate import _sMC_CAM_PROPERTY as Prop
from mcstudio.controller.mc.enums import _eMC_CAM_CURVE as C

NODES = [Node(90, 10, C._mcModifiedSine, PhasePitch=0.05), Node(180, 10, C._mcConstantLine, PhasePitch=0.05),
         Node(270, 30, C._mcStraightLine, PhasePitch=0.05), Node(360, 0, C._mcCycloidal, PhasePitch=0.05)]


def profile() -> CamProfile:
    prof = plan(NODES, Prop(CycleTime=1.0))
    assert isinstance(prof, CamProfile)
    return prof


def test_kinematics_are_the_derivatives_of_the_generated_distances() -> None:
    """At the generated points, distance equals the REAL table and v, a are the time derivatives of it
    (master at 360 units/s: differences of the dense table agree with the analytic values)."""
    prof = profile()
    r = generate(NODES, Prop(CycleTime=1.0), table_size=10000)
    k = kinematics(prof)
    assert k.master_velocity == 360.0 and k.phase.size == r.phase.size
    assert np.allclose(k.distance, r.distance, atol=1e-5)
    dt = 0.05 / 360.0
    inner = slice(1, 1799)  # inside the modified sine
    v_num = (k.distance[2:1800] - k.distance[0:1798]) / (2 * dt)
    assert np.allclose(v_num, k.velocity[inner], rtol=1e-4, atol=1e-3)
    a_num = (k.velocity[2:1800] - k.velocity[0:1798]) / (2 * dt)
    assert np.allclose(a_num, k.acceleration[inner], rtol=1e-3, atol=0.5)


def test_segment_and_table_characteristics_in_user_units() -> None:
    """max|v| = |h|·Vm·V/ΔP, max|a| = |h|·Am·(V/ΔP)², max|j| = |h|·Jm·(V/ΔP)³ per segment; the table's maxima and
    the node reaching them; doubling the master velocity scales them by 2, 4, 8."""
    pc = profile_characteristics(profile())
    ms, dwell, straight, cyc = pc.segments
    rate = 360.0 / 90.0
    c_ms = characteristics(C._mcModifiedSine)
    assert (ms.v_max, ms.a_max, ms.j_max) == pytest.approx((10 * c_ms.Vm * rate, 10 * c_ms.Am * rate**2,
                                                            10 * c_ms.Jm * rate**3))
    assert ms.dimensionless == c_ms and dwell.dimensionless is None and dwell.v_max == 0
    assert straight.v_max == pytest.approx(80.0) and straight.a_max == 0
    assert cyc.v_max == pytest.approx(30 * 2 * rate) and cyc.a_max == pytest.approx(30 * 2 * np.pi * rate**2)
    assert (pc.v_max, pc.v_node) == (pytest.approx(240.0), 3) and pc.a_node == 3 and pc.j_node == 3
    assert (pc.Vm, pc.Am, pc.Jm) == (pytest.approx(2.0), pytest.approx(2 * np.pi), pytest.approx(c_ms.Jm))
    fast = profile_characteristics(profile(), master_velocity=720.0)
    assert (fast.v_max, fast.a_max, fast.j_max) == pytest.approx((2 * pc.v_max, 4 * pc.a_max, 8 * pc.j_max))


def test_continuity_flags_jumps_with_index_and_size() -> None:
    """Dwell → straight line at 180 and line → cycloid at 270 jump in velocity (0 → 80 → 0 units/s); the
    boundary is named by the node whose segment ends there and by its cam data index."""
    jumps = continuity(profile())
    assert [(j.node, j.point, j.phase, j.quantity) for j in jumps] == [
        (1, 3600, 180.0, "velocity"), (2, 5400, 270.0, "velocity")]
    assert jumps[0].size == pytest.approx(80.0) and jumps[1].size == pytest.approx(-80.0)


def test_acceleration_jump_and_periodic_wrap() -> None:
    """Simple harmonic after a dwell jumps in acceleration (A(0) = π²/2 ≠ 0); a periodic cam that ends moving
    jumps at the wrap from the end point back to the start."""
    prof = plan([Node(10, 0, C._mcConstantLine, PhasePitch=1), Node(20, 5, C._mcSimpleHarmonic, PhasePitch=1),
                 Node(30, 10, C._mcStraightLine, PhasePitch=1)], Prop(CycleTime=1.0))
    assert isinstance(prof, CamProfile)
    jumps = continuity(prof)
    assert [(j.node, j.quantity) for j in jumps] == [(0, "acceleration"), (1, "velocity"), (1, "acceleration")]
    wrap = [j for j in continuity(prof, periodic=True) if j.node == 2]
    assert [(j.point, j.quantity) for j in wrap] == [(30, "velocity")]
    assert wrap[0].left == pytest.approx(5 / 10 * 30) and wrap[0].right == 0.0


def test_kinematics_at_given_phases_and_bad_master_velocity() -> None:
    k = kinematics(profile(), phase=np.array([-5.0, 45.0, 225.0, 400.0]))
    assert k.phase.tolist() == [0.0, 45.0, 225.0, 360.0]
    assert k.distance == pytest.approx([0.0, 5.0, 20.0, 0.0]) and k.velocity[2] == pytest.approx(80.0)
    with pytest.raises(ValueError):
        kinematics(profile(), master_velocity=0.0)
