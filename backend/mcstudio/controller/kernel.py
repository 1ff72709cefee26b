"""The deterministic controller kernel: a fixed control period, a cycle counter and one call per period.

One control period (architecture.md):
  1. fieldbus exchange — drives receive last period's outputs, the mechanism advances, inputs are latched;
  2. inputs — process image → axis actual values and drive status;
  3. program — every FB instance is called in creation order;
  4. motion — profiles advance, states update;
  5. outputs — command values → process image;
  6. snapshot publication.

Time is `cycle × period`, never the wall clock: the same project and the same commands at the same cycles give
bit-identical variables. The only wall-clock input is the dead-man lease of an FB instance, read through an injectable
`clock` so tests can drive it. The kernel is single-threaded: other threads talk to it through `Runner` (commands at
cycle boundaries) and read the published immutable `Snapshot`.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

from ..drives.cia402 import SensorLayout
from ..fieldbus.config import resolve_slaves
from ..fieldbus.library import DeviceLibrary
from ..fieldbus.network import Network
from ..plant.ideal import Mechanics
from ..project.models import AxisConfig, Project
from .events import EventLog
from .mc.cam.table import CamTable
from .mc.enums import _eMC_AXIS_TYPE
from .mc.fb.base import FBInputError, FunctionBlock
from .mc.fb.registry import FB_TYPES
from .mc.module import MotionModule
from .mc.units import pulses_per_unit
from .trace import TraceSet


def sensor_layout(axes: list[AxisConfig | None]) -> SensorLayout:
    """Sensor positions of the simulated mechanism behind each slave, from command units to motor pulses (the
    mechanism's frame: pulses = units × pulses-per-unit at the power-on coordinate system). None: a slave without
    an axis (no sensors)."""
    layout = SensorLayout(len(axes))
    for k, a in enumerate(axes):
        if a is None:
            continue
        s = a.sensors
        ppu = pulses_per_unit(a.parameters)
        if s.PositiveLimit is not None:
            layout.pos_limit[k] = s.PositiveLimit * ppu
        if s.NegativeLimit is not None:
            layout.neg_limit[k] = s.NegativeLimit * ppu
        for zone, lo, hi in ((layout.prox, s.HomeProximityStart, s.HomeProximityEnd),
                             (layout.ext1, s.ExternalHomeStart, s.ExternalHomeEnd),
                             (layout.ext2, s.Latch2Start, s.Latch2End)):
            if lo is not None and hi is not None:
                zone[k] = sorted((lo * ppu, hi * ppu))
        layout.z_offset[k] = float(s.ZPhaseOffset)
        layout.z_period[k] = float(a.parameters.UnitConversion.CmdPlsCountPerMotorRotation)
    return layout


def mechanics(axes: list[AxisConfig | None]) -> Mechanics:
    """The mechanism behind each slave's drive from the axes' servo-drive settings (None: defaults)."""
    mech = Mechanics(len(axes))
    for k, a in enumerate(axes):
        if a is None:
            continue
        d = a.drive
        mech.pulses_per_rev[k] = float(a.parameters.UnitConversion.CmdPlsCountPerMotorRotation)
        mech.rated_torque[k] = d.RatedTorque
        mech.inertia[k] = d.Inertia
        mech.viscous[k] = d.ViscousFriction
        mech.load[k] = d.LoadTorque
        mech.cst[k] = d.CyclicTorqueMode
        if hasattr(mech, "model"):
            mech.model[k] = 1 if d.PositionLoop == "SecondOrder" else 0
            mech.bandwidth_hz[k] = d.PositionLoopBandwidth
            mech.damping[k] = d.PositionLoopDamping
            mech.feedforward[k] = d.VelocityFeedForward / 100.0
    return mech


class KernelError(Exception):
    """A request the kernel refuses (unknown instance, wrong until-condition …); `field` names what is wrong."""

    def __init__(self, field: str, message: str, status: int = 422) -> None:
        super().__init__(f"{field}: {message}")
        self.field = field
        self.message = message
        self.status = status


@dataclass
class ProgramEntry:
    fb: FunctionBlock
    lease_s: float | None = None
    lease_deadline: float | None = None
    created_cycle: int = 0


@dataclass(frozen=True)
class FBView:
    id: int
    type: str
    inputs: dict[str, Any]
    outputs: dict[str, Any]
    lease_s: float | None


@dataclass(frozen=True)
class Snapshot:
    """Immutable view of the controller after a cycle, for readers in other threads."""

    cycle: int
    time_s: float
    period_s: float
    project: str
    mc: dict[str, Any]
    fbs: dict[int, FBView]
    event_seq: int
    wall: float = field(default_factory=time.monotonic)


@dataclass(frozen=True)
class Until:
    fb: int
    output: str
    equals: Any


class Controller:
    def __init__(self, project: Project, *, clock: Callable[[], float] = time.monotonic,
                 library: DeviceLibrary | None = None, cams: Mapping[str, CamTable] | None = None) -> None:
        """`cams`: the project's cam data variables by name (as downloaded); the controller works on copies, so
        what a program writes into them (MC_GenerateCamTable) is lost with the controller unless saved."""
        self.project = project
        self.library = library
        self.cams = dict(cams or {})
        self.period_s = project.controller.period_s
        self.clock = clock
        self.events = EventLog()
        slaves = resolve_slaves(project, library)
        axis_of = {a.node_address: a for a in project.axes
                   if a.node_address is not None and a.type in (_eMC_AXIS_TYPE._mcServo, _eMC_AXIS_TYPE._mcEncdr)}
        behind = [axis_of.get(s.config.node_address) for s in slaves]
        self.network = Network(slaves, sensor_layout(behind), period_s=self.period_s, mechanics=mechanics(behind),
                               auto_restart=project.ethercat.master.auto_restart_slaves, library=library)
        self.mc = MotionModule(project, period_s=self.period_s, events=self.events, network=self.network)
        self.mc.cam_tables = {name: t.copy() for name, t in self.cams.items()}
        self.cycle = 0
        self.program: dict[int, ProgramEntry] = {}
        self._calls: list[FunctionBlock] | None = None  # the program's instances in call order (cached)
        self._leased: dict[int, ProgramEntry] = {}  # the instances with a dead-man lease
        self._awake: list[FunctionBlock] | None = None  # instances awake after the last full program pass …
        self._awake_wakes = -1  # … and the wake-up count then
        # skip the calls of settled (sleeping) instances; False calls every instance every period, which must give
        # the same outputs (tests/controller/test_fb_scheduling.py)
        self.skip_settled = True
        self._next_id = 1
        self._view_cache: dict[int, tuple[dict[str, Any], dict[str, Any], FBView]] = {}
        self._program_version = 0  # instances added or deleted (the snapshot then looks at every instance)
        self._snapshot_program = -1
        self.traces = TraceSet(self)  # data traces, sampled at the end of each period (trace.py)
        self.snapshot: Snapshot = self._make_snapshot()
        self.events.add(cycle=0, time_s=0.0, source="controller", code="00000000", level="information",
                        message=f"project '{project.name}' loaded: {len(self.mc.axes)} axes, "
                        f"primary period {project.controller.primary_period_us} µs")
        self._network_events()

    @property
    def time_s(self) -> float:
        return self.cycle * self.period_s

    # ------------------------------------------------------------------ program (FB instances)
    def fb(self, type_name: str, *, lease_s: float | None = None, **inputs: Any) -> FunctionBlock:
        """Create an instruction instance; it is called every period from the next cycle on (PLC semantics)."""
        cls = FB_TYPES.get(type_name)
        if cls is None:
            raise KernelError("type", f"unknown instruction {type_name!r}; GET /api/v1/fb-types lists them")
        self._check_inouts(cls, inputs)
        if lease_s is not None and not (0 < lease_s <= 3600):
            raise KernelError("lease_s", "must be > 0 and at most 3600 seconds")
        fb = cls(self.mc, self._next_id, inputs)
        self._next_id += 1
        entry = ProgramEntry(fb, lease_s, None, self.cycle)
        if lease_s is not None:
            entry.lease_deadline = self.clock() + lease_s
        self.program[fb.id] = entry
        self._program_version += 1
        if lease_s is not None:
            self._leased[fb.id] = entry
        self._calls = None
        return fb

    def _check_inouts(self, cls: type[FunctionBlock], inputs: dict[str, Any]) -> None:
        for var in cls.DEF.inouts:
            if var.name in inputs:
                value = var.coerce(inputs[var.name])
                if var.type == "_sAXIS_REF" and value not in self.mc.by_name:
                    known = ", ".join(self.mc.by_name) or "none"
                    raise FBInputError(var.name, f"no axis named {value!r} in this project (axes: {known})")
                if var.type == "_sGROUP_REF" and value not in self.mc.groups_by_name:
                    known = ", ".join(self.mc.groups_by_name) or "none"
                    raise FBInputError(var.name, f"no axes group named {value!r} in this project (groups: {known})")

    def get_fb(self, fb_id: int) -> FunctionBlock:
        entry = self.program.get(fb_id)
        if entry is None:
            raise KernelError("id", f"no function-block instance {fb_id}", status=404)
        return entry.fb

    def set_inputs(self, fb_id: int, inputs: dict[str, Any]) -> FunctionBlock:
        fb = self.get_fb(fb_id)
        self._check_inouts(type(fb), inputs)
        fb.set_inputs(inputs)
        self.renew_lease(fb_id)
        return fb

    def renew_lease(self, fb_id: int) -> None:
        entry = self.program.get(fb_id)
        if entry is not None and entry.lease_s is not None:
            entry.lease_deadline = self.clock() + entry.lease_s

    def delete_fb(self, fb_id: int) -> None:
        entry = self.program.pop(fb_id, None)
        self._program_version += 1
        self._leased.pop(fb_id, None)
        self._calls = None
        if entry is None:
            raise KernelError("id", f"no function-block instance {fb_id}", status=404)
        entry.fb.on_delete()

    def check_leases(self) -> None:
        """Dead-man: an instance whose lease was not renewed drops its Execute/Enable-type inputs."""
        if not self._leased:
            return
        now = None
        for entry in self._leased.values():
            if entry.lease_deadline is None:
                continue
            now = self.clock() if now is None else now
            if now >= entry.lease_deadline:
                entry.lease_deadline = None
                fb = entry.fb
                if any(fb.inp.get(v.name) for v in fb.DEF.inputs if v.dead_man):
                    fb.drop_dead_man()
                    self.events.add(cycle=self.cycle, time_s=self.time_s, source=fb.label, code="00000000",
                                    level="information",
                                    message=f"lease of {entry.lease_s:g} s expired: Execute/Enable inputs set FALSE",
                                    source_kind="instruction", source_name=fb.label, instruction=fb.label)

    # ------------------------------------------------------------------ the control period
    def run_cycle(self) -> None:
        mc = self.mc
        mc.cycle = self.cycle
        net = self.network
        net.exchange()
        if net.pending_events:
            self._network_events()
        mc.inputs()
        self._program_stage(mc)
        mc.motion()
        mc.outputs()
        if self.traces.running:
            self.traces.sample(self.cycle)
        self.cycle += 1

    def _program_stage(self, mc: MotionModule) -> None:
        """Stage 3: every instance in creation order, except those asleep when their turn comes (a settled instance's
        call changes nothing; `FunctionBlock.sleep`). While no instance was woken since the last full pass, only the
        instances awake after it can be awake, so only they are visited; a wake-up during the pass (a call aborting
        another instance's job …) continues it over every later instance."""
        fbs = self._calls
        if fbs is None:  # the program changed: the instances in creation order
            fbs = self._calls = [e.fb for e in self.program.values()]
            for k, fb in enumerate(fbs):
                fb._order = k
            self._awake = None
        # Every call is guarded: an exception inside one instance is contained by that instance (decision D120) and
        # the pass goes on (a try block costs nothing in Python ≥ 3.11 until something raises).
        if not self.skip_settled:
            for fb in fbs:
                try:
                    fb.call()
                except Exception as exc:
                    fb.contain(exc)
            return
        awake = self._awake
        if awake is not None and mc.fb_wakes == self._awake_wakes:
            w0 = mc.fb_wakes
            for fb in awake:
                if not fb._asleep:
                    try:
                        fb.call()
                    except Exception as exc:
                        fb.contain(exc)
                    if mc.fb_wakes != w0:  # woke something: the rest of the pass visits every instance
                        for later in fbs[fb._order + 1:]:
                            if not later._asleep:
                                try:
                                    later.call()
                                except Exception as exc:
                                    later.contain(exc)
                        self._awake = None
                        return
            return
        for fb in fbs:
            if not fb._asleep:
                try:
                    fb.call()
                except Exception as exc:
                    fb.contain(exc)
        # the instances awake now; valid while nothing wakes another one
        self._awake = [fb for fb in fbs if not fb._asleep]
        self._awake_wakes = mc.fb_wakes

    def _network_events(self) -> None:
        for level, code, message, slave in self.network.pending_events:
            self.events.add(cycle=self.cycle, time_s=self.time_s, source="EtherCAT master", code=code,
                            level=level, message=message, source_kind="slave", source_name=slave)  # type: ignore[arg-type]
        self.network.pending_events.clear()

    def step(self, cycles: int = 1, until: Until | None = None, *, publish: bool = True) -> int:
        """Run `cycles` periods (stopping early once `until` holds). Returns the number of cycles run."""
        if until is not None:
            fb = self.get_fb(until.fb)
            if until.output not in fb.out:
                raise KernelError("until.output", f"{fb.DEF.name} has no output {until.output!r}; outputs: "
                                  + ", ".join(fb.out))
        n = 0
        for _ in range(cycles):
            self.check_leases()
            self.run_cycle()
            n += 1
            if until is not None and self.until_holds(until):
                break
        if publish:
            self.publish()
        return n

    def until_holds(self, until: Until) -> bool:
        entry = self.program.get(until.fb)
        if entry is None:
            return True
        fb = entry.fb
        raw = fb.out[until.output]
        if isinstance(until.equals, bool):
            return isinstance(raw, bool) and raw == until.equals
        if raw == until.equals:
            return True
        return fb.outputs_json()[until.output] == until.equals

    # ------------------------------------------------------------------ snapshot
    def _make_snapshot(self) -> Snapshot:
        # an instance's view is rebuilt only when its raw inputs or outputs changed since the last publication
        cache = self._view_cache
        touched, self.mc.fb_touched = self.mc.fb_touched, set()
        # an instance asleep since the last publication (not woken, not put to sleep since) has not changed
        prev = getattr(self, "snapshot", None)
        skip = prev is not None and self._snapshot_program == self._program_version
        self._snapshot_program = self._program_version
        fbs = {}
        for fid, e in self.program.items():
            fb = e.fb
            if skip and fb._asleep and fid not in touched:
                fbs[fid] = prev.fbs[fid]  # type: ignore[union-attr]
                continue
            hit = cache.get(fid)
            same_inputs = hit is not None and hit[0] == fb.inp
            if same_inputs and hit[1] == fb.out and hit[2].lease_s == e.lease_s:  # type: ignore[index]
                fbs[fid] = hit[2]  # type: ignore[index]
                continue
            # outputs changed (the usual case: a running instruction): the rendered inputs are reused
            inputs = hit[2].inputs if same_inputs else fb.inputs_json()  # type: ignore[index]
            view = FBView(fid, fb.DEF.name, inputs, fb.outputs_json(), e.lease_s)
            cache[fid] = (hit[0] if same_inputs else dict(fb.inp), dict(fb.out), view)  # type: ignore[index]
            fbs[fid] = view
        if len(cache) > len(fbs):
            for fid in [k for k in cache if k not in fbs]:
                del cache[fid]
        return Snapshot(self.cycle, self.time_s, self.period_s, self.project.name, self.mc.capture(), fbs,
                        self.events.last_seq)

    def publish(self) -> Snapshot:
        self.snapshot = self._make_snapshot()
        return self.snapshot
