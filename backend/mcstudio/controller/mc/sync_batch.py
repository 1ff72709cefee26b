"""Periodic cam followers in their steady state, computed together: the fast path of the sync stage.

A follower whose MC_CamIn is InSync on a periodic table, without Direction restriction, phase compensation, offset
instruction or buffered successor, and whose master is not itself a slave, does the same every period: sample the
master, wrap the phase into the table, interpolate, add its reference and offsets. `CamBatch` does that for all of
them with a handful of numpy operations (one `searchsorted` over the flattened tables of `CamTableSet`) instead of a
Python call per follower. Wrapping (once per cycle) and changes of the Index output are handled per follower. The
batch is rebuilt whenever the set of laws or one of those conditions may have changed (`MotionModule.sync_changed`);
its state is written back to the laws before, so the per-law path continues exactly where the batch left off.
`tests/controller/mc/test_sync_batch.py` compares both paths period by period.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ...fastnp import count_nonzero
from .cam.table import CamTableSet
from .sync import REF_FEEDBACK, REF_LATEST, CamLaw

if TYPE_CHECKING:
    from .module import MotionModule
    from .sync import Law


def batchable(law: Law, laws: dict[int, Law]) -> bool:
    """The follower can run in the batch (see the module docstring)."""
    return (isinstance(law, CamLaw) and law.in_sync and law.periodic and law.direction == 4
            and law.phasing is None and law.phase_base == 0.0 and getattr(law, "offset_owner", None) is None
            and law.slave.buffered is None and law.master.i not in laws and len(law.P) > 1 and law.mscale > 0)


class CamBatch:
    def __init__(self, m: MotionModule, laws: list[CamLaw]) -> None:
        self.m = m
        self.laws = laws
        self.slave = np.array([law.slave.i for law in laws], dtype=np.int64)
        master = np.array([law.master.i for law in laws], dtype=np.int64)
        ref = np.array([law.ref for law in laws])
        self.src_feedback = master[ref == REF_FEEDBACK]
        self.src_latest = master[ref == REF_LATEST]
        self.src_command = master[(ref != REF_FEEDBACK) & (ref != REF_LATEST)]
        self.sel_feedback = np.flatnonzero(ref == REF_FEEDBACK)
        self.sel_latest = np.flatnonzero(ref == REF_LATEST)
        self.sel_command = np.flatnonzero((ref != REF_FEEDBACK) & (ref != REF_LATEST))
        tables: list[object] = []
        which: list[int] = []
        for law in laws:
            key = law.table
            if key not in tables:
                tables.append(key)
            which.append(tables.index(key))
        self.set = CamTableSet(tables)  # type: ignore[arg-type]
        self.tbl = np.array(which, dtype=np.int64)
        self.lo = self.set.start[self.tbl]
        self.hi = self.set.end[self.tbl]
        self.p_lo = self.set.P[self.lo]
        self.p_hi = self.set.P[self.hi]
        self.key_off = self.set.offset[self.tbl]
        self.base = np.array([law.base for law in laws])
        self.sref = np.array([law.sref for law in laws])
        self.mscale = np.array([law.mscale for law in laws])
        self.sscale = np.array([law.sscale for law in laws])
        self.add = np.array([law.soffset + law.offset for law in laws])
        self.end = np.array([law.end_phase for law in laws])
        self.index = np.array([law.index for law in laws], dtype=np.int64)
        self.mpos = np.array([law.last_master for law in laws])
        self.master = master
        self.half = self.end / 2.0
        n = len(laws)
        self._phase, self._w, self._pos = np.zeros(n), np.zeros(n), np.zeros(n)
        self._b = np.zeros(n, dtype=bool)
        self._g = np.zeros(n, dtype=np.int64)
        refs = set(ref.tolist())
        self.single_source = None
        if len(refs) == 1:
            r = refs.pop()
            self.single_source = ((lambda mm: mm.act_pos) if r == REF_FEEDBACK else (lambda mm: mm.cmd_pos)
                                  if r == REF_LATEST else (lambda mm: mm.prev_cmd_pos))
        # per table: its phases, distances and slopes (local indices); the flattened set for mixed batches
        cs = self.set
        icpt = cs.D - cs.slope * cs.P
        per_table = []
        for t in range(len(tables)):
            a, b = int(cs.start[t]), int(cs.end[t])
            per_table.append((cs.P[a:b + 1], icpt[a:b + 1], cs.slope[a:b + 1]))
        self.flat = (cs.P, icpt, cs.slope)
        self.c0 = self.sref + self.add
        m.prof_acc[self.slave] = 0.0
        self.one_table = per_table[0] if len(tables) == 1 else None
        self.last_interval = int(cs.end[0] - cs.start[0]) - 1
        self.groups = [(np.flatnonzero(self.tbl == t), per_table[t], int(cs.end[t] - cs.start[t]) - 1)
                       for t in range(len(tables))]

    def step(self, T: float) -> None:
        m = self.m
        mpos = self.mpos
        if self.single_source is not None:
            self.single_source(m).take(self.master, out=mpos)
        else:
            if self.sel_latest.size:
                mpos[self.sel_latest] = m.cmd_pos[self.src_latest]
            if self.sel_command.size:
                mpos[self.sel_command] = m.prev_cmd_pos[self.src_command]
            if self.sel_feedback.size:
                mpos[self.sel_feedback] = m.act_pos[self.src_feedback]
        phase, w = self._phase, self._w
        np.subtract(mpos, self.base, out=phase)
        np.divide(phase, self.mscale, out=phase)
        # outside [0, end): |phase − end/2| > end/2 (exactly at end counts: the next cycle starts there)
        np.subtract(phase, self.half, out=w)
        np.abs(w, out=w)
        if count_nonzero(np.greater_equal(w, self.half, out=self._b)):
            for k in np.flatnonzero(self._b).tolist():
                if not 0.0 <= phase[k] < self.end[k]:
                    self._wrap(k, phase)
        # phase is in [0, end) now: no clipping; each table is searched on its own phases (exact bisection)
        g = self._g
        if self.one_table is not None:
            P, icpt, slope = self.one_table
            g[:] = P.searchsorted(phase, side="right")
            g -= 1
            np.minimum(g, self.last_interval, out=g)
            np.maximum(g, 0, out=g)
        else:
            for sel, (Pt, _Dt, _st), last in self.groups:
                gi = Pt.searchsorted(phase[sel], side="right") - 1
                np.clip(gi, 0, last, out=gi)
                g[sel] = gi
            P, icpt, slope = self.flat
            g += self.lo  # local → flattened (groups use local indices)
        # distance = intercept + slope · phase of the interval (intercept = D − slope · P, precomputed)
        slope.take(g, out=w)
        w *= phase
        w += icpt.take(g)
        if self.one_table is None:
            g -= self.lo
        pos = self._pos
        np.multiply(self.sscale, w, out=pos)
        pos += self.c0  # reference + SlaveOffset + offset
        s = self.slave
        old = m.cmd_pos.take(s)
        np.subtract(pos, old, out=old)
        old /= T
        m.prof_vel[s] = old  # (prof_acc of the followers is 0 from the start of the batch)
        m.cmd_pos[s] = pos
        if count_nonzero(np.not_equal(g, self.index, out=self._b)):
            for k in np.flatnonzero(self._b).tolist():
                self.index[k] = g[k]
                law = self.laws[k]
                law.index = int(g[k])
                self._push(law)

    def _wrap(self, k: int, phase: np.ndarray) -> None:
        """A follower passed the end (or the start) of its table: next (previous) cycle, EndOfProfile."""
        law = self.laws[k]
        end = float(self.end[k])
        ms = float(self.mscale[k])
        step = float(self.sscale[k]) * law.end_distance
        p = float(phase[k])
        eop = False
        while p >= end:
            self.base[k] += end * ms
            self.sref[k] += step
            self.c0[k] += step
            p -= end
            eop = True
        while p < 0.0:
            self.base[k] -= end * ms
            self.sref[k] -= step
            self.c0[k] -= step
            p += end
        phase[k] = p
        if eop:
            law.eop_cycle = self.m.cycle
            self._push(law)

    def _push(self, law: CamLaw) -> None:
        self.m.push_law_outputs(law.job, pulse=law.eop_cycle == self.m.cycle)

    def write_back(self) -> None:
        """Hand the state to the laws (before the batch is rebuilt or a law leaves it)."""
        for k, law in enumerate(self.laws):
            law.base = float(self.base[k])
            law.sref = float(self.sref[k])
            law.index = int(self.index[k])
            law.last_master = float(self.mpos[k])
