"""One axis of the MC function module: its state machine, the instructions running on it, and `_sAXIS_REF`.

Continuous quantities (command and actual values, profiles) live in the `MotionModule` arrays, one row per axis, so
the control period can treat all axes at once; the discrete side (state, jobs, errors) lives here and changes only on
events. State names and transitions follow `omron-mc-basics.md` §A-3 (A-3.4 table, A-3.8 acceptance).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from . import errors as E
from .enums import AxisState, _eMC_AXIS_TYPE, _eMC_BUFFER_MODE
from .jobs import Job, JobKind, JobStatus
from .units import pulses_per_unit

if TYPE_CHECKING:
    from ...project.models import AxisConfig
    from .module import MotionModule

S = AxisState

# Axis states in which a new positioning/velocity instruction is accepted (A-3.4 columns B–E).
_MOVE_OK = {S.Standstill, S.Discrete, S.Continuous, S.Synchronized}


class Axis:
    def __init__(self, module: MotionModule, index: int, config: AxisConfig) -> None:
        self.m = module
        self.i = index
        self.config = config
        self.name = config.name
        self.number = config.number
        self.type = config.type
        self.params = config.parameters
        self.ppu = pulses_per_unit(config.parameters)
        self.virtual = config.type in (_eMC_AXIS_TYPE._mcVirServo, _eMC_AXIS_TYPE._mcVirEncdr)
        self.encoder = config.type in (_eMC_AXIS_TYPE._mcEncdr, _eMC_AXIS_TYPE._mcVirEncdr)
        self.state = S.Disabled
        self.current: Job | None = None
        self.buffered: Job | None = None
        self.stop_holders: set[int] = set()  # ids of MC_Stop instances whose Execute is still TRUE
        self.power_owner: int | None = None  # id of the MC_Power instance in control (later instance wins)
        self.servo_request = False
        self.error_code = 0  # MFaultLvl.Code (0 = no minor fault)
        self.obsr_code = 0
        self.reset_generation = 0  # increments each time the axis error is reset (releases FB Error outputs)
        self.homed = False
        self.in_pos_waiting = False

    # ------------------------------------------------------------------ helpers
    @property
    def servo_on(self) -> bool:
        return bool(self.m.servo_on[self.i])

    @property
    def last_direction(self) -> int:
        """+1 / −1: direction of the last command motion (for _mcCurrentDirection)."""
        return int(self.m.last_dir[self.i])

    @property
    def cmd_pos(self) -> float:
        return float(self.m.cmd_pos[self.i])

    @property
    def act_pos(self) -> float:
        return float(self.m.act_pos[self.i])

    def _set_state(self, state: AxisState) -> None:
        self.state = state
        self.m.state[self.i] = state

    def _rest_state(self) -> AxisState:
        """State of a stopped axis without error: Disabled / Standstill / Stopping (MC_Stop held)."""
        if not self.servo_on:
            return S.Disabled
        return S.Stopping if self.stop_holders else S.Standstill

    def _end_job(self, job: Job | None, status: JobStatus, error_id: int = 0) -> None:
        if job is None or not job.running:
            return
        job.status = status
        job.error_id = error_id
        job.finished_cycle = self.m.cycle
        self.m.job_changed(job)
        if job is self.current:
            self.current = None
        if job is self.buffered:
            self.buffered = None

    def abort_all(self) -> None:
        """Every instruction running or buffered on this axis gets CommandAborted."""
        self._end_job(self.buffered, JobStatus.ABORTED)
        self._end_job(self.current, JobStatus.ABORTED)

    # ------------------------------------------------------------------ errors
    def raise_error(self, code: int, *, source: str | None = None, stop: bool = True, detail: str = "") -> None:
        """Axis minor fault: MFaultLvl, ErrorStop, running instructions aborted, deceleration stop (A-1 effect AX-D)."""
        first = self.error_code == 0
        if first:
            self.error_code = code
        self.m.log_error(code, axis=self, source=source, detail=detail)
        self.abort_all()
        self.in_pos_waiting = False
        self._set_state(S.ErrorStop)
        if stop and self.servo_on:
            self._start_error_stop()

    def _start_error_stop(self) -> None:
        # Deceleration stop at the axis maximum deceleration; immediate stop when it is 0 (no limit) — decisions.md.
        job = Job(JobKind.ERROR_STOP, None, deceleration=self.params.Operation.MaxDec)
        self.current = job
        self.m.schedule(self)

    # ------------------------------------------------------------------ MC_Power
    def power(self, fb_id: int, enable: bool, enable_changed: bool) -> None:
        if enable_changed or self.power_owner is None:
            self.power_owner = fb_id
        if self.power_owner != fb_id:
            return
        if enable == self.servo_request:
            return
        self.servo_request = enable
        self.m.servo_req[self.i] = enable
        if not enable:
            # Releasing the ready state aborts the running instruction; the command output stops at once.
            for job in (self.buffered, self.current):
                if job is not None and job.kind == JobKind.STOP:
                    self._end_job(job, JobStatus.DONE)
            self.abort_all()
            self.m.profiles.clear(self.i)
            self.m.prof_vel[self.i] = 0.0
            self.m.prof_acc[self.i] = 0.0
            self.in_pos_waiting = False

    def on_servo_changed(self, on: bool) -> None:
        """Inputs stage: the drive reports a change of *Operation enabled*."""
        if self.state == S.ErrorStop:
            return  # ErrorStop dominates; MC_Reset decides the next state
        if on:
            self._set_state(self._rest_state())
        else:
            if self.servo_request and not self.virtual:
                # The drive left Operation enabled on its own (fault, power loss): the EtherCAT issue maps drive
                # errors to their codes; until then the axis is simply released.
                self.servo_request = False
                self.m.servo_req[self.i] = False
            self.abort_all()
            self.m.profiles.clear(self.i)
            self._set_state(S.Disabled)

    # ------------------------------------------------------------------ MC_Reset
    def reset(self) -> bool:
        """Reset the axis error. Returns False (Failure) while the axis is still decelerating from the error."""
        if self.state == S.ErrorStop and self.current is not None and self.current.kind == JobKind.ERROR_STOP:
            return False
        if self.error_code or self.state == S.ErrorStop:
            self.error_code = 0
            self.reset_generation += 1
            self._end_job(self.current, JobStatus.DONE)
            self._set_state(self._rest_state())
            self.m.log_info(self, f"axis error reset on {self.name}")
        return True

    # ------------------------------------------------------------------ motion requests
    def check_start(self, *, jog: bool = False) -> tuple[str, int]:
        """Acceptance of a single-axis motion instruction in the current state (A-3.4/A-3.8).

        Returns ("ok", 0), ("abort", 0) for CommandAborted without error, or ("error", code).
        """
        st = self.state
        if st == S.ErrorStop or st == S.Stopping:
            return "abort", 0
        if self.encoder:
            return "error", E.E_AXIS_TYPE
        if st == S.Disabled:
            return "error", E.E_SERVO_OFF
        if st == S.Coordinated:
            return "error", 0x543E
        if jog:
            return ("ok", 0) if st == S.Standstill else ("error", E.E_MULTIEXEC_DISABLED)
        if st in _MOVE_OK:
            return "ok", 0
        return "error", E.E_MULTIEXEC_DISABLED  # Homing

    def submit(self, job: Job) -> int:
        """Start or buffer `job` according to its BufferMode. Returns an ErrorID (0 = accepted)."""
        mode = job.buffer_mode
        if mode == _eMC_BUFFER_MODE._mcAborting or self.current is None or self.current.kind in (
            JobKind.STOP,
            JobKind.ERROR_STOP,
        ):
            self.abort_all()
            self._start(job)
            return 0
        # Buffered (and, until blending lands, the blending modes wait for Done as Buffered does)
        if self.buffered is not None:
            return E.E_BUFFER_LIMIT
        job.status = JobStatus.WAITING
        self.buffered = job
        if self.current.kind in (JobKind.VELOCITY, JobKind.JOG) and self.current.in_velocity:
            self._promote_buffered()
        return 0

    def _start(self, job: Job) -> None:
        job.status = JobStatus.STARTING
        self.current = job
        self.in_pos_waiting = False
        if job.kind == JobKind.POSITION:
            self._set_state(S.Discrete)
        elif job.kind in (JobKind.VELOCITY, JobKind.JOG):
            self._set_state(S.Continuous)
        elif job.kind == JobKind.STOP:
            self._set_state(S.Stopping)
        self.m.schedule(self)

    def _promote_buffered(self) -> None:
        job = self.buffered
        self.buffered = None
        if self.current is not None and self.current.running:
            # A velocity instruction hands over at InVelocity and ends with CommandAborted (MC_MoveVelocity rules).
            self._end_job(self.current, JobStatus.ABORTED)
        if job is not None:
            self._start(job)

    def replan(self, job: Job) -> None:
        """Re-execution changed the parameters of a running job."""
        if job is self.current and job.status in (JobStatus.STARTING, JobStatus.ACTIVE):
            job.replan = True
            job.in_velocity = False
            self.in_pos_waiting = False
            self.m.schedule(self)

    def stop(self, job: Job) -> str:
        """MC_Stop: abort everything and decelerate. Returns "ok", "abort" (ErrorStop) or "done" (Disabled)."""
        if self.state == S.ErrorStop:
            return "abort"
        if self.state == S.Disabled or not self.servo_on:
            return "done"
        if self.current is not None and self.current.kind == JobKind.STOP:
            # MC_Stop instances may multi-execute; the running one ends with Done (seed 000 line 5980, decisions.md)
            self._end_job(self.current, JobStatus.DONE)
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

    # ------------------------------------------------------------------ motion stage callbacks
    def on_planned(self, job: Job) -> None:
        job.status = JobStatus.ACTIVE
        job.replan = False
        job.cmd_done_cycle = -1

    def on_profile_finished(self, job: Job) -> bool:
        """The profile of the current job reached its tail (target position / target velocity / standstill).

        Returns True while the end is still pending and must be reported again next period. Ends are reported one
        period after the profile reached them, when the command values the axis reports agree: Cmd.Vel (a difference
        of positions) equals the target velocity (InVelocity) or 0, and the final command value has reached the
        drive (positioning complete, stop complete). A positioning with an in-position check time also waits until
        the actual position is inside the in-position range.
        """
        i = self.i
        cycle = self.m.cycle
        if job.cmd_done_cycle < 0:
            job.cmd_done_cycle = cycle
        if cycle <= job.cmd_done_cycle:
            return True  # the final command value is sent in this period's outputs
        if job.kind in (JobKind.VELOCITY, JobKind.JOG) and not job.stopping:
            # InVelocity: Cmd.Vel (difference of positions) has reached the target velocity
            if not job.in_velocity:
                job.in_velocity = True
                self.m.job_changed(job)
                if self.buffered is not None:
                    self._promote_buffered()
            return False
        if job.kind == JobKind.POSITION:
            op = self.params.Operation
            if op.InPosCheckTime > 0 and abs(float(self.m.act_pos[i]) - job.target) > op.InPosRange:
                self.in_pos_waiting = True
                return True
            self.in_pos_waiting = False
        self.m.profiles.clear(i)
        self._end_job(job, JobStatus.DONE)
        if job.kind == JobKind.ERROR_STOP:
            return False
        if job.kind == JobKind.POSITION and self.buffered is not None:
            self._promote_buffered()
        else:
            self._set_state(self._rest_state())
        return False

    # ------------------------------------------------------------------ _sAXIS_REF
    def capture(self) -> tuple[int, int, int, bool, bool, bool]:
        """Discrete part of the axis variable, captured by the kernel thread when a snapshot is published."""
        busy = self.current is not None and self.current.status in (JobStatus.STARTING, JobStatus.ACTIVE)
        idle = not busy and not self.in_pos_waiting
        return (int(self.state), self.error_code, self.obsr_code, self.homed, self.in_pos_waiting, idle)


def axis_variables(axis: Axis, discrete: tuple[int, int, int, bool, bool, bool], row: dict[str, Any]) -> dict[str, Any]:
    """The axis variable in the `_sAXIS_REF` layout (`omron-mc-basics.md` §2.3), from captured snapshot data."""
    state, error_code, obsr_code, homed, in_pos_waiting, idle = discrete
    st = S(state)
    p = axis.params
    return {
        "Status": {"Ready": st == S.Standstill, **{s.name: st == s for s in S}},
        "Details": {
            "Idle": idle,
            "InPosWaiting": in_pos_waiting,
            "Homed": homed,
            "InHome": homed and abs(row["act_pos"]) <= p.Operation.ZeroPosRange,
            "VelLimit": False,
        },
        "Dir": {"Posi": row["cmd_vel"] > 0, "Nega": row["cmd_vel"] < 0},
        "DrvStatus": row["drv"],
        "Cmd": {
            "Pos": row["cmd_pos"],
            "Vel": row["cmd_vel"],
            "AccDec": row["cmd_accdec"],
            "Jerk": row["cmd_jerk"],
            "Trq": 0.0,
        },
        "Act": {"Pos": row["act_pos"], "Vel": row["act_vel"], "Trq": 0.0, "TimeStamp": 0},
        "MFaultLvl": {"Active": error_code != 0, "Code": f"{error_code:04X}"},
        "Obsr": {"Active": obsr_code != 0, "Code": f"{obsr_code:04X}"},
        "Cfg": {
            "AxNo": axis.number,
            "AxEnable": axis.config.use.name,
            "AxType": axis.type.name,
            "NodeAddress": axis.config.node_address if axis.config.node_address is not None else 0xFFFF,
            "ExecID": 1,
        },
        "Scale": {
            "Num": p.UnitConversion.CmdPlsCountPerMotorRotation,
            "Den": p.UnitConversion.WorkTravelDistancePerMotorRotation,
            "Units": p.UnitConversion.UnitDisplay.name,
            "CountMode": p.PosCount.CountMode.name,
            "MaxPos": p.PosCount.ModuloMaxPosVal,
            "MinPos": p.PosCount.ModuloMinPosVal,
        },
    }
