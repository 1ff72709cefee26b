"""Enumerations of the NJ/NX MC function module, with the manual's literal names and values.

Source: `omron-mc-basics.md` §2.7 (seed 000 lines 1957–2009) and the enumerations embedded in §2.3/§2.4.
Members keep the vendor spelling (`_mcAborting`), so code reads against the manual.
"""

from __future__ import annotations

import enum


class _eMC_BUFFER_MODE(enum.IntEnum):
    _mcAborting = 0
    _mcBuffered = 1
    _mcBlendingLow = 2
    _mcBlendingPrevious = 3
    _mcBlendingNext = 4
    _mcBlendingHigh = 5


class _eMC_DIRECTION(enum.IntEnum):
    _mcPositiveDirection = 0
    _mcShortestWay = 1
    _mcNegativeDirection = 2
    _mcCurrentDirection = 3
    _mcNoDirection = 4


class _eMC_STOP_MODE(enum.IntEnum):
    _mcDecelerationStop = 0
    _mcImmediateStop = 1
    _mcImmediateStopFEReset = 2
    _mcFreeRunStop = 3
    _mcNonStop = 4


class _eMC_MOVE_MODE(enum.IntEnum):
    _mcAbsolute = 0
    _mcRelative = 1
    _mcVelocity = 2


class _eMC_AXIS_TYPE(enum.IntEnum):
    _mcServo = 0
    _mcEncdr = 1
    _mcVirServo = 2
    _mcVirEncdr = 3


class _eMC_AXIS_USE(enum.IntEnum):
    _mcNoneAxis = 0
    _mcUnusedAxis = 1
    _mcUsedAxis = 2


class _eMC_UNITS(enum.IntEnum):
    _mcPls = 0
    _mcMm = 1
    _mcUm = 2
    _mcNm = 3
    _mcDeg = 4
    _mcInch = 5


class _eMC_COUNT_MODE(enum.IntEnum):
    _mcCountModeLinear = 0
    _mcCountModeRotary = 1


class _eMC_ACCDECOVER(enum.IntEnum):
    _mcAccDecOverBuffer = 0
    _mcAccDecOverRapid = 1
    _mcAccDecOverErrorStop = 2


class _eMC_REVERSE_MODE(enum.IntEnum):
    _mcReverseModeDecelerationStop = 0
    _mcReverseModeImmediateStop = 1


class _eMC_SWLMT_MODE(enum.IntEnum):
    _mcNonSwLmt = 0
    _mcCmdDecelerationStop = 1
    _mcCmdImmediateStop = 2
    _mcActDecelerationStop = 3
    _mcActImmediateStop = 4


class _eMC_HOMING_MODE(enum.IntEnum):
    _mcHomeSwTurnHomeSwOff = 0
    _mcHomeSwTurnHomeSwOn = 1
    _mcHomeSwOff = 4
    _mcHomeSwOn = 5
    _mcLimitInputOff = 8
    _mcHomeSwTurnHomeMask = 9
    _mcLimitInputOnly = 11
    _mcHomeSwTurnHoldingTime = 12
    _mcNoHomeSwHoldingHomeInput = 13
    _mcHomePreset = 14


class _eMC_HOME_INPUT(enum.IntEnum):
    _mcZPhase = 0
    _mcExternalSignal = 1


class _eMC_LIMIT_REVERSE_MODE(enum.IntEnum):
    _mcErrorStop = 0
    _mcRevImmediateStop = 1
    _mcRevDecelerationStop = 2


class _eMC_TRIGGER_MODE(enum.IntEnum):
    _mcDrive = 0
    _mcController = 1


class _eMC_TRIGGER_LATCH_ID(enum.IntEnum):
    _mcLatch1 = 0
    _mcLatch2 = 1


class _eMC_TRIGGER_INPUT_DRIVE(enum.IntEnum):
    _mcEncoderMark = 0
    _mcEXT = 1


class _eMC_REFERENCE_TYPE(enum.IntEnum):
    _mcCommand = 0
    _mcFeedback = 1
    _mcLatestCommand = 2


class _eMC_EXECUTION_MODE(enum.IntEnum):
    _mcImmediately = 0


class _eMC_PARAMETER_NUMBER(enum.IntEnum):
    _mcChkVel = 0
    _mcChkAcc = 1
    _mcChkDec = 2
    _mcPosiChkTrq = 3
    _mcNegaChkTrq = 4
    _mcFELmt = 5
    _mcChkFELmt = 6
    _mcSwLmtMode = 7
    _mcPosiSwLmt = 8
    _mcNegaSwLmt = 9
    _mcInPosTime = 10
    _mcInPosRange = 11
    _mcStartVel = 12


class _eMC_CAM_CURVE(enum.IntEnum):
    """Curve shape of one cam node (MC_GenerateCamTable, `omron-group-and-cam.md` §5.4.2, seed 000 line 17948).

    The double "l" of Trapeclloid is the manual's spelling, kept so programs read against it."""

    _mcConstantLine = 0
    _mcStraightLine = 1
    _mcParabolic = 2
    _mcModifiedConstantVel = 3
    _mcModifiedTrapezoid = 4
    _mcModifiedSine = 5
    _mcCycloidal = 6
    _mcTrapeclloid = 7
    _mcReverseTrapeclloid = 8
    _mcSimpleHarmonic = 9
    _mcDoubleHarmonic = 10
    _mcReverseDoubleHarmonic = 11
    _mcNC2Curve = 12
    _mcPolynomic3 = 13
    _mcPolynomic5 = 14


# synchronized control (omron-axis-instructions.md MC_CamIn … MC_SyncOffsetPosition)
class _eMC_START_MODE(enum.IntEnum):
    _mcAbsolutePosition = 0
    _mcRelativePosition = 1


class _eMC_CAM_TRANSITION(enum.IntEnum):
    _mcCTNone = 0


class _eMC_OUT_MODE(enum.IntEnum):
    _mcStop = 0


class _eMC_LINKOPTION(enum.IntEnum):
    _mcCommandExecution = 0
    _mcTriggerDetection = 1
    _mcMasterReach = 2


class _eMC_COMBINE_MODE(enum.IntEnum):
    _mcAddAxes = 0
    _mcSubAxes = 1


class _eMC_CMDPOS_MODE(enum.IntEnum):
    _mcCount = 0


class _eMC_SWITCH_MODE(enum.IntEnum):
    _mcSwitchDisable = 0
    _mcPositionBased = 1
    _mcTimeBased = 2


# axes groups (omron-mc-basics.md §2.4, omron-group-and-cam.md §0.5; seed 000 lines 1716–1767)
class _eMC_GROUP_USE(enum.IntEnum):
    _mcNoneGroup = 0
    _mcUnusedGroup = 1
    _mcUsedGroup = 2


class _eMC_GROUP_TYPE(enum.IntEnum):
    """Axis composition of a group (`_sGROUP_REF.Kinematics.GrpType`)."""

    _mcXY = 0
    _mcXYZ = 1
    _mcXYZU = 2


class _eMC_COORD_SYSTEM(enum.IntEnum):
    _mcACS = 0


class _eMC_TRANSITION_MODE(enum.IntEnum):
    _mcTMNone = 0
    _mcTMCornerSuperimposed = 10


class _eMC_CIRC_MODE(enum.IntEnum):
    _mcBorder = 0
    _mcCenter = 1
    _mcRadius = 2


class _eMC_CIRC_PATHCHOICE(enum.IntEnum):
    _mcCW = 0
    _mcCCW = 1


class _eMC_RBT_COORD_SYSTEM(enum.IntEnum):
    """Coordinate system of the robot instructions (omron-robot-delta3.md §8.1; 2 is not defined)."""

    _mcRBT_MCS = 1
    _mcRBT_UCS = 3


ENUMS: dict[str, type[enum.IntEnum]] = {
    cls.__name__: cls
    for cls in (
        _eMC_BUFFER_MODE,
        _eMC_DIRECTION,
        _eMC_STOP_MODE,
        _eMC_MOVE_MODE,
        _eMC_AXIS_TYPE,
        _eMC_AXIS_USE,
        _eMC_UNITS,
        _eMC_COUNT_MODE,
        _eMC_ACCDECOVER,
        _eMC_REVERSE_MODE,
        _eMC_SWLMT_MODE,
        _eMC_HOMING_MODE,
        _eMC_HOME_INPUT,
        _eMC_LIMIT_REVERSE_MODE,
        _eMC_TRIGGER_MODE,
        _eMC_TRIGGER_LATCH_ID,
        _eMC_TRIGGER_INPUT_DRIVE,
        _eMC_REFERENCE_TYPE,
        _eMC_EXECUTION_MODE,
        _eMC_PARAMETER_NUMBER,
        _eMC_CAM_CURVE,
        _eMC_START_MODE,
        _eMC_CAM_TRANSITION,
        _eMC_OUT_MODE,
        _eMC_LINKOPTION,
        _eMC_COMBINE_MODE,
        _eMC_CMDPOS_MODE,
        _eMC_SWITCH_MODE,
        _eMC_GROUP_USE,
        _eMC_GROUP_TYPE,
        _eMC_COORD_SYSTEM,
        _eMC_TRANSITION_MODE,
        _eMC_CIRC_MODE,
        _eMC_CIRC_PATHCHOICE,
        _eMC_RBT_COORD_SYSTEM,
    )
}


class AxisState(enum.IntEnum):
    """The nine mutually exclusive axis states (A-3.2 letters A–I), one of which is TRUE in `Status`."""

    Disabled = 0
    Standstill = 1
    Discrete = 2
    Continuous = 3
    Synchronized = 4
    Homing = 5
    Stopping = 6
    ErrorStop = 7
    Coordinated = 8
