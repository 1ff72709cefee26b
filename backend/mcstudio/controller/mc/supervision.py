"""Per-period supervision of every axis (vectorised): software limits, following error, limit inputs, warnings.

* Software limits (`Limit.SwLimitMode`, Linear Mode, home defined; `omron-group-and-cam.md` §5.5.5): checked on the
  command position — deceleration stop planned to stop exactly at the limit, or immediate stop at the limit — or on
  the actual position — deceleration or immediate stop once it is beyond. Positioning targets beyond a limit are
  refused at start (6440/6441); here the limits catch motion without a target (velocity, jog).
* Following error: above `FollowingErrorOverVal` the axis error-stops (immediate stop); above
  `FollowingErrorWarningVal` an observation is set (cleared when it falls back).
* Limit inputs: the positive (negative) limit input ON while the command moves positive (negative) error-stops the
  axis with the Limit Input Stop Method.
* Velocity / acceleration / deceleration warning values: observations.
Codes of the run-time faults are MC Studio assignments (docs/decisions.md D19).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ...drives.cia402 import DI_NEGATIVE_LIMIT, DI_POSITIVE_LIMIT
from . import errors as E
from .enums import AxisState

if TYPE_CHECKING:
    from .module import MotionModule

_BUSY_STATES = (int(AxisState.ErrorStop), int(AxisState.Disabled))


def supervise(m: MotionModule) -> None:
    on = m.servo_on & (m.state != AxisState.ErrorStop)
    if not on.any():
        return
    T = m.period_s
    homing = m.state == AxisState.Homing
    vel = m.cmd_vel
    # ---- following error (not in torque control: no position loop, Cmd.Pos is the feedback of one period earlier)
    fe = np.abs(m.cmd_pos - m.act_pos)
    pos_loop = on & m.fe_check & ~m.trq_active
    over = pos_loop & (m.fe_over > 0) & (fe > m.fe_over)
    for i in np.flatnonzero(over):
        m.axes[i].raise_error(E.E_FOLLOWING_ERROR, stop="immediate",
                              detail=f"following error {fe[i]:g} > {m.fe_over[i]:g}")
    warn = pos_loop & (m.fe_warn > 0) & (fe > m.fe_warn)
    _observe(m, E.O_FOLLOWING_ERROR_WARNING, warn, on)
    # ---- limit inputs during motion (homing handles them itself)
    check = on & m.limit_check & ~homing
    pos_hit = check & ((m.din & DI_POSITIVE_LIMIT) != 0) & (vel > 0)
    neg_hit = check & ((m.din & DI_NEGATIVE_LIMIT) != 0) & (vel < 0)
    for i in np.flatnonzero(pos_hit | neg_hit):
        ax = m.axes[i]
        if ax.state == AxisState.ErrorStop:
            continue
        code = E.E_POSI_LIMIT_DETECTED if pos_hit[i] else E.E_NEGA_LIMIT_DETECTED
        ax.raise_error(code, stop=ax.limit_input_stop_mode())
    # ---- software limits (Linear Mode, home defined)
    sw = on & (m.sw_mode > 0) & ~m.rotary & m.homed & ~homing & (m.state != AxisState.ErrorStop)
    if sw.any():
        _software_limits(m, sw, T)
    # ---- Linear Mode: the command position leaves the signed 40-bit pulse range (not in torque control, where
    # overflow is "motion without a target position")
    hi = m.cmd_pos > m.lin_max
    out = hi | (m.cmd_pos < m.lin_min)
    if out.any():  # rare: build the masks only then
        for i in np.flatnonzero(out & on & ~m.rotary & ~m.trq_active):
            m.axes[i].position_overflow(1 if hi[i] else -1)
    # ---- warnings (observations)
    _observe(m, E.O_VELOCITY_WARNING, on & (m.vel_warn > 0) & (np.abs(vel) > m.vel_warn), on)
    _observe(m, E.O_ACCELERATION_WARNING, on & (m.acc_warn > 0) & (m.cmd_accdec > m.acc_warn), on)
    _observe(m, E.O_DECELERATION_WARNING, on & (m.dec_warn > 0) & (-m.cmd_accdec > m.dec_warn), on)


def _observe(m: MotionModule, code: int, active: np.ndarray, scope: np.ndarray) -> None:
    """Set the observation where `active`, clear it where it was set by this check and `scope` holds. `m.obs_set`
    remembers where this check set it, so a period without warnings costs two vector operations, no axis loop."""
    flags = m.obs_set.get(code)
    if flags is None:
        flags = m.obs_set[code] = np.zeros(m.n, dtype=bool)
    if active.any():
        for i in np.flatnonzero(active):
            m.axes[i].set_observation(code, True)
        flags |= active
    gone = flags & ~active & scope
    if gone.any():
        for i in np.flatnonzero(gone):
            a = m.axes[i]
            if code in a.observations:
                a.set_observation(code, False)
        flags &= ~gone


def _software_limits(m: MotionModule, sw: np.ndarray, T: float) -> None:
    mode = m.sw_mode
    v = m.prof_vel
    trq = sw & m.trq_active
    cmd_mode = sw & ((mode == 1) | (mode == 2)) & ~m.target_checked & ~trq
    act_mode = sw & ((mode == 3) | (mode == 4)) & ~trq
    if trq.any():
        # torque control: the limits apply whatever the mode selects, on the feedback position, and the axis stops
        # at once (no deceleration stop in torque control; MC_TorqueControl rules "software limits", D25)
        pos_hit = trq & (m.act_pos >= m.posi_sw) & (m.act_vel > 0)
        neg_hit = trq & (m.act_pos <= m.nega_sw) & (m.act_vel < 0)
        for i in np.flatnonzero(pos_hit | neg_hit):
            code = E.E_SW_LIMIT_POSI if pos_hit[i] else E.E_SW_LIMIT_NEGA
            m.axes[i].raise_error(code, stop="immediate",
                                  detail=f"feedback position {m.act_pos[i]:g} in torque control")
    if cmd_mode.any():
        dec = np.where(m.stop_dec > 0, m.stop_dec, m.max_dec)
        with np.errstate(divide="ignore", invalid="ignore"):
            brake = np.where(dec > 0, v * v / (2 * dec), 0.0)
        ahead = m.cmd_pos + np.sign(v) * (brake + np.abs(v) * T)
        # deceleration stop: start braking so that the axis stops on the limit; immediate: stop at the limit
        look = np.where(mode == 1, ahead, m.cmd_pos)
        pos_hit = cmd_mode & (v > 0) & (look >= m.posi_sw)
        neg_hit = cmd_mode & (v < 0) & (look <= m.nega_sw)
        for i in np.flatnonzero(pos_hit | neg_hit):
            ax = m.axes[i]
            limit = float(m.posi_sw[i] if pos_hit[i] else m.nega_sw[i])
            code = E.E_SW_LIMIT_POSI if pos_hit[i] else E.E_SW_LIMIT_NEGA
            beyond = (m.cmd_pos[i] - limit) * (1 if pos_hit[i] else -1) >= 0
            if mode[i] == 2 or beyond or dec[i] <= 0:
                m.cmd_pos[i] = limit if not beyond else m.cmd_pos[i]
                ax.raise_error(code, stop="immediate")
            else:
                ax.raise_error(code, stop="decel", stop_at=limit, deceleration=float(dec[i]))
    if act_mode.any():
        pos_hit = act_mode & (v >= 0) & (m.act_pos >= m.posi_sw) & (m.cmd_vel > 0)
        neg_hit = act_mode & (v <= 0) & (m.act_pos <= m.nega_sw) & (m.cmd_vel < 0)
        for i in np.flatnonzero(pos_hit | neg_hit):
            code = E.E_SW_LIMIT_POSI if pos_hit[i] else E.E_SW_LIMIT_NEGA
            dec = float(m.stop_dec[i] or m.max_dec[i])
            m.axes[i].raise_error(code, stop="decel" if mode[i] == 3 else "immediate", deceleration=dec)
