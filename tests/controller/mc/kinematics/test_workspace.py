"""The Delta3 workspace and its 0.1 mm margin (`omron-robot-delta3.md` §3.2, §12.6; seed 003 L1968–2073; D30.4/.7)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mcstudio.controller.mc.kinematics import (
    Delta3Params,
    Delta3Workspace,
    Status,
    WorkspaceCheck,
    contains_point,
    inverse,
    signed_distance_point,
)


def test_reference_points(ws: Delta3Workspace) -> None:
    """The eight points of the §12.9 script's `in_workspace` run, with its answers."""
    pts = [(0, 0, -50), (0, 0, -50.2), (299.95, 0, -200), (299.85, 0, -200), (200, 0, -420), (200, 0, -380),
           (0, 0, -449.95), (0, 0, -449.8)]
    assert ws.contains(pts).tolist() == [False, True, False, True, False, True, False, True]


@pytest.mark.parametrize(("point", "inside"), [
    # top face z = Zu = −50: a target exactly 0.1 mm below is inside (manual: "set targets 0.1 mm inside")
    ((0.0, 0.0, -50.1), True), ((0.0, 0.0, -50.0999), False), ((100.0, 100.0, -50.1), True),
    # bottom face z = Zu − Hcy − Hco = −450
    ((0.0, 0.0, -449.9), True), ((0.0, 0.0, -449.9001), False), ((50.0, -50.0, -449.9), True),
    # cylinder wall r = 300 (at z = −200), also off the axes
    ((299.9, 0.0, -200.0), True), ((299.9001, 0.0, -200.0), False),
    ((299.9 / math.sqrt(2), -299.9 / math.sqrt(2), -200.0), True),
    ((299.9001 / math.sqrt(2), -299.9001 / math.sqrt(2), -200.0), False),
    # cone wall at z = −380: radius 220, face at 45°, so 0.1 mm normal to it is 0.1·√2 mm in r
    ((220.0 - 0.1 * math.sqrt(2), 0.0, -380.0), True), ((220.0 - 0.1 * math.sqrt(2) + 1e-4, 0.0, -380.0), False),
    # outside altogether
    ((0.0, 0.0, 0.0), False), ((400.0, 0.0, -200.0), False), ((0.0, 0.0, -500.0), False),
])
def test_margin_on_every_face(ws: Delta3Workspace, point: tuple[float, float, float], inside: bool) -> None:
    """Manual 3.3.2 (3): the drivable region is 0.1 mm inside every face of the configured workspace (D30.4)."""
    assert bool(ws.contains(point)) is inside
    assert contains_point(ws, *point) is inside


def test_margin_at_the_cylinder_cone_edge(ws: Delta3Workspace) -> None:
    """D30.4: 0.1 mm from every surface point also at the edge where the cylinder meets the cone. 0.1 mm inside the
    wall and 0.01 mm above the edge, the point is only 0.078 mm from the cone face: outside (§12.6's per-face rule
    would let it in). 0.15 mm inside the wall it is 0.11 mm from the cone: inside."""
    p = (299.9, 0.0, -299.99)
    assert ws.signed_distance(p) == pytest.approx(0.11 / math.sqrt(2), abs=1e-9)
    assert not ws.contains(p)
    assert ws.contains((299.85, 0.0, -299.99))


def test_widening_cone_rounds_the_inner_edge() -> None:
    """A cone wider at the bottom (Rco > Rcy) is valid; at its re-entrant edge the drivable region keeps 0.1 mm
    from the edge ring itself, so a point 0.1005 mm from the ring (and further from both faces) is inside."""
    wide = Delta3Workspace(Zu=-50.0, Rcy=200.0, Hcy=100.0, Rco=300.0, Hco=100.0)
    a = math.radians(200.0)  # direction from the ring (200, −150) into the solid, below the edge
    p = (200.0 + 0.1005 * math.cos(a), 0.0, -150.0 + 0.1005 * math.sin(a))
    assert wide.signed_distance(p) == pytest.approx(0.1005, abs=1e-9)
    assert wide.contains(p)
    assert not wide.contains((199.93, 0.0, -150.02))  # 0.073 mm from the ring
    # The bottom corner is a 45° wedge: 0.1 mm from the bottom face and 0.14 mm from the cone is inside.
    assert wide.contains((299.7, 0.0, -249.9))
    assert not wide.contains((299.7, 0.0, -249.95))
    assert not wide.contains((299.8, 0.0, -249.9))  # 0.07 mm from the cone face


def test_no_cone_and_pointed_cone() -> None:
    """WorkspaceParam[3], [4] may be 0 (§8.2): Hco = 0 is a plain cylinder; Rco = 0 a cone down to a point."""
    cyl = Delta3Workspace(Zu=0.0, Rcy=100.0, Hcy=100.0, Rco=0.0, Hco=0.0)
    assert cyl.contains([(0.0, 0.0, -99.9), (99.9, 0.0, -50.0), (0.0, 0.0, -0.1)]).all()
    assert not cyl.contains([(0.0, 0.0, -99.95), (99.95, 0.0, -50.0), (0.0, 0.0, -0.05)]).any()
    point = Delta3Workspace(Zu=0.0, Rcy=100.0, Hcy=100.0, Rco=0.0, Hco=100.0)  # 45° cone, apex at z = −200
    assert point.signed_distance((0.0, 0.0, -199.5)) == pytest.approx(0.5 / math.sqrt(2), abs=1e-9)
    assert point.contains((0.0, 0.0, -199.5))
    assert not point.contains((0.0, 0.0, -199.88))
    for p in [(0.0, 0.0, -199.5), (0.0, 0.0, -199.88), (50.0, 20.0, -120.0), (99.0, 0.0, -101.0)]:
        assert signed_distance_point(point, *p) == pytest.approx(float(point.signed_distance(p)), abs=1e-12)


def test_signed_distance_outside(ws: Delta3Workspace) -> None:
    """Negative outside, by the distance to the surface (for event texts): 50 mm above the top, 100 mm beside the
    cylinder, NaN for non-finite points (which are outside)."""
    d = ws.signed_distance([(0.0, 0.0, 0.0), (400.0, 0.0, -200.0), (np.nan, 0.0, -200.0), (0.0, np.inf, -200.0)])
    assert d[0] == pytest.approx(-50.0) and d[1] == pytest.approx(-100.0)
    assert np.isnan(d[2]) and np.isnan(d[3])
    assert not ws.contains([(np.nan, 0.0, -200.0), (0.0, np.inf, -200.0)]).any()
    assert not contains_point(ws, math.nan, 0.0, -200.0)


def test_workspace_checks_and_codes() -> None:
    """§3.2's four checks and their codes: (1) current position at start 6701, (2) target at start 571B
    (MC_MoveTimeAbsolute) / 5719 (MC_SyncLinearConveyor initial workpiece), (3) every generated command 6700,
    (4) feedback while stopped — no code in the manual, 6701 (D30.7)."""
    codes = {c.name: (c.number, c.error_id) for c in WorkspaceCheck}
    assert codes == {"CURRENT_AT_START": (1, 0x6701), "TARGET_AT_START": (2, 0x571B),
                     "WORKPIECE_AT_START": (2, 0x5719), "COMMAND_EVERY_PERIOD": (3, 0x6700),
                     "FEEDBACK_WHILE_STOPPED": (4, 0x6701)}


def test_target_outside_the_workspace_gives_the_manuals_error(robot: Delta3Params, ws: Delta3Workspace) -> None:
    """§9.4: MC_MoveTimeAbsolute with a target outside the workspace → 571B; MC_SyncLinearConveyor's initial
    workpiece position outside → 5719; a generated command outside → 6700; the current position → 6701. The same
    reachable point inside the workspace passes."""
    outside = (0.0, 0.0, -20.0)  # reachable (between the zero pose and the top face) but above Zu − 0.1
    for check in WorkspaceCheck:
        r = inverse(robot, outside, workspace=ws, check=check)
        assert r.status == Status.OUTSIDE_WORKSPACE and r.error_id == check.error_id and r.reachable
    assert inverse(robot, (0.0, 0.0, -200.0), workspace=ws, check=WorkspaceCheck.TARGET_AT_START).ok


def test_param_round_trip() -> None:
    """`WorkspaceParam[0..7]` order Zu, Rcy, Hcy, Rco, Hco (§8.2)."""
    w = Delta3Workspace.from_workspace_param([-50.0, 300.0, 250.0, 150.0, 150.0, 0.0, 0.0, 0.0])
    assert (w.Zu, w.Rcy, w.Hcy, w.Rco, w.Hco, w.margin) == (-50.0, 300.0, 250.0, 150.0, 150.0, 0.1)
    assert w.workspace_param() == [-50.0, 300.0, 250.0, 150.0, 150.0, 0.0, 0.0, 0.0]
    assert w.profile() == [(0.0, -50.0), (300.0, -50.0), (300.0, -300.0), (150.0, -450.0), (0.0, -450.0)]
