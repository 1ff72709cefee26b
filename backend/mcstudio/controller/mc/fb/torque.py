"""Torque instructions: MC_TorqueControl and MC_SetTorqueLimit (`omron-axis-instructions.md`, seed 000 lines
10597–11117).

MC_TorqueControl puts the drive into cyclic synchronous torque mode (CST, 6060h = 10) and ramps the command torque
(6071h) to the target; Velocity is the drive's velocity limit (607Fh). The MC module's torque stage computes the
command torque each period (`module.py`), the drive and the mechanism behind it (`drives/cia402.py`,
`plant/ideal.py`) turn it into motion. MC_SetTorqueLimit writes the drive's torque limits (60E0h/60E1h).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from .. import errors as E
from ..axis import round_tenth
from ..jobs import Job, JobKind, JobStatus
from .admin import I_ENABLE, O_ENABLED, _EnableFB
from .base import I_EXECUTE, IO_AXIS, O_ABORTED, O_ACTIVE, O_BUSY, O_ERROR, O_ERRORID, FBDef, FunctionBlock, Var
from .single_axis import _clamp_profile, _MotionFB, start_limit_error

if TYPE_CHECKING:
    from ..axis import Axis

# objects MC_TorqueControl needs in the PDO mapping (omron-mc-basics.md §2.11): target torque, modes of operation,
# torque actual value, modes of operation display
TORQUE_CONTROL_PDO = (0x6071, 0x6060, 0x6077, 0x6061)
TORQUE_LIMIT_PDO = (0x60E0, 0x60E1)  # positive / negative torque limit value


# --------------------------------------------------------------------------------------------------- MC_TorqueControl
class MC_TorqueControl(_MotionFB):
    DEF = FBDef(
        name="MC_TorqueControl",
        title="Torque control",
        summary="Torque control in the drive's cyclic synchronous torque mode: the command torque ramps to Torque "
        "in Direction; Velocity limits the speed. Runs until aborted (InTorque, never Done).",
        kind="execute",
        inouts=(IO_AXIS,),
        inputs=(
            I_EXECUTE,
            Var("Torque", "LREAL", 300.0, "Target torque in % of the rated torque (above 1000 → 1000, negative → 0; "
                "0.1 % resolution)", "%", "0 to 1000.0"),
            Var("TorqueRamp", "LREAL", 0.0, "Rate of change from the current to the target torque (0 = step change)",
                "%/s", "positive or 0"),
            Var("Velocity", "LREAL", 0.0, "Velocity limit during torque control (the drive reduces the torque at "
                "it; 0 = the axis does not move)", "unit/s", "positive or 0"),
            Var("Direction", "_eMC_DIRECTION", 0, "Direction in which the target torque is output", None, "0, 2",
                allowed=(0, 2)),
            Var("BufferMode", "_eMC_BUFFER_MODE", 0, "Behaviour on multi-execution", None, "0, 1", allowed=(0, 1)),
        ),
        outputs=(
            Var("InTorque", "BOOL", False, "TRUE while the target torque is output to the drive"),
            O_BUSY,
            O_ACTIVE,
            O_ABORTED,
            O_ERROR,
            O_ERRORID,
        ),
        spec="omron-axis-instructions.md MC_TorqueControl (seed 000 line 10597)",
    )
    KIND = JobKind.TORQUE
    OVERRIDABLE = False  # MC_SetOverride names seven instructions; this is not one of them

    def _check(self, axis: Axis) -> int:
        i = self.inp
        if not i["TorqueRamp"] >= 0:
            return E.E_TORQUE_RAMP
        if not i["Velocity"] >= 0:
            return E.E_VELOCITY
        if i["Direction"] not in (0, 2):
            return E.E_DIRECTION
        if i["BufferMode"] not in (0, 1):
            return E.E_BUFFER_MODE
        return 0

    def _fill(self, job: Job, axis: Axis) -> None:
        i = self.inp
        torque = round_tenth(min(max(i["Torque"], 0.0), 1000.0))
        job.info["torque"] = torque if i["Direction"] == 0 else -torque
        job.info["ramp"] = i["TorqueRamp"]
        job.velocity, _, _ = _clamp_profile(axis, i["Velocity"], 0.0, 0.0)  # at most the Maximum Velocity

    def _limits(self, job: Job, axis: Axis) -> int:
        if axis.pdo_missing(TORQUE_CONTROL_PDO):
            return E.E_PDO_MISSING
        return start_limit_error(axis, 1 if self.inp["Direction"] == 0 else -1)

    def reexecute(self, axis: Axis) -> None:
        # Torque, TorqueRamp and Velocity may change; InTorque drops when the target torque changes
        job = self.job
        before = job.info.get("torque") if job is not None else None
        super().reexecute(axis)
        if job is not None and self.job is job and job.info.get("torque") != before:
            self.out["InTorque"] = False

    def sync_job(self) -> None:
        job = self.job
        super().sync_job()
        if job is not None and job.status == JobStatus.ACTIVE:
            self.out["InTorque"] = job.in_velocity

    def _finish(self, flag: str) -> None:
        super()._finish(flag)
        self.out["InTorque"] = False

    def _set_error(self, code: int, axis: Axis | None) -> None:
        super()._set_error(code, axis)
        self.out["InTorque"] = False


# --------------------------------------------------------------------------------------------------- MC_SetTorqueLimit
class MC_SetTorqueLimit(_EnableFB):
    DEF = FBDef(
        name="MC_SetTorqueLimit",
        title="Set torque limit",
        summary="Limits the drive's output torque (60E0h/60E1h) in the enabled directions while Enable is TRUE.",
        kind="enable",
        inouts=(IO_AXIS,),
        inputs=(
            I_ENABLE,
            Var("PositiveEnable", "BOOL", False, "TRUE: the positive torque limit is active"),
            Var("PositiveValue", "LREAL", 300.0, "Positive torque limit (above [Maximum Positive Torque Limit] → "
                "that value; 0 or negative act as 0; 0.1 % resolution)", "%", "0.1 to 1000.0 or 0.0"),
            Var("NegativeEnable", "BOOL", False, "TRUE: the negative torque limit is active"),
            Var("NegativeValue", "LREAL", 300.0, "Negative torque limit (above [Maximum Negative Torque Limit] → "
                "that value; 0 or negative act as 0; 0.1 % resolution)", "%", "0.1 to 1000.0 or 0.0"),
        ),
        outputs=(O_ENABLED, O_BUSY, O_ERROR, O_ERRORID),
        spec="omron-axis-instructions.md MC_SetTorqueLimit (seed 000 line 10917)",
    )

    def __init__(self, mc: Any, fb_id: int, inputs: dict[str, Any] | None = None) -> None:
        super().__init__(mc, fb_id, inputs)
        self._axis_ref: Axis | None = None

    def enabled(self, changed: bool) -> None:
        axis = self.resolve_axis()
        if axis is None:
            self.fail(E.E_ILLEGAL_AXIS, None)
            return
        if axis.encoder:
            self.fail(E.E_AXIS_TYPE, axis)  # encoder axes: error at start
            return
        if axis.pdo_missing(TORQUE_LIMIT_PDO):
            self.fail(E.E_PDO_MISSING, axis)
            return
        i = self.inp
        if not axis.virtual:  # a virtual servo axis accepts the instruction and does nothing
            axis.set_torque_limit(self.id, (bool(i["PositiveEnable"]), i["PositiveValue"],
                                            bool(i["NegativeEnable"]), i["NegativeValue"]), changed)
        self._axis_ref = axis
        # Enabled shows the instruction's state, TRUE only with the servo ON (no torque limit while OFF)
        self.out["Enabled"] = axis.servo_on

    def disable(self) -> None:
        axis = self._axis_ref
        if axis is not None and not axis.virtual:
            axis.set_torque_limit(self.id, None, True)

    def on_delete(self) -> None:
        if self.inp["Enable"]:
            self.disable()


TORQUE_CLASSES: tuple[type[FunctionBlock], ...] = (MC_TorqueControl, MC_SetTorqueLimit)
