"""ErrorIDs of the NJ501-4□□□ robot functions that the kinematics module hands back as values, and the four
workspace checks of the manual with the code each one raises (`omron-robot-delta3.md` §3.2, §9.1, §11;
seed 003 lines 1975–1983, 5390–5440, 5660–5700).

The module never raises for bad user input: every function returns one of these codes (0 = no error) and the MC
layer turns it into the instance's ErrorID and the event. The codes are kept here rather than in
`controller/mc/errors.py` so this package stays pure (no import of the MC layer)."""

from __future__ import annotations

import enum

E_NONE = 0x0000
E_KIN_PARAM = 0x5708  # KinParam / ExpansionParam out of range (incl. restrictions (1), (3): D30.6)
E_KIN_TYPE = 0x5707  # KinType ≠ 100 (_mcDelta3Type1)
E_WORKSPACE_TYPE = 0x5709  # WorkspaceType ≠ 100 (_mcDelta3Workspace)
E_WORKSPACE_PARAM = 0x570A  # WorkspaceParam out of range
E_CSID = 0x570B  # user coordinate system number out of range / not defined
E_POSE = 0x570C  # CoordTransform.Pose out of range
E_KIN_CALC = 0x570F  # kinematics cannot be calculated (IK of a target, FK of the axes)
E_INIT_WORKPIECE_OUTSIDE = 0x5719  # MC_SyncLinearConveyor: InitWorkpiecePosition outside the workspace
E_TARGET_OUTSIDE = 0x571B  # MC_MoveTimeAbsolute: Position outside the workspace
E_KIN_INIT = 0x571F  # kinematics initialisation error (restrictions (2), (4), (5), zero pose: D30.6)
E_COMMAND_OUTSIDE = 0x6700  # a generated command position outside the workspace
E_CURRENT_OUTSIDE = 0x6701  # current position outside the workspace at the start of an instruction


class WorkspaceCheck(enum.Enum):
    """The four checks of manual 3.3.2 (seed 003 L1975–1983). The value is (check number 1–4, ErrorID).

    Check 2 has two codes, one per instruction (571B MC_MoveTimeAbsolute, 5719 MC_SyncLinearConveyor). Check 4
    ("TCP feedback while the robot is stopped") has no code in the manual; it raises 6701, the code named
    "current position outside the workspace" (decision D30.7)."""

    CURRENT_AT_START = (1, E_CURRENT_OUTSIDE)
    TARGET_AT_START = (2, E_TARGET_OUTSIDE)
    WORKPIECE_AT_START = (2, E_INIT_WORKPIECE_OUTSIDE)
    COMMAND_EVERY_PERIOD = (3, E_COMMAND_OUTSIDE)
    FEEDBACK_WHILE_STOPPED = (4, E_CURRENT_OUTSIDE)

    @property
    def number(self) -> int:
        """The check's number in the manual's list (1–4)."""
        return int(self.value[0])

    @property
    def error_id(self) -> int:
        """The ErrorID raised when a point fails this check."""
        return int(self.value[1])


class Status(enum.IntEnum):
    """Per-point result of `inverse`, `forward` and the velocity functions (an int8 array of these)."""

    OK = 0
    OUTSIDE_WORKSPACE = 1  # finite and (maybe) reachable, but outside the 0.1 mm-shrunk workspace
    UNREACHABLE = 2  # no solution on the robot's branch (570F)
    NOT_FINITE = 3  # NaN or ±inf in the input (570F)
    SINGULAR = 4  # velocity functions only: the Jacobian cannot be inverted here
