"""Robot kinematics of the NJ501-4□□□ robot functions: Delta3 (`omron-robot-delta3.md` §2–§4, §12; docs/robot.md).

Pure numpy/math, no MC-layer state, no exceptions for bad input (statuses and ErrorIDs are values):

* `check_kin_transform(KinParam=…, ExpansionParam=…, WorkspaceParam=…)` — MC_SetKinTransform's checks → `KinCheck`
  (error_id, restriction, parameter, message, and on success `params` and `workspace`);
* vectorised over (..., 3): `inverse`, `forward`, `arm_geometry`, `jacobian`, `tcp_velocity`, `joint_velocity`,
  `Delta3Workspace.contains` / `signed_distance`;
* one point per period (plain math, ~4 µs): `inverse_point`, `forward_point`, `tcp_velocity_point`,
  `joint_velocity_point`, `contains_point`, `signed_distance_point`;
* user coordinate systems: `UserCoordSystem`, `check_pose` (570C), `check_csid` (570B).
"""

from .codes import Status, WorkspaceCheck
from .delta3 import (
    ArmGeometry,
    ForwardResult,
    InverseResult,
    arm_geometry,
    forward,
    inverse,
    jacobian,
    joint_velocity,
    tcp_velocity,
)
from .params import ARM_AZIMUTH0_DEG, Delta3Params
from .point import (
    contains_point,
    forward_point,
    inverse_point,
    joint_velocity_point,
    signed_distance_point,
    tcp_velocity_point,
)
from .restrictions import KinCheck, check_kin_transform, check_restrictions
from .ucs import UserCoordSystem, check_csid, check_pose
from .workspace import MARGIN_MM, Delta3Workspace

__all__ = [
    "ARM_AZIMUTH0_DEG",
    "MARGIN_MM",
    "ArmGeometry",
    "Delta3Params",
    "Delta3Workspace",
    "ForwardResult",
    "InverseResult",
    "KinCheck",
    "Status",
    "UserCoordSystem",
    "WorkspaceCheck",
    "arm_geometry",
    "check_csid",
    "check_kin_transform",
    "check_pose",
    "check_restrictions",
    "contains_point",
    "forward",
    "forward_point",
    "inverse",
    "inverse_point",
    "jacobian",
    "joint_velocity",
    "joint_velocity_point",
    "signed_distance_point",
    "tcp_velocity",
    "tcp_velocity_point",
]
