"""Data trace: variables sampled at the end of control periods into preallocated rings, with a trigger.

Like Sysmac Studio's data trace (or TwinCAT Scope, the CODESYS trace): a trace records up to 32 variables — axis and
axes-group variables, outputs of FB instances, PDO entries of slaves — every N primary periods, at the end of the
period (after the outputs stage, step 6 of architecture.md), stamped with the period's cycle number; time is always
`cycle × period`. A trigger on one variable (edge or level against a value) starts the record; a share of the samples
is kept from before it. Modes: `single` (one record), `continuous` (a ring of the last N samples until stopped),
`repeat` (re-armed after every record; the last complete record is readable while the next one fills).

Cost per sampled period: each variable is compiled once into an accessor — an element of a numpy array of the MC
module or the process image (most variables), or a small Python read (FB outputs, group variables). Array accessors
are grouped by source array so that all variables of one array are copied by one fancy-indexed assignment into a
staging row; the row then goes into the ring with one row copy. Nothing is allocated per period except the small
temporaries of those gathers. The rings are allocated when a trace is configured, within a memory budget.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from ..project.trace_models import MAX_TRACES, TraceSettings, TraceVariable
from .mc.enums import AxisState
from .mc.group import GroupState
from .mc.module import DRV_BITS

if TYPE_CHECKING:
    from .kernel import Controller

MEMORY_BUDGET_BYTES = 256 * 1024 * 1024  # all rings of all traces of one controller together
NUMERIC_TYPES = frozenset(("BOOL", "SINT", "INT", "DINT", "LINT", "USINT", "UINT", "UDINT", "ULINT", "BYTE", "WORD",
                           "DWORD", "LWORD", "REAL", "LREAL"))


class TraceError(Exception):
    """A trace request the engine refuses; `field` names the offending setting (`variables[1].target` …)."""

    def __init__(self, field: str, message: str, status: int = 422) -> None:
        super().__init__(f"{field}: {message}")
        self.field = field
        self.message = message
        self.status = status


@dataclass
class Accessor:
    """Where one variable's value is read each sampled period, and how a recorded column reads back."""

    label: str
    unit: str
    type: str  # "REAL", "BOOL" or "INT"
    array: np.ndarray | None = None  # source array and element …
    index: int = 0
    read: Callable[[], float] | None = None  # … or a Python read
    post: Callable[[np.ndarray], np.ndarray] | None = None  # recorded raw column → reported values


# ---------------------------------------------------------------------------------------------------- accessors
_AXIS_ARRAYS = {  # member → (MotionModule array, unit suffix, wrap on the ring counter)
    "Cmd.Pos": ("cmd_pos", "", True), "Cmd.Vel": ("cmd_vel", "/s", False), "Cmd.AccDec": ("cmd_accdec", "/s²", False),
    "Cmd.Jerk": ("cmd_jerk", "/s³", False), "Act.Pos": ("act_pos", "", True), "Act.Vel": ("act_vel", "/s", False),
    "Act.Trq": ("act_trq", "%", False),
}
_AXIS_OTHER = ("Cmd.Trq", "Dir.Posi", "Dir.Nega", "Details.Homed", "MFaultLvl.Active", "Obsr.Active")
_GROUP_MEMBERS = ("Cmd.Vel", "Cmd.AccDec", "MFaultLvl.Active")


def axis_members() -> list[str]:
    return [*_AXIS_ARRAYS, *_AXIS_OTHER, "Status.Ready", *(f"Status.{s.name}" for s in AxisState),
            *(f"DrvStatus.{b}" for b in DRV_BITS)]


def group_members(n_axes: int) -> list[str]:
    return [*_GROUP_MEMBERS, *(f"CmdPos[{k}]" for k in range(n_axes)), "Status.Ready",
            *(f"Status.{s.name}" for s in GroupState)]


def _eq(code: int) -> Callable[[np.ndarray], np.ndarray]:
    return lambda col: (col == code).astype(float)


def _bit(mask: int) -> Callable[[np.ndarray], np.ndarray]:
    return lambda col: ((col.astype(np.int64) & mask) != 0).astype(float)


def _axis_accessor(ctrl: Controller, v: TraceVariable, where: str) -> Accessor:
    mc = ctrl.mc
    axis = mc.by_name.get(v.target)
    if axis is None:
        raise TraceError(f"{where}.target", f"no axis named {v.target!r} (axes: {', '.join(mc.by_name) or 'none'})")
    i, name = axis.i, v.name
    units = axis.params.UnitConversion.UnitDisplay.name.removeprefix("_mc").lower()
    label = v.label
    if name in _AXIS_ARRAYS:
        attr, suffix, wrap = _AXIS_ARRAYS[name]
        unit = "%" if suffix == "%" else units + suffix
        post = None
        if wrap and axis.rotary:
            lo, span = float(mc.mod_min[i]), float(mc.mod_len[i])
            post = lambda col: lo + np.mod(col - lo, span)  # noqa: E731 — as the snapshot reports it
        return Accessor(label, unit, "REAL", array=getattr(mc, attr), index=i, post=post)
    if name == "Cmd.Trq":  # Cmd.Trq = Act.Trq outside torque control (MotionModule.capture)
        return Accessor(label, "%", "REAL", read=lambda: mc.trq_cmd.item(i) if mc.trq_active.item(i)
                        else mc.act_trq.item(i))
    if name in ("Dir.Posi", "Dir.Nega"):
        sign = 1.0 if name == "Dir.Posi" else -1.0
        return Accessor(label, "bool", "BOOL", array=mc.cmd_vel, index=i,
                        post=lambda col: (col * sign > 0).astype(float))
    if name == "Details.Homed":
        return Accessor(label, "bool", "BOOL", array=mc.homed, index=i)
    if name == "MFaultLvl.Active":
        return Accessor(label, "bool", "BOOL", read=lambda: float(axis.error_code != 0))
    if name == "Obsr.Active":
        return Accessor(label, "bool", "BOOL", read=lambda: float(bool(axis.observations)))
    if name.startswith("Status."):
        state = name.removeprefix("Status.")
        code = AxisState.Standstill if state == "Ready" else getattr(AxisState, state, None)
        if code is not None:
            return Accessor(label, "bool", "BOOL", array=mc.state, index=i, post=_eq(int(code)))
    if name.startswith("DrvStatus."):
        bit = name.removeprefix("DrvStatus.")
        if bit in DRV_BITS:
            return Accessor(label, "bool", "BOOL", array=mc.drv, index=i, post=_bit(1 << DRV_BITS.index(bit)))
    raise TraceError(f"{where}.name", f"the axis variable has no traceable member {name!r}; members: "
                     + ", ".join(axis_members()))


def _group_accessor(ctrl: Controller, v: TraceVariable, where: str) -> Accessor:
    mc = ctrl.mc
    g = mc.groups_by_name.get(v.target)
    if g is None:
        raise TraceError(f"{where}.target", f"no axes group named {v.target!r} (groups: "
                         f"{', '.join(mc.groups_by_name) or 'none'})")
    name, label = v.name, v.label
    units = g.axes[0].params.UnitConversion.UnitDisplay.name.removeprefix("_mc").lower() if g.axes else "pls"
    if name == "Cmd.Vel":
        return Accessor(label, units + "/s", "REAL", read=lambda: g.cmd_vel)
    if name == "Cmd.AccDec":
        return Accessor(label, units + "/s²", "REAL", read=lambda: g.cmd_accdec)
    if name == "MFaultLvl.Active":
        return Accessor(label, "bool", "BOOL", read=lambda: float(g.error_code != 0))
    m = re.fullmatch(r"CmdPos\[(\d)\]", name)
    if m and int(m.group(1)) < len(g.idx):
        return Accessor(label, units, "REAL", array=mc.cmd_pos, index=g.idx[int(m.group(1))])
    if name.startswith("Status."):
        state = name.removeprefix("Status.")
        if state == "Ready":
            return Accessor(label, "bool", "BOOL", read=lambda: float(bool(g.capture()["Status"]["Ready"])))
        code = getattr(GroupState, state, None)
        if code is not None:
            return Accessor(label, "bool", "BOOL", read=lambda: float(g.state == code))
    raise TraceError(f"{where}.name", f"the axes group variable has no traceable member {name!r}; members: "
                     + ", ".join(group_members(len(g.idx))))


def _fb_accessor(ctrl: Controller, v: TraceVariable, where: str) -> Accessor:
    try:
        fb_id = int(v.target)
    except ValueError:
        raise TraceError(f"{where}.target", f"an instance is named by its id (a number), not {v.target!r}") from None
    entry = ctrl.program.get(fb_id)
    if entry is None:
        raise TraceError(f"{where}.target", f"no function-block instance {fb_id}")
    fb = entry.fb
    var = next((o for o in fb.DEF.outputs if o.name == v.name), None)
    if var is None:
        raise TraceError(f"{where}.name", f"{fb.DEF.name} has no output {v.name!r}; outputs: "
                         + ", ".join(o.name for o in fb.DEF.outputs))
    if var.type not in NUMERIC_TYPES and var.enum is None:
        raise TraceError(f"{where}.name", f"output {v.name} is of type {var.type}; only BOOL, numbers and "
                         "enumerations can be traced")
    out, key = fb.out, v.name
    kind = "BOOL" if var.type == "BOOL" else ("REAL" if var.type in ("REAL", "LREAL") else "INT")
    # the instance's outputs dict is read where it lives: a deleted instance keeps its last values
    return Accessor(f"{fb.DEF.name}#{fb_id}.{v.name}", "bool" if kind == "BOOL" else (var.unit or ""), kind,
                    read=lambda: float(out[key] or 0))


_INDEX_RE = re.compile(r"(?:0x)?([0-9a-fA-F]{4})h?(?:[:.](?:0x)?([0-9a-fA-F]{1,2})h?)?")


def _pdo_accessor(ctrl: Controller, v: TraceVariable, where: str) -> Accessor:
    net = ctrl.network
    try:
        node = int(v.target)
    except ValueError:
        raise TraceError(f"{where}.target", f"a slave is named by its node address (a number), not {v.target!r}") \
            from None
    pos = net.index_of_node.get(node)
    if pos is None:
        raise TraceError(f"{where}.target", f"no slave with node address {node} (nodes: "
                         f"{', '.join(str(n) for n in net.index_of_node) or 'none'})")
    s = net.slaves[pos]
    mapped = [(d, e) for d, layout in (("rx", s.rx_layout), ("tx", s.tx_layout)) for e in layout.entries if e.index]
    m = _INDEX_RE.fullmatch(v.name.strip())
    hit = None
    index = int(m.group(1), 16) if m is not None else -1
    sub = int(m.group(2), 16) if m is not None and m.group(2) is not None else None
    for d, e in mapped:
        if e.index == index and (sub is None or e.subindex == sub):
            hit = (d, e)
            break
        if e.name and e.name.lower() == v.name.strip().lower():
            hit = (d, e)
            break
    if hit is None:
        listing = ", ".join(f"{e.index:04X}:{e.subindex:02X} {e.name}" for _, e in mapped) or "none"
        raise TraceError(f"{where}.name", f"{v.name!r} is not in the PDO mapping of node {node} (mapped: {listing})")
    d, e = hit
    if e.field is None:
        raise TraceError(f"{where}.name", f"object {e.index:04X}:{e.subindex:02X} is mapped but the emulated "
                         f"{s.kind} device has no value for it")
    record = net.rx if d == "rx" else net.tx
    label = f"Node{node}.{e.index:04X}:{e.subindex:02X}"
    dt = e.data_type
    return Accessor(label, "", "BOOL" if dt == "BOOL" else ("REAL" if dt in ("REAL", "LREAL") else "INT"),
                    array=record[e.field], index=pos)


def compile_accessor(ctrl: Controller, v: TraceVariable, where: str) -> Accessor:
    kinds = {"axis": _axis_accessor, "group": _group_accessor, "fb": _fb_accessor, "pdo": _pdo_accessor}
    return kinds[v.kind](ctrl, v, where)


class Gather:
    """The accessors of a trace compiled into one staging row: per source array, one fancy-indexed copy into a
    contiguous run of columns (or one `.item` for a single element); Python reads last."""

    def __init__(self, accessors: list[Accessor]) -> None:
        by_array: dict[int, list[int]] = {}
        reads = []
        for k, a in enumerate(accessors):
            if a.array is not None:
                by_array.setdefault(id(a.array), []).append(k)
            else:
                reads.append(k)
        order = [k for ks in by_array.values() for k in ks] + reads
        self.column = [0] * len(accessors)  # accessor k → column of the row
        for col, k in enumerate(order):
            self.column[k] = col
        self.row = np.zeros(len(accessors))
        self.runs: list[tuple[slice, np.ndarray, np.ndarray]] = []
        self.items: list[tuple[int, Callable[[int], Any], int]] = []
        col = 0
        for ks in by_array.values():
            arr = accessors[ks[0]].array
            assert arr is not None
            if len(ks) == 1:
                self.items.append((col, arr.item, accessors[ks[0]].index))
            else:
                self.runs.append((slice(col, col + len(ks)), arr, np.array([accessors[k].index for k in ks],
                                                                            dtype=np.intp)))
            col += len(ks)
        self.reads = [(self.column[k], accessors[k].read) for k in reads]

    def __call__(self) -> np.ndarray:
        row = self.row
        for sl, arr, idx in self.runs:
            row[sl] = arr[idx]
        for col, item, i in self.items:
            row[col] = item(i)
        for col, read in self.reads:
            row[col] = read()  # type: ignore[misc]
        return row


# ---------------------------------------------------------------------------------------------------- the trace
class Trace:
    """One configured trace: its rings (two in repeat mode), the record's progress and its trigger."""

    def __init__(self, trace_id: int, settings: TraceSettings, accessors: list[Accessor], *, start_cycle: int,
                 period_s: float) -> None:
        self.id = trace_id
        self.settings = settings
        self.accessors = accessors  # the variables, then the trigger variable if it is not among them
        self.n_vars = len(settings.variables)
        self.gather = Gather(accessors)
        self.period_s = period_s
        n = self.samples = settings.samples
        ncols = len(accessors)
        n_rings = 2 if settings.mode == "repeat" else 1
        self._rings = [(np.zeros((n, ncols)), np.zeros(n, dtype=np.int64)) for _ in range(n_rings)]
        trig = settings.trigger
        self.pre = min(n - 1, round(n * trig.pre_trigger_percent / 100.0)) if trig is not None else 0
        tk = (settings.variables.index(trig.variable) if trig.variable in settings.variables else self.n_vars) \
            if trig is not None else -1
        self._tcol = self.gather.column[tk] if tk >= 0 else -1  # the trigger variable's column of the row
        self._edge_bool = tk >= 0 and accessors[tk].type == "BOOL"
        self.records = 0  # complete records so far (repeat mode)
        self._last: tuple[np.ndarray, np.ndarray, int, int, int] | None = None  # repeat: the last complete record
        self.start(start_cycle)

    @staticmethod
    def ring_bytes(settings: TraceSettings, columns: int) -> int:
        return settings.samples * (columns + 1) * 8 * (2 if settings.mode == "repeat" else 1)

    def start(self, cycle: int) -> None:
        """(Re)arm: an empty record; the first sample is taken at the end of the current period."""
        self._ring = 0
        self.buf, self.cyc = self._rings[0]
        self.w = 0
        self.count = 0  # samples written in this record
        self.trig_count = -1  # sample number of the trigger in this record
        self.post_left = 0
        self._countdown = 0
        self._prev: float | None = None
        self.start_cycle = cycle
        self.records = 0
        self._last = None
        self.state = "running" if self.settings.mode == "continuous" else "waiting"

    @property
    def active(self) -> bool:
        return self.state in ("waiting", "triggered", "running")

    def _fires(self, prev: float | None, cur: float) -> bool:
        trig = self.settings.trigger
        if trig is None:
            return True
        c, level = trig.condition, trig.level
        if c == "rising" or c == "falling":
            if prev is None:
                return False
            if self._edge_bool:
                return (prev == 0 and cur != 0) if c == "rising" else (prev != 0 and cur == 0)
            return (prev < level <= cur) if c == "rising" else (prev > level >= cur)
        if c == "gt":
            return cur > level
        if c == "lt":
            return cur < level
        if c == "eq":
            return cur == level
        return cur != level

    def sample(self, cycle: int) -> None:
        """End of period `cycle`: take a sample if one is due and advance the record."""
        if self._countdown:
            self._countdown -= 1
            return
        self._countdown = self.settings.sampling_periods - 1
        row = self.gather()
        w = self.w
        self.buf[w] = row
        self.cyc[w] = cycle
        self.w = w + 1 if w + 1 < self.samples else 0
        self.count += 1
        state = self.state
        if state == "waiting":
            cur = row.item(self._tcol) if self._tcol >= 0 else 0.0
            if self.count > self.pre and self._fires(self._prev, cur):
                self.state = "triggered"
                self.trig_count = self.count - 1
                self.post_left = self.samples - self.pre - 1
                if self.post_left == 0:
                    self._complete()
            self._prev = cur
        elif state == "triggered":
            self.post_left -= 1
            if self.post_left == 0:
                self._complete()

    def _complete(self) -> None:
        if self.settings.mode == "single":
            self.state = "done"
            return
        # repeat: keep this record readable, re-arm on the other ring
        self._last = (self.buf, self.cyc, self.w, self.count, self.trig_count)
        self.records += 1
        self._ring ^= 1
        self.buf, self.cyc = self._rings[self._ring]
        self.w = self.count = 0
        self.trig_count = -1
        self._prev = None
        self.state = "waiting"

    def stop(self) -> None:
        if self.active:
            self.state = "stopped"

    # ------------------------------------------------------------------ reading (kernel thread)
    def read(self, *, max_points: int | None = None, decimation: int | None = None) -> dict[str, Any]:
        """The record (repeat: the last complete one once there is one), oldest sample first, every `decimation`-th
        sample (default: the smallest that gives at most `max_points`)."""
        if self._last is not None:
            buf, cyc, w, count, trig = self._last
        else:
            buf, cyc, w, count, trig = self.buf, self.cyc, self.w, self.count, self.trig_count
        n_ring = self.samples
        n = min(count, n_ring)
        if decimation is None:
            decimation = max(1, math.ceil(n / max_points)) if max_points else 1
        first = count - n  # sample number of the oldest sample kept
        idx = (np.arange(0, n, decimation, dtype=np.intp) + (w - n)) % n_ring
        cycles = cyc[idx]
        values = buf[idx]  # a copy (fancy indexing)
        series = []
        for k in range(self.n_vars):
            a = self.accessors[k]
            col = values[:, self.gather.column[k]]
            if a.post is not None:
                col = a.post(col)
            series.append({"label": a.label, "unit": a.unit, "type": a.type, "values": col})
        trigger_index = trig - first if trig >= 0 and trig >= first else None
        trigger_cycle = int(cyc[(w - n + trigger_index) % n_ring]) if trigger_index is not None else None
        return {
            "id": self.id, "name": self.settings.name, "state": self.state, "records": self.records,
            "armed": self.state != "waiting" or self.count >= self.pre,
            "sample_count": n, "decimation": decimation, "pre_trigger_samples": self.pre,
            "trigger_index": trigger_index, "trigger_cycle": trigger_cycle,
            "trigger_time_s": trigger_cycle * self.period_s if trigger_cycle is not None else None,
            "start_cycle": self.start_cycle, "period_s": self.period_s, "cycles": cycles,
            "time_s": cycles * self.period_s, "series": series,
        }


class TraceSet:
    """The traces of one controller (at most `MAX_TRACES`); the kernel calls `sample()` at the end of each period."""

    def __init__(self, ctrl: Controller) -> None:
        self._ctrl = ctrl
        self.traces: dict[int, Trace] = {}
        self.running: list[Trace] = []  # the active traces (empty: the period costs one truth test)
        self._next_id = 1

    def configure(self, settings: TraceSettings) -> Trace:
        """Compile and start a trace (first sample at the end of the current period)."""
        if len(self.traces) >= MAX_TRACES:
            raise TraceError("traces", f"at most {MAX_TRACES} traces at once; delete one first", status=409)
        ctrl = self._ctrl
        accessors = [compile_accessor(ctrl, v, f"variables[{k}]") for k, v in enumerate(settings.variables)]
        trig = settings.trigger
        if trig is not None and trig.variable not in settings.variables:
            accessors.append(compile_accessor(ctrl, trig.variable, "trigger.variable"))
        need = Trace.ring_bytes(settings, len(accessors))
        used = sum(Trace.ring_bytes(t.settings, len(t.accessors)) for t in self.traces.values())
        if used + need > MEMORY_BUDGET_BYTES:
            raise TraceError("samples", f"the rings would take {need / 2**20:.1f} MiB and the other traces use "
                             f"{used / 2**20:.1f} MiB of the {MEMORY_BUDGET_BYTES / 2**20:.0f} MiB budget; record "
                             "fewer samples or variables")
        trace = Trace(self._next_id, settings, accessors, start_cycle=ctrl.cycle, period_s=ctrl.period_s)
        self._next_id += 1
        self.traces[trace.id] = trace
        self._refresh()
        return trace

    def get(self, trace_id: int) -> Trace:
        t = self.traces.get(trace_id)
        if t is None:
            raise TraceError("id", f"no trace {trace_id}", status=404)
        return t

    def stop(self, trace_id: int) -> Trace:
        t = self.get(trace_id)
        t.stop()
        self._refresh()
        return t

    def restart(self, trace_id: int) -> Trace:
        t = self.get(trace_id)
        t.start(self._ctrl.cycle)
        self._refresh()
        return t

    def delete(self, trace_id: int) -> None:
        self.get(trace_id)
        del self.traces[trace_id]
        self._refresh()

    def _refresh(self) -> None:
        self.running = [t for t in self.traces.values() if t.active]

    def sample(self, cycle: int) -> None:
        finished = False
        for t in self.running:
            t.sample(cycle)
            if t.state == "done":
                finished = True
        if finished:
            self._refresh()


def catalog(ctrl: Controller) -> dict[str, list[dict[str, Any]]]:
    """The traceable variables of the controller (kernel thread), grouped by axes, groups, instances, slaves; each
    variable with the unit and type a trace would record."""

    def target(kind: str, tgt: str, label: str, names: list[str]) -> dict[str, Any]:
        out = []
        for n in names:
            try:
                a = compile_accessor(ctrl, TraceVariable(kind=kind, target=tgt, name=n), "v")  # type: ignore[arg-type]
            except TraceError:
                continue
            out.append({"name": n, "unit": a.unit, "type": a.type, "description": ""})
        return {"kind": kind, "target": tgt, "label": label, "variables": out}

    mc, net = ctrl.mc, ctrl.network
    axes = [target("axis", a.name, a.name, axis_members()) for a in mc.axes]
    groups = [target("group", g.name, g.name, group_members(len(g.idx))) for g in mc.groups]
    instances = []
    for fid, entry in ctrl.program.items():
        fb = entry.fb
        axis = fb.inp.get("Axis") or fb.inp.get("AxesGroup") or ""
        names = [o.name for o in fb.DEF.outputs if o.type in NUMERIC_TYPES or o.enum is not None]
        instances.append(target("fb", str(fid), f"#{fid} {fb.DEF.name}" + (f" ({axis})" if axis else ""), names))
    slaves = []
    for s in net.slaves:
        names = [f"{e.index:04X}:{e.subindex:02X}" for layout in (s.rx_layout, s.tx_layout) for e in layout.entries
                 if e.index and e.field is not None]
        t = target("pdo", str(s.node_address), f"Node {s.node_address} {s.name}", names)
        by_key = {f"{e.index:04X}:{e.subindex:02X}": e.name for layout in (s.rx_layout, s.tx_layout)
                  for e in layout.entries}
        for v in t["variables"]:
            v["description"] = by_key.get(v["name"], "")
        slaves.append(t)
    return {"axes": axes, "groups": groups, "instances": instances, "slaves": slaves}
