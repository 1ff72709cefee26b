"""Motion jobs: what an instruction asks an axis to do, and how far the axis has got.

An instruction (FB) submits a job when it is executed; the axis accepts it (starting it now or buffering it), refuses
it, or aborts it later. The FB reads the job's status at its next call — exactly the one-period delay with which the
manual's `Active`, `Done` and `CommandAborted` follow the MC function module's processing.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from .profile import Planner, Segments


class JobStatus(enum.IntEnum):
    WAITING = 0  # buffered behind the running instruction
    STARTING = 1  # accepted; the profile is planned in this period's motion stage
    ACTIVE = 2  # controlling the axis
    DONE = 3
    ABORTED = 4
    ERROR = 5


class JobKind(enum.IntEnum):
    POSITION = 0  # Discrete: MC_MoveAbsolute, MC_MoveRelative, MC_Move
    VELOCITY = 1  # Continuous: MC_MoveVelocity
    JOG = 2  # Continuous: MC_MoveJog
    STOP = 3  # Stopping: MC_Stop
    ERROR_STOP = 4  # ErrorStop deceleration (no owner)


@dataclass(eq=False, slots=True)
class Job:
    kind: JobKind
    owner: Any  # the FunctionBlock instance, None for internal jobs
    velocity: float = 0.0  # target velocity [unit/s], signed for velocity jobs
    acceleration: float = 0.0
    deceleration: float = 0.0
    jerk: float = 0.0
    target: float = 0.0  # absolute target [unit] of a position job
    relative: bool = False
    distance: float = 0.0  # MC_MoveRelative: distance from `origin`
    origin: float | None = None  # command position at the job's first start (MoveRelative reference)
    buffer_mode: int = 0
    direction: int = 0
    status: JobStatus = JobStatus.STARTING
    error_id: int = 0
    in_velocity: bool = False
    replan: bool = False  # parameters changed (re-execution): plan again from the current state
    stopping: bool = False  # jog released: decelerating to the end of the job
    in_pos_waiting: bool = False
    finished_cycle: int = -1
    cmd_done_cycle: int = -1  # period in which the command profile reached its end
    info: dict[str, Any] = field(default_factory=dict)

    @property
    def running(self) -> bool:
        return self.status in (JobStatus.WAITING, JobStatus.STARTING, JobStatus.ACTIVE)

    def plan(self, planner: Planner, p0: float, v0: float, a0: float, override: float) -> Segments:
        """Profile from the current command state (override scales the target velocity)."""
        if self.kind == JobKind.POSITION:
            return planner.position(p0=p0, v0=v0, a0=a0, target=self.target, velocity=self.velocity * override,
                                    acceleration=self.acceleration, deceleration=self.deceleration, jerk=self.jerk)
        if self.kind in (JobKind.VELOCITY, JobKind.JOG):
            v = 0.0 if self.stopping else self.velocity * override
            return planner.velocity(p0=p0, v0=v0, a0=a0, target_velocity=v, acceleration=self.acceleration,
                                    deceleration=self.deceleration, jerk=self.jerk)
        return planner.stop(p0=p0, v0=v0, a0=a0, deceleration=self.deceleration, jerk=self.jerk)
