"""Sensors on the mechanism and the latch function, vectorised over drives (CiA402 60FDh, 60B8h–60BDh).

Sensor positions are in motor pulses of the mechanism's frame (`SensorLayout`, nan/±inf when not fitted). A zone
[lo, hi] is ON while lo ≤ p ≤ hi: the negative limit switch is the zone (−inf, neg_limit], the positive limit switch
[pos_limit, +inf), the home proximity switch, EXT1 and EXT2 are finite zones, and the encoder's Z phase is a pulse
of zero width at z_offset + k·z_period.

Edges are found exactly on the path p0 → p1 a drive moved in one period (not by sampling), so a latch holds the
switch position itself whatever the speed.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..fastnp import count_nonzero

# 60FDh digital inputs: CiA402 bits 0–2; vendor bits for the external latch inputs (MC Studio layout)
DI_NEGATIVE_LIMIT = 1 << 0
DI_POSITIVE_LIMIT = 1 << 1
DI_HOME_SWITCH = 1 << 2
DI_EXT1 = 1 << 16
DI_EXT2 = 1 << 17

# 60B8h touch probe function (CiA402)
TP1_ENABLE = 0x0001
TP1_CONTINUOUS = 0x0002
TP1_SOURCE_Z = 0x0004  # bits 2–3 = 01: zero impulse of the encoder; 00: touch probe input 1 (EXT1)
TP1_POS_EDGE = 0x0010
TP1_NEG_EDGE = 0x0020
TP2_ENABLE = 0x0100
TP2_CONTINUOUS = 0x0200
TP2_SOURCE_Z = 0x0400  # bits 10–11 = 01: zero impulse; 00: touch probe input 2 (EXT2)
TP2_POS_EDGE = 0x1000
TP2_NEG_EDGE = 0x2000
# 60B9h touch probe status (CiA402)
TS1_ENABLED = 0x0001
TS1_STORED = 0x0002  # positive edge position stored (60BAh)
TS1_NEG_STORED = 0x0004  # negative edge position stored (60BBh)
TS2_ENABLED = 0x0100
TS2_STORED = 0x0200  # 60BCh
TS2_NEG_STORED = 0x0400  # 60BDh
_TP_ENABLES = TP1_ENABLE | TP2_ENABLE


@dataclass
class SensorLayout:
    """Sensor positions of the mechanism behind each drive, in motor pulses (nan/inf when not fitted)."""

    n: int
    pos_limit: np.ndarray = field(init=False)
    neg_limit: np.ndarray = field(init=False)
    prox: np.ndarray = field(init=False)  # (n, 2) zone
    ext1: np.ndarray = field(init=False)
    ext2: np.ndarray = field(init=False)
    z_offset: np.ndarray = field(init=False)
    z_period: np.ndarray = field(init=False)

    def __post_init__(self) -> None:
        n = self.n
        self.pos_limit = np.full(n, np.inf)
        self.neg_limit = np.full(n, -np.inf)
        self.prox = np.full((n, 2), np.nan)
        self.ext1 = np.full((n, 2), np.nan)
        self.ext2 = np.full((n, 2), np.nan)
        self.z_offset = np.zeros(n)
        self.z_period = np.full(n, np.inf)

    def limit_zone(self, negative: bool, idx: np.ndarray | slice = slice(None)) -> tuple[np.ndarray, np.ndarray]:
        """(lo, hi) of a limit switch as a zone."""
        if negative:
            lim = self.neg_limit[idx]
            return np.full(lim.shape, -np.inf), lim
        lim = self.pos_limit[idx]
        return lim, np.full(lim.shape, np.inf)


def in_zone(p: np.ndarray, zone: np.ndarray) -> np.ndarray:
    return (p >= zone[:, 0]) & (p <= zone[:, 1])


class DigitalInputs:
    """60FDh of N devices from their positions, computing only the sensors that are fitted somewhere.

    Every input is constant on the open intervals between consecutive sensor edges, so each device keeps the interval
    its position is in (`lo` < p < `hi`) with the inputs there; a period recomputes only the devices that left their
    interval (`changed` tells whether any input changed). Which sensors are fitted is taken from the layout when this
    object is made; call `refresh` after changing the layout's values in place (assigning a new layout to a drive's
    `sensors` does it)."""

    def __init__(self, sensors: SensorLayout) -> None:
        self.sensors = sensors
        self.refresh()

    def refresh(self) -> None:
        s = self.sensors
        self._pos = bool(np.isfinite(s.pos_limit).any())
        self._neg = bool(np.isfinite(s.neg_limit).any())
        self._zones = [(np.ascontiguousarray(z[:, 0]), np.ascontiguousarray(z[:, 1]), np.uint32(bit))
                       for z, bit in ((s.prox, DI_HOME_SWITCH), (s.ext1, DI_EXT1), (s.ext2, DI_EXT2))
                       if bool((~np.isnan(z[:, 0]) & ~np.isnan(z[:, 1])).any())]
        self.fitted = self._pos or self._neg or bool(self._zones)
        # every edge of every device (n, 8); nan where a sensor is not fitted
        edges = np.column_stack([s.pos_limit, s.neg_limit, s.prox, s.ext1, s.ext2]).astype(float)
        edges[~np.isfinite(edges)] = np.nan
        self._edges = edges
        n = s.n
        self._lo = np.full(n, np.nan)  # the interval each device is in (nan: unknown → computed at the next call)
        self._hi = np.full(n, np.nan)
        self._di = np.zeros(n, dtype=np.uint32)
        self._out = np.zeros(n, dtype=bool)
        self._w = np.zeros(n, dtype=bool)
        self.changed = True

    def _compute(self, p: np.ndarray) -> np.ndarray:
        s = self.sensors
        di = np.zeros(p.shape, dtype=np.uint32)
        if self._pos:
            di |= (p >= s.pos_limit).view(np.uint8) << np.uint8(1)
        if self._neg:
            di |= (p <= s.neg_limit).view(np.uint8)
        for lo, hi, bit in self._zones:
            di |= ((p >= lo) & (p <= hi)) * bit
        return di

    def __call__(self, p: np.ndarray) -> np.ndarray:
        """60FDh bits for the positions `p` [pulse] (an array this object owns: copy it to keep it)."""
        # outside its interval (or unknown: the comparisons with nan are False)
        out = np.greater(p, self._lo, self._out)
        out &= np.less(p, self._hi, self._w)
        np.logical_not(out, out)
        if not count_nonzero(out):
            self.changed = False
            return self._di
        k = np.flatnonzero(out)
        pk = p[k]
        new = self._compute(p)[k]  # (all rows: cheaper than indexing every layout array)
        self.changed = bool((new != self._di[k]).any())
        self._di[k] = new
        e = self._edges[k]
        with np.errstate(invalid="ignore"):
            lo = np.where(e <= pk[:, None], e, -np.inf).max(axis=1)
            hi = np.where(e > pk[:, None], e, np.inf).min(axis=1)
        on_edge = lo == pk  # exactly on an edge: no open interval, recompute next time
        lo[on_edge] = hi[on_edge] = np.nan
        self._lo[k] = lo
        self._hi[k] = hi
        return self._di


def digital_inputs(p: np.ndarray, s: SensorLayout) -> np.ndarray:
    """60FDh from the positions `p` [pulse] of the mechanisms (all sensors, no plan)."""
    di = np.where(p >= s.pos_limit, DI_POSITIVE_LIMIT, 0) | np.where(p <= s.neg_limit, DI_NEGATIVE_LIMIT, 0)
    di |= np.where(in_zone(p, s.prox), DI_HOME_SWITCH, 0)
    di |= np.where(in_zone(p, s.ext1), DI_EXT1, 0) | np.where(in_zone(p, s.ext2), DI_EXT2, 0)
    return di.astype(np.uint32)


def zone_on_edge(p0: np.ndarray, p1: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """Position of the OFF→ON edge of the zone [lo, hi] on the way p0 → p1 (nan: none). A zone the drive starts in
    has no ON edge in this period."""
    with np.errstate(invalid="ignore"):
        up = (p1 > p0) & (p0 < lo) & (lo <= p1)
        down = (p1 < p0) & (p0 > hi) & (hi >= p1)
    return np.where(up, lo, np.where(down, hi, np.nan))


def zone_off_edge(p0: np.ndarray, p1: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """Position of the ON→OFF edge of the zone [lo, hi] on the way p0 → p1 (nan: none); a zone crossed completely
    in one period has both edges."""
    with np.errstate(invalid="ignore"):
        ok = lo <= hi
        up = ok & (p1 > p0) & (p0 <= hi) & (hi < p1)
        down = ok & (p1 < p0) & (p1 < lo) & (lo <= p0)
    return np.where(up, hi, np.where(down, lo, np.nan))


def z_edge(p0: np.ndarray, p1: np.ndarray, offset: np.ndarray, period: np.ndarray) -> np.ndarray:
    """Position of the first Z (index) pulse strictly after p0 on the way to p1 (nan: none)."""
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        rel = (p0 - offset) / period
        up = p1 > p0
        k = np.where(up, np.floor(rel) + 1.0, np.ceil(rel) - 1.0)
        z = offset + k * period
        hit = np.isfinite(period) & np.where(up, z <= p1, (z >= p1) & (p1 < p0))
    return np.where(hit, z, np.nan)


class TouchProbes:
    """Touch probes 1 and 2 of N devices (60B8h function → 60B9h status, 60BAh/60BBh, 60BCh/60BDh positions).

    Per probe: bit 0 (8) enable; bit 1 (9) continuous (else first event: an edge is stored once until re-armed);
    bit 2 (10) source Z pulse (else the touch probe input: EXT1 for probe 1, EXT2 for probe 2); bit 4 (12) latch the
    positive edge; bit 5 (13) latch the negative edge. Enabling a probe or an edge (its bit rising) re-arms it and
    clears its stored bit; disabling the probe clears its status. The Z pulse has zero width: its negative edge is
    at the same position as its positive edge. Latched positions are reported as the position of the edge plus
    `shift` (the device's home shift, 6064h = mechanism position + shift).
    """

    def __init__(self, n: int) -> None:
        self.n = n
        self.status = np.zeros(n, dtype=np.uint16)
        self.pos1 = np.zeros(n, dtype=np.int64)
        self.neg1 = np.zeros(n, dtype=np.int64)
        self.pos2 = np.zeros(n, dtype=np.int64)
        self.neg2 = np.zeros(n, dtype=np.int64)
        self._prev_fn = np.zeros(n, dtype=np.uint16)

    def update(self, p0: np.ndarray, p1: np.ndarray, fn: np.ndarray, sensors: SensorLayout,
               shift: np.ndarray | None = None) -> None:
        """One period: the devices moved p0 → p1 [pulse] with the function words `fn` (60B8h) of this period."""
        active = (fn | self._prev_fn) & _TP_ENABLES
        if not active.any():
            self._prev_fn[:] = fn
            return
        idx = np.flatnonzero(active)
        f = fn[idx].astype(np.int64)
        prev = self._prev_fn[idx].astype(np.int64)
        st = self.status[idx].astype(np.int64)
        a, b = p0[idx], p1[idx]
        sh = shift[idx] if shift is not None else None
        s = sensors
        for probe, zone, store_pos, store_neg in ((0, s.ext1, self.pos1, self.neg1),
                                                  (8, s.ext2, self.pos2, self.neg2)):
            en, cont, src_z = TP1_ENABLE << probe, TP1_CONTINUOUS << probe, TP1_SOURCE_Z << probe
            pos_en, neg_en = TP1_POS_EDGE << probe, TP1_NEG_EDGE << probe
            ts_en, ts_pos, ts_neg = TS1_ENABLED << probe, TS1_STORED << probe, TS1_NEG_STORED << probe
            on = (f & en) != 0
            armed_now = on & ((prev & en) == 0)
            st = np.where(on, st | ts_en, st & ~(ts_en | ts_pos | ts_neg))
            st = np.where(armed_now | (((f & pos_en) != 0) & ((prev & pos_en) == 0)), st & ~ts_pos, st)
            st = np.where(armed_now | (((f & neg_en) != 0) & ((prev & neg_en) == 0)), st & ~ts_neg, st)
            moved = on & (a != b)
            if not moved.any():
                continue
            z = (f & src_z) != 0
            zpos = z_edge(a, b, s.z_offset[idx], s.z_period[idx]) if z.any() else None
            lo, hi = zone[idx, 0], zone[idx, 1]
            for edge_en, ts_bit, store, edge_fn in ((pos_en, ts_pos, store_pos, zone_on_edge),
                                                    (neg_en, ts_neg, store_neg, zone_off_edge)):
                want = moved & ((f & edge_en) != 0) & (((st & ts_bit) == 0) | ((f & cont) != 0))
                if not want.any():
                    continue
                e = edge_fn(a, b, lo, hi)
                if zpos is not None:
                    e = np.where(z, zpos, e)
                hit = want & ~np.isnan(e)
                if hit.any():
                    k = np.flatnonzero(hit)
                    latched = np.rint(e[k]).astype(np.int64)
                    if sh is not None:
                        latched += sh[k]
                    store[idx[k]] = latched
                    st[k] |= ts_bit
        self.status[idx] = st.astype(np.uint16)
        self._prev_fn[:] = fn
