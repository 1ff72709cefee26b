"""One axis of the MC function module: its state machine, the instructions running on it, and `_sAXIS_REF`.

Continuous quantities (command and actual values, profiles) live in the `MotionModule` arrays, one row per axis, so
the control period treats all axes at once; the discrete side (state, jobs, errors) lives here and changes only on
events. States and transitions follow `omron-mc-basics.md` §A-3; profiles are planned in `axis_planning.py`.

Coordinates: internally positions are continuous ("unwrapped"); in Rotary Mode the axis reports them on the ring
counter [ModuloMinPosVal, ModuloMaxPosVal). `pos_offset` maps the drive's pulse count to command units, so
MC_SetPosition and the homing preset move the coordinate system without touching the drive.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

from . import errors as E
from .acceptance import verdict
from .axis_planning import AxisPlanning
from .enums import AxisState, _eMC_AXIS_TYPE, _eMC_BUFFER_MODE, _eMC_COUNT_MODE, _eMC_DIRECTION, _eMC_STOP_MODE
from .jobs import LAW_KINDS, MOTION_KINDS, Job, JobKind, JobStatus
from .units import pulses_per_unit

if TYPE_CHECKING:
    from ...project.models import AxisConfig, AxisParameters
    from .module import MotionModule

S = AxisState
STOP_DECEL, STOP_IMMEDIATE, STOP_FE_RESET, STOP_FREE_RUN, STOP_NONE = "decel", "immediate", "fe_reset", "free", "none"
_STOP_OF_MODE = {
    int(_eMC_STOP_MODE._mcDecelerationStop): STOP_DECEL,
    int(_eMC_STOP_MODE._mcImmediateStop): STOP_IMMEDIATE,
    int(_eMC_STOP_MODE._mcImmediateStopFEReset): STOP_FE_RESET,
    int(_eMC_STOP_MODE._mcFreeRunStop): STOP_FREE_RUN,
}


class Axis(AxisPlanning):
    def __init__(self, module: MotionModule, index: int, config: AxisConfig) -> None:
        self.m = module
        self.i = index
        self.config = config
        self.name = config.name
        self.number = config.number
        self.type = config.type
        self.used = config.use.name == "_mcUsedAxis"
        self.virtual = config.type in (_eMC_AXIS_TYPE._mcVirServo, _eMC_AXIS_TYPE._mcVirEncdr)
        self.encoder = config.type in (_eMC_AXIS_TYPE._mcEncdr, _eMC_AXIS_TYPE._mcVirEncdr)
        self.params: AxisParameters = config.parameters.model_copy(deep=True)  # runtime copy (MC_Write …)
        self.apply_parameters(self.params, initial=True)
        self.state = S.Disabled
        self.current: Job | None = None
        self.buffered: Job | None = None
        self.stop_holders: set[int] = set()  # ids of MC_Stop instances whose Execute is still TRUE
        self.power_owner: int | None = None  # MC_Power instance in control (the later instance wins)
        self.power_sleepers: list[Any] = []  # MC_Power instances asleep on this axis's servo state
        self.override_owner: int | None = None
        self.torque_limit_owner: int | None = None  # MC_SetTorqueLimit instance in control (the later one wins)
        self.torque_limits: tuple[bool, float, bool, float] | None = None  # its inputs (direction enables, values)
        self.servo_request = False
        self.forced_off = False
        self.error_code = 0  # MFaultLvl.Code (0 = no minor fault)
        self.observations: dict[int, bool] = {}  # active observation codes (Obsr)
        self.reset_generation = 0  # increments each time the axis error is reset (releases FB Error outputs)
        # Absolute encoder: home is defined when EtherCAT process data communication becomes established (CPU
        # ≥ 1.10, omron-axis-instructions.md line 100). The emulated network is established from cycle 0.
        self._homed = self.config.drive.EncoderType == "absolute" and not self.virtual
        self.in_pos_waiting = False
        self.vel_limit = False  # Details.VelLimit: command velocity saturated (group_monitor.py)
        self.homing: Any = None  # the running Homing sequence (mc/homing.py)
        self.latch_owner: dict[int, Any] = {}  # LatchID → instruction using the drive latch
        self.group: Any = None  # the enabled axes group this axis is a composition axis of (group.py)

    # ------------------------------------------------------------------ configuration
    def apply_parameters(self, params: AxisParameters, *, initial: bool = False) -> None:
        """(Re)read the parameters the period uses: scale, count mode (MC_WriteAxisParameter, MC_Write)."""
        old = None if initial else (self.ppu, self.rotary, self.mod_min, self.mod_max)
        self.params = params
        self.ppu = pulses_per_unit(params)
        pc = params.PosCount
        self.rotary = pc.CountMode == _eMC_COUNT_MODE._mcCountModeRotary
        self.mod_min = pc.ModuloMinPosVal
        self.mod_max = pc.ModuloMaxPosVal
        if not initial:
            m, i = self.m, self.i
            m.ppu[i] = self.ppu
            m.rotary[i] = self.rotary
            m.mod_min[i] = self.mod_min
            m.mod_len[i] = self.mod_max - self.mod_min if self.rotary else 0.0
            m.refresh_params(self)
            if old != (self.ppu, self.rotary, self.mod_min, self.mod_max):
                # new unit conversion or position count settings: home must be defined again (manual §2.3)
                m.pos_offset[i] = 0.0
                m.act_pos[i] = m.act_count[i] / self.ppu
                m.cmd_pos[i] = m.prev_cmd_pos[i] = m.act_pos[i]
                self.homed = False

    # ------------------------------------------------------------------ coordinates
    def wrap(self, x: float) -> float:
        if not self.rotary:
            return x
        span = self.mod_max - self.mod_min
        return self.mod_min + (x - self.mod_min) % span

    @property
    def homed(self) -> bool:
        return self._homed

    @homed.setter
    def homed(self, value: bool) -> None:
        self._homed = value
        self.m.homed[self.i] = value
        if value:
            self.m.ovf[self.i] = 0  # homing (or a preset) ends an overflow/underflow

    def position_overflow(self, sign: int) -> None:
        """Linear Mode: the command position reached the end of the signed 40-bit pulse range. The command stops at
        Scale.MaxPos/MinPos, the running instruction is CommandAborted and the axis is in overflow/underflow: until
        MC_SetPosition or homing, positioning, motion toward that end and torque control give 6442 (D28)."""
        m, i = self.m, self.i
        m.cmd_pos[i] = m.lin_max[i] if sign > 0 else m.lin_min[i]
        m.ovf[i] = sign
        self.abort_all()
        self.halt()
        if self.state != S.ErrorStop:
            self._set_state(self._rest_state())
        m.log_info(self, f"{self.name}: command position {'overflow' if sign > 0 else 'underflow'} at "
                         f"{float(m.cmd_pos[i]):.6g} (end of the 40-bit pulse range); preset the position "
                         "(MC_SetPosition) or home before positioning again (6442)")

    def overflow_refusal(self, job: Job) -> int:
        """6442 for an instruction the overflow/underflow state forbids (A-1 #144, seed 000 line 21275): positioning,
        continuous control toward the overflow side, and the instructions of indeterminate direction — torque control
        and the synchronization functions (MC_CamIn, MC_GearIn, MC_GearInPos, MC_MoveLink, MC_CombineAxes and the
        cyclic synchronous MC_SyncMoveAbsolute / MC_SyncMoveVelocity, as D132 reads "no defined direction"), else 0."""
        sign = int(self.m.ovf[self.i])
        if not sign:
            return 0
        if job.kind in (JobKind.POSITION, JobKind.TORQUE, JobKind.SYNC, JobKind.CYCLIC, JobKind.CSV):
            return E.E_POSITION_OVERFLOW
        if job.kind in (JobKind.VELOCITY, JobKind.JOG):
            direction = (job.velocity > 0) - (job.velocity < 0)
            if direction in (0, sign):
                return E.E_POSITION_OVERFLOW
        return 0

    @property
    def servo_on(self) -> bool:
        return bool(self.m.servo_on[self.i])

    @property
    def cmd_pos(self) -> float:
        """Command current position as reported (wrapped in Rotary Mode)."""
        return self.wrap(float(self.m.cmd_pos[self.i]))

    @property
    def act_pos(self) -> float:
        return self.wrap(float(self.m.act_pos[self.i]))

    @property
    def last_direction(self) -> int:
        """+1 / −1: direction of the last command motion (for _mcCurrentDirection)."""
        return int(self.m.last_dir[self.i])

    def resolve_target(self, position: float, direction: int, base: float | None = None) -> tuple[int, float]:
        """Absolute target → (error, internal target) by Count Mode and Direction (MC_MoveAbsolute rules), seen
        from `base` (default: the command current position)."""
        p = float(self.m.cmd_pos[self.i]) if base is None else base
        if not self.rotary:
            return 0, position
        if direction == _eMC_DIRECTION._mcNoDirection:
            # numeric comparison within the ring; beyond the limits = extra relative travel (multi-turn)
            return 0, p + (position - self.wrap(p))
        if not self.mod_min <= position <= self.mod_max:
            return E.E_TARGET_POSITION, 0.0  # seed 000 line 3618: above the upper or below the lower limit
        span = self.mod_max - self.mod_min
        cur = self.wrap(p)
        fwd = (position - cur) % span
        back = (cur - position) % span
        if fwd == 0.0:
            return 0, p
        if direction == _eMC_DIRECTION._mcShortestWay:
            if fwd == back:
                direction = _eMC_DIRECTION._mcCurrentDirection
            else:
                return 0, p + fwd if fwd < back else p - back
        if direction == _eMC_DIRECTION._mcCurrentDirection:
            v = float(self.m.prof_vel[self.i])
            positive = v > 0 if v != 0 else self.last_direction > 0
            return 0, p + fwd if positive else p - back
        return 0, p + fwd if direction == _eMC_DIRECTION._mcPositiveDirection else p - back

    # ------------------------------------------------------------------ helpers
    def _set_state(self, state: AxisState) -> None:
        self.state = state
        self.m.state[self.i] = state

    def _rest_state(self) -> AxisState:
        """State of a stopped axis without error: Disabled / Standstill / Stopping (MC_Stop held); Coordinated while
        its axes group is enabled (A-3: servo ON or OFF)."""
        if self.group is not None:
            return S.Coordinated
        if not self.servo_on:
            return S.Disabled
        return S.Stopping if self.stop_holders else S.Standstill

    def _end_job(self, job: Job | None, status: JobStatus, error_id: int = 0) -> None:
        if job is None or not job.running:
            return
        if job.kind in LAW_KINDS:
            self.m.sync_changed()  # the sync stage drops the law (sync_batch.py)
        job.status = status
        job.error_id = error_id
        job.finished_cycle = self.m.cycle
        self.m.job_changed(job)
        if job is self.current:
            self.current = None
            if job.kind == JobKind.TORQUE:
                self.m.leave_torque(self.i)  # back to position control (CSP) at once (MC_TorqueControl rules)
            elif job.kind == JobKind.CSV:
                self.m.leave_csv(self.i)  # back to CSP with the servo locked at the feedback (decision D47)
        if job is self.buffered:
            self.buffered = None
            cur = self.current
            if cur is not None and cur.info.get("split_time") is not None and cur.running:
                cur.replan = True  # the blending successor is gone: plan the move to stop at its own target
                self.m.schedule(self)
        if job.kind == JobKind.HOMING and self.homing is not None:
            self.homing.close()
            self.homing = None

    def abort_all(self) -> None:
        """Every instruction running or buffered on this axis gets CommandAborted."""
        self._end_job(self.buffered, JobStatus.ABORTED)
        self._end_job(self.current, JobStatus.ABORTED)

    def halt(self) -> None:
        """Stop the command where it is (immediate stop): the profile ends, the command holds."""
        m, i = self.m, self.i
        m.profiles.clear(i)
        m.prof_vel[i] = 0.0
        m.prof_acc[i] = 0.0
        self.in_pos_waiting = False

    # ------------------------------------------------------------------ errors and observations
    def raise_error(self, code: int, *, source: str | None = None, stop: str = STOP_DECEL, detail: str = "",
                    stop_at: float | None = None, deceleration: float | None = None) -> None:
        """Axis minor fault: MFaultLvl, ErrorStop, running instructions aborted and the axis stopped (A-1 effects).

        `stop`: deceleration stop (at the axis Maximum Deceleration, or `deceleration`; immediate when 0), immediate
        stop, immediate stop with following-error reset, free-run (servo OFF), or none. `stop_at`: decelerate to a
        stop exactly at this position (command-position software limits)."""
        if self.error_code == 0:
            self.error_code = code
        self.m.log_error(code, axis=self, source=source, detail=detail)
        if self.current is not None and self.current.kind == JobKind.CYCLIC and stop == STOP_DECEL:
            stop = STOP_IMMEDIATE  # an error during MC_SyncMoveAbsolute stops the axis immediately (its rules)
        self.abort_all()
        self.in_pos_waiting = False
        self._set_state(S.ErrorStop)
        if self.group is not None:
            self.group.on_axis_error(self, code)  # 7430 on a moving group: its axes stop immediately
        if not self.servo_on or stop == STOP_NONE:
            return
        if stop == STOP_IMMEDIATE:
            self.halt()
        elif stop == STOP_FE_RESET:
            self.halt()
            self.m.reset_following_error(self.i)
        elif stop == STOP_FREE_RUN:
            self.halt()
            self._release_servo()
            self.forced_off = True
        else:
            dec = self.params.Operation.MaxDec if deceleration is None else deceleration
            job = Job(JobKind.ERROR_STOP, None, deceleration=dec)
            if stop_at is not None:
                job.info["stop_at"] = stop_at
            moving = self.m.profiles.active[self.i] and (self.m.prof_vel[self.i] != 0 or self.m.prof_acc[self.i] != 0)
            if (dec <= 0 and stop_at is None) or not moving:
                self.halt()  # no limit set (decision D3) or nothing to decelerate: stop where the command is
                return
            self.current = job
            self.m.schedule(self)

    def set_observation(self, code: int, active: bool, detail: str = "") -> None:
        """Observation level events (Obsr): warnings that do not stop the axis; cleared when the cause is gone."""
        was = self.observations.get(code, False)
        if active and not was:
            self.observations[code] = True
            self.m.log_error(code, axis=self, source=None, detail=detail)
        elif not active and was:
            del self.observations[code]

    @property
    def obsr_code(self) -> int:
        return next(iter(self.observations), 0)

    # ------------------------------------------------------------------ MC_Power
    def wake_power(self) -> None:
        """The servo state, request, owner or use of the axis changes: MC_Power instances watching it wake."""
        if self.power_sleepers:
            for fb in self.power_sleepers:
                fb.wake()
            self.power_sleepers.clear()

    def power(self, fb_id: int, enable: bool, enable_changed: bool) -> None:
        self.wake_power()
        if enable_changed or self.power_owner is None:
            self.power_owner = fb_id
            self.forced_off = False
        if self.power_owner != fb_id or enable == self.servo_request:
            return
        if enable and self.forced_off:
            return  # turned OFF by the system (free-run stop): servo ON again needs a new Enable edge
        if enable:
            self.servo_request = True
            self.m.servo_req[self.i] = True
        else:
            self._release_servo()

    def _release_servo(self) -> None:
        """Servo OFF: the running instruction is aborted and the command output stops at once."""
        self.wake_power()
        self.servo_request = False
        self.m.servo_req[self.i] = False
        for job in (self.buffered, self.current):
            if job is not None and job.kind == JobKind.STOP:
                self._end_job(job, JobStatus.DONE)  # MC_Stop is Done when the axis is turned OFF
        self.abort_all()
        self.halt()

    def on_servo_changed(self, on: bool) -> None:
        """Inputs stage: the drive reports a change of *Operation enabled*."""
        self.wake_power()
        if on and self.config.drive.EncoderType == "absolute" and not self.homed:
            # absolute encoder: home defined when the axis becomes ready, with the [Absolute encoder home offset]
            # applied (MC_Power rules; omron-axis-instructions.md line 100)
            offset = self.config.drive.AbsoluteEncoderHomeOffset
            self.m.shift_coordinates(self.i, offset - float(self.m.pos_offset[self.i]))
            self.homed = True
        if self.state == S.ErrorStop:
            return  # ErrorStop dominates; MC_Reset decides the next state
        if on:
            self._set_state(self._rest_state())
        else:
            if self.servo_request and not self.virtual:
                self.servo_request = False  # the drive left Operation enabled on its own
                self.m.servo_req[self.i] = False
                self.forced_off = True
            self.abort_all()
            self.halt()
            if self.group is not None:
                self.group.on_member_servo_off(self)
            self._set_state(self._rest_state())

    # ------------------------------------------------------------------ MC_Reset
    def reset(self) -> bool:
        """Reset the axis error. Returns False (Failure) while the axis is still decelerating from the error."""
        cur = self.current
        if self.state == S.ErrorStop and cur is not None and cur.kind == JobKind.ERROR_STOP and cur.running:
            return False  # still decelerating from the error
        if self.error_code or self.state == S.ErrorStop or self.observations:
            self.error_code = 0
            self.observations.clear()
            self.reset_generation += 1
            self._end_job(self.current, JobStatus.DONE)
            self._set_state(self._rest_state())
            self.m.log_info(self, f"axis error reset on {self.name}")
        return True

    # ------------------------------------------------------------------ starting instructions
    def check_start(self, kind: str = "move") -> tuple[str, int]:
        """Acceptance in the current state (A-3.4/A-3.8, `acceptance.py`): ("ok"|"abort"|"error", code)."""
        if self.m.cfg_fault[self.i] and kind != "admin":
            return "error", int(self.m.cfg_fault[self.i])  # 3460: the axis cannot operate (D29)
        if self.encoder and kind not in ("admin", "latch", "set_position"):
            return "error", E.E_AXIS_TYPE
        v = verdict(kind, self.state)
        if v == "ok" or v == "abort":
            return str(v), 0
        return "error", int(v)

    def submit(self, job: Job) -> int:
        """Start or buffer `job` according to its BufferMode. Returns an ErrorID (0 = accepted)."""
        refusal = self.overflow_refusal(job)
        if refusal:
            return refusal
        mode = job.buffer_mode
        cur = self.current
        if mode == _eMC_BUFFER_MODE._mcAborting or cur is None or cur.kind not in MOTION_KINDS:
            self.abort_all()
            self._start(job)
            return 0
        if cur.info.get("feed"):
            # only Aborting onto MC_MoveFeed: the new instruction errors and MC_MoveFeed is aborted (543C)
            self._end_job(cur, JobStatus.ABORTED)
            self.halt()
            return E.E_MULTIEXEC_DISABLED
        if self.buffered is not None:
            return E.E_BUFFER_LIMIT
        blending = mode >= _eMC_BUFFER_MODE._mcBlendingLow
        if cur.kind in LAW_KINDS:
            # onto synchronized control: Buffered only onto MC_CamIn (taking over at EndOfProfile), blending only
            # MC_CamIn onto MC_CamIn with the same master and ReferenceType; onto MC_GearIn, MC_GearInPos,
            # MC_MoveLink and MC_CombineAxes only Aborting (their rules, decision D39)
            law = cur.info["law"]
            nxt = job.info.get("law")
            if law.kind != "cam" or (blending and (nxt is None or not law.can_blend_into(nxt))):
                return E.E_MULTIEXEC_DISABLED
            job.status = JobStatus.WAITING
            self.buffered = job
            self.m.sync_changed()  # the running cam must finish its cycle on its own (not in the batch)
            return 0
        if blending and not (cur.blendable and job.blendable):
            # Blending onto an instruction that does not accept it (MC_MoveVelocity, MC_MoveJog,
            # MC_MoveZeroPosition, MC_MoveFeed): multi-execution disabled (decision D18)
            return E.E_MULTIEXEC_DISABLED
        job.status = JobStatus.WAITING
        self.buffered = job
        if blending:
            cur.replan = True  # re-plan the running move to reach its target at the transit velocity
            self.m.schedule(self)
        elif cur.kind in (JobKind.VELOCITY, JobKind.JOG, JobKind.TORQUE, JobKind.CSV) and cur.in_velocity:
            self._promote_buffered()  # the running instruction has reached InVelocity / InTorque
        return 0

    def _start(self, job: Job) -> None:
        job.status = JobStatus.STARTING
        self.current = job
        self.in_pos_waiting = False
        state = {
            JobKind.POSITION: S.Discrete,
            JobKind.VELOCITY: S.Continuous,
            JobKind.JOG: S.Continuous,
            JobKind.TORQUE: S.Continuous,
            JobKind.STOP: S.Stopping,
            JobKind.RESET_FE: S.Stopping,
            JobKind.HOMING: S.Homing,
            JobKind.SYNC: S.Synchronized,
            JobKind.SYNC_OUT: S.Discrete,
            JobKind.CYCLIC: S.Discrete,
            JobKind.CSV: S.Continuous,
        }.get(job.kind)
        if job.kind == JobKind.RESET_FE and self.state == S.Standstill:
            state = None  # MC_ResetFollowingError on a standing axis keeps Standstill (A-3.4: B → B; C/D/E → G)
        if state is not None:
            self._set_state(state)
        self.m.schedule(self)

    def _promote_buffered(self) -> None:
        job = self.buffered
        self.buffered = None
        if self.current is not None and self.current.running:
            # A velocity instruction hands over at InVelocity and ends with CommandAborted (MC_MoveVelocity rules).
            self._end_job(self.current, JobStatus.ABORTED)
        if job is not None:
            self._start(job)

    def sync_finished(self, law: Any) -> None:
        """Synchronized control ended by itself (a non-periodic cam output its end point, MC_MoveLink arrived, a
        periodic cam finished the cycle in which a successor was buffered): Done, then the buffered instruction —
        a blended MC_CamIn starts at once from where this one ended."""
        job = law.job
        self._end_job(job, JobStatus.DONE)
        nxt = self.buffered
        if nxt is not None:
            nlaw = nxt.info.get("law")
            if nlaw is not None and nxt.buffer_mode >= _eMC_BUFFER_MODE._mcBlendingLow:
                nlaw.blend_from = float(self.m.cmd_pos[self.i])
            self._promote_buffered()
        else:
            self.m.prof_vel[self.i] = 0.0
            self._set_state(self._rest_state())

    def replan(self, job: Job) -> None:
        """Re-execution changed the parameters of a running job."""
        if job is self.current and job.status in (JobStatus.STARTING, JobStatus.ACTIVE):
            job.replan = True
            job.in_velocity = False
            job.paused = False
            self.in_pos_waiting = False
            self.m.schedule(self)

    def stop(self, job: Job) -> str:
        """MC_Stop: abort everything and decelerate. Returns "ok", "abort" (ErrorStop) or "done" (Disabled)."""
        if self.state == S.ErrorStop:
            return "abort"
        if self.state == S.Disabled or not self.servo_on:
            return "done"
        cur = self.current
        if cur is not None and cur.kind == JobKind.STOP:
            # MC_Stop instances may multi-execute; the running one ends with Done (seed 000 line 5980, D4)
            self._end_job(cur, JobStatus.DONE)
        elif cur is not None and cur.kind == JobKind.RESET_FE:
            job.deceleration = 0.0  # MC_Stop during MC_ResetFollowingError stops immediately (MC_Stop rules)
        elif cur is not None and cur.kind == JobKind.CYCLIC:
            job.deceleration = 0.0  # MC_Stop during MC_SyncMoveAbsolute stops immediately (its rules)
        elif cur is not None and cur.kind == JobKind.TORQUE:
            # MC_Stop during torque control stops immediately: back to CSP with the servo locked at the feedback
            # position (MC_TorqueControl rules, "axis stop during torque control"; decision D25)
            job.deceleration = 0.0
        self.abort_all()
        self._start(job)
        return "ok"

    def hold_stop(self, fb_id: int, held: bool) -> None:
        """MC_Stop keeps the axis in Stopping while its Execute stays TRUE."""
        if held:
            self.stop_holders.add(fb_id)
            return
        if fb_id in self.stop_holders:
            self.stop_holders.discard(fb_id)
            if not self.stop_holders and self.state == S.Stopping and self.current is None:
                self._set_state(self._rest_state())

    def release_jog(self, job: Job) -> None:
        if job is self.current and not job.stopping:
            job.stopping = True
            job.replan = True
            self.m.schedule(self)

    def immediate_stop(self, stop_mode: int, source: str) -> None:
        """MC_ImmediateStop: stop by StopMode and raise 5485 (the axis goes to ErrorStop)."""
        self.raise_error(E.E_IMMEDIATE_STOP, source=source, stop=_STOP_OF_MODE.get(stop_mode, STOP_IMMEDIATE))

    def limit_input_stop_mode(self) -> str:
        return _STOP_OF_MODE.get(int(self.params.OtherOperation.LimitInputStopMode), STOP_IMMEDIATE)

    def set_override(self, fb_id: int, factor: float | None, changed: bool) -> None:
        """MC_SetOverride: `factor` in % (None = Enable FALSE → 100 %); the later instance has priority."""
        if changed and factor is not None:
            self.override_owner = fb_id  # an Enable edge takes the override over
        if self.override_owner != fb_id:
            return
        if factor is None:
            # the owner's Enable FALSE disables the override (100 %) until an instance is enabled again
            self.override_owner = -1
            factor = 100.0
        value = factor / 100.0
        m, i = self.m, self.i
        if m.override[i] == value:
            return
        m.override[i] = value
        cur = self.current
        if cur is not None and cur.overridable and cur.status == JobStatus.ACTIVE and not cur.stopping:
            cur.replan = True
            cur.paused = False
            self.m.schedule(self)

    def set_torque_limit(self, fb_id: int, limits: tuple[bool, float, bool, float] | None, changed: bool) -> None:
        """MC_SetTorqueLimit: `limits` = (PositiveEnable, PositiveValue, NegativeEnable, NegativeValue) while Enable
        is TRUE, None when Enable went FALSE; the later instance has priority, its Enable FALSE disables the limit."""
        if changed and limits is not None:
            self.torque_limit_owner = fb_id
        if self.torque_limit_owner != fb_id:
            return
        if limits is None:
            self.torque_limit_owner = -1
        self.torque_limits = limits
        self.apply_torque_limits()

    def apply_torque_limits(self) -> None:
        """60E0h/60E1h: the axis parameters [Maximum Positive/Negative Torque Limit], or the MC_SetTorqueLimit
        values of an enabled direction (clamped to the parameter, 0 or negative acting as 0, 0.1 % resolution) while
        the servo is ON."""
        oo = self.params.OtherOperation
        pos, neg = float(oo.MaxPosiTrqLimit), float(oo.MaxNegaTrqLimit)
        lim = self.torque_limits
        if lim is not None and self.servo_on:
            pe, pv, ne, nv = lim
            if pe:
                pos = min(max(round_tenth(pv), 0.0), pos)
            if ne:
                neg = min(max(round_tenth(nv), 0.0), neg)
        m, i = self.m, self.i
        if m.trq_lim_pos[i] != pos or m.trq_lim_neg[i] != neg:
            m.trq_lim_pos[i] = pos
            m.trq_lim_neg[i] = neg
            m.trq_lim_dirty = True

    def pdo_missing(self, objects: tuple[int, ...]) -> bool:
        """An object an instruction needs is not in the PDO mapping of the axis's slave (3461). Axes without a
        slave (virtual servo axes) need none."""
        mapped = self.m.pdo_objects[self.i]
        return mapped is not None and not set(objects) <= mapped

    def set_position(self, position: float) -> None:
        """MC_SetPosition: the command position becomes `position`, the actual keeps the following error; a running
        MC_MoveAbsolute keeps its absolute target in the new coordinates, relative and velocity motion continue."""
        m, i = self.m, self.i
        delta = position - float(m.cmd_pos[i])
        m.shift_coordinates(i, delta)
        self.homed = False
        m.ovf[i] = 0  # a preset ends an overflow/underflow (A-1 #144)
        for job in (self.current, self.buffered):
            if job is None:
                continue
            if job.absolute_target is not None:
                _, job.target = self.resolve_target(job.absolute_target, job.direction)
                if job is self.current and job.status == JobStatus.ACTIVE:
                    job.replan = True
                    self.m.schedule(self)
            else:
                job.target += delta
                if job.origin is not None:
                    job.origin += delta

    def define_home(self, position: float) -> None:
        """Homing complete (or MC_HomeWithParameter mode 14): preset the command position, home defined."""
        m, i = self.m, self.i
        m.shift_coordinates(i, position - float(m.cmd_pos[i]))
        self.homed = True

    # ------------------------------------------------------------------ _sAXIS_REF
    def capture(self, state: int) -> tuple[int, int, int, bool, bool, bool, bool]:
        """Discrete part of the axis variable (`state`: its state as an int), captured by the kernel thread when a
        snapshot is published."""
        cur = self.current
        busy = cur is not None and (cur.status == JobStatus.STARTING or cur.status == JobStatus.ACTIVE)
        wait = self.in_pos_waiting
        obs = self.observations
        return (state, self.error_code, next(iter(obs)) if obs else 0, self._homed, wait, not busy and not wait,
                self.vel_limit)


def round_tenth(x: float) -> float:
    """0.1 % resolution of the torque inputs: the second decimal is rounded half up (manual: 四舍五入)."""
    return math.floor(x * 10.0 + 0.5) / 10.0


def axis_variables(axis: Axis, discrete: tuple[int, int, int, bool, bool, bool, bool],
                   row: dict[str, Any]) -> dict[str, Any]:
    """The axis variable in the `_sAXIS_REF` layout (`omron-mc-basics.md` §2.3), from captured snapshot data."""
    state, error_code, obsr_code, homed, in_pos_waiting, idle, vel_limit = discrete
    st = S(state)
    p = axis.params
    return {
        "Status": {"Ready": st == S.Standstill, **{s.name: st == s for s in S}},
        "Details": {
            "Idle": idle,
            "InPosWaiting": in_pos_waiting,
            "Homed": homed,
            "InHome": homed and abs(row["act_pos"]) <= p.Operation.ZeroPosRange,
            "VelLimit": vel_limit,
        },
        "Dir": {"Posi": row["cmd_vel"] > 0, "Nega": row["cmd_vel"] < 0},
        "DrvStatus": row["drv"],
        "Cmd": {
            "Pos": row["cmd_pos"],
            "Vel": row["cmd_vel"],
            "AccDec": row["cmd_accdec"],
            "Jerk": row["cmd_jerk"],
            "Trq": row.get("cmd_trq", 0.0),
        },
        "Act": {"Pos": row["act_pos"], "Vel": row["act_vel"], "Trq": row.get("act_trq", 0.0), "TimeStamp": 0},
        "MFaultLvl": {"Active": error_code != 0, "Code": f"{error_code:04X}"},
        "Obsr": {"Active": obsr_code != 0, "Code": f"{obsr_code:04X}"},
        "Cfg": {
            "AxNo": axis.number,
            "AxEnable": "_mcUsedAxis" if axis.used else "_mcUnusedAxis",
            "AxType": axis.type.name,
            "NodeAddress": axis.config.node_address if axis.config.node_address is not None else 0xFFFF,
            "ExecID": 1,
        },
        "Scale": {
            "Num": p.UnitConversion.CmdPlsCountPerMotorRotation,
            "Den": p.UnitConversion.WorkTravelDistancePerMotorRotation,
            "Units": p.UnitConversion.UnitDisplay.name,
            "CountMode": p.PosCount.CountMode.name,
            # Linear Mode: the positions just before overflow/underflow; Rotary Mode: the ring counter limits
            "MaxPos": p.PosCount.ModuloMaxPosVal if axis.rotary else float(axis.m.lin_max[axis.i]),
            "MinPos": p.PosCount.ModuloMinPosVal if axis.rotary else float(axis.m.lin_min[axis.i]),
        },
    }
