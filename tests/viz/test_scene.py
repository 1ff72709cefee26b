"""The live scene follows a stepped controller: step the kernel, call `SceneServer.update(snapshot)` directly, read
the handles (no viz thread, no wall clock). Positions in the scene are metres, the kinematics' are mm."""

from __future__ import annotations

import dataclasses
from collections.abc import Iterator

import numpy as np
import pytest

from mcstudio.controller.kernel import Controller, Snapshot
from mcstudio.controller.mc.kinematics import Status, UserCoordSystem, forward_point, inverse_point
from mcstudio.viz.geometry import MM, RODS, UPPER_ARMS, robot_pose
from mcstudio.viz.robot_view import ALARM_COLOR, ARM_COLOR, PLATFORM_COLOR
from mcstudio.viz.scene import SceneServer
from tests.conftest import power_on, step_until
from tests.viz.conftest import delta_project, free_port

AXES = ("MC_Axis000", "MC_Axis001", "MC_Axis002")


@pytest.fixture
def scene() -> Iterator[SceneServer]:
    s = SceneServer(port=free_port())
    yield s
    s.stop()


def _with_angles(snap: Snapshot, angles: tuple[float, float, float], *, error_axis: int | None = None) -> Snapshot:
    """A copy of `snap` with other feedback positions (and optionally one axis in ErrorStop with 6701)."""
    mc = dict(snap.mc)
    act = mc["act_pos"].copy()
    act[:3] = angles
    mc["act_pos"] = act
    if error_axis is not None:
        discrete = list(mc["discrete"])
        d = discrete[error_axis]
        discrete[error_axis] = (7, 0x6701, *d[2:])
        mc["discrete"] = tuple(discrete)
    return dataclasses.replace(snap, mc=mc)


def _move_all(c: Controller, angles: tuple[float, float, float]) -> None:
    """MC_Power and MC_Home (home preset) on A0–A2, then MC_MoveAbsolute of each to its angle, stepped to Done."""
    moves = []
    for name, a in zip(AXES, angles, strict=True):
        power_on(c, name)
        home = c.fb("MC_Home", Axis=name, Execute=True)
        step_until(c, home, "Done")
        moves.append(c.fb("MC_MoveAbsolute", Axis=name, Position=a, Velocity=90.0, Acceleration=900.0,
                          Deceleration=900.0, Execute=True))
    for mv in moves:
        step_until(c, mv, "Done")
    c.publish()


def test_scene_follows_the_feedback_of_a_stepped_controller(scene: SceneServer) -> None:
    """Cycle 0: zero pose, platform at the MCS origin; after MC_MoveAbsolute of A0–A2 to the inverse kinematics of
    (100, −50, −250) mm the platform handle is there (in m) and the links are the pose builder's."""
    c = Controller(delta_project())
    scene.rebuild(c)
    view = scene.robots[0].view
    np.testing.assert_allclose(view.platform.position, 0.0, atol=1e-9)

    target = (100.0, -50.0, -250.0)
    status, angles = inverse_point(view.spec.params, *target)
    assert status == Status.OK
    _move_all(c, angles)
    assert scene.update(c.snapshot)

    act = c.snapshot.mc["act_pos"][:3]
    np.testing.assert_allclose(act, angles, atol=1e-6)
    np.testing.assert_allclose(view.platform.position, np.array(target) * MM, atol=1e-6)
    pose = robot_pose(view.spec.params, act, view.style)
    np.testing.assert_allclose(view.links.batched_positions[UPPER_ARMS], pose.links[UPPER_ARMS, 0] * MM, atol=1e-6)
    np.testing.assert_allclose(view.links.batched_positions[RODS], pose.links[RODS, 0] * MM, atol=1e-6)
    np.testing.assert_allclose(view.links.batched_scales[RODS, 2], view.spec.params.Lm * MM, rtol=1e-5)
    np.testing.assert_allclose(view.joints.batched_positions, pose.joints * MM, atol=1e-6)
    assert len(view.trail) >= 2  # the TCP left a trail


def test_unchanged_snapshot_is_skipped(scene: SceneServer) -> None:
    c = Controller(delta_project())
    scene.rebuild(c)
    frames = scene.stats.frames
    c.step(10)  # nothing moves
    assert not scene.update(c.snapshot)
    assert scene.stats.frames == frames and scene.stats.skipped >= 1
    assert scene.update(_with_angles(c.snapshot, (5.0, 5.0, 5.0)))
    assert scene.stats.frames == frames + 1


def test_alarm_turns_the_robot_red_and_names_the_error(scene: SceneServer) -> None:
    c = Controller(delta_project())
    scene.rebuild(c)
    view = scene.robots[0].view
    assert not view.alarm_label.visible
    assert tuple(view.platform.color) == PLATFORM_COLOR
    scene.update(_with_angles(c.snapshot, (10.0, 10.0, 10.0), error_axis=1))
    assert view.alarm_label.visible
    assert "A1 MC_Axis001 ErrorStop 6701" in view.alarm_label.text
    assert tuple(view.platform.color) == ALARM_COLOR
    assert tuple(view.links.batched_colors[0]) == ALARM_COLOR
    scene.update(_with_angles(c.snapshot, (10.0, 10.0, 10.0)))  # error reset
    assert not view.alarm_label.visible
    assert tuple(view.links.batched_colors[0]) == ARM_COLOR


def test_unsolvable_feedback_hides_the_forearms(scene: SceneServer) -> None:
    c = Controller(delta_project())
    scene.rebuild(c)
    view = scene.robots[0].view
    scene.update(_with_angles(c.snapshot, (0.0, 0.0, 170.0)))
    assert not view.platform.visible
    assert np.all(view.links.batched_scales[RODS] == 0.0)
    assert "570F" in view.alarm_label.text


def test_conveyor_follows_its_axis_and_shows_workpieces(scene: SceneServer) -> None:
    """The conveyor axis (rotary, mm; §6.3) moves the cleats; `set_conveyor` places workpieces in its CS."""
    c = Controller(delta_project())
    scene.rebuild(c)
    conv = scene.conveyor
    assert conv is not None
    assert scene._conveyor_index == 3
    np.testing.assert_allclose(conv.cleats.batched_positions[:, 0], -0.5 * conv.spec.length * MM
                               + np.arange(conv.n_cleats) * conv.spec.cleat_pitch * MM, atol=1e-6)
    snap = c.snapshot
    mc = dict(snap.mc)
    act = mc["act_pos"].copy()
    act[3] = 30.0
    mc["act_pos"] = act
    assert scene.update(dataclasses.replace(snap, mc=mc))
    x = np.sort(conv.cleats.batched_positions[:, 0])  # every cleat moved 30 mm along X (and wrapped round)
    np.testing.assert_allclose(x, -0.5 * conv.spec.length * MM + (np.arange(conv.n_cleats) * conv.spec.cleat_pitch
                                                                  + 30.0) * MM, atol=1e-6)
    scene.set_conveyor(30.0, [(-200.0, 0.0, 0.0), (150.0, 50.0, 0.0)])
    assert conv.workpiece_count == 2
    np.testing.assert_allclose(conv.workpieces.batched_positions[:2], [[-0.2, 0.0, 0.0], [0.15, 0.05, 0.0]])
    assert np.all(conv.workpieces.batched_scales[2:] == 0.0)


def test_coordinate_systems_are_drawn_at_their_pose(scene: SceneServer) -> None:
    c = Controller(delta_project())
    scene.rebuild(c)
    ucs = UserCoordSystem(Tx=100.0, Ty=-50.0, Tz=-400.0, Rz=30.0)
    scene.set_coord_systems("MC_Group000", {1: ucs})
    frame = scene.robots[0].view._ucs[1]
    np.testing.assert_allclose(frame.position, [0.1, -0.05, -0.4])
    np.testing.assert_allclose(frame.wxyz, [np.cos(np.radians(15)), 0.0, 0.0, np.sin(np.radians(15))], atol=1e-12)


def test_project_without_robot_draws_no_robot(scene: SceneServer) -> None:
    from tests.conftest import small_project

    scene.rebuild(Controller(small_project()))
    assert scene.robots == [] and scene.conveyor is None
    assert not scene.update(Controller(small_project()).snapshot)


def test_forward_kinematics_of_the_feedback_is_the_platform_position(scene: SceneServer) -> None:
    c = Controller(delta_project())
    scene.rebuild(c)
    view = scene.robots[0].view
    for angles in [(12.0, 30.0, 44.0), (-20.0, 5.0, 25.0)]:
        scene.update(_with_angles(c.snapshot, angles))
        status, tcp = forward_point(view.spec.params, *angles)
        assert status == Status.OK
        np.testing.assert_allclose(view.platform.position, np.array(tcp) * MM, atol=1e-9)


def test_group_error_stop_is_an_alarm(scene: SceneServer) -> None:
    """A group in ErrorStop (`mc["groups"]`, `_sGROUP_REF` shape) shows its ErrorID even with healthy axes."""
    c = Controller(delta_project())
    scene.rebuild(c)
    view = scene.robots[0].view
    snap = _with_angles(c.snapshot, (10.0, 10.0, 10.0))
    mc = dict(snap.mc)
    mc["groups"] = ({"name": "MC_Group000", "Status": {"Ready": False, "Disabled": False, "ErrorStop": True},
                     "MFaultLvl": {"Active": True, "Code": "6700"}},)
    scene.update(dataclasses.replace(snap, mc=mc))
    assert view.alarm_label.visible and "MC_Group000 ErrorStop 6700" in view.alarm_label.text


def test_trail_is_bounded_and_sent_when_the_robot_stops(scene: SceneServer) -> None:
    """The trail keeps the last TRAIL_POINTS distinct TCP points (≥ 1 mm apart), oldest first; points added since
    the last send go out with the first skipped (unchanged) frame."""
    from mcstudio.viz.robot_view import TRAIL_POINTS, TRAIL_STEP_MM

    c = Controller(delta_project())
    scene.rebuild(c)
    view = scene.robots[0].view
    expected = [np.zeros(3)]  # the zero pose drawn by rebuild
    angles = (0.0, 0.0, 0.0)
    for k in range(TRAIL_POINTS + 200):  # the arms circle round: the TCP runs a closed path ~3 mm per frame
        ph = 2.0 * np.pi * k / 200.0
        angles = tuple(25.0 + 15.0 * np.sin(ph + j * 2.0 * np.pi / 3.0) for j in range(3))
        scene.update(_with_angles(c.snapshot, angles))
        tcp = np.array(forward_point(view.spec.params, *angles)[1])
        if np.linalg.norm(tcp - expected[-1]) >= TRAIL_STEP_MM:
            expected.append(tcp)
    assert len(expected) > TRAIL_POINTS
    np.testing.assert_allclose(view.trail, expected[-TRAIL_POINTS:], atol=1e-9)
    scene.update(_with_angles(c.snapshot, angles))  # unchanged: skipped, but the trail's last points are sent
    assert not view.trail_dirty
    assert view.trail_handle.points.shape == (TRAIL_POINTS - 1, 2, 3)
    np.testing.assert_allclose(view.trail_handle.points[-1, 1], expected[-1] * MM, atol=1e-6)


def test_plant_workpieces_ride_on_the_conveyor_axis(scene: SceneServer) -> None:
    """Without `set_conveyor`, the plant's workpieces (plant/workpieces.py: one every 200 mm of belt travel) move
    with the conveyor axis's feedback."""
    from mcstudio.plant.workpieces import WorkpieceSource

    c = Controller(delta_project())
    scene.rebuild(c)
    conv = scene.conveyor
    assert conv is not None
    snap = c.snapshot
    mc = dict(snap.mc)
    act = mc["act_pos"].copy()
    act[3] = 450.0
    mc["act_pos"] = act
    scene.update(dataclasses.replace(snap, mc=mc))
    half = conv.spec.length / 2.0
    expected = WorkpieceSource(pitch=200.0, entry_x=-half, exit_x=half).positions(450.0)
    assert conv.workpiece_count == len(expected) >= 2
    np.testing.assert_allclose(conv.workpieces.batched_positions[: len(expected)], np.array(expected) * MM,
                               atol=1e-12)


def test_coordinate_systems_defined_by_the_program_are_shown(scene: SceneServer) -> None:
    """MC_DefineCoordSystem in the controller → the UCS frame appears in the next frame."""
    import types

    c = Controller(delta_project())
    scene.rebuild(c)
    scene._runner = types.SimpleNamespace(controller=c, epoch=0)  # type: ignore[assignment]
    d = c.fb("MC_DefineCoordSystem", AxesGroup="MC_Group000", Execute=True,
             CoordTransform={"CSID": 2, "Pose": [10.0, 20.0, -300.0, 0.0, 0.0, 90.0]})
    step_until(c, d, "Done")
    scene.update(c.snapshot, force=True)
    frame = scene.robots[0].view._ucs[2]
    np.testing.assert_allclose(frame.position, [0.01, 0.02, -0.3])


def test_the_robot_is_redrawn_with_the_kinematics_mc_set_kin_transform_sets(scene: SceneServer) -> None:
    """D94 (instructions.md MC_SetKinTransform): the view draws the kinematics **in force**. MC_SetKinTransform on
    the running controller (θ 30°, Lf 320 mm, a smaller workspace) → the next frame rebuilds the robot: its spec is
    the new one, the platform sits at the forward kinematics of the feedback with the new parameters, the workspace
    mesh has the new radius; after a 571F (kinematics deleted) the project's parameters are drawn again."""
    import types

    c = Controller(delta_project())
    scene.rebuild(c)
    scene._runner = types.SimpleNamespace(controller=c, epoch=0)  # type: ignore[assignment]
    _move_all(c, (20.0, 25.0, 30.0))
    scene.update(c.snapshot)
    assert scene.robots[0].view.spec.params.theta == 0.0
    kin = c.fb("MC_SetKinTransform", AxesGroup="MC_Group000", Execute=True,
               KinTransform={"KinType": 100, "KinParam": [200.0, 320.0, 50.0, 800.0], "ExpansionParam": [30.0]},
               Workspace={"WorkspaceType": 100, "WorkspaceParam": [-60.0, 250.0, 250.0, 150.0, 150.0]})
    step_until(c, kin, "Done")
    c.publish()
    assert scene.update(c.snapshot)
    view = scene.robots[0].view
    p = view.spec.params
    assert (p.Rf, p.Lf, p.Rm, p.Lm, p.theta) == (200.0, 320.0, 50.0, 800.0, 30.0)
    assert view.spec.workspace is not None and view.spec.workspace.Rcy == 250.0
    st, tcp = forward_point(p, *c.snapshot.mc["act_pos"][:3])
    assert st == Status.OK
    np.testing.assert_allclose(view.platform.position, np.array(tcp) * MM, atol=1e-9)
    radius = np.hypot(view.workspace.vertices[:, 0], view.workspace.vertices[:, 1]).max()
    assert radius == pytest.approx(250.0 * MM, rel=1e-9)
    assert not scene.update(c.snapshot), "unchanged: no second rebuild"
    # restriction (5) violated (Rcy > Lm·cos 30°) → 571F deletes the kinematics: the project's are drawn
    bad = c.fb("MC_SetKinTransform", AxesGroup="MC_Group000", Execute=True,
               KinTransform={"KinType": 100, "KinParam": [200.0, 350.0, 50.0, 800.0], "ExpansionParam": [0.0]},
               Workspace={"WorkspaceType": 100, "WorkspaceParam": [-50.0, 700.0, 250.0, 150.0, 150.0]})
    c.step(1)
    assert bad.ErrorID == 0x571F and c.mc.groups_by_name["MC_Group000"].kinematics is None
    c.publish()
    scene.update(c.snapshot)
    assert scene.robots[0].view.spec.params.theta == 0.0 and scene.robots[0].view.spec.params.Lf == 350.0
