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
from ...fastnp import count_nonzero
from . import errors as E
from .enums import AxisState

if TYPE_CHECKING:
    from .module import MotionModule

class Supervision:
    """The supervision of all axes, with what each check needs precomputed from the discrete state.

    Which axes a check applies to (servo ON, state, homing, torque control, home defined …) and its thresholds change
    only with events, so they are compiled into per-check threshold arrays (+inf where the check is off) whenever one
    of their sources changes; a period then costs a few comparisons of the continuous values against them.
    """

    def __init__(self, m: MotionModule) -> None:
        self.m = m
        n = m.n
        self._key: bytes | None = None
        self.n_on = 0
        self.on = np.zeros(n, dtype=bool)
        self.fe_over = np.full(n, np.inf)  # following error over value where checked, +inf elsewhere
        self.fe_warn = np.full(n, np.inf)
        self.any_fe_warn = False
        self.limit_scope = np.zeros(n, dtype=bool)  # limit inputs checked (servo ON, not homing)
        self.pos_limit_on = np.zeros(n, dtype=bool)  # … and the positive / negative limit input is ON
        self.neg_limit_on = np.zeros(n, dtype=bool)
        self.any_limit_on = False
        self.sw = np.zeros(n, dtype=bool)
        self.any_sw = False
        self.ovf_scope = np.zeros(n, dtype=bool)
        self.warn: dict[int, np.ndarray] = {}  # observation code → threshold (+inf where off)
        self._fe = np.zeros(n)
        self._b1 = np.zeros(n, dtype=bool)
        self._b2 = np.zeros(n, dtype=bool)
        self._w = np.zeros(n)

    def _compile(self, key: bytes) -> None:
        m = self.m
        self._key = key
        on = m.servo_on & (m.state != AxisState.ErrorStop)
        self.on = on
        self.n_on = int(count_nonzero(on))
        homing = m.state == AxisState.Homing
        pos_loop = on & m.fe_check & ~m.trq_active
        self.fe_over = np.where(pos_loop & (m.fe_over > 0), m.fe_over, np.inf)
        self.fe_warn = np.where(pos_loop & (m.fe_warn > 0), m.fe_warn, np.inf)
        self.any_fe_warn = bool(np.isfinite(self.fe_warn).any())
        self.limit_scope = on & m.limit_check & ~homing
        self.pos_limit_on = self.limit_scope & ((m.din & DI_POSITIVE_LIMIT) != 0)
        self.neg_limit_on = self.limit_scope & ((m.din & DI_NEGATIVE_LIMIT) != 0)
        self.any_limit_on = bool(self.pos_limit_on.any() or self.neg_limit_on.any())
        self.sw = on & (m.sw_mode > 0) & ~m.rotary & m.homed & ~homing
        self.any_sw = bool(self.sw.any())
        self.ovf_scope = on & ~m.rotary & ~m.trq_active
        self.warn = {}
        for code, limit in ((E.O_VELOCITY_WARNING, m.vel_warn), (E.O_ACCELERATION_WARNING, m.acc_warn),
                            (E.O_DECELERATION_WARNING, m.dec_warn)):
            armed = on & (limit > 0)
            if armed.any():
                self.warn[code] = np.where(armed, limit, np.inf)

    def __call__(self) -> None:
        m = self.m
        key = b"".join((m.servo_on.tobytes(), m.state.tobytes(), m.fe_check.tobytes(), m.limit_check.tobytes(),
                        m.trq_active.tobytes(), m.homed.tobytes(), m.din.tobytes(),
                        m.sup_params_version.to_bytes(8, "little")))
        if key != self._key:
            self._compile(key)
        if not self.n_on:
            return
        on = self.on
        b1, b2 = self._b1, self._b2
        # ---- following error (not in torque control: no position loop, Cmd.Pos is the feedback of one period
        # earlier)
        fe = np.subtract(m.cmd_pos, m.act_pos, self._fe)
        np.abs(fe, fe)
        over = np.greater(fe, self.fe_over, b1)
        if count_nonzero(over):
            for i in np.flatnonzero(over):
                m.axes[i].raise_error(E.E_FOLLOWING_ERROR, stop="immediate",
                                      detail=f"following error {fe[i]:g} > {m.fe_over[i]:g}")
        if self.any_fe_warn or E.O_FOLLOWING_ERROR_WARNING in m.obs_set:
            _observe(m, E.O_FOLLOWING_ERROR_WARNING, np.greater(fe, self.fe_warn, b2), on)
        vel = m.cmd_vel
        # ---- limit inputs during motion (homing handles them itself)
        if self.any_limit_on:
            pos_hit = self.pos_limit_on & (vel > 0)
            neg_hit = self.neg_limit_on & (vel < 0)
            for i in np.flatnonzero(pos_hit | neg_hit):
                ax = m.axes[i]
                if ax.state == AxisState.ErrorStop:
                    continue
                code = E.E_POSI_LIMIT_DETECTED if pos_hit[i] else E.E_NEGA_LIMIT_DETECTED
                ax.raise_error(code, stop=ax.limit_input_stop_mode())
        # ---- software limits (Linear Mode, home defined)
        if self.any_sw:
            sw = self.sw & (m.state != AxisState.ErrorStop)  # (an error stop of this period)
            _software_limits(m, sw, m.period_s)
        # ---- Linear Mode: the command position leaves the signed 40-bit pulse range (not in torque control, where
        # overflow is "motion without a target position")
        hi = np.greater(m.cmd_pos, m.lin_max, b1)
        lo = np.less(m.cmd_pos, m.lin_min, b2)
        lo |= hi
        if count_nonzero(lo):  # rare: build the masks only then
            for i in np.flatnonzero(lo & self.ovf_scope):
                m.axes[i].position_overflow(1 if hi[i] else -1)
        # ---- warnings (observations)
        warn = self.warn
        if warn or m.obs_set:
            w = self._w
            for code in (E.O_VELOCITY_WARNING, E.O_ACCELERATION_WARNING, E.O_DECELERATION_WARNING):
                limit = warn.get(code)
                if limit is not None:
                    if code == E.O_VELOCITY_WARNING:
                        values = np.abs(vel, w)
                    elif code == E.O_ACCELERATION_WARNING:
                        values = m.cmd_accdec
                    else:
                        values = np.negative(m.cmd_accdec, w)
                    _observe(m, code, np.greater(values, limit, b2), on)
                elif code in m.obs_set:
                    _observe(m, code, np.zeros(m.n, dtype=bool), on)


def _observe(m: MotionModule, code: int, active: np.ndarray, scope: np.ndarray) -> None:
    """Set the observation where `active`, clear it where it was set by this check and `scope` holds. `m.obs_set`
    holds where each check has set its observation (a code is removed when no axis has it any more), so a period
    without warnings costs one comparison per configured check."""
    flags = m.obs_set.get(code)
    if count_nonzero(active):
        if flags is None:
            flags = m.obs_set[code] = np.zeros(m.n, dtype=bool)
        for i in np.flatnonzero(active):
            m.axes[i].set_observation(code, True)
        flags |= active
    if flags is None:
        return
    gone = flags & ~active & scope
    if count_nonzero(gone):
        for i in np.flatnonzero(gone):
            a = m.axes[i]
            if code in a.observations:
                a.set_observation(code, False)
        flags &= ~gone
        if not count_nonzero(flags):
            del m.obs_set[code]


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
