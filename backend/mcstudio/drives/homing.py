"""Drive-side homing (CiA402 homing mode, 6060h = 6; codesys-lc1200.md §A).

A homing method is a sequence of *phases*; each phase moves at speed 1 (6099h:01, search for switch) or speed 2
(6099h:02, search for zero) in one direction until an edge of one signal — negative limit switch (NLS, 60FDh bit 0),
positive limit switch (PLS, bit 1), home switch (HS, bit 2) or the encoder's index pulse (Z) — and the edge of the
last phase is the home position. Speed changes and reversals ramp with the homing acceleration 609Ah. The switch
state when homing starts selects the branch ("case 1 / case 2" of §A.3/§A.4).

Implemented (§A.4, §A.5; 1–6 are 17–22 with the first index pulse after the switch edge as home, moving on in the
direction of the last phase at speed 2):

| method | start: switch OFF | start: switch ON | home |
|---|---|---|---|
| 17 (NLS) | reverse at speed 1 to NLS ON, forward at speed 2 | forward at speed 2 | NLS OFF edge |
| 18 (PLS) | forward at speed 1 to PLS ON, reverse at speed 2 | reverse at speed 2 | PLS OFF edge |
| 19 (HS) | forward at speed 1 to HS ON, reverse at speed 2 | reverse at speed 2 | HS OFF edge (negative side) |
| 20 (HS) | forward at speed 1 | reverse at speed 2 to HS OFF, forward at speed 2 | HS ON edge (negative side) |
| 21 (HS) | reverse at speed 1 to HS ON, forward at speed 2 | forward at speed 2 | HS OFF edge (positive side) |
| 22 (HS) | reverse at speed 1 | forward at speed 2 to HS OFF, reverse at speed 2 | HS ON edge (positive side) |
| 33 / 34 | reverse / forward at speed 2 | | first Z pulse |
| 35 / 37 | no motion | | the current position |

Edges only count when the drive moves in the phase's direction (the overshoot after a reversal point does not end a
phase), and their position is the exact switch position. Homing fails (statusword bit 13) when a limit switch that
is not the phase's signal turns ON during a search, when a phase takes longer than the drive's homing time-out
(`Cia402Drives.homing_timeout_s`, default 60 s — a switch or Z pulse that is not fitted is never found), or for
the methods not implemented (0, 7–16, 23–32, 36, and the negative manufacturer methods).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from .sensing import (
    DI_HOME_SWITCH,
    DI_NEGATIVE_LIMIT,
    DI_POSITIVE_LIMIT,
    SensorLayout,
    z_edge,
    zone_off_edge,
    zone_on_edge,
)

NLS, PLS, HS, Z = 0, 1, 2, 3
_DI_OF = {NLS: DI_NEGATIVE_LIMIT, PLS: DI_POSITIVE_LIMIT, HS: DI_HOME_SWITCH}

# statusword bits 13/12/10 in homing mode (CiA402)
HM_IDLE = 0x0400  # homing not started or interrupted (target reached)
HM_RUNNING = 0x0000  # homing in progress
HM_ATTAINED_MOVING = 0x1000  # home found, the drive is still stopping
HM_DONE = 0x1400  # homing attained and target reached
HM_ERROR_MOVING = 0x2000  # homing error, velocity ≠ 0
HM_ERROR = 0x2400  # homing error, velocity = 0

IMMEDIATE_METHODS = (35, 37)


@dataclass(frozen=True)
class Phase:
    direction: int  # +1 forward, −1 reverse
    fast: bool  # speed 1 (6099h:01) or speed 2 (6099h:02)
    signal: int  # NLS, PLS, HS or Z
    on: bool  # the OFF→ON edge (True) or the ON→OFF edge; a Z pulse has only one
    home: bool = False  # the edge of this phase is the home position


def _ph(direction: int, fast: bool, signal: int, on: bool, home: bool = False) -> Phase:
    return Phase(direction, fast, signal, on, home)


F, S = True, False
# method → (phases when the method's switch is OFF at the start, phases when it is ON)
_SWITCH_METHODS: dict[int, tuple[int, tuple[Phase, ...], tuple[Phase, ...]]] = {
    17: (NLS, (_ph(-1, F, NLS, True), _ph(+1, S, NLS, False, True)), (_ph(+1, S, NLS, False, True),)),
    18: (PLS, (_ph(+1, F, PLS, True), _ph(-1, S, PLS, False, True)), (_ph(-1, S, PLS, False, True),)),
    19: (HS, (_ph(+1, F, HS, True), _ph(-1, S, HS, False, True)), (_ph(-1, S, HS, False, True),)),
    20: (HS, (_ph(+1, F, HS, True, True),), (_ph(-1, S, HS, False), _ph(+1, S, HS, True, True))),
    21: (HS, (_ph(-1, F, HS, True), _ph(+1, S, HS, False, True)), (_ph(+1, S, HS, False, True),)),
    22: (HS, (_ph(-1, F, HS, True, True),), (_ph(+1, S, HS, False), _ph(-1, S, HS, True, True))),
}


def homing_phases(method: int, digital_inputs: int) -> tuple[Phase, ...] | None:
    """The phases of `method` started with the given 60FDh bits; () for a method without motion, None when the
    method is not implemented."""
    if method in IMMEDIATE_METHODS:
        return ()
    if method in (33, 34):
        return (_ph(-1 if method == 33 else +1, S, Z, True, True),)
    base = method + 16 if 1 <= method <= 6 else method
    if base not in _SWITCH_METHODS:
        return None
    signal, off, on = _SWITCH_METHODS[base]
    phases = on if digital_inputs & _DI_OF[signal] else off
    if base != method:  # with index pulse: the switch edge is followed by the first Z pulse
        last = phases[-1]
        phases = (*phases[:-1], replace(last, home=False), _ph(last.direction, S, Z, True, True))
    return phases


class Homing:
    """Homing state of N drives: per drive the phase list of a running homing and the statusword bits."""

    def __init__(self, n: int) -> None:
        self.n = n
        self.status = np.full(n, HM_IDLE, dtype=np.uint16)  # statusword bits 13/12/10
        self.running = np.zeros(n, dtype=bool)  # searching (phases in progress)
        self.stopping = np.zeros(n, dtype=bool)  # decelerating after the home point, an error or an interruption
        self.final = np.full(n, HM_IDLE, dtype=np.uint16)  # status once stopped
        self.velocity_goal = np.zeros(n)  # [pulse/s] of the current phase
        self.acc = np.zeros(n)  # 609Ah captured at the start
        self.elapsed = np.zeros(n, dtype=np.int64)  # periods in the current phase
        self.phases: list[tuple[Phase, ...]] = [()] * n
        self.phase = np.zeros(n, dtype=np.int64)
        self.speeds = np.zeros((n, 2))  # (speed 1, speed 2) captured at the start
        self.offset = np.zeros(n, dtype=np.int64)  # 607Ch captured at the start
        self._sig = np.zeros(n, dtype=np.int8)
        self._on = np.zeros(n, dtype=bool)
        self._dir = np.zeros(n, dtype=np.int8)

    def start(self, i: int, phases: tuple[Phase, ...], fast: float, slow: float, acc: float, offset: int) -> None:
        self.phases[i] = phases
        self.speeds[i] = (fast, slow)
        self.acc[i] = acc
        self.offset[i] = offset
        self.running[i] = True
        self.stopping[i] = False
        self.status[i] = HM_RUNNING
        self._enter(i, 0)

    def _enter(self, i: int, k: int) -> None:
        ph = self.phases[i][k]
        self.phase[i] = k
        self.elapsed[i] = 0
        self._sig[i] = ph.signal
        self._on[i] = ph.on
        self._dir[i] = ph.direction
        self.velocity_goal[i] = ph.direction * self.speeds[i, 0 if ph.fast else 1]

    def stop(self, i: int, moving_status: int, final: int) -> None:
        """End the search: decelerate with 609Ah; `final` once the drive stands still."""
        self.running[i] = False
        self.stopping[i] = True
        self.velocity_goal[i] = 0.0
        self.status[i] = moving_status
        self.final[i] = final

    def abort(self, idx: np.ndarray | slice) -> None:
        """The drive left homing (disabled, mode changed): interrupted."""
        self.running[idx] = False
        self.stopping[idx] = False
        self.velocity_goal[idx] = 0.0
        self.status[idx] = HM_IDLE

    def detect(self, p0: np.ndarray, p1: np.ndarray, sensors: SensorLayout, timeout_periods: np.ndarray,
               ) -> list[tuple[int, str, float]]:
        """Events of the running drives on their way p0 → p1 [pulse, mechanism frame] this period: (drive, "home",
        position) or (drive, "error", nan). Phases that end before the home point are advanced here."""
        idx = np.flatnonzero(self.running)
        if not idx.size:
            return []
        self.elapsed[idx] += 1
        a, b = p0[idx], p1[idx]
        moving = np.sign(b - a)
        sig = self._sig[idx]
        e = _signal_edges(a, b, sig, self._on[idx], sensors, idx)
        found = ~np.isnan(e) & (moving == self._dir[idx])
        nls = zone_on_edge(a, b, np.full(idx.size, -np.inf), sensors.neg_limit[idx])
        pls = zone_on_edge(a, b, sensors.pos_limit[idx], np.full(idx.size, np.inf))
        hit_limit = (~np.isnan(nls) & (sig != NLS)) | (~np.isnan(pls) & (sig != PLS))
        late = self.elapsed[idx] > timeout_periods[idx]
        events: list[tuple[int, str, float]] = []
        for j in np.flatnonzero(found | hit_limit | late):
            events.append(self._advance(int(idx[j]), float(a[j]), float(b[j]), bool(late[j]), sensors))
        return [ev for ev in events if ev[1] != "phase"]

    def _advance(self, i: int, a: float, b: float, late: bool, sensors: SensorLayout) -> tuple[int, str, float]:
        """Walk drive i's phases along a → b (several edges may fall into one period)."""
        start = a
        ii = np.array([i])
        while True:
            ph = self.phases[i][int(self.phase[i])]
            pa, pb = np.array([start]), np.array([b])
            e = float(_signal_edges(pa, pb, np.array([ph.signal]), np.array([ph.on]), sensors, ii)[0])
            if np.sign(b - start) != ph.direction:
                e = float("nan")
            limits = [float(zone_on_edge(pa, pb, np.array([-np.inf]), sensors.neg_limit[ii])[0])
                      if ph.signal != NLS else float("nan"),
                      float(zone_on_edge(pa, pb, sensors.pos_limit[ii], np.array([np.inf]))[0])
                      if ph.signal != PLS else float("nan")]
            hit = [x for x in limits if not np.isnan(x)]
            if hit and (np.isnan(e) or min(abs(x - start) for x in hit) < abs(e - start)):
                return (i, "error", float("nan"))
            if np.isnan(e):
                return (i, "error", float("nan")) if late else (i, "phase", float("nan"))
            if ph.home:
                return (i, "home", e)
            self._enter(i, int(self.phase[i]) + 1)
            if self._dir[i] != np.sign(b - e):
                return (i, "phase", float("nan"))
            start = e


def _signal_edges(a: np.ndarray, b: np.ndarray, sig: np.ndarray, on: np.ndarray, s: SensorLayout,
                  idx: np.ndarray) -> np.ndarray:
    """Edge of each drive's phase signal on its way a → b (nan: none)."""
    inf = np.full(idx.size, np.inf)
    lo = np.select([sig == NLS, sig == PLS], [-inf, s.pos_limit[idx]], s.prox[idx, 0])
    hi = np.select([sig == NLS, sig == PLS], [s.neg_limit[idx], inf], s.prox[idx, 1])
    e = np.where(on, zone_on_edge(a, b, lo, hi), zone_off_edge(a, b, lo, hi))
    if (sig == Z).any():
        e = np.where(sig == Z, z_edge(a, b, s.z_offset[idx], s.z_period[idx]), e)
    return e
