"""Time-stamp instructions: MC_TimeStampToPos and MC_DigitalCamSwitch (`omron-axis-instructions.md`, seed 000 lines
12897–13983).

On the NX the time stamp of an axis is the time its position was latched by a time-stamp-capable encoder input unit
(object 6010h, DC enabled). The emulated devices sample their positions at the distributed-clock Sync0 event of each
period, so every axis on the emulated bus has a time stamp: DC time = period number × primary period [ns] (decision
D48). Virtual axes have none (their instructions give 543D).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

from .. import errors as E
from .admin import I_ENABLE, O_ENABLED, _EnableFB
from .base import IO_AXIS, O_BUSY, O_ERROR, O_ERRORID, FBDef, FBInputError, Var

if TYPE_CHECKING:
    from ..axis import Axis

MAX_SWITCHES = 256
MAX_TRACKS = 16
MAX_EDGES = 16  # OnTime/OffTime: ARRAY[0..15] OF ULINT


def axis_time_stamp(axis: Axis) -> int | None:
    """Act.TimeStamp [ns]: the DC time of this period's position sample; None for an axis without a device."""
    m = axis.m
    if not m.on_bus[axis.i]:
        return None
    return round(m.cycle * m.period_s * 1e9)


class _TimeStampFB(_EnableFB):
    def _axis(self) -> tuple[Axis | None, bool]:
        """(axis, ready): an unused axis (or none) gives Busy without Enabled or Error (the manual's rule)."""
        axis = self.mc.by_name.get(self.inp.get("Axis") or "")
        if axis is None or not axis.used:
            self.out["Busy"] = True
            if "Enabled" in self.out:
                self.out["Enabled"] = False
            return None, False
        if axis_time_stamp(axis) is None:
            self.fail(E.E_AXIS_TYPE, axis)  # no time-stamped position (a virtual axis), D48
            return None, False
        return axis, True


class MC_TimeStampToPos(_TimeStampFB):
    DEF = FBDef(
        name="MC_TimeStampToPos",
        title="Time stamp to axis position calculation",
        summary="The axis position at a time stamp, from the feedback position, velocity and time stamp of the axis.",
        kind="enable",
        inouts=(IO_AXIS,),
        inputs=(I_ENABLE, Var("TimeStamp", "ULINT", 0, "Time stamp [ns] (DC time) to compute the position for", "ns",
                              "positive or 0")),
        outputs=(O_ENABLED, O_BUSY, Var("CalcPosition", "LREAL", 0.0, "Feedback position at TimeStamp", "unit"),
                 O_ERROR, O_ERRORID),
        spec="omron-axis-instructions.md MC_TimeStampToPos (seed 000 line 13539)",
        notes="Every axis on the emulated bus has a time stamp (D48); accurate at constant velocity.",
    )

    def enabled(self, changed: bool) -> None:
        axis, ready = self._axis()
        if not ready or axis is None:
            return
        ts = axis_time_stamp(axis)
        assert ts is not None
        m, i = axis.m, axis.i
        pos = m.act_pos.item(i) + m.act_vel.item(i) * (self.inp["TimeStamp"] - ts) * 1e-9
        self.out["CalcPosition"] = axis.wrap(pos) if axis.rotary else pos
        self.out["Enabled"] = True


SWITCH_MEMBERS = {"TrackNumber": "UINT", "FirstOnPosition": "LREAL", "LastOnPosition": "LREAL",
                  "AxisDirection": "_eMC_DIRECTION", "CamSwitchMode": "_eMC_SWITCH_MODE", "Duration": "LREAL"}
TRACK_MEMBERS = {"OnCompensation": "LREAL", "OffCompensation": "LREAL"}


def _structs(field: str, value: Any, members: dict[str, str], limit: int) -> list[dict[str, Any]]:
    if not isinstance(value, list) or len(value) > limit:
        raise FBInputError(field, f"expected an array of at most {limit} structures")
    out = []
    for k, item in enumerate(value):
        if not isinstance(item, dict):
            raise FBInputError(f"{field}[{k}]", f"expected a structure (JSON object), got {item!r}")
        row: dict[str, Any] = {}
        for name, v in item.items():
            t = members.get(name)
            if t is None:
                raise FBInputError(f"{field}[{k}]", f"no member {name!r} (members: {', '.join(members)})")
            row[name] = Var(f"{field}[{k}].{name}", t).coerce(v)
        out.append(row)
    return out


class _SwitchArray(Var):
    def coerce(self, value: Any) -> Any:
        return _structs(self.name, value, SWITCH_MEMBERS, MAX_SWITCHES)


class _TrackArray(Var):
    def coerce(self, value: Any) -> Any:
        return _structs(self.name, value, TRACK_MEMBERS, MAX_TRACKS)


class MC_DigitalCamSwitch(_TimeStampFB):
    DEF = FBDef(
        name="MC_DigitalCamSwitch",
        title="Enable digital cam switch",
        summary="Computes, per track, the time stamps at which its outputs turn ON and OFF from the axis feedback "
                "position and velocity (position-based or time-based switches, direction, compensation).",
        kind="enable",
        inouts=(
            IO_AXIS,
            _SwitchArray("Switches", "ARRAY OF _sCAMSWITCH_REF", [], "Switch patterns (≤ 256): TrackNumber, "
                         "FirstOnPosition, LastOnPosition, AxisDirection, CamSwitchMode, Duration [ms]"),
            _TrackArray("TrackOptions", "ARRAY OF _sTRACK_REF", [], "Per track: OnCompensation, OffCompensation [ms] "
                        "(−1000 … 1000)"),
        ),
        inputs=(I_ENABLE, Var("EnableMask", "WORD", 0, "Track n enabled when bit n is 1", None, "16#0000–FFFF")),
        outputs=(
            Var("InOperation", "BOOL", False, "TRUE while valid output timings are produced"),
            O_BUSY,
            Var("Outputs", "ARRAY OF _sOUTPUT_REF", [], "Per track: EnableOut, OnTime[0..15], OffTime[0..15] [ns] "
                "of the switchings in the coming period (0 = none)"),
            Var("TrackState", "WORD", 0, "MC Studio: bit n = track n's output is ON at the current position"),
            O_ERROR, O_ERRORID,
        ),
        spec="omron-axis-instructions.md MC_DigitalCamSwitch (seed 000 line 12897)",
        notes="Outputs is an in-out on the controller; MC Studio returns it as an output. TIME values in ms. D48.",
    )

    def enabled(self, changed: bool) -> None:
        axis, ready = self._axis()
        if not ready or axis is None:
            self.out["InOperation"] = False
            return
        ts = axis_time_stamp(axis)
        assert ts is not None
        m, i = axis.m, axis.i
        pos = m.act_pos.item(i)
        vel = m.act_vel.item(i)
        period_ns = m.period_s * 1e9
        tracks = max(len(self.inp["TrackOptions"]), 1 + max((s.get("TrackNumber", 0) for s in self.inp["Switches"]),
                                                            default=-1))
        tracks = min(max(tracks, 1), MAX_TRACKS)
        options = self.inp["TrackOptions"]
        mask = self.inp["EnableMask"]
        outputs = []
        state = 0
        in_operation = True
        for t in range(tracks):
            opt = options[t] if t < len(options) else {}
            on_c = float(opt.get("OnCompensation", 0.0)) * 1e6
            off_c = float(opt.get("OffCompensation", 0.0)) * 1e6
            enable_out = bool(mask >> t & 1)
            if axis.rotary and vel != 0:
                half_turn_ns = (axis.mod_max - axis.mod_min) / 2 / abs(vel) * 1e9
                if abs(on_c) > half_turn_ns or abs(off_c) > half_turn_ns:
                    enable_out = False  # compensation beyond half a revolution (CPU ≥ 1.09 rule)
                    in_operation = False
            on_times: list[int] = []
            off_times: list[int] = []
            for sw in self.inp["Switches"]:
                if sw.get("TrackNumber", 0) != t or not enable_out:
                    continue
                mode = sw.get("CamSwitchMode", 0)
                if mode == 0:
                    continue
                d = sw.get("AxisDirection", 0)
                if (d == 0 and vel < 0) or (d == 2 and vel > 0):
                    continue
                first = sw.get("FirstOnPosition", 0.0)
                last = sw.get("LastOnPosition", 0.0) if mode == 1 else None
                if self._inside(axis, pos, first, last, sw, vel):
                    state |= 1 << t
                if vel == 0:
                    continue
                t_on = self._crossing(axis, pos, vel, first)
                if t_on is not None:
                    on_times.append(ts + int(t_on * 1e9 + on_c))
                if mode == 1 and last is not None:
                    t_off = self._crossing(axis, pos, vel, last)
                    if t_off is not None:
                        off_times.append(ts + int(t_off * 1e9 + off_c))
                elif mode == 2 and t_on is not None:
                    off_times.append(ts + int(t_on * 1e9 + on_c + float(sw.get("Duration", 0.0)) * 1e6))
            window_end = ts + period_ns
            on_times = sorted(x for x in on_times if ts <= x < window_end + period_ns)[:MAX_EDGES]
            off_times = sorted(x for x in off_times if ts <= x < window_end + period_ns)[:MAX_EDGES]
            outputs.append({"EnableOut": enable_out, "OnTime": on_times + [0] * (MAX_EDGES - len(on_times)),
                            "OffTime": off_times + [0] * (MAX_EDGES - len(off_times))})
        self.out["Outputs"] = outputs
        self.out["TrackState"] = state
        self.out["InOperation"] = in_operation

    @staticmethod
    def _crossing(axis: Axis, pos: float, vel: float, target: float) -> float | None:
        """Seconds until the feedback position reaches `target` at the current velocity (rotary: the next time
        round the ring); None if it moves away (linear)."""
        d = target - pos
        if axis.rotary:
            ring = axis.mod_max - axis.mod_min
            d = d % ring if vel > 0 else -((-d) % ring)
        t = d / vel
        return t if t >= 0 and math.isfinite(t) else None

    @staticmethod
    def _inside(axis: Axis, pos: float, first: float, last: float | None, sw: dict[str, Any], vel: float) -> bool:
        if last is None:  # time based: ON from FirstOnPosition for Duration — ON while within Duration of travel
            dur = float(sw.get("Duration", 0.0)) * 1e-3
            span = abs(vel) * dur
            last = first + span if vel >= 0 else first - span
            first, last = (first, last) if vel >= 0 else (last, first)
        if axis.rotary:
            ring = axis.mod_max - axis.mod_min
            p = (pos - first) % ring
            return p <= (last - first) % ring
        return first <= pos <= last

    def disable(self) -> None:
        self.out["InOperation"] = False


TIMESTAMP_CLASSES = (MC_TimeStampToPos, MC_DigitalCamSwitch)
