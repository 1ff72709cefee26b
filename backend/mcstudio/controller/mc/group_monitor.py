"""Monitoring of an axes group (mixed into `AxesGroup`): the in-position check at the end of a group move, the
interpolation velocity/acceleration/deceleration warnings, `Details.VelLimit` of the composition axes under
MC_GroupSyncMoveAbsolute, and the drive side of MC_GroupReset.

* In-position check (decision D103): Done of an interpolation instruction waits until every composition axis with an
  In-position Check Time > 0 has |Act.Pos − Cmd.Pos| ≤ its In-position Range (the single-axis rule of D9, per
  composition axis); meanwhile the group shows `Details.InPosWaiting` (“any composition axis is waiting for
  in-position”, `omron-mc-basics.md` §2.4 L378) and stays Moving (§0.4 c), and the waiting axes show it too. When an
  axis's check time runs out first, the group error-stops with 6455 (the in-position check time code, D19).
* Interpolation warning values (D104): the group's Cmd.Vel above MaxInterpolationVel × InterpolationVelWarningVal %,
  Cmd.AccDec above MaxInterpolationAcc × InterpolationAccWarningVal % or below −MaxInterpolationDec ×
  InterpolationDecWarningVal % set an observation of the group (`Obsr`, 6464/6465/6466); it clears when the value is
  back under the threshold and with MC_GroupReset.
* `Details.VelLimit` (D107): a composition axis whose MC_GroupSyncMoveAbsolute step is cut to its Maximum Velocity
  (`omron-group-and-cam.md` §4.12, seed 000 line 17041).
* MC_GroupReset (D108): members with a drive error get the CiA402 fault reset first (`fb/group_fb.py`).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from . import errors as E
from .enums import AxisState
from .jobs import Job, JobKind

if TYPE_CHECKING:
    from ...project.models import GroupOperationSettings
    from .axis import Axis
    from .group_types import Motion
    from .module import MotionModule

# MC Studio codes of the group's interpolation warnings (observations; D19 block, decision D104)
O_INTERP_VEL_WARNING = 0x6464
O_INTERP_ACC_WARNING = 0x6465
O_INTERP_DEC_WARNING = 0x6466
WARNING_CODES = (O_INTERP_VEL_WARNING, O_INTERP_ACC_WARNING, O_INTERP_DEC_WARNING)


def warning_limits(op: GroupOperationSettings) -> tuple[float, float, float]:
    """Thresholds of the interpolation warnings (0 = no warning): a percentage of the maximum interpolation
    velocity / acceleration / deceleration; a maximum of 0 ("no limit") gives no warning (D104)."""
    return (op.MaxInterpolationVel * op.InterpolationVelWarningVal / 100.0,
            op.MaxInterpolationAcc * op.InterpolationAccWarningVal / 100.0,
            op.MaxInterpolationDec * op.InterpolationDecWarningVal / 100.0)


class GroupMonitor:
    m: MotionModule
    name: str
    axes: list[Axis]
    cmd_vel: float
    cmd_accdec: float
    enabled: bool
    current: Job | None
    in_pos_waiting: bool
    observations: dict[int, bool]
    warn_limits: tuple[float, float, float]
    warn_on: bool

    # ------------------------------------------------------------------ in-position check
    def _in_position_pending(self, mv: Motion, cycle: int) -> bool:
        """The period after the final command value of a move and the following ones: True while Done must wait
        for the in-position check (or the check failed and the group error-stopped with 6455)."""
        m = self.m
        waited_ms = (cycle - mv.end_cycle) * m.period_s * 1000.0
        waiting = False
        for a in self.axes:
            op = a.params.Operation
            i = a.i
            if op.InPosCheckTime > 0 and abs(float(m.act_pos[i]) - float(m.cmd_pos[i])) > op.InPosRange:
                if waited_ms >= op.InPosCheckTime:
                    dev = abs(float(m.act_pos[i]) - float(m.cmd_pos[i]))
                    self.clear_member_flags()
                    self.raise_error(E.E_INPOS_TIME, source=a.name,  # type: ignore[attr-defined]
                                     detail=f"{a.name}: |Act.Pos − target| = {dev:g} after {op.InPosCheckTime} ms")
                    return True
                waiting = True
                a.in_pos_waiting = True
            elif a.in_pos_waiting:
                a.in_pos_waiting = False
        self.in_pos_waiting = waiting
        return waiting

    def clear_member_flags(self) -> None:
        """The group move that set them ended (Done, aborted, stopped, error): InPosWaiting and VelLimit off."""
        self.in_pos_waiting = False
        for a in self.axes:
            if a.in_pos_waiting and a.state == AxisState.Coordinated:
                a.in_pos_waiting = False
            a.vel_limit = False

    # ------------------------------------------------------------------ interpolation warnings
    def check_warnings(self) -> None:
        """Compare the group's Cmd.Vel / Cmd.AccDec with the interpolation warning values (D104)."""
        v_lim, a_lim, d_lim = self.warn_limits
        v, acc = abs(self.cmd_vel), self.cmd_accdec
        self.set_observation(O_INTERP_VEL_WARNING, 0.0 < v_lim < v, f"Cmd.Vel {v:g} > {v_lim:g}")
        self.set_observation(O_INTERP_ACC_WARNING, 0.0 < a_lim < acc, f"Cmd.AccDec {acc:g} > {a_lim:g}")
        self.set_observation(O_INTERP_DEC_WARNING, 0.0 < d_lim < -acc, f"Cmd.AccDec {acc:g} < {-d_lim:g}")

    def set_observation(self, code: int, active: bool, detail: str = "") -> None:
        """Observation level events of the group (`Obsr`): warnings that do not stop it; cleared when the cause is
        gone (logged once when they appear)."""
        if active == self.observations.get(code, False):
            return
        if active:
            self.observations[code] = True
            self.m.log_error(code, axis=None, source=self.name, detail=f"{self.name}: {detail}", group=self.name)
        else:
            del self.observations[code]

    @property
    def obsr_code(self) -> int:
        return next(iter(self.observations), 0)

    # ------------------------------------------------------------------ MC_GroupReset
    def reset_failure_cause(self) -> bool:
        """MC_GroupReset must report Failure before doing anything: the group or an axis still decelerates because
        of an error (§4.13), or, while the group is enabled, an axis in error whose cause persists (3460
        configuration error, slave not in process-data communication: MC_Reset's rule, D29)."""
        cur = self.current
        if cur is not None and cur.kind == JobKind.GROUP_STOP and cur.owner is None and cur.running:
            return True
        m = self.m
        for a in self.axes:
            c = a.current
            if a.state == AxisState.ErrorStop and c is not None and c.kind == JobKind.ERROR_STOP and c.running:
                return True
        if self.enabled:
            for a in self.axes:
                if (a.error_code or a.state == AxisState.ErrorStop) and (m.cfg_fault[a.i] or not m.pd_ok[a.i]):
                    return True
        return False

    def drive_faults(self) -> list[Axis]:
        """Composition axes whose drive reports a fault: MC_GroupReset resets them first (only while the group is
        enabled: the axes' errors are only cleared then, §4.13)."""
        if not self.enabled:
            return []
        m = self.m
        return [a for a in self.axes if m.drv_fault[a.i]]
