"""Axes groups: `_sGROUP_REF`, the group state machine, and the group motion of the interpolation instructions.

States and transitions: `omron-group-and-cam.md` §0.4 (appendix A-3, seed 000 lines 21676–21700). A group is
Disabled, Standby, Moving, Stopping or ErrorStop; while it is enabled its composition axes are Coordinated (axis
state I), so single-axis motion on them is refused with 543E (`acceptance.py`). A group runs one motion instruction
and buffers up to seven more (5443 for the eighth).

Group motion is a path (`group_path.py`) and a 1-D profile s(t) along it, planned once per move with the axis planner
(`profile.Planner`: trapezoid when Jerk = 0, S-curve otherwise) and re-planned only on events (blending successor,
override, MC_GroupStop). Every period `step` evaluates s(t) — a few float operations — and writes the composition
axes' command positions, so the generic command-value stage of the MC module derives Cmd.Vel/AccDec from them.
Decisions on unclear points: docs/decisions.md D50–D56.

The group motion itself is mixed in: `group_planning.py` (start/buffer/blend/plan/override), `group_motion.py`
(the period, stops, MC_GroupSyncMoveAbsolute) and `group_monitor.py` (in-position check, interpolation warnings,
VelLimit, the drive side of MC_GroupReset); shared types in `group_types.py` (re-exported here).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from ...drives.cia402 import DI_NEGATIVE_LIMIT, DI_POSITIVE_LIMIT
from . import errors as E
from .enums import AxisState, _eMC_STOP_MODE
from .group_monitor import GroupMonitor, warning_limits
from .group_motion import GroupMotion
from .group_planning import GroupPlanning
from .group_types import (
    E_CHANGE_AXES,
    E_COUNT_MODE,
    E_GROUP_CANNOT_ENABLE,
    E_GROUP_DISABLED,
    E_GROUP_IMMEDIATE_STOP,
    E_ILLEGAL_GROUP,
    E_MEMBER_ERROR,
    E_MEMBER_STOPPING,
    MAX_BUFFERED,
    G,
    GroupState,
    Motion,
    _Pos,
    decel_start,
    sample,
    transition_error,
)
from .jobs import Job, JobKind, JobStatus

if TYPE_CHECKING:
    from ...project.models import AxesGroupConfig
    from .axis import Axis
    from .module import MotionModule

__all__ = [
    "E_CHANGE_AXES", "E_COUNT_MODE", "E_GROUP_CANNOT_ENABLE", "E_GROUP_DISABLED", "E_GROUP_IMMEDIATE_STOP",
    "E_ILLEGAL_GROUP", "E_MEMBER_ERROR", "E_MEMBER_STOPPING", "MAX_BUFFERED", "AxesGroup", "G", "GroupState",
    "Motion", "_Pos", "decel_start", "sample", "transition_error",
]


# acceptance of group instructions per group state (§0.4, A-3-2 with the cell colours reconstructed, D50):
# "ok", "abort" (CommandAborted) or an ErrorID
_VERDICT: dict[str, tuple[str | int, ...]] = {
    #               Disabled          Standby  Moving   Stopping ErrorStop
    "move": (E_GROUP_DISABLED, "ok", "ok", "abort", "abort"),
    "stop": (E_GROUP_DISABLED, "ok", "ok", "ok", "abort"),
    "immediate_stop": (E_GROUP_DISABLED, "ok", "ok", "ok", "ok"),
    "change_axes": ("ok", 0x543C, 0x543C, 0x543C, 0x543C),
}


class AxesGroup(GroupMotion, GroupPlanning, GroupMonitor):
    def __init__(self, module: MotionModule, config: AxesGroupConfig) -> None:
        self.m = module
        self.config = config
        self.name = config.name
        self.number = config.number
        self.op = config.operation
        self.kinematics = config.kinematics
        # robot.kinematics_of: (kinematics object, Delta3Params, Delta3Workspace) of the kinematics in force
        self.robot_kin_cache: tuple[Any, Any, Any] | None = None
        # MC_SetKinTransform (fb/robot_fb.py): kinematics usable by the robot instructions from this cycle on (the
        # period after Done, §9.1), and EnableWorkspace; the project's kinematics apply from cycle 0
        self.kin_from_cycle = 0
        self.workspace_check = True
        # MC_DefineCoordSystem: user coordinate systems by CSID (volatile, robot.py)
        self.coord_systems: dict[int, Any] = {}
        self.axes: list[Axis] = [module.by_name[n] for n in config.axes if n in module.by_name]
        self.idx: list[int] = [a.i for a in self.axes]
        self.enabled = False
        self.state = G.Disabled
        self.error_code = 0
        self.reset_generation = 0
        self.stop_holders: set[int] = set()
        self.member_fault: tuple[int, int] | None = None  # (code, logical axis) of the last member_error(), A-1 info 1
        self.current: Job | None = None  # the running group instruction (move, stop, synchronous positioning)
        self.queue: list[Job] = []  # buffered group motion instructions
        self.motion: Motion | None = None
        self.overlap: Motion | None = None  # corner superimposition: the previous move finishing its deceleration
        self.override = 1.0
        self.override_owner: int | None = None
        self.sync_target: tuple[float, ...] | None = None  # MC_GroupSyncMoveAbsolute: target of the last period
        self.cmd_vel = 0.0
        self.cmd_accdec = 0.0
        self._last_point: tuple[float, ...] | None = None
        self.in_pos_waiting = False  # Details.InPosWaiting (group_monitor.py, D103)
        self.observations: dict[int, bool] = {}  # active observation codes (Obsr): interpolation warnings (D104)
        self.warn_limits = warning_limits(self.op)
        self.warn_on = any(v > 0 for v in self.warn_limits)

    # ------------------------------------------------------------------ helpers
    @property
    def label(self) -> str:
        return self.name

    def _set_state(self, state: GroupState) -> None:
        self.state = state

    def _rest_state(self) -> GroupState:
        if self.error_code:
            return G.ErrorStop
        if not self.enabled:
            return G.Disabled
        return G.Stopping if self.stop_holders else G.Standby

    def point(self) -> tuple[float, ...]:
        cmd = self.m.cmd_pos
        return tuple(float(cmd[i]) for i in self.idx)

    def check_start(self, kind: str) -> tuple[str, int]:
        v = _VERDICT[kind][int(self.state)]
        if isinstance(v, int):
            return "error", v
        return v, 0

    def member_error(self) -> int:
        """Start conditions of a group motion instruction on the composition axes (A-1: 5441, 5466, 5442,
        6443/6444 — the limit inputs whatever the direction, "any axes group motion instruction", D130)."""
        code, logical = self._member_fault()
        self.member_fault = (code, logical) if code else None
        return code

    def _member_fault(self) -> tuple[int, int]:
        """The first start condition a composition axis fails, and its logical axis number (A0 = 0 …)."""
        m = self.m
        for n, a in enumerate(self.axes):
            if not m.servo_on[a.i]:
                return E.E_SERVO_OFF, n
        for n, a in enumerate(self.axes):
            if not a.homed:
                return E.E_HOME_UNDEFINED, n
        for n, a in enumerate(self.axes):
            if a.stop_holders:
                return E_MEMBER_STOPPING, n
        for n, a in enumerate(self.axes):
            din = int(m.din[a.i])
            if din & DI_POSITIVE_LIMIT:
                return E.E_POSI_LIMIT_INPUT, n
            if din & DI_NEGATIVE_LIMIT:
                return E.E_NEGA_LIMIT_INPUT, n
        return 0, 0

    def _end_job(self, job: Job | None, status: JobStatus, error_id: int = 0) -> None:
        if job is None or not job.running:
            return
        job.status = status
        job.error_id = error_id
        job.finished_cycle = self.m.cycle
        self.m.job_changed(job)
        if job is self.current:
            self.current = None
        if job in self.queue:
            self.queue.remove(job)

    def abort_all(self) -> None:
        for job in list(self.queue):
            self._end_job(job, JobStatus.ABORTED)
        self.queue.clear()
        self._end_job(self.current, JobStatus.ABORTED)

    def halt(self) -> None:
        """Immediate stop: the command positions hold where they are."""
        m = self.m
        self.motion = None
        self.overlap = None
        for i in self.idx:
            m.prof_vel[i] = 0.0
            m.prof_acc[i] = 0.0
        m.moving_groups.pop(self.number, None)
        self.sync_target = None
        self.cmd_vel = self.cmd_accdec = 0.0
        self.clear_member_flags()
        if self.observations:
            self.check_warnings()

    # ------------------------------------------------------------------ errors
    def raise_error(self, code: int, *, source: str | None = None, detail: str = "", immediate: bool = False) -> None:
        """Group minor fault (A-1 source Group): MFaultLvl, ErrorStop, every group instruction aborted, the group
        stopped — by the [Axes group stop method] (immediate, or decelerating along the path at the maximum
        interpolation deceleration), immediately for robots and when `immediate` (D53). Member axes keep no error
        (§4.1: a group error does not put the composition axes into error)."""
        if self.error_code == 0:
            self.error_code = code
        fault, self.member_fault = self.member_fault, None
        if not detail and fault is not None and fault[0] == code:
            # A-1 attached information 1 of a group source: the logical axis number of the composition axis
            # (basics L1199: 5441, 5466, 6443, 6444; for 5442 the axis MC_Stop is stopping)
            n = fault[1]
            detail = f"attached information 1: {n} (logical axis A{n}, {self.axes[n].name})"
        self.m.log_error(code, axis=None, source=f"{self.name} / {source}" if source else self.name, detail=detail,
                         group=self.name)
        self.abort_all()
        self._set_state(G.ErrorStop)
        mv = self.motion
        dec = self.op.MaxInterpolationDec
        decelerate = (not immediate and self.kinematics is None and mv is not None and not mv.paused
                      and self.op.GroupStopMethod == _eMC_STOP_MODE._mcDecelerationStop and dec > 0
                      and (mv.sd != 0 or mv.sdd != 0))
        if not decelerate:
            self.halt()
            return
        job = Job(JobKind.GROUP_STOP, None, deceleration=dec)
        self.current = job
        self._decelerate(job, dec, 0.0)

    def on_axis_error(self, axis: Axis, code: int) -> None:
        """A composition axis had an error: on a moving group 7430, the axes stop immediately (robot functions
        manual A-1 #7430; group stop method D53)."""
        if self.motion is not None or self.state == G.Moving:
            self.raise_error(E_MEMBER_ERROR, source=axis.name, immediate=True,
                             detail=f"{axis.name}: error {code:04X} during group motion")

    def on_member_servo_off(self, axis: Axis) -> None:
        if self.motion is not None or self.state == G.Moving:
            self.raise_error(E_MEMBER_ERROR, source=axis.name, immediate=True,
                             detail=f"{axis.name}: servo OFF during group motion")

    # ------------------------------------------------------------------ MC_GroupEnable / MC_GroupDisable
    def enable(self) -> str | int:
        """Returns "done", "abort" or an ErrorID."""
        if self.state == G.ErrorStop:
            return "abort"  # D50: §0.4 e (*1)
        if self.enabled:
            return "done"
        for a in self.axes:
            if a.encoder:
                return E.E_AXIS_TYPE
        for a in self.axes:
            if not a.used:
                return E_ILLEGAL_GROUP
            if a.state not in (AxisState.Disabled, AxisState.Standstill) or a.group is not None or a.latch_owner:
                return E_GROUP_CANNOT_ENABLE
        m = self.m
        for a in self.axes:
            m.profiles.clear(a.i)
            m.prof_vel[a.i] = 0.0
            m.prof_acc[a.i] = 0.0
            a.group = self
            a._set_state(AxisState.Coordinated)
        self.enabled = True
        self._set_state(self._rest_state())
        return "done"

    def disable(self) -> None:
        """MC_GroupDisable: buffered and running group instructions CommandAborted; moving axes decelerate at their
        Maximum Deceleration; the axes leave Coordinated (A-3 *2). In ErrorStop the group stays ErrorStop (D50)."""
        self.abort_all()
        m = self.m
        moving = [a for a in self.axes if m.prof_vel[a.i] != 0.0]
        self.halt()
        if not self.enabled:
            return
        self.enabled = False
        for a in self.axes:
            a.group = None
        for a in self.axes:
            if a.state == AxisState.ErrorStop:
                continue
            if a in moving and m.servo_on[a.i] and a.params.Operation.MaxDec > 0:
                # the path velocity of the last period, per axis: the single-axis planner decelerates from it
                m.prof_vel[a.i] = float(m.cmd_vel[a.i])
                a._start(Job(JobKind.STOP, None, deceleration=a.params.Operation.MaxDec))
            else:
                a._set_state(a._rest_state())
        if self.state != G.ErrorStop:
            self._set_state(G.Disabled)

    # ------------------------------------------------------------------ MC_GroupReset
    def reset(self) -> bool:
        """Clears the group error and observations and (while the group is enabled) the errors of its axes. False
        (Failure) while the group or an axis still decelerates because of an error, or an axis error's cause persists
        (`reset_failure_cause`). The drive error reset runs before this (MC_GroupReset, D108)."""
        if self.reset_failure_cause():
            return False
        self.observations.clear()
        if self.enabled:
            for a in self.axes:
                if a.error_code or a.state == AxisState.ErrorStop or a.observations:
                    a.reset()
        if self.error_code or self.state == G.ErrorStop:
            self.error_code = 0
            self.reset_generation += 1
            self._set_state(self._rest_state())
            self.m.log_info(None, f"axes group error reset on {self.name}", group=self.name)
        return True

    def immediate_stop(self, source: str) -> None:
        """MC_GroupImmediateStop: every axis stops by its [Immediate stop input stop method]; ErrorStop with 5486."""
        m = self.m
        running_stop = self.current if self.current is not None and self.current.kind == JobKind.GROUP_STOP else None
        self._end_job(running_stop, JobStatus.ABORTED)
        self.halt()
        self.raise_error(E_GROUP_IMMEDIATE_STOP, source=source, immediate=True)
        for a in self.axes:
            mode = int(a.params.OtherOperation.ImmediateStopInputStopMode)
            if mode == _eMC_STOP_MODE._mcImmediateStopFEReset:
                m.reset_following_error(a.i)
            elif mode == _eMC_STOP_MODE._mcFreeRunStop and m.servo_on[a.i]:
                a._release_servo()
                a.forced_off = True

    def hold_stop(self, fb_id: int, held: bool) -> None:
        if held:
            self.stop_holders.add(fb_id)
            return
        if fb_id in self.stop_holders:
            self.stop_holders.discard(fb_id)
            if not self.stop_holders and self.state == G.Stopping and self.current is None:
                self._set_state(self._rest_state())


    # ------------------------------------------------------------------ MC_ChangeAxesInGroup
    def change_axes(self, axes: list[Axis]) -> None:
        self.axes = axes
        self.idx = [a.i for a in axes]

    # ------------------------------------------------------------------ _sGROUP_REF
    def capture(self) -> dict[str, Any]:
        st = self.state
        m = self.m
        ready = (st == G.Standby and all(bool(m.servo_on[i]) for i in self.idx) and all(a.homed for a in self.axes)
                 and not any(a.stop_holders for a in self.axes))
        busy = self.current is not None and self.current.running
        return {
            "name": self.name,
            "Status": {"Ready": ready, **{s.name: st == s for s in G}},
            "Details": {"Idle": not busy and not self.in_pos_waiting, "InPosWaiting": self.in_pos_waiting},
            "Cmd": {"Vel": self.cmd_vel, "AccDec": self.cmd_accdec},
            "MFaultLvl": {"Active": self.error_code != 0, "Code": f"{self.error_code:04X}"},
            "Obsr": {"Active": bool(self.observations), "Code": f"{self.obsr_code:04X}"},
            "Cfg": {"GrpNo": self.number, "GrpEnable": "_mcUsedGroup", "ExecID": 1},
            "Kinematics": {"GrpType": self.config.composition.name,
                           "Axis": [a.number for a in self.axes] + [0] * (4 - len(self.axes))},
            "CmdPos": list(self.point()),
        }

