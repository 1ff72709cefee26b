"""The drive's own trajectory generator (CiA402 profile position/velocity, homing, and the stop ramps of quick stop,
halt and fault reaction), vectorised over the drives that use it in a period.

Each drive has a generator state (position [pulse, mechanism frame], velocity [pulse/s]). A period moves it towards
either a *velocity goal* (PV, homing searches, stop ramps) or a *position goal* (PP), with the acceleration `acc`
while the speed grows and `dec` while it shrinks, the speed limited to `vmax`; positions integrate the velocity by
the trapezoidal rule. Towards a position goal the speed is limited by the discrete braking curve: the velocity u1
towards the goal at the end of the step is at most the largest value from which a stop at the deceleration `dec`
still ends at the goal, ``u1² + dec·T·u1 + dec·T·u0 − 2·dec·|d| ≤ 0`` (d the distance before the step, u0 the
velocity towards the goal): on that curve the deceleration is exactly `dec` and the profile lands on the goal
(``at_goal``) with a final step below dec·T. A goal behind the drive, or too close to stop, is passed with a full
deceleration and approached again from the other side (a reversal).

Accelerations ≤ 0 are taken as unbounded (the velocity changes within one period).
"""

from __future__ import annotations

import numpy as np

_UNBOUNDED = 1e18  # pulse/s²: an acceleration that reaches any velocity within one period


class ProfileGenerator:
    """Per-drive profile state; `step` advances the drives `idx` by one period."""

    def __init__(self, n: int) -> None:
        self.pos = np.zeros(n)
        self.vel = np.zeros(n)
        self.at_goal = np.ones(n, dtype=bool)

    def start(self, idx: np.ndarray | slice, pos: np.ndarray | float, vel: np.ndarray | float) -> None:
        """Start the drives `idx` from position `pos` [pulse] and velocity `vel` [pulse/s] (continuity of the
        demand when a profile or a stop ramp takes over)."""
        self.pos[idx] = pos
        self.vel[idx] = vel
        self.at_goal[idx] = False

    def step(self, idx: np.ndarray, T: float, goal_pos: np.ndarray, goal_vel: np.ndarray, vmax: np.ndarray,
             acc: np.ndarray, dec: np.ndarray) -> None:
        """One period for the drives `idx`. `goal_pos`: position goal, nan where the drive has a velocity goal
        `goal_vel` instead. All arrays are per drive of `idx`."""
        acc = np.where(acc > 0, acc, _UNBOUNDED)
        dec = np.where(dec > 0, dec, _UNBOUNDED)
        p0 = self.pos[idx]
        v0 = self.vel[idx]
        pos_mode = ~np.isnan(goal_pos)
        dist = np.where(pos_mode, goal_pos - p0, 0.0)
        direction = np.sign(dist)
        u0 = v0 * direction
        dT = dec * T
        disc = dT * dT + 8.0 * dec * np.abs(dist) - 4.0 * dT * u0
        u_brake = 0.5 * (np.sqrt(np.maximum(disc, 0.0)) - dT)
        v_des = np.where(pos_mode, direction * np.minimum(vmax, np.maximum(u_brake, 0.0)),
                         np.clip(goal_vel, -vmax, vmax))
        speeding = (v_des * v0 >= 0) & (np.abs(v_des) > np.abs(v0))
        rate = np.where(speeding, acc, dec) * T
        v1 = np.clip(v_des, v0 - rate, v0 + rate)
        p1 = p0 + 0.5 * (v0 + v1) * T
        if pos_mode.any():
            rest = goal_pos - p1
            land = pos_mode & (rest * dist <= 0.0) & (np.abs(v1) <= dT * (1.0 + 1e-9))
            p1 = np.where(land, goal_pos, p1)
            v1 = np.where(land, 0.0, v1)
            self.at_goal[idx] = np.where(pos_mode, land, v1 == v_des)
        else:
            self.at_goal[idx] = v1 == v_des
        self.pos[idx] = p1
        self.vel[idx] = v1
