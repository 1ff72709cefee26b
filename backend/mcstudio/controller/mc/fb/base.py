"""Function-block framework: instruction definitions, input coercion and the PLC call semantics.

An instruction is defined once (`FBDef`: name, inputs, outputs, in-outs with types, defaults, ranges and units); the
definition drives the emulator, input validation at the API and the `GET /api/v1/fb-types` catalog the studio renders
its forms from. Instances are called once per period in program order, like FB calls in a PLC program, and read the
MC module's progress at each call.

Output timing of Execute-type instructions (`omron-mc-basics.md` §2.5/§2.8, `omron-group-and-cam.md` §0.1):
Busy rises with the Execute edge; Active follows one period later; Done/CommandAborted stay TRUE while Execute is held,
or for exactly one period if Execute was already FALSE; Error is sticky until the error is reset (Omron deviation from
PLCopen) and a new rising edge is needed afterwards.
"""

from __future__ import annotations

import enum
import logging
import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, ClassVar

from ..enums import ENUMS
from ..errors import E_COORDINATED, E_ILLEGAL_AXIS, E_REEXEC_DISABLED
from ..jobs import JobStatus

if TYPE_CHECKING:
    from ..axis import Axis
    from ..jobs import Job
    from ..module import MotionModule

INT_RANGES = {
    "SINT": (-128, 127),
    "INT": (-32768, 32767),
    "DINT": (-(2**31), 2**31 - 1),
    "USINT": (0, 255),
    "UINT": (0, 65535),
    "UDINT": (0, 2**32 - 1),
    "WORD": (0, 65535),
    "ULINT": (0, 2**64 - 1),
}


STRUCT_TYPES = ("_sHOMING_REF", "_sAXIS_PARAM", "_sTRIGGER_REF", "_sMC_KIN_REF", "_sMC_WORKSPACE_REF",
                "_sMC_COORD_REF", "_sMC_MOVE_TRAJ_REF", "_sMC_SYNC_TRAJ_REF", "_sMC_SYNCOUT_TRAJ_REF")
# member names of the structures (a misspelt member is a 422 naming it, not silently the default value)
STRUCT_MEMBERS: dict[str, frozenset[str]] = {
    "_sHOMING_REF": frozenset(("HomingMode", "HomeInput", "StartDir", "HomeDir", "PosiLmtMode", "NegaLmtMode", "Vel",
                               "ApproachVel", "Acc", "Dec", "Jerk", "Mask", "Offset", "PushTime", "Compensation",
                               "CompensationVel")),
    "_sTRIGGER_REF": frozenset(("Mode", "LatchID", "InputDrive")),
    "_sAXIS_PARAM": frozenset(("UnitConversion", "Operation", "OtherOperation", "Limit", "PosCount", "Homing")),
    "_sMC_KIN_REF": frozenset(("KinType", "KinParam", "ExpansionParam")),
    "_sMC_WORKSPACE_REF": frozenset(("WorkspaceType", "WorkspaceParam")),
    # robot structures (omron-robot-delta3.md §8.2); the manual's spelling MaxVelociy is accepted as well
    "_sMC_COORD_REF": frozenset(("CSID", "Pose")),
    "_sMC_MOVE_TRAJ_REF": frozenset(("MoveTrajType", "TrajTime", "MaxVelocity", "MaxVelociy", "MaxAcceleration")),
    "_sMC_SYNC_TRAJ_REF": frozenset(("SyncTrajType", "TrajTime", "TrajTransition", "TrajDistance", "MaxVelocity",
                                     "MaxVelociy", "MaxAcceleration")),
    "_sMC_SYNCOUT_TRAJ_REF": frozenset(("SyncStopType", "TrajTime", "TrajTransition", "TrajDistance", "MaxVelocity",
                                        "MaxVelociy", "MaxAcceleration")),
}


CAM_PROPERTY_MEMBERS = {"InitVel": "REAL", "InitAcc": "REAL", "CycleTime": "REAL"}
CAM_NODE_MEMBERS = {"Phase": "REAL", "Distance": "REAL", "Curve": "_eMC_CAM_CURVE", "ConnectingVelEnable": "BOOL",
                    "ConnectingVel": "REAL", "ConnectingAccEnable": "BOOL", "ConnectingAcc": "REAL",
                    "PhasePitch": "REAL"}
MAX_CAM_NODES = 1000  # the instruction takes ≤ 359 valid nodes; longer arrays are refused at the API (bounded input)


def _coerce_struct(field: str, value: Any, members: dict[str, str], type_name: str) -> dict[str, Any]:
    """A structure given as a JSON object: known members only, each coerced to its type (enumerators by name)."""
    if not isinstance(value, dict):
        raise FBInputError(field, f"expected a {type_name} structure (JSON object), got {value!r}")
    out: dict[str, Any] = {}
    for k, v in value.items():
        t = members.get(k)
        if t is None:
            raise FBInputError(field, f"{type_name} has no member {k!r} (members: {', '.join(members)})")
        out[k] = Var(f"{field}.{k}", t).coerce(v)
    return out


class FBInputError(ValueError):
    """An input value has the wrong type for its variable; `field` names the variable."""

    def __init__(self, field: str, message: str) -> None:
        super().__init__(f"{field}: {message}")
        self.field = field
        self.message = message


@dataclass(frozen=True)
class Var:
    name: str
    type: str  # BOOL, LREAL, UINT, WORD, an _eMC_ enumeration, or _sAXIS_REF for in-outs
    default: Any = None
    description: str = ""
    unit: str | None = None
    valid: str | None = None  # the manual's "valid range" column, as text
    allowed: tuple[int, ...] | None = None  # enumerators valid for this instruction (others → the manual's ErrorID)
    dead_man: bool = False  # Execute/Enable-type input that a lease drops to FALSE

    @property
    def enum(self) -> type[enum.IntEnum] | None:
        return ENUMS.get(self.type)

    def coerce(self, value: Any) -> Any:
        """Convert a JSON value to the variable's Python value or raise FBInputError."""
        t = self.type
        if t == "BOOL":
            if isinstance(value, bool):
                return value
            if isinstance(value, int) and value in (0, 1):
                return bool(value)
            raise FBInputError(self.name, f"expected a BOOL (true/false), got {value!r}")
        if t in ("LREAL", "REAL"):
            if isinstance(value, bool) or not isinstance(value, int | float):
                raise FBInputError(self.name, f"expected a number ({t}), got {value!r}")
            v = float(value)
            if not math.isfinite(v):
                raise FBInputError(self.name, f"expected a finite number ({t}), got {value!r}")
            return v
        if t in INT_RANGES:
            lo, hi = INT_RANGES[t]
            if (isinstance(value, bool) or not isinstance(value, int | float)
                    or (isinstance(value, float) and not value.is_integer())):  # (NaN and ±inf are not integers)
                raise FBInputError(self.name, f"expected an integer ({t}), got {value!r}")
            v = int(value)
            if not lo <= v <= hi:
                raise FBInputError(self.name, f"{v} is outside the {t} range {lo}…{hi}")
            return v
        en = self.enum
        if en is not None:
            # Names must exist; any INT number is passed on so the instruction can answer with the manual's ErrorID
            # for an out-of-range enumerator (e.g. 542B for BufferMode), as the controller does.
            if isinstance(value, str):
                if value in en.__members__:
                    return int(en[value])
                if value.lstrip("-").isascii() and value.lstrip("-").isdigit():  # ('²'.isdigit() is True)
                    value = int(value)
                else:
                    raise FBInputError(self.name, f"{value!r} is not an enumerator of {t}; use one of "
                                       + ", ".join(m.name for m in en))
            if isinstance(value, bool) or not isinstance(value, int):
                raise FBInputError(self.name, f"expected an enumerator name or number of {t}, got {value!r}")
            if not -32768 <= value <= 32767:
                raise FBInputError(self.name, f"{value} is outside the INT range of an enumeration")
            return value
        if t in ("_sAXIS_REF", "_sGROUP_REF", "_sMC_CAM_REF"):
            if not isinstance(value, str) or not value:
                what = "a cam data variable (cam table)" if t == "_sMC_CAM_REF" else "an axis variable"
                raise FBInputError(self.name, f"expected the name of {what}, got {value!r}")
            return value
        if t.startswith("ARRAY["):  # ARRAY[0..N] OF LREAL/UINT: a JSON list, missing elements take the default 0
            return coerce_array(self.name, t, value)
        if t == "ANY_NUM":  # MC_Write SettingValue: a number or an enumerator name, checked by the instruction
            if isinstance(value, bool) or not isinstance(value, int | float | str):
                raise FBInputError(self.name, f"expected a number or an enumerator name, got {value!r}")
            if isinstance(value, float) and not math.isfinite(value):
                raise FBInputError(self.name, f"expected a finite number, got {value!r}")
            return value
        if t == "_sMC_CAM_PROPERTY":
            return _coerce_struct(self.name, value, CAM_PROPERTY_MEMBERS, t)
        if t == "ARRAY OF _sMC_CAM_NODE":
            if not isinstance(value, list) or not 1 <= len(value) <= MAX_CAM_NODES:
                raise FBInputError(self.name, f"expected an array of 1 … {MAX_CAM_NODES} _sMC_CAM_NODE structures")
            return [_coerce_struct(f"{self.name}[{k}]", item, CAM_NODE_MEMBERS, "_sMC_CAM_NODE")
                    for k, item in enumerate(value)]
        if t in STRUCT_TYPES:
            # a structure variable: a JSON object; members are checked by the instruction (manual ErrorIDs)
            if not isinstance(value, dict):
                raise FBInputError(self.name, f"expected a {t} structure (JSON object), got {value!r}")
            unknown = sorted(set(value) - STRUCT_MEMBERS[t])
            if unknown:
                raise FBInputError(self.name, f"{t} has no member {unknown[0]!r} (members: "
                                              f"{', '.join(sorted(STRUCT_MEMBERS[t]))})")
            for k, v in value.items():
                if isinstance(v, float) and not math.isfinite(v):
                    raise FBInputError(self.name, f"member {k} must be a finite number")
            return dict(value)
        raise FBInputError(self.name, f"unsupported data type {t}")

    def present(self, value: Any) -> Any:
        """Python value → JSON value (enumerations as their names when valid)."""
        en = self.enum
        if en is not None and isinstance(value, int):
            try:
                return en(value).name
            except ValueError:
                return value
        if self.type == "WORD" and isinstance(value, int):
            return f"{value:04X}"
        return value

    def catalog(self) -> dict[str, Any]:
        en = self.enum
        out: dict[str, Any] = {
            "name": self.name,
            "type": self.type,
            "default": self.present(self.default),
            "description": self.description,
            "unit": self.unit,
            "valid": self.valid,
        }
        if en is not None:
            out["enumerators"] = [
                {"name": m.name, "value": int(m)} for m in en if self.allowed is None or int(m) in self.allowed
            ]
        return out


def coerce_array(name: str, t: str, value: Any) -> list[Any]:
    """`ARRAY[0..N] OF LREAL` / `OF UINT` (the group instructions' Position, AuxPoint, CircAxes …)."""
    bounds, _, elem = t[len("ARRAY["):].partition("] OF ")
    size = int(bounds.split("..")[1]) + 1
    if not isinstance(value, list | tuple) or len(value) > size:
        raise FBInputError(name, f"expected a list of at most {size} numbers ({t}), got {value!r}")
    item = Var(name, elem)
    out = [item.coerce(v) for v in value]
    out.extend([0.0 if elem == "LREAL" else 0] * (size - len(out)))
    return out


@dataclass(frozen=True)
class FBDef:
    name: str
    title: str
    summary: str
    kind: str  # "execute" | "enable"
    inputs: tuple[Var, ...]
    outputs: tuple[Var, ...]
    inouts: tuple[Var, ...] = ()
    spec: str = ""  # where the behaviour is specified
    status: str = "complete"
    notes: str = ""
    by_name: dict[str, Var] = field(default_factory=dict, compare=False)

    def __post_init__(self) -> None:
        for v in (*self.inouts, *self.inputs):
            self.by_name[v.name] = v

    def catalog(self) -> dict[str, Any]:
        return {
            "name": self.name,
            "title": self.title,
            "summary": self.summary,
            "kind": self.kind,
            "inputs": [v.catalog() for v in self.inputs],
            "outputs": [v.catalog() for v in self.outputs],
            "inouts": [v.catalog() for v in self.inouts],
            "spec": self.spec,
            "status": self.status,
            "notes": self.notes,
        }


# Output variables shared by most instructions
O_DONE = Var("Done", "BOOL", False, "TRUE when the instruction completes")
O_BUSY = Var("Busy", "BOOL", False, "TRUE once the instruction is acknowledged")
O_ACTIVE = Var("Active", "BOOL", False, "TRUE while the instruction is controlling the axis")
O_ABORTED = Var("CommandAborted", "BOOL", False, "TRUE when the instruction was aborted or could not start")
O_ERROR = Var("Error", "BOOL", False, "TRUE while an error exists; cleared by an error reset")
O_ERRORID = Var("ErrorID", "WORD", 0, "Error code (16#0000 = normal)")
IO_AXIS = Var("Axis", "_sAXIS_REF", None, "Axis (name of the axis variable, e.g. MC_Axis000)")
I_EXECUTE = Var("Execute", "BOOL", False, "The instruction starts on the rising edge", dead_man=True)


class FunctionBlock:
    """Base of all instruction instances. Inputs and outputs are also readable/writable as attributes."""

    DEF: ClassVar[FBDef]

    def __init__(self, mc: MotionModule, fb_id: int, inputs: dict[str, Any] | None = None) -> None:
        object.__setattr__(self, "_ready", False)
        # a settled instance sleeps: the kernel skips its calls until an input, its job or its axis wakes it
        self._asleep = False
        self._order = 0  # position in the program's call order (kept by the kernel)
        self.mc = mc
        self.id = fb_id
        self.inp: dict[str, Any] = {v.name: v.default for v in (*self.DEF.inouts, *self.DEF.inputs)}
        self.out: dict[str, Any] = {v.name: v.default for v in self.DEF.outputs}
        self._err_axis: Axis | None = None
        self._err_gen = 0
        if inputs:
            self.set_inputs(inputs)
        object.__setattr__(self, "_ready", True)

    # -- handle-style access (viser convention): fb.Execute = True; fb.Done
    def __getattr__(self, name: str) -> Any:
        d = self.__dict__
        if "inp" in d and name in d["inp"]:
            return d["inp"][name]
        if "out" in d and name in d["out"]:
            return d["out"][name]
        raise AttributeError(name)

    def __setattr__(self, name: str, value: Any) -> None:
        if self.__dict__.get("_ready") and name in self.DEF.by_name:
            self.set_inputs({name: value})
        else:
            object.__setattr__(self, name, value)

    def set_inputs(self, values: dict[str, Any]) -> None:
        coerced = {}
        for k, v in values.items():
            var = self.DEF.by_name.get(k)
            if var is None:
                raise FBInputError(k, f"{self.DEF.name} has no input or in-out named {k!r}")
            coerced[k] = var.coerce(v)
        self.inp.update(coerced)
        self.wake()

    def wake(self) -> None:
        """Call this instance again from the next call of the program on (something its call reads changed)."""
        self.__dict__["_asleep"] = False
        mc = self.mc
        mc.fb_touched.add(self.id)
        mc.fb_wakes += 1

    def sleep(self) -> None:
        """The instance's call would change nothing until one of its inputs, its job or its axis changes: the kernel
        skips it until `wake`. Only instances whose wake-up sources are all hooked may sleep (ExecuteFB without per-call
        hooks, MC_Power). `fb_touched` tells the snapshot which sleeping instances may have changed since it was
        last published."""
        self.__dict__["_asleep"] = True
        self.mc.fb_touched.add(self.id)

    def on_delete(self) -> None:
        """The instance is removed from the program (release what it holds, e.g. a latch)."""

    def drop_dead_man(self) -> None:
        for v in self.DEF.inputs:
            if v.dead_man:
                self.inp[v.name] = False
        self.wake()

    @property
    def label(self) -> str:
        return f"fb {self.id} {self.DEF.name}"

    def outputs_json(self) -> dict[str, Any]:
        return {v.name: v.present(self.out[v.name]) for v in self.DEF.outputs}

    def inputs_json(self) -> dict[str, Any]:
        defs = self.DEF.by_name
        return {k: defs[k].present(v) for k, v in self.inp.items()}

    def resolve_axis(self, name_input: str = "Axis", *, allow_unused: bool = False) -> Axis | None:
        """The axis named by an in-out; an unused axis counts as no axis (5460) except where the instruction works
        on unused axes (MC_ChangeAxisUse, MC_WriteAxisParameter, MC_ReadAxisParameter)."""
        axis = self.mc.by_name.get(self.inp.get(name_input) or "")
        if axis is not None and not axis.used and not allow_unused:
            return None
        return axis

    # -- error latch: Error stays TRUE until the axis error is reset (or, without an axis, a common reset)
    def _set_error(self, code: int, axis: Axis | None) -> None:
        self.wake()
        o = self.out
        o["Error"] = True
        o["ErrorID"] = code
        for k in ("Busy", "Active", "Done", "CommandAborted", "Status", "InVelocity"):
            if k in o:
                o[k] = False
        self._err_axis = axis
        self._err_gen = axis.reset_generation if axis is not None else self.mc.common_reset_generation

    def _error_released(self) -> bool:
        ax = self._err_axis
        if ax is None:  # MC common source: released by ResetMCError
            return self.mc.common_reset_generation != self._err_gen
        return ax.reset_generation != self._err_gen

    def fail(self, code: int, axis: Axis | None, *, fault_axis: bool = True) -> None:
        """The instruction ends in Error with `code`; the axis gets the minor fault (A-1 source Axis)."""
        if code == E_COORDINATED and axis is not None and getattr(axis, "group", None) is not None:
            # 543E on a Coordinated axis is the group's error: the group decelerates to a stop and the axis stays
            # Coordinated (A-3.4 column I → group e; A-1 #31; decision D70). MC_GroupReset releases the outputs.
            grp = axis.group
            self._set_error(code, grp)  # type: ignore[arg-type]
            grp.raise_error(code, source=self.label)
            return
        self._set_error(code, axis)
        if axis is not None and fault_axis:
            axis.raise_error(code, source=self.label)
        elif axis is None:
            self.mc.log_error(code, axis=None, source=self.label)

    def call(self) -> None:  # pragma: no cover - abstract
        raise NotImplementedError

    # -- fault containment (decision D120): an exception inside one instance's call must not stop the kernel
    def contain(self, exc: BaseException) -> None:
        """The kernel caught `exc` from this instance's call: Error TRUE with ErrorID FFFF (emulator-internal, D15),
        an FFFF0000 event naming the instance and the exception, the axis (or axes group) it commands error-stopped
        like any instruction error (A-1: deceleration stop), and the instance quarantined — not called again until
        that error is reset (MC_Reset / MC_GroupReset, or ResetMCError without an axis)."""
        from ..module import E_INTERNAL  # (module imports the instructions)

        _log.error("%s raised in its call; contained (D120)", self.label, exc_info=exc)
        detail = f"{type(exc).__name__}: {exc}"[:500]
        d = self.__dict__
        target: Any = None
        try:  # what the instance commands: its axes group, else its (slave) axis
            inp = self.inp
            target = self.mc.groups_by_name.get(inp.get("AxesGroup") or "") or d.get("axis")
            for name in ("Slave", "Axis", "Target"):
                if target is None and isinstance(inp.get(name), str):
                    target = self.mc.by_name.get(inp[name])
        except Exception:  # the instance's own state may be what is broken
            target = None
        try:
            self._set_error(E_INTERNAL, target)
            if target is not None:
                target.raise_error(E_INTERNAL, source=self.label, detail=detail)
            else:
                self.mc.log_error(E_INTERNAL, axis=None, source=self.label, detail=detail)
        except Exception:  # never let containment itself take the kernel down
            _log.exception("containment of %s failed", self.label)
            self.out["Error"], self.out["ErrorID"] = True, E_INTERNAL
        if "job" in d:
            d["job"] = None
        d["call"] = self._quarantined  # an instance attribute shadows the class's call()

    def _quarantined(self) -> None:
        """The call of a contained instance: nothing until its error is reset, then the normal call again (a new
        Execute edge is needed, as after any instruction error)."""
        if not self._error_released():
            return
        del self.__dict__["call"]
        o = self.out
        o["Error"], o["ErrorID"] = False, 0
        self.wake()


_log = logging.getLogger(__name__)


class ExecuteFB(FunctionBlock):
    """Execute-type instruction with a motion job: Busy/Active/Done/CommandAborted/Error timing."""

    HAS_ACTIVE: ClassVar[bool] = True
    _plain: ClassVar[bool] = True  # no per-call hooks (sync_job/after_call/call overridden): calls may be skipped

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        cls._plain = all(getattr(cls, name) is getattr(ExecuteFB, name) for name in ("sync_job", "after_call", "call"))

    def __init__(self, mc: MotionModule, fb_id: int, inputs: dict[str, Any] | None = None) -> None:
        super().__init__(mc, fb_id, inputs)
        self._prev_exe = False
        self._steady = False
        self._seen_status: JobStatus | None = None
        self._seen_inv = False
        self._end_cycle = -1
        self.job: Job | None = None
        self.axis: Axis | None = None

    # subclasses implement these
    def execute(self, axis: Axis) -> None:
        raise NotImplementedError

    def reexecute(self, axis: Axis) -> None:
        self.fail(E_REEXEC_DISABLED, axis)

    def on_job_end(self) -> None:
        """Hook after the job ended (e.g. MC_Stop releases the Stopping hold)."""

    def _finish(self, flag: str) -> None:
        self.wake()
        o = self.out
        o["Busy"] = False
        if "Active" in o:
            o["Active"] = False
        if "InVelocity" in o:
            o["InVelocity"] = False
        o[flag] = True
        self._end_cycle = self.mc.cycle

    def sync_job(self) -> None:
        """Read the job's progress (the MC module's processing of the previous period)."""
        job = self.job
        if job is None:
            return
        st = job.status
        o = self.out
        if st == JobStatus.ACTIVE:
            if self.HAS_ACTIVE:
                o["Active"] = True
            if "InVelocity" in o:
                o["InVelocity"] = job.in_velocity
        elif st == JobStatus.DONE:
            self.job = None
            self._finish("Done")
            self.on_job_end()
        elif st == JobStatus.ABORTED:
            self.job = None
            self._finish("CommandAborted")
            self.on_job_end()
        elif st == JobStatus.ERROR:
            self.job = None
            self._set_error(job.error_id, self.axis)
            self.on_job_end()

    def call(self) -> None:
        o = self.out
        exe = bool(self.inp["Execute"])
        d = self.__dict__
        if exe is d["_prev_exe"] and self._plain and not o["Error"]:
            # Execute unchanged and no per-call hooks: the call changes nothing while the instance is settled
            # (finished or never started) or while its job reports what it reported at the last call
            job = d["job"]
            if job is None:
                if d["_steady"]:
                    self.sleep()
                    return
            elif job.status is d["_seen_status"] and job.in_velocity == d["_seen_inv"]:
                self.sleep()  # woken by a change of the job's status or InVelocity
                return
        edge = exe and not self._prev_exe
        d["_prev_exe"] = exe  # (hot path: bypasses FunctionBlock.__setattr__)
        self._call(o, exe, edge)
        job = d["job"]
        if job is not None:
            d["_seen_status"], d["_seen_inv"] = job.status, job.in_velocity
            d["_steady"] = False
        else:
            d["_seen_status"] = None
            # settled: no Busy, no error to release, completion flags held (Execute TRUE) or cleared
            d["_steady"] = (not o["Busy"] and not o["Error"]
                            and (exe or not (o.get("Done") or o.get("CommandAborted") or o.get("Failure"))))

    def _call(self, o: dict[str, Any], exe: bool, edge: bool) -> None:
        if o["Error"] and self._error_released():
            o["Error"] = False
            o["ErrorID"] = 0
        if not exe and self._end_cycle < self.mc.cycle:
            # completion flags: held while Execute is TRUE, one period only if it was already FALSE
            for k in ("Done", "CommandAborted", "Failure"):
                if k in o:
                    o[k] = False
        self.sync_job()
        if edge and not o["Error"]:
            if o["Busy"]:
                axis = self.resolve_axis()
                if axis is not self.axis:
                    self.fail(0x5453 if axis is not None else E_ILLEGAL_AXIS, self.axis)
                    return
                self.reexecute(self.axis)  # type: ignore[arg-type]
                return
            for k in ("Done", "CommandAborted", "Failure"):
                if k in o:
                    o[k] = False
            axis = self.resolve_axis()
            self.axis = axis
            if axis is None:
                self.fail(E_ILLEGAL_AXIS, None)
                return
            o["Busy"] = True
            self.execute(axis)
        self.after_call(exe)

    def after_call(self, exe: bool) -> None:
        """Hook for per-call work of running instructions (e.g. MC_Stop's Stopping hold)."""

    # helpers for subclasses
    def start_job(self, axis: Axis, job: Job) -> None:
        """Submit a motion job with the manual's acceptance rules; sets outputs for refusals."""
        verdict, code = axis.check_start("move")
        self._submit(axis, job, verdict, code)

    def _submit(self, axis: Axis, job: Job, verdict: str, code: int) -> None:
        if verdict == "abort":
            self._finish("CommandAborted")
            return
        if verdict == "error":
            self.fail(code, axis)
            return
        err = axis.submit(job)
        if err:
            self.fail(err, axis)
            return
        self.job = job


class OneShotFB(ExecuteFB):
    """Execute-type instruction completed by its own call, without a motion job: its end flag (Done, or Failure for
    MC_Reset) shows in the next period, as the manual's charts draw it."""

    HAS_ACTIVE = False
    _result: str | None = None

    def done_next(self, flag: str = "Done") -> None:
        self._result = flag

    def sync_job(self) -> None:
        if self._result:
            flag, self._result = self._result, None
            self._finish(flag)
