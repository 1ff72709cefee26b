"""Motion jobs: what an instruction asks an axis to do, and how far the axis has got.

An instruction (FB) submits a job when it is executed; the axis accepts it (starting it now or buffering it), refuses
it, or aborts it later. Status changes are pushed to the instance at the end of the motion stage (Done,
CommandAborted, Error, InVelocity); Active is read by the instance at its next call, one period after Busy.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass, field
from typing import Any


class JobStatus(enum.IntEnum):
    WAITING = 0  # buffered behind the running instruction
    STARTING = 1  # accepted; the profile is planned in this period's motion stage
    ACTIVE = 2  # controlling the axis
    DONE = 3
    ABORTED = 4
    ERROR = 5


class JobKind(enum.IntEnum):
    POSITION = 0  # Discrete: MC_Move, MC_MoveAbsolute, MC_MoveRelative, MC_MoveZeroPosition
    VELOCITY = 1  # Continuous: MC_MoveVelocity
    JOG = 2  # Continuous: MC_MoveJog
    STOP = 3  # Stopping: MC_Stop
    ERROR_STOP = 4  # ErrorStop deceleration (no owner)
    RESET_FE = 5  # Stopping: MC_ResetFollowingError
    HOMING = 6  # Homing: MC_Home, MC_HomeWithParameter (driven by a Homing sequence)
    GROUP_MOVE = 20  # axes group: MC_MoveLinear*, MC_MoveCircular2D (a path of `group_path.py`, group.py)
    GROUP_STOP = 21  # axes group: MC_GroupStop
    GROUP_SYNC = 22  # axes group: MC_GroupSyncMoveAbsolute
    GROUP_ROBOT = 23  # robot group: MC_MoveTimeAbsolute, MC_SyncLinearConveyor, MC_SyncOut (robot.py)
    TORQUE = 7  # Continuous: MC_TorqueControl (the drive in CST; torque stage of the MC module, no profile)
    SYNC = 8  # Synchronized: MC_CamIn, MC_GearIn, MC_GearInPos, MC_MoveLink, MC_CombineAxes (a law in `sync.py`)
    SYNC_OUT = 9  # Discrete: MC_CamOut, MC_GearOut — decelerate the slave to 0 (Done at velocity 0)
    CYCLIC = 10  # Discrete: MC_SyncMoveAbsolute — a target position from the program every period (a law in sync.py)
    CSV = 11  # Continuous: MC_SyncMoveVelocity — the drive in CSV with the program's velocity every period


MOTION_KINDS = (JobKind.POSITION, JobKind.VELOCITY, JobKind.JOG, JobKind.TORQUE, JobKind.SYNC, JobKind.SYNC_OUT,
                JobKind.CYCLIC, JobKind.CSV)
LAW_KINDS = (JobKind.SYNC, JobKind.CYCLIC)  # jobs whose command position a law computes in the sync stage


@dataclass(eq=False, slots=True)
class Job:
    kind: JobKind
    owner: Any  # the FunctionBlock instance, None for internal jobs
    velocity: float = 0.0  # target velocity [unit/s] (signed for velocity and jog jobs)
    acceleration: float = 0.0
    deceleration: float = 0.0
    jerk: float = 0.0
    target: float = 0.0  # absolute target [unit] of a position job (unwrapped coordinates)
    relative: bool = False
    distance: float = 0.0  # MC_MoveRelative: distance from `origin`
    origin: float | None = None  # command position at the job's first start (MoveRelative reference)
    absolute_target: float | None = None  # MC_MoveAbsolute/MoveZeroPosition target as given (wrapped, rotary)
    buffer_mode: int = 0
    direction: int = 0
    overridable: bool = False  # MC_SetOverride applies (the seven instructions the manual names)
    blendable: bool = False  # other positioning instructions may blend onto it
    _status: JobStatus = JobStatus.STARTING
    error_id: int = 0
    _in_velocity: bool = False
    replan: bool = False  # parameters changed (re-execution, override, SetPosition): plan again
    stopping: bool = False  # jog released: decelerating to the end of the job
    paused: bool = False  # override 0: the position job decelerated to 0 and waits
    v_end: float = 0.0  # transit velocity at the target (blending), signed
    finished_cycle: int = -1
    cmd_done_cycle: int = -1  # period in which the command profile reached its end
    rapid: bool = False  # Acceleration/Deceleration Over: planned with the acc/dec needed to make it
    info: dict[str, Any] = field(default_factory=dict)

    # A change of status or InVelocity wakes the owning instance (the kernel does not call a settled instance;
    # `FunctionBlock.wake`).
    @property
    def status(self) -> JobStatus:
        return self._status

    @status.setter
    def status(self, value: JobStatus) -> None:
        if value != self._status:
            self._status = value
            if self.owner is not None:
                self.owner.wake()

    @property
    def in_velocity(self) -> bool:
        return self._in_velocity

    @in_velocity.setter
    def in_velocity(self, value: bool) -> None:
        if value != self._in_velocity:
            self._in_velocity = value
            if self.owner is not None:
                self.owner.wake()

    @property
    def running(self) -> bool:
        return self.status in (JobStatus.WAITING, JobStatus.STARTING, JobStatus.ACTIVE)
