"""The 3-D view's pure geometry: the Delta3 pose builder against the kinematics (`omron-robot-delta3.md` §12.8),
meshes and transforms."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mcstudio.controller.mc.kinematics import (
    Delta3Params,
    Delta3Workspace,
    Status,
    UserCoordSystem,
    arm_geometry,
    forward_point,
    inverse_point,
)
from mcstudio.viz.geometry import (
    ELBOW_BARS,
    RODS,
    UPPER_ARMS,
    RobotStyle,
    base_polygon,
    platform_polygon,
    quat_from_matrix,
    quat_z_to,
    revolve,
    robot_pose,
    rotate_by_quat,
    segment_transforms,
    unit_cylinder,
    workspace_mesh,
    workspace_outline,
)

POSES = [(0.0, 0.0, 0.0), (20.0, 35.0, 10.0), (-15.0, 40.0, 55.0), (60.0, 60.0, 60.0)]


@pytest.mark.parametrize("angles", POSES)
def test_arm_end_points_are_the_kinematics_elbows_and_wrists(params: Delta3Params,
                                                               angles: tuple[float, float, float]) -> None:
    """Upper arm i runs Mᵢ → Eᵢ, its two rods Eᵢ ± w/2·tᵢ → Wᵢ ± w/2·tᵢ (§12.8), every rod is Lm long and the
    platform centre is the forward kinematics' TCP."""
    style = RobotStyle.for_params(params)
    pose = robot_pose(params, angles, style)
    g = arm_geometry(params, angles, rod_spacing=style.rod_spacing)
    assert pose.ok
    np.testing.assert_allclose(pose.links[UPPER_ARMS, 0], g.shoulders, atol=1e-12)
    np.testing.assert_allclose(pose.links[UPPER_ARMS, 1], g.elbows, atol=1e-12)
    np.testing.assert_allclose(np.linalg.norm(pose.links[UPPER_ARMS, 1] - pose.links[UPPER_ARMS, 0], axis=-1),
                               params.Lf, atol=1e-9)
    half = 0.5 * style.rod_spacing * params.tangential
    for i in range(3):
        for k, sign in enumerate((1.0, -1.0)):
            rod = pose.links[RODS][2 * i + k]
            np.testing.assert_allclose(rod[0], g.elbows[i] + sign * half[i], atol=1e-9)
            np.testing.assert_allclose(rod[1], g.wrists[i] + sign * half[i], atol=1e-9)
            assert math.isclose(float(np.linalg.norm(rod[1] - rod[0])), params.Lm, abs_tol=1e-6)
        bar = pose.links[ELBOW_BARS][i]
        np.testing.assert_allclose(0.5 * (bar[0] + bar[1]), g.elbows[i], atol=1e-9)
    status, tcp = forward_point(params, *angles)
    assert status == Status.OK
    np.testing.assert_allclose(pose.tcp, tcp, atol=1e-9)
    # wrists sit on the platform, Rm from its centre, in its plane (the platform only translates)
    np.testing.assert_allclose(np.linalg.norm(pose.wrists - pose.tcp, axis=-1), params.Rm, atol=1e-9)
    np.testing.assert_allclose(pose.wrists[:, 2], pose.tcp[2], atol=1e-9)


def test_pose_of_an_inverse_kinematics_target_puts_the_platform_on_the_target(params: Delta3Params) -> None:
    target = (120.0, -80.0, -300.0)
    status, angles = inverse_point(params, *target)
    assert status == Status.OK
    np.testing.assert_allclose(robot_pose(params, angles).tcp, target, atol=1e-9)


def test_zero_pose_is_the_mcs_origin(params: Delta3Params) -> None:
    """§12.1/D30.2: the TCP is at the MCS origin when A0 = A1 = A2 = 0 and the motor plane at z = −Z0."""
    pose = robot_pose(params, (0.0, 0.0, 0.0))
    np.testing.assert_allclose(pose.tcp, 0.0, atol=1e-9)
    np.testing.assert_allclose(pose.shoulders[:, 2], params.motor_plane_z)


def test_unsolvable_angles_give_a_status_not_an_exception(params: Delta3Params) -> None:
    pose = robot_pose(params, (0.0, 0.0, 170.0))  # A2 folded back over the base: the forearms cannot close
    assert not pose.ok
    assert np.all(np.isnan(pose.tcp))
    assert np.all(np.isfinite(pose.links[UPPER_ARMS]))  # the upper arms follow from the angles alone


def test_workspace_mesh_bounds_are_the_configured_workspace(workspace: Delta3Workspace) -> None:
    m = workspace_mesh(workspace, segments=96)
    lo, hi = m.bounds
    assert hi[2] == pytest.approx(workspace.Zu)
    assert lo[2] == pytest.approx(workspace.z_bottom)
    assert hi[0] == pytest.approx(workspace.Rcy) and lo[0] == pytest.approx(-workspace.Rcy)
    r = np.hypot(m.vertices[:, 0], m.vertices[:, 1])
    assert r.max() == pytest.approx(workspace.Rcy)
    # the cone's lower face has radius Rco; the cylinder/cone edge lies at Zu − Hcy with radius Rcy
    assert r[np.isclose(m.vertices[:, 2], workspace.z_bottom)].max() == pytest.approx(workspace.Rco)
    assert r[np.isclose(m.vertices[:, 2], workspace.z_cylinder_bottom)].max() == pytest.approx(workspace.Rcy)
    assert m.faces.max() < len(m.vertices)
    edges = workspace_outline(workspace)
    assert edges.shape[1:] == (2, 3)
    assert edges[..., 2].max() == pytest.approx(workspace.Zu) and edges[..., 2].min() == pytest.approx(
        workspace.z_bottom)


def test_revolve_faces_point_outward() -> None:
    """A closed body of revolution has a positive volume with counter-clockwise faces seen from outside."""
    m = revolve([(0.0, 1.0), (2.0, 1.0), (2.0, 0.0), (0.0, 0.0)], segments=128)
    v = m.vertices[m.faces]
    volume = np.einsum("ij,ij->i", v[:, 0], np.cross(v[:, 1], v[:, 2])).sum() / 6.0
    assert volume == pytest.approx(math.pi * 4.0, rel=2e-3)


def test_segment_transforms_map_the_unit_cylinder_onto_the_segment() -> None:
    rng = np.random.default_rng(7)
    segs = rng.normal(size=(50, 2, 3))
    segs[0, 1] = segs[0, 0] - (0.0, 0.0, 2.0)  # straight down: the antiparallel case of quat_z_to
    tf = segment_transforms(segs, 0.1)
    cyl = unit_cylinder(8)
    for k in range(len(segs)):
        top = rotate_by_quat(tf.wxyzs[k], np.array([0.0, 0.0, 1.0]) * tf.scales[k]) + tf.positions[k]
        np.testing.assert_allclose(top, segs[k, 1], atol=1e-12)
        pts = rotate_by_quat(tf.wxyzs[k], cyl.vertices * tf.scales[k]) + tf.positions[k]
        axis = (segs[k, 1] - segs[k, 0]) / np.linalg.norm(segs[k, 1] - segs[k, 0])
        radial = (pts - segs[k, 0]) - np.outer((pts - segs[k, 0]) @ axis, axis)
        assert np.linalg.norm(radial, axis=-1).max() == pytest.approx(0.1)
    np.testing.assert_allclose(np.linalg.norm(quat_z_to(segs[:, 1] - segs[:, 0]), axis=-1), 1.0)


def test_quaternion_of_a_ucs_rotation_matches_its_matrix() -> None:
    """UCS frames are drawn with R = Rz·Ry·Rx (§4) turned into a quaternion."""
    for pose in [(0, 0, 0, 0, 0, 0), (10, 20, -30, 170, -80, 45), (0, 0, 0, 180, 0, 0), (0, 0, 0, 0, 90, -180)]:
        ucs = UserCoordSystem.from_pose(pose)
        q = quat_from_matrix(ucs.R)
        np.testing.assert_allclose(rotate_by_quat(q, np.eye(3)), ucs.R.T, atol=1e-12)


def test_plates_hold_the_motors_and_the_wrist_joints(params: Delta3Params) -> None:
    style = RobotStyle.for_params(params)
    base = base_polygon(params, margin=0.12 * params.Rf)
    plate = platform_polygon(params, style)
    pose = robot_pose(params, (0.0, 0.0, 0.0), style)

    def inside(poly: np.ndarray, pts: np.ndarray) -> bool:
        edges = np.roll(poly, -1, axis=0) - poly
        rel = pts[:, None, :2] - poly[None]
        return bool(np.all(edges[None, :, 0] * rel[..., 1] - edges[None, :, 1] * rel[..., 0] >= -1e-9))

    assert inside(base, pose.shoulders)
    joints = pose.links[RODS, 1] - pose.tcp  # the rods' lower ends around the platform centre
    assert inside(plate, joints)
