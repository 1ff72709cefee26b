"""Motion profiles: planned once with ruckig, evaluated every period as piecewise constant-jerk segments.

A move is planned when it starts or changes (re-execution, override, blending), never per period. ruckig's result is
converted into a small table of segments `(t_start, p0, v0, a0, j)`; the last segment is an open-ended tail at the
final velocity, so a velocity move keeps going and a position move holds its target. Evaluating the table is plain
polynomial arithmetic, which `ProfileTable.evaluate` does for all axes at once with numpy.

Conventions (architecture.md "Profile generation"): Jerk = 0 is the manual's trapezoid (ruckig with infinite jerk);
Acceleration or Deceleration = 0 is the manual's step change, realised as reaching the new velocity within one period.
Tolerances: a finished position profile ends exactly on its target (the tail holds the commanded target, not a
polynomial value); inputs are sanitised so that residual velocities below 1e-9 unit/s count as zero.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from ruckig import ControlInterface, InputParameter, Result, Ruckig, RuckigError, Trajectory

from ...fastnp import count_nonzero

MAX_SEGMENTS = 24  # brake (2) + 7 per ruckig stage, two stages for a reversal, plus the tail
_TINY = 1e-9


class PlanningError(Exception):
    """ruckig refused the inputs; `result` is its Result value."""

    def __init__(self, result: Result, detail: str) -> None:
        super().__init__(f"profile planning failed ({result.name}): {detail}")
        self.result = result


@dataclass(slots=True)
class Segments:
    """Piecewise constant-jerk description of a profile, relative to its own start (t = 0)."""

    t: list[float]  # start time of each segment
    p: list[float]
    v: list[float]
    a: list[float]
    j: list[float]
    duration: float  # time at which the tail (constant velocity, a = 0) begins
    end_position: float
    end_velocity: float
    overshoot: bool = False  # a position profile passes its target before arriving (the deceleration is too low)

    def sample(self, t: float) -> tuple[float, float, float]:
        """Scalar evaluation (for tests and planning); the kernel uses ProfileTable.evaluate."""
        k = max(i for i, ts in enumerate(self.t) if t >= ts) if t >= 0 else 0
        tau = t - self.t[k]
        j, a, v = self.j[k], self.a[k], self.v[k]
        return (
            self.p[k] + tau * (v + tau * (a / 2 + tau * j / 6)),
            v + tau * (a + tau * j / 2),
            a + tau * j,
        )


def _clean(x: float) -> float:
    return 0.0 if abs(x) < _TINY else x


class Planner:
    """Plans single-axis moves with ruckig. One instance per controller; not thread-safe (kernel thread only)."""

    def __init__(self, period_s: float) -> None:
        self.period_s = period_s
        self._otg = Ruckig(1)
        self._inp = InputParameter(1)
        self._traj = Trajectory(1)

    def _step_limit(self, speed: float) -> float:
        # The manual's "0 = step change": reach the new velocity within one period.
        return max(abs(speed), 1.0) / self.period_s

    def _run(self, *, p0: float, v0: float, a0: float, target_p: float | None, target_v: float,
             vmax: float, acc: float, dec: float, jerk: float, forward: bool, v_end: float = 0.0) -> Segments:
        inp = self._inp
        inp.current_position = [p0]
        inp.current_velocity = [v0]
        inp.current_acceleration = [a0]
        # ruckig bounds the signed acceleration; map Omron's acceleration/deceleration to the bounds in the direction
        # of travel: moving forward, speeding up is +a (Acceleration), slowing down is −a (Deceleration).
        up, down = (acc, dec) if forward else (dec, acc)
        inp.max_acceleration = [up]
        inp.min_acceleration = [-down]
        inp.max_jerk = [jerk if jerk > 0 else math.inf]
        if target_p is None:
            inp.control_interface = ControlInterface.Velocity
            inp.target_position = [p0]
            inp.target_velocity = [target_v]
            inp.target_acceleration = [0.0]
            inp.max_velocity = [max(abs(target_v), abs(v0), 1.0)]
        else:
            inp.control_interface = ControlInterface.Position
            inp.target_position = [target_p]
            inp.target_velocity = [v_end]
            inp.target_acceleration = [0.0]
            inp.max_velocity = [max(vmax, abs(v_end), abs(v0) if abs(v0) > vmax else 0.0, 1e-9)]
        try:
            result = self._otg.calculate(inp, self._traj)
        except RuckigError as err:  # ruckig raises (instead of returning an error) for some inputs it cannot plan,
            # e.g. Acceleration 1e-12 to 100 units/s (a 10^14 s ramp): a PlanningError like the others (D15, D124)
            raise PlanningError(Result.Error, f"p0={p0} v0={v0} a0={a0} target={target_p} v={target_v} vmax={vmax} "
                                f"acc={acc} dec={dec}: {str(err).splitlines()[0]}") from None
        if result not in (Result.Working, Result.Finished):
            raise PlanningError(result, f"p0={p0} v0={v0} a0={a0} target={target_p} v={target_v} vmax={vmax}")
        seg = _segments_from_trajectory(self._traj, target_p=target_p)
        if target_p is not None:
            ext = self._traj.position_extrema[0]
            tol = 1e-9 * max(1.0, abs(target_p))
            seg.overshoot = (forward and ext.max > target_p + tol) or (not forward and ext.min < target_p - tol)
        return seg

    def position(self, *, p0: float, v0: float, a0: float, target: float, velocity: float,
                 acceleration: float, deceleration: float, jerk: float, v_end: float = 0.0,
                 v_start: float = 0.0, reverse_immediate: bool = False) -> Segments:
        """Point-to-point move to `target`, arriving with `v_end` (a blending transit velocity, else 0).

        If the axis moves away from the target it first stops — decelerating, or at once with `reverse_immediate`
        (Operation Selection at Reversing) — then moves. `v_start` is the axis Start Velocity: from standstill the
        velocity steps to it and the profile ends at it before stepping to 0.
        """
        v0, a0 = _clean(v0), _clean(a0)
        vmax = abs(velocity)
        acc = acceleration if acceleration > 0 else self._step_limit(vmax)
        dec = deceleration if deceleration > 0 else self._step_limit(max(vmax, abs(v0), abs(v_end)))
        forward = target >= p0
        moving_away = (v0 > 0 and not forward) or (v0 < 0 and forward)
        if moving_away:
            if reverse_immediate:
                stop = hold(p0)
            else:
                stop = self._run(p0=p0, v0=v0, a0=a0, target_p=None, target_v=0.0, vmax=vmax,
                                 acc=acc, dec=dec, jerk=jerk, forward=v0 > 0)
            rest = self.position(p0=stop.end_position, v0=0.0, a0=0.0, target=target, velocity=velocity,
                                 acceleration=acceleration, deceleration=deceleration, jerk=jerk, v_end=v_end,
                                 v_start=v_start)
            return concat(stop, rest)
        sign = 1.0 if forward else -1.0
        if v0 == 0 and a0 == 0 and 0 < v_start < vmax and target != p0:
            v0 = sign * v_start  # Start Velocity: the velocity steps up at the start …
            if v_end == 0:
                v_end = sign * v_start  # … and steps down to 0 at the target
        return self._run(p0=p0, v0=v0, a0=a0, target_p=target, target_v=0.0, vmax=vmax,
                         acc=acc, dec=dec, jerk=jerk, forward=forward, v_end=v_end)

    def velocity(self, *, p0: float, v0: float, a0: float, target_velocity: float,
                 acceleration: float, deceleration: float, jerk: float) -> Segments:
        """Reach `target_velocity` (signed) and keep it. A sign change decelerates to 0 with Deceleration first."""
        v0, a0 = _clean(v0), _clean(a0)
        acc = acceleration if acceleration > 0 else self._step_limit(target_velocity)
        dec = deceleration if deceleration > 0 else self._step_limit(max(abs(v0), abs(target_velocity)))
        if v0 * target_velocity < 0:
            stop = self._run(p0=p0, v0=v0, a0=a0, target_p=None, target_v=0.0, vmax=abs(v0),
                             acc=acc, dec=dec, jerk=jerk, forward=v0 > 0)
            rest = self._run(p0=stop.end_position, v0=0.0, a0=0.0, target_p=None, target_v=target_velocity,
                             vmax=abs(target_velocity), acc=acc, dec=dec, jerk=jerk, forward=target_velocity > 0)
            return concat(stop, rest)
        forward = target_velocity > 0 or (target_velocity == 0 and v0 > 0)
        return self._run(p0=p0, v0=v0, a0=a0, target_p=None, target_v=target_velocity, vmax=abs(target_velocity),
                         acc=acc, dec=dec, jerk=jerk, forward=forward)

    def stop(self, *, p0: float, v0: float, a0: float, deceleration: float, jerk: float) -> Segments:
        """Decelerate to standstill (MC_Stop); Deceleration = 0 stops immediately."""
        v0, a0 = _clean(v0), _clean(a0)
        if deceleration <= 0 or (v0 == 0 and a0 == 0):
            return hold(p0)
        return self._run(p0=p0, v0=v0, a0=a0, target_p=None, target_v=0.0, vmax=abs(v0),
                         acc=deceleration, dec=deceleration, jerk=jerk, forward=v0 > 0)


    def timed(self, *, p0: float, v0: float, target: float, v_end: float, velocity: float, acceleration: float,
              deceleration: float, duration: float) -> Segments | None:
        """A move from (p0, v0) that arrives at `target` with `v_end` after exactly `duration` seconds, within
        |v| ≤ velocity and the acceleration/deceleration limits (MC_GearInPos catch-up); None when no such profile
        exists (too short a time for the limits, or the limits cannot fill it)."""
        if duration <= 0:
            return None
        inp = self._inp
        acc = acceleration if acceleration > 0 else self._step_limit(velocity)
        dec = deceleration if deceleration > 0 else self._step_limit(velocity)
        inp.control_interface = ControlInterface.Position
        inp.current_position = [p0]
        inp.current_velocity = [_clean(v0)]
        inp.current_acceleration = [0.0]
        inp.target_position = [target]
        inp.target_velocity = [v_end]
        inp.target_acceleration = [0.0]
        vmax = max(abs(velocity), abs(v0), abs(v_end))
        inp.max_velocity = [vmax]
        inp.max_acceleration = [max(acc, dec)]
        inp.min_acceleration = [-max(acc, dec)]
        inp.max_jerk = [math.inf]
        inp.minimum_duration = duration
        try:
            result = self._otg.calculate(inp, self._traj)
        finally:
            inp.minimum_duration = None
        if result not in (Result.Working, Result.Finished):
            return None
        if abs(self._traj.duration - duration) > max(1e-9, 1e-6 * duration):
            return None  # the limits do not allow arriving in time
        return _segments_from_trajectory(self._traj, target_p=target)


def hold(position: float) -> Segments:
    return Segments([0.0], [position], [0.0], [0.0], [0.0], 0.0, position, 0.0)


def _segments_from_trajectory(traj: Trajectory, *, target_p: float | None) -> Segments:
    prof = traj.profiles[0][0]
    ts: list[float] = []
    ps: list[float] = []
    vs: list[float] = []
    as_: list[float] = []
    js: list[float] = []
    t = 0.0
    brake = prof.brake
    if brake.duration > 0:
        for k in range(2):
            if brake.t[k] > 0:
                ts.append(t)
                ps.append(brake.p[k])
                vs.append(brake.v[k])
                as_.append(brake.a[k])
                js.append(brake.j[k])
                t += brake.t[k]
    for k in range(7):
        if prof.t[k] > 0:
            ts.append(t)
            ps.append(prof.p[k])
            vs.append(prof.v[k])
            as_.append(prof.a[k])
            js.append(prof.j[k])
            t += prof.t[k]
    duration = traj.duration
    end_p = prof.p[7] if target_p is None else target_p
    end_v = prof.v[7]
    end_v = 0.0 if abs(end_v) < _TINY else end_v
    # tail: hold the final velocity for ever (exact target for position moves; a position move that ends with a
    # non-zero velocity — a blend or Start Velocity — is ended by the MC module at that moment)
    if target_p is not None and end_v != 0.0:
        end_v = 0.0
    ts.append(duration)
    ps.append(end_p)
    vs.append(end_v)
    as_.append(0.0)
    js.append(0.0)
    return Segments(ts, ps, vs, as_, js, duration, end_p, end_v)


def concat(first: Segments, second: Segments) -> Segments:
    """`second` starts when `first` reaches its tail."""
    off = first.duration
    n = len(first.t) - 1  # drop first's tail
    return Segments(
        first.t[:n] + [off + t for t in second.t],
        first.p[:n] + second.p,
        first.v[:n] + second.v,
        first.a[:n] + second.a,
        first.j[:n] + second.j,
        off + second.duration,
        second.end_position,
        second.end_velocity,
    )


class ProfileTable:
    """Segment tables of all axes in arrays of shape (n_axes, MAX_SEGMENTS), evaluated together each period.

    The segment an axis is in is cached with its polynomial coefficients in 1-D arrays (`c_*`), so a period costs a
    dozen vector operations over all axes; the table is searched only for the axes that crossed a segment start
    (`next_t`) in that period.
    """

    def __init__(self, n: int) -> None:
        self.n = n
        self.t = np.full((n, MAX_SEGMENTS), np.inf)
        self.p = np.zeros((n, MAX_SEGMENTS))
        self.v = np.zeros((n, MAX_SEGMENTS))
        self.a = np.zeros((n, MAX_SEGMENTS))
        self.j = np.zeros((n, MAX_SEGMENTS))
        self.duration = np.zeros(n)
        self.start_cycle = np.zeros(n, dtype=np.int64)
        self.active = np.zeros(n, dtype=bool)
        self.n_active = 0  # count of `active` (kept with it: no reduction per period)
        # the current segment of each axis: start time, coefficients p + τ(v + τ(a/2 + τ·j/6)), next start
        self.seg = np.zeros(n, dtype=np.intp)
        self.c_t0 = np.zeros(n)
        self.c_p = np.zeros(n)
        self.c_v = np.zeros(n)
        self.c_a = np.zeros(n)
        self.c_j = np.zeros(n)
        self.c_a2 = np.zeros(n)
        self.c_j2 = np.zeros(n)
        self.c_j6 = np.zeros(n)
        self.next_t = np.full(n, np.inf)
        # work arrays of `evaluate` (no allocation per period)
        self._k = np.zeros(n, dtype=np.int64)
        self._t = np.zeros(n)
        self._tau = np.zeros(n)
        self._w = np.zeros(n)
        self.pos = np.zeros(n)
        self.vel = np.zeros(n)
        self.acc = np.zeros(n)
        self.finished = np.zeros(n, dtype=bool)
        self._cross = np.zeros(n, dtype=bool)
        self._c1 = np.array(0, dtype=np.int64)
        self._T = np.array(0.0)

    def load(self, i: int, seg: Segments, start_cycle: int) -> None:
        m = len(seg.t)
        if m > MAX_SEGMENTS:
            raise PlanningError(Result.Error, f"profile has {m} segments (max {MAX_SEGMENTS})")
        self.t[i, :m] = seg.t
        self.t[i, m:] = np.inf
        self.p[i, :m] = seg.p
        self.v[i, :m] = seg.v
        self.a[i, :m] = seg.a
        self.j[i, :m] = seg.j
        self.duration[i] = seg.duration
        self.start_cycle[i] = start_cycle
        if not self.active[i]:
            self.active[i] = True
            self.n_active += 1
        self._enter(i, 0)

    def _enter(self, i: int, k: int) -> None:
        """Axis i is in segment k."""
        self.seg[i] = k
        self.c_t0[i] = self.t[i, k]
        self.c_p[i] = self.p[i, k]
        self.c_v[i] = self.v[i, k]
        self.c_a[i] = a = self.a[i, k]
        self.c_j[i] = j = self.j[i, k]
        self.c_a2[i] = a * 0.5
        self.c_j2[i] = j * 0.5
        self.c_j6[i] = j * (1.0 / 6.0)
        self.next_t[i] = self.t[i, k + 1] if k + 1 < MAX_SEGMENTS else np.inf

    def shift(self, i: int, delta: float) -> None:
        """Move axis i's profile by `delta` (a coordinate system shift)."""
        self.p[i] += delta
        self.c_p[i] += delta

    def clear(self, i: int) -> None:
        if self.active[i]:
            self.active[i] = False
            self.n_active -= 1

    def evaluate(self, cycle: int, period_s: float, out: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None
                 ) -> tuple[np.ndarray, ...]:
        """Position, velocity, acceleration and 'finished' flags of every axis at the end of `cycle` (meaningful
        where `active`; the arrays are reused by the next call, or are `out` when given).

        A profile loaded at cycle c0 has advanced one period at the end of c0 (the instruction's first command value
        appears in the period in which it was accepted; its Active output follows one period later).
        """
        k, t, tau, w = self._k, self._t, self._tau, self._w
        c1, T = self._c1, self._T
        c1[()] = cycle + 1  # (0-d arrays: a Python scalar operand costs numpy several times more)
        if T[()] != period_s:
            T[()] = period_s
        np.subtract(c1, self.start_cycle, k)
        np.multiply(k, T, t)
        cross = np.greater_equal(t, self.next_t, self._cross)
        if count_nonzero(cross):
            for i in np.flatnonzero(cross):
                self._enter(i, max(int(np.searchsorted(self.t[i], t[i], side="right")) - 1, 0))
        np.subtract(t, self.c_t0, tau)
        # position p + τ(v + τ(a/2 + τ·j/6)), velocity v + τ(a + τ·j/2), acceleration a + τ·j
        pos, vel, acc = out if out is not None else (self.pos, self.vel, self.acc)
        np.multiply(tau, self.c_j6, w)
        w += self.c_a2
        w *= tau
        w += self.c_v
        w *= tau
        np.add(w, self.c_p, pos)
        np.multiply(tau, self.c_j2, w)
        w += self.c_a
        w *= tau
        np.add(w, self.c_v, vel)
        np.multiply(tau, self.c_j, acc)
        acc += self.c_a
        np.greater_equal(t, self.duration, self.finished)
        return pos, vel, acc, self.finished
