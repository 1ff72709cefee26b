"""MC_Home and MC_HomeWithParameter (`omron-axis-instructions.md`, seed 000 lines 2713 and 3229)."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

from .. import errors as E
from ..enums import _eMC_DIRECTION, _eMC_HOME_INPUT, _eMC_HOMING_MODE, _eMC_LIMIT_REVERSE_MODE
from ..homing import Homing, HomingParams, params_from_axis
from ..jobs import Job, JobKind
from ..units import fits_distance, fits_position
from .base import I_EXECUTE, IO_AXIS, O_ABORTED, O_BUSY, O_DONE, O_ERROR, O_ERRORID, ExecuteFB, FBDef, Var

if TYPE_CHECKING:
    from ..axis import Axis

_OUTPUTS = (O_DONE, O_BUSY, O_ABORTED, O_ERROR, O_ERRORID)
# modes that use no latch (11 limit inputs only, 12 holding time, 14 preset) need no touch-probe objects (3461)
_NO_LATCH_MODES = (11, 12, 14)
_HOMING_LATCH_PDO = (0x60B8, 0x60B9, 0x60BA)
_M = _eMC_HOMING_MODE
# members of _sHOMING_REF with their 5700 detail code and default
HOMING_REF_MEMBERS: tuple[tuple[str, int, Any], ...] = (
    ("HomingMode", 1, "_mcHomeSwTurnHomeSwOff"),
    ("HomeInput", 2, "_mcZPhase"),
    ("StartDir", 3, "_mcPositiveDirection"),
    ("HomeDir", 4, "_mcPositiveDirection"),
    ("PosiLmtMode", 5, "_mcErrorStop"),
    ("NegaLmtMode", 6, "_mcErrorStop"),
    ("Vel", 7, 0.0),
    ("ApproachVel", 8, 0.0),
    ("Acc", 9, 0.0),
    ("Dec", 10, 0.0),
    ("Jerk", 11, 0.0),
    ("Mask", 12, 0.0),
    ("Offset", 13, 0.0),
    ("PushTime", 14, 0),
    ("Compensation", 15, 0.0),
    ("CompensationVel", 16, 0.0),
)


def _enum(cls: Any, value: Any, allowed: tuple[int, ...] | None = None) -> int | None:
    if isinstance(value, str) and value in cls.__members__:
        v = int(cls[value])
    elif isinstance(value, int) and not isinstance(value, bool):
        v = value
    else:
        return None
    if v not in [int(m) for m in cls] or (allowed is not None and v not in allowed):
        return None
    return v


def parse_homing_ref(ref: dict[str, Any], axis: Axis) -> tuple[HomingParams | None, int, str]:
    """`_sHOMING_REF` → parameters, or (None, detail code, message) for error 5700. Members the selected mode does
    not use are not checked (MC_HomeWithParameter rules)."""
    unknown = set(ref) - {n for n, _, _ in HOMING_REF_MEMBERS}
    if unknown:
        return None, 0, f"unknown member(s) {', '.join(sorted(unknown))}"
    r = {n: ref.get(n, d) for n, _, d in HOMING_REF_MEMBERS}
    code = {n: c for n, c, _ in HOMING_REF_MEMBERS}
    mode = _enum(_M, r["HomingMode"])
    if mode is None:
        return None, 1, "HomingMode out of range"
    home_input = _enum(_eMC_HOME_INPUT, r["HomeInput"])
    start = _enum(_eMC_DIRECTION, r["StartDir"], (0, 2))
    home_dir = _enum(_eMC_DIRECTION, r["HomeDir"], (0, 2))
    posi = _enum(_eMC_LIMIT_REVERSE_MODE, r["PosiLmtMode"])
    nega = _enum(_eMC_LIMIT_REVERSE_MODE, r["NegaLmtMode"])
    for name, v in (("HomeInput", home_input), ("StartDir", start), ("HomeDir", home_dir),
                    ("PosiLmtMode", posi), ("NegaLmtMode", nega)):
        if v is None and mode != _M._mcHomePreset:
            return None, code[name], f"{name} out of range"

    def num(name: str) -> float | None:
        v = r[name]
        if isinstance(v, bool) or not isinstance(v, int | float) or not math.isfinite(float(v)):
            return None
        return float(v)

    vals = {n: num(n) for n in ("Vel", "ApproachVel", "Acc", "Dec", "Jerk", "Mask", "Offset", "PushTime",
                                "Compensation", "CompensationVel")}
    used = set(vals) if mode != _M._mcHomePreset else {"Offset"}
    if mode != _M._mcHomeSwTurnHomeMask:
        used.discard("Mask")
    if mode != _M._mcHomeSwTurnHoldingTime:
        used.discard("PushTime")
    positive = {"Vel", "ApproachVel", "CompensationVel"}
    non_negative = {"Acc", "Dec", "Jerk", "Mask"}
    for name in sorted(used, key=lambda n: code[n]):
        v = vals[name]
        if v is None or (name in positive and not v > 0) or (name in non_negative and v < 0) or \
                (name == "PushTime" and not (0 <= v <= 10000 and float(v).is_integer())):
            return None, code[name], f"{name} out of range"
    op = axis.params.Operation
    ppu = axis.ppu
    if mode != _M._mcHomePreset:
        assert vals["Vel"] is not None and vals["ApproachVel"] is not None
        if "Mask" in used and not fits_distance(vals["Mask"] or 0.0, ppu):
            return None, 100, "home input mask distance exceeds 40 bits in pulses"
        if "Mask" in used and axis.rotary and (vals["Mask"] or 0.0) > axis.mod_max - axis.mod_min:
            return None, 101, "home input mask distance exceeds the ring length"
        comp = vals["Compensation"] or 0.0
        if not fits_distance(comp, ppu):
            return None, 102, "homing compensation value exceeds 40 bits in pulses"
        if axis.rotary and abs(comp) > axis.mod_max - axis.mod_min:
            return None, 103, "homing compensation value exceeds the ring length"
    offset = vals["Offset"] or 0.0
    if not fits_position(offset, ppu):
        return None, 104, "home offset exceeds 40 bits in pulses"
    if axis.rotary and not axis.mod_min <= offset < axis.mod_max:
        return None, 105, "home offset outside the ring counter range"
    if mode != _M._mcHomePreset:
        if vals["Vel"] > op.MaxVel:  # type: ignore[operator]
            return None, 106, "homing velocity exceeds the maximum velocity"
        if vals["ApproachVel"] > op.MaxVel:  # type: ignore[operator]
            return None, 107, "approach velocity exceeds the maximum velocity"
        if not vals["ApproachVel"] <= vals["Vel"]:  # type: ignore[operator]
            return None, 108, "approach velocity must not exceed the homing velocity"
        if not (vals["CompensationVel"] or 0.0) <= vals["Vel"]:  # type: ignore[operator]
            return None, 109, "compensation velocity must not exceed the homing velocity"
        if op.MaxAcc > 0 and (vals["Acc"] or 0.0) > op.MaxAcc:
            return None, 110, "homing acceleration exceeds the maximum acceleration"
        if op.MaxDec > 0 and (vals["Dec"] or 0.0) > op.MaxDec:
            return None, 111, "homing deceleration exceeds the maximum deceleration"

    def d(x: int | None) -> int:
        return -1 if x == _eMC_DIRECTION._mcNegativeDirection else 1

    params = HomingParams(
        mode, home_input == _eMC_HOME_INPUT._mcZPhase, d(start), d(home_dir), posi or 0, nega or 0,
        vals["Vel"] or 0.0, vals["ApproachVel"] or 0.0, vals["Acc"] or 0.0, vals["Dec"] or 0.0, vals["Jerk"] or 0.0,
        vals["Mask"] or 0.0, offset, int(vals["PushTime"] or 0), vals["Compensation"] or 0.0,
        vals["CompensationVel"] or 0.0,
    )
    return params, 0, ""


class MC_Home(ExecuteFB):
    DEF = FBDef(
        name="MC_Home",
        title="Home",
        summary="Defines home with limit, home proximity and home input signals, by the axis homing settings.",
        kind="execute",
        inouts=(IO_AXIS,),
        inputs=(I_EXECUTE,),
        outputs=_OUTPUTS,
        spec="omron-axis-instructions.md MC_Home (seed 000 line 2713)",
    )
    HAS_ACTIVE = False

    def homing_params(self, axis: Axis) -> HomingParams | None:
        return params_from_axis(axis)

    def execute(self, axis: Axis) -> None:
        verdict, code = axis.check_start("standstill_only")
        if verdict == "abort":
            self._finish("CommandAborted")
            return
        if code:
            self.fail(code, axis)
            return
        params = self.homing_params(axis)
        if params is None:
            return
        if params.mode not in _NO_LATCH_MODES and axis.pdo_missing(_HOMING_LATCH_PDO):
            self.fail(E.E_PDO_MISSING, axis)  # the latch objects are not mapped (omron-mc-basics.md §2.11)
            return
        job = Job(JobKind.HOMING, self)
        axis.abort_all()
        axis.homing = Homing(axis, job, params)
        axis._start(job)
        self.job = job


class MC_HomeWithParameter(MC_Home):
    DEF = FBDef(
        name="MC_HomeWithParameter",
        title="Home with parameters",
        summary="As MC_Home, with the homing parameters given in HomingParameter (_sHOMING_REF).",
        kind="execute",
        inouts=(IO_AXIS, Var("HomingParameter", "_sHOMING_REF", None,
                             "Homing parameters: " + ", ".join(n for n, _, _ in HOMING_REF_MEMBERS))),
        inputs=(I_EXECUTE,),
        outputs=_OUTPUTS,
        spec="omron-axis-instructions.md MC_HomeWithParameter (seed 000 line 3229)",
    )

    def homing_params(self, axis: Axis) -> HomingParams | None:
        ref = self.inp.get("HomingParameter")
        params, detail, message = parse_homing_ref(ref or {}, axis)
        if params is None:
            # an axis minor fault (A-1 #122, source Axis): MFaultLvl, ErrorStop (A-3.2 H), released by MC_Reset
            self._set_error(E.E_HOMING_PARAMETER, axis)
            axis.raise_error(E.E_HOMING_PARAMETER, source=self.label,
                             detail=f"attached information {detail}: {message}")
            return None
        return params


HOMING_CLASSES = (MC_Home, MC_HomeWithParameter)
