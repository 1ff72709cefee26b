"""MC_GenerateCamTable (`omron-group-and-cam.md` §5.4; seed 000 lines 17762–18345, error details lines
21082–21180): generation, point counts, connecting conditions, rounding, and every error with its
ErrorParameterCode and ErrorNodePointIndex."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mcstudio.controller.mc.cam.analysis import continuity, kinematics
from mcstudio.controller.mc.cam.generate import CamProfile, generate, generate_into, plan
from mcstudio.controller.mc.cam.generate import _sMC_CAM_NODE as Node
from mcstudio.controller.mc.cam.generate import _sMC_CAM_PROPERTY as Prop
from mcstudio.controller.mc.cam.table import CamTable
from mcstudio.controller.mc.enums import _eMC_CAM_CURVE as C


def line(phase: float, dist: float, pitch: float = 0.1, **kw: object) -> Node:
    return Node(Phase=phase, Distance=dist, Curve=C._mcStraightLine, PhasePitch=pitch, **kw)  # type: ignore[arg-type]


def err(nodes: list[Node], prop: Prop | None = None, size: int = 100000) -> tuple[int, int, int]:
    e = generate(nodes, prop or Prop(CycleTime=1.0), table_size=size).error
    assert e is not None
    return e.ErrorID, e.ErrorParameterCode, e.ErrorNodePointIndex


def test_generation_example_3601_points() -> None:
    """§5.4.4 generation example (seed 000 line ~17960): (180, 180) and (360, 0) straight lines, pitch 0.1, a table
    of 4000 undefined elements → [1..1800] = (0.1, 0.1)…(180, 180), [1801..3600] = (180.1, 179.9)…(360, 0),
    [3601].Phase := 0 (its Distance untouched), EndPointIndex 3600; Tcd = 1800 + 1800 + 1."""
    t = CamTable(4000)
    t.phase[:], t.distance[:] = np.nan, np.nan
    r = generate_into(t, [line(180, 180), line(360, 0), Node()], Prop(CycleTime=1.0))
    assert r.ok and r.end_point_index == 3600 and r.profile is not None and r.profile.point_count == 3601
    assert t.end_point_index == 3600
    expect = {0: (0.0, 0.0), 1: (0.1, 0.1), 1799: (179.9, 179.9), 1800: (180.0, 180.0), 1801: (180.1, 179.9),
              3599: (359.9, 0.1), 3600: (360.0, 0.0)}
    for i, (p, d) in expect.items():
        assert (t.phase[i], t.distance[i]) == (np.float32(p), pytest.approx(np.float32(d), abs=2e-5)), i
    assert t.phase[3601] == 0 and np.isnan(t.distance[3601])
    assert np.all(np.isnan(t.phase[3602:]))
    assert t.set_cam_table_property().end_point_index == 3600, "no MC_SetCamTableProperty needed, but agrees"


def test_no_terminator_when_the_table_is_full() -> None:
    """§5.4.4 step 3: with exactly Tcd elements there is no element after the end point; nothing is zeroed."""
    t = CamTable(3601)
    r = generate_into(t, [line(180, 180), line(360, 0)], Prop(CycleTime=1.0))
    assert r.ok and t.end_point_index == 3600 and t.phase[-1] == 360.0


def test_sample_program_36001_points_and_blend_into_the_line() -> None:
    """Sample program (seed 000 lines 18345–18400): CycleTime 0.8; (180, −100, quintic), (200, −102, straight
    line), (360, 0, quintic), pitch 0.01, into ARRAY[0..36000] → Tcd = 18000 + 2000 + 16000 + 1 = 36001, no
    terminator, EndPointIndex 36000; the quintics join the line's slope (−102 − (−100))/(200 − 180)·360/0.8 =
    −45 units/s with no velocity or acceleration jump."""
    nodes = [Node(180, -100, C._mcPolynomic5, PhasePitch=0.01), Node(200, -102, C._mcStraightLine, PhasePitch=0.01),
             Node(360, 0, C._mcPolynomic5, PhasePitch=0.01), Node()]
    t = CamTable(36001)
    r = generate_into(t, nodes, Prop(CycleTime=0.8))
    assert r.ok and r.end_point_index == 36000 and t.end_point_index == 36000
    prof = r.profile
    assert prof is not None and [s.count for s in prof.segments] == [18000, 2000, 16000]
    assert prof.master_velocity == pytest.approx(450.0)
    q0, _, q2 = prof.segments
    assert (q0.v_init, q0.v_fin, q2.v_init, q2.v_fin) == (0.0, pytest.approx(-45.0), pytest.approx(-45.0), 0.0)
    assert (t.distance[18000], t.distance[19000], t.distance[20000], t.distance[36000]) == (
        -100.0, pytest.approx(-101.0, abs=1e-5), -102.0, 0.0)
    k = kinematics(prof, phase=np.array([0.0, 180.0, 190.0, 200.0, 360.0]))
    assert np.allclose(k.velocity, [0, -45, -45, -45, 0], atol=1e-9)
    assert continuity(prof) == [] and continuity(prof, periodic=True) == []


def test_sample_program_initial_nodes() -> None:
    """The sample's editor values (modified sine to (180, −100), quintic to (360, 0), CycleTime 1.0): the quintic
    starts at rest (the previous curve is neither a line nor a polynomial)."""
    r = generate([Node(180, -100, C._mcModifiedSine, PhasePitch=0.01), Node(360, 0, C._mcPolynomic5, PhasePitch=0.01)],
                 Prop(CycleTime=1.0), table_size=36001)
    assert r.ok and r.profile is not None
    assert (r.profile.segments[1].v_init, r.profile.segments[1].a_init) == (0.0, 0.0)
    assert continuity(r.profile) == []


def test_point_count_rounds_up_when_the_pitch_does_not_divide() -> None:
    """§5.4.4: N = floor(ΔP/pitch) + 1 when not exact; Phase(N) = P_final; Distance(N) = d_final."""
    r = generate([line(100, 50, pitch=0.3)], Prop(CycleTime=1.0), table_size=1000)
    assert r.ok and r.end_point_index == 334
    assert r.phase[-3:].tolist() == pytest.approx([99.6, 99.9, 100.0]) and r.distance[-1] == 50.0
    assert r.distance[1] == pytest.approx(0.15)


def test_node_list_ends_at_the_first_phase_zero() -> None:
    """§5.4.3: valid nodes 0–4, element 5 Phase 0, elements 6–9 arbitrary (even out of range): no error."""
    nodes = [line(10.0 * (i + 1), float(i)) for i in range(5)] + [Node()]
    nodes += [Node(Phase=math.nan, Curve=99, PhasePitch=-1), Node(5.0), Node(-3.0), Node(1e39)]
    r = generate(nodes, Prop(CycleTime=1.0), table_size=1000)
    assert r.ok and r.profile is not None and len(r.profile.segments) == 5 and r.profile.p_max == 50.0


def test_constant_line_takes_the_previous_distance() -> None:
    """§5.4.2 *3: `_mcConstantLine` ignores its Distance (not even range-checked): previous node's, 0 at [0]."""
    r = generate([Node(10, 0.0001, C._mcConstantLine, PhasePitch=1), line(20, 5, pitch=1),
                  Node(30, math.nan, C._mcConstantLine, PhasePitch=1)], Prop(CycleTime=1.0), table_size=100)
    assert r.ok
    assert r.distance[:11].tolist() == [0.0] * 11 and r.distance[20:].tolist() == [5.0] * 11


def test_inputs_rounded_and_truncated() -> None:
    """§5.4.1/5.4.2 *1, *2: REAL inputs rounded half up at the 4th decimal; Phase and Distance keep 7 significant
    digits (the 8th on dropped) — on the decimal the REAL stands for, so 359.9 stays 359.9."""
    prof = plan([Node(12345.6789, 1.23456789, C._mcStraightLine, PhasePitch=0.0015),
                 Node(12359.9, 359.9, C._mcStraightLine, PhasePitch=0.0005 + 0.0005)], Prop(CycleTime=0.0015))
    assert isinstance(prof, CamProfile)
    s0, s1 = prof.segments
    assert (s0.p1, s0.d1, s0.pitch) == (12345.67, 1.235, 0.002)
    assert (s1.p1, s1.d1, s1.pitch) == (12359.9, 359.9, 0.001)
    assert prof.cycle_time == 0.002


def test_truncation_that_makes_phases_equal_is_5740() -> None:
    """§5.4.2 *2 and A-2 5740 (seed 000 line 21138): 10000.001 and 10000.002 both keep 10000.00 → 5740 at the
    node whose phase is no longer above the previous one."""
    assert err([line(10000.001, 1), line(10000.002, 2)]) == (0x5740, 0, 1)
    assert err([line(10, 1), line(20, 2), line(15, 3)]) == (0x5740, 0, 2)
    assert err([line(10, 1), line(10, 2)]) == (0x5740, 0, 1)


def test_573c_cam_property_out_of_range() -> None:
    """573C with ErrorParameterCode 0000 InitVel, 0001 InitAcc, 0002 CycleTime (seed 000 line 21082)."""
    nodes = [line(10, 1)]
    assert err(nodes, Prop(InitVel=0.0005, CycleTime=1)) == (0x573C, 0x0000, 0)
    assert err(nodes, Prop(InitAcc=math.nan, CycleTime=1)) == (0x573C, 0x0001, 0)
    assert err(nodes, Prop(InitAcc=1e39, CycleTime=1)) == (0x573C, 0x0001, 0)
    for cycle in (0.0, -1.0, 0.0009, math.inf):
        assert err(nodes, Prop(CycleTime=cycle)) == (0x573C, 0x0002, 0)
    assert generate(nodes, Prop(InitVel=-0.001, InitAcc=0.0, CycleTime=0.001), table_size=200).ok


@pytest.mark.parametrize(("member", "value", "code"), [
    ("Phase", 0.0005, 0x0000), ("Phase", -1.0, 0x0000), ("Phase", math.nan, 0x0000),
    ("Distance", 0.0002, 0x0001), ("Distance", math.inf, 0x0001),
    ("Curve", 15, 0x0002), ("Curve", -1, 0x0002),
    ("ConnectingVel", 0.0001, 0x0003), ("ConnectingAcc", -0.0009, 0x0004),
    ("PhasePitch", 0.0, 0x0005), ("PhasePitch", 0.0009, 0x0005), ("PhasePitch", -0.1, 0x0005),
])
def test_573d_cam_node_out_of_range(member: str, value: float, code: int) -> None:
    """573D with ErrorParameterCode 0000 Phase … 0005 PhasePitch and the node in ErrorNodePointIndex
    (seed 000 line 21096); the connecting values are checked when enabled."""
    bad = Node(20, 2, C._mcPolynomic5, ConnectingVelEnable=True, ConnectingAccEnable=True, PhasePitch=0.1)
    setattr(bad, member, value)
    assert err([line(10, 1), bad, line(30, 3)]) == (0x573D, code, 1)


def test_disabled_connecting_values_are_not_checked() -> None:
    bad = Node(20, 2, C._mcPolynomic3, ConnectingVel=0.0001, ConnectingAcc=math.nan, PhasePitch=0.1)
    assert generate([line(10, 1), bad], Prop(CycleTime=1.0), table_size=1000).ok


def test_573e_573f_and_check_order() -> None:
    """573F: CamNodes[0].Phase = 0 (seed 000 line 21124); 573E: more than 359 elements (D37); 573C is checked
    before the nodes, and nodes in index order (a range error at node 1 before the order error at node 2)."""
    assert err([Node(), line(10, 1)]) == (0x573F, 0, 0)
    assert err([]) == (0x573F, 0, 0)
    assert err([line(1, 1)] * 360) == (0x573E, 0, 0)
    assert err([Node()], Prop(CycleTime=0)) == (0x573C, 0x0002, 0)
    assert err([line(10, 1), Node(20, 0.0001, C._mcStraightLine, PhasePitch=1), line(15, 2)]) == (0x573D, 1, 1)


def test_5741_too_many_cam_data() -> None:
    """5741 with the node at which the cam data exceed the table (seed 000 line 21152) — or 65,535 points."""
    nodes = [line(180, 180), line(360, 0)]
    assert err(nodes, size=3600) == (0x5741, 0, 1)
    assert err(nodes, size=1800) == (0x5741, 0, 0)
    big = [line(65.534, 1, pitch=0.001)]
    r = generate(big, Prop(CycleTime=1.0), table_size=65535)
    assert r.ok and r.end_point_index == 65534
    assert err([line(65.535, 1, pitch=0.001)], size=65536) == (0x5741, 0, 0)
    t = CamTable.from_points([0, 1, 2], [0, 5, 6], size=3000)
    before = t.phase.copy()
    assert not generate_into(t, nodes, Prop(CycleTime=1.0)).ok
    assert np.array_equal(t.phase, before) and t.end_point_index == 2, "on error the table keeps its data"


def test_5742_distance_overflow_aborts_and_leaves_the_error_state() -> None:
    """5742 (seed 000 lines 18078, 21166): a cubic/quintic Distance beyond REAL: that Distance is not written,
    generation stops, the table enters the error state (5743 for its users) until a generation succeeds."""
    prop = Prop(CycleTime=1000.0)
    nodes = [line(1, 1, pitch=0.5), Node(2, 2, C._mcPolynomic3, ConnectingVelEnable=True, ConnectingVel=3e38,
                                         PhasePitch=0.25)]
    t = CamTable(20)
    t.phase[:] = 99.0
    r = generate_into(t, nodes, prop)
    assert r.error is not None and (r.error.ErrorID, r.error.ErrorNodePointIndex) == (0x5742, 1)
    assert t.generation_aborted and t.phase[:3].tolist() == [0.0, 0.5, 1.0]
    assert t.phase[3] == 99.0, "the overflowing point and everything after are not written"
    assert generate_into(t, [line(1, 1, pitch=0.5)], prop).ok and not t.generation_aborted


@pytest.mark.parametrize("curve", [C._mcPolynomic3, C._mcPolynomic5])
def test_polynomial_with_zero_rise(curve: C) -> None:
    """h = d_final − d_init = 0 (the source divides by h): the products h·a_i are used, so an out-and-back
    with InitVel 10 is finite, starts at 10 units/s and ends at rest (D34)."""
    r = generate([Node(10, 0, curve, PhasePitch=0.5)], Prop(InitVel=10, CycleTime=1.0), table_size=100)
    assert r.ok and r.profile is not None and np.all(np.isfinite(r.distance))
    k = kinematics(r.profile, phase=np.array([0.0, 10.0]))
    assert k.velocity == pytest.approx([10.0, 0.0]) and k.distance == pytest.approx([0.0, 0.0])
    if curve == C._mcPolynomic3:  # b1 = Vinit·T = 10, b2 = 3h − 2·Vinit·T = −20, b3 = Vinit·T − 2h = 10 at x = ½
        assert r.distance[10] == pytest.approx(10 * 0.5 - 20 * 0.25 + 10 * 0.125, abs=1e-6)


def test_cubic_and_quintic_meet_their_boundary_values() -> None:
    """§5.4.4 formulas: f'(0)·h/T = Vinit, f'(1)·h/T = Vfin, and for the quintic f''·h/T² = Ainit, Afin."""
    prop = Prop(InitVel=30, InitAcc=-200, CycleTime=2.0)
    nodes = [Node(90, 20, C._mcPolynomic5, ConnectingVelEnable=True, ConnectingVel=5, ConnectingAccEnable=True,
                  ConnectingAcc=40, PhasePitch=0.1),
             Node(180, 0, C._mcPolynomic3, ConnectingVelEnable=True, ConnectingVel=-7, PhasePitch=0.1)]
    prof = plan(nodes, prop)
    assert isinstance(prof, CamProfile)
    k = kinematics(prof, phase=np.array([0.0, 90.0, 180.0]))
    assert k.velocity == pytest.approx([30, 5, -7]) and k.acceleration[:2] == pytest.approx([-200, 40])
    jumps = continuity(prof)
    assert [(j.quantity, j.node) for j in jumps] == [("acceleration", 0)], "the cubic cannot take Ainit = 40"


def test_connecting_conditions() -> None:
    """§5.4.4 table: Vinit from a previous cubic/quintic is its ConnectingVel only when enabled; from another
    curve 0 (even if its enable flag is set); Ainit from a previous quintic follows ConnectingAccEnable (D34)."""
    prop = Prop(CycleTime=1.0)
    p5 = C._mcPolynomic5
    prof = plan([Node(10, 5, p5, ConnectingVelEnable=True, ConnectingVel=3, ConnectingAccEnable=True,
                      ConnectingAcc=50, PhasePitch=1),
                 Node(20, 10, p5, ConnectingAccEnable=True, ConnectingAcc=60, PhasePitch=1),
                 Node(30, 15, p5, PhasePitch=1),
                 Node(40, 20, C._mcCycloidal, ConnectingVelEnable=True, ConnectingVel=9, PhasePitch=1),
                 Node(50, 25, p5, PhasePitch=1)], prop)
    assert isinstance(prof, CamProfile)
    s = prof.segments
    assert (s[1].v_init, s[1].a_init) == (3.0, 50.0)
    assert (s[2].v_init, s[2].a_init) == (0.0, 60.0), "velocity not enabled at node 1, acceleration enabled"
    assert (s[4].v_init, s[4].a_init) == (0.0, 0.0)
    assert continuity(prof, master_velocity=100.0) == []
