"""User coordinate systems: pose (Tx, Ty, Tz, Rx, Ry, Rz), R = Rz·Ry·Rx (intrinsic Z-Y′-X″), MCS ↔ UCS, and
MC_DefineCoordSystem's checks (`omron-robot-delta3.md` §4, §8.2, §9.2; seed 003 L2187–2234; D30.8)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mcstudio.controller.mc.kinematics import UserCoordSystem, check_csid, check_pose
from mcstudio.controller.mc.kinematics.ucs import rotation


def test_rotation_order_and_signs() -> None:
    """Seed L2205–2215: Rz positive turns Xu toward Yu; then Ry about the new Yu1, positive turning Zu1 toward Xu1;
    then Rx about the new Xu2, positive turning Yu2 toward Zu2."""
    np.testing.assert_allclose(rotation(0, 0, 90) @ [1, 0, 0], [0, 1, 0], atol=1e-15)  # X → Y
    np.testing.assert_allclose(rotation(0, 90, 0) @ [0, 0, 1], [1, 0, 0], atol=1e-15)  # Z → X
    np.testing.assert_allclose(rotation(90, 0, 0) @ [0, 1, 0], [0, 0, 1], atol=1e-15)  # Y → Z
    # Intrinsic: after Rz = 90° the Ry rotation turns about the new Y axis (= old −X): Z goes to +Y.
    np.testing.assert_allclose(rotation(0, 90, 90) @ [0, 0, 1], [0, 1, 0], atol=1e-15)
    r = rotation(10, 20, 30)
    np.testing.assert_allclose(r @ r.T, np.eye(3), atol=1e-15)
    assert np.linalg.det(r) == pytest.approx(1.0)


def test_translation_and_round_trip() -> None:
    """p_MCS = T + R·p_UCS; p_UCS = Rᵀ·(p_MCS − T); velocities rotate without translation (MC_GroupMon, §9.3)."""
    u = UserCoordSystem(Tx=100.0, Ty=-50.0, Tz=-300.0, Rz=90.0)
    np.testing.assert_allclose(u.to_mcs([0.0, 0.0, 0.0]), [100.0, -50.0, -300.0])
    np.testing.assert_allclose(u.to_mcs([10.0, 0.0, 0.0]), [100.0, -40.0, -300.0], atol=1e-12)
    np.testing.assert_allclose(u.vector_from_mcs([0.0, 5.0, 0.0]), [5.0, 0.0, 0.0], atol=1e-12)
    rng = np.random.default_rng(12)
    for _ in range(50):
        pose = [*rng.uniform(-500, 500, 3), rng.uniform(-180, 180), rng.uniform(-90, 90), rng.uniform(-180, 180)]
        ucs = UserCoordSystem.from_pose(pose)
        assert ucs.pose() == pytest.approx(pose)
        pts = rng.uniform(-1000, 1000, (100, 3))
        np.testing.assert_allclose(ucs.from_mcs(ucs.to_mcs(pts)), pts, atol=1e-9)
        np.testing.assert_allclose(ucs.to_mcs(ucs.from_mcs(pts)), pts, atol=1e-9)
        np.testing.assert_allclose(ucs.vector_to_mcs(ucs.vector_from_mcs(pts)), pts, atol=1e-9)
        assert np.linalg.norm(ucs.to_mcs(pts) - ucs.T, axis=-1) == pytest.approx(np.linalg.norm(pts, axis=-1))


def test_planar_pose_for_conveyor_tracking() -> None:
    """§9.5 [Emulator]: MC_SyncLinearConveyor uses only Tx, Ty, Tz, Rz of a UCS."""
    u = UserCoordSystem(Tx=1.0, Ty=2.0, Tz=3.0, Rx=10.0, Ry=20.0, Rz=30.0).planar()
    assert u.pose() == [1.0, 2.0, 3.0, 0.0, 0.0, 30.0]


@pytest.mark.parametrize(("pose", "code"), [
    ([0, 0, 0, 180, 90, -180], 0), ([1e6, -1e6, 0, 0, 0, 0], 0), ([0, 0, 0, 180.001, 0, 0], 0x570C),
    ([0, 0, 0, 0, -90.001, 0], 0x570C), ([0, 0, 0, 0, 0, 181], 0x570C), ([math.nan, 0, 0, 0, 0, 0], 0x570C),
    ([0, math.inf, 0, 0, 0, 0], 0x570C), ([0] * 7, 0x570C),
])
def test_pose_ranges(pose: list[float], code: int) -> None:
    """570C: Pose[3] Rx −180…180, Pose[4] Ry −90…90, Pose[5] Rz −180…180; Tx, Ty, Tz any finite value (D30.8)."""
    assert check_pose(pose)[0] == code


def test_csid() -> None:
    """570B: CSID 0–15, and (when asked) defined by MC_DefineCoordSystem."""
    assert check_csid(0)[0] == 0 and check_csid(15)[0] == 0
    assert check_csid(16)[0] == 0x570B and check_csid(-1)[0] == 0x570B
    assert check_csid(3, defined=[0, 1])[0] == 0x570B and check_csid(1, defined=[0, 1])[0] == 0
