"""Common instructions on axis parameters: MC_Write, MC_WriteAxisParameter, MC_ReadAxisParameter
(`omron-group-and-cam.md` §5.3, §5.5, §5.6; 573B ErrorParameterCode §5.5.9)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from pydantic import ValidationError

from ....project.checks import RANGE_CODES, check_axis_parameters
from ....project.models import AxisParameters
from .. import errors as E
from ..enums import _eMC_SWLMT_MODE
from .base import I_EXECUTE, IO_AXIS, O_ABORTED, O_BUSY, O_DONE, O_ERROR, O_ERRORID, FBDef, OneShotFB, Var

if TYPE_CHECKING:
    from ..axis import Axis

_OUT = (O_DONE, O_BUSY, O_ABORTED, O_ERROR, O_ERRORID)


# ParameterNumber → (group, member, SettingValue type, check)
_WRITABLE: dict[int, tuple[str, str, str]] = {
    0: ("Operation", "VelWarningVal", "pct100"),
    1: ("Operation", "AccWarningVal", "pct100"),
    2: ("Operation", "DecWarningVal", "pct100"),
    3: ("Operation", "PosiTrqWarningVal", "pct1000"),
    4: ("Operation", "NegaTrqWarningVal", "pct1000"),
    5: ("Limit", "FollowingErrorOverVal", "positive"),
    6: ("Limit", "FollowingErrorWarningVal", "positive"),
    7: ("Limit", "SwLimitMode", "swlmt"),
    8: ("Limit", "PosiSwLimit", "any"),
    9: ("Limit", "NegaSwLimit", "any"),
    10: ("Operation", "InPosCheckTime", "ms"),
    11: ("Operation", "InPosRange", "non_negative"),
    12: ("Operation", "StartVel", "non_negative"),
}


def _setting(kind: str, value: Any) -> Any:
    """SettingValue for the parameter's type, or None when out of range or of the wrong type (544F)."""
    if kind == "swlmt":
        if isinstance(value, str) and value in _eMC_SWLMT_MODE.__members__:
            return _eMC_SWLMT_MODE[value]
        if isinstance(value, int) and not isinstance(value, bool) and 0 <= value <= 4:
            return _eMC_SWLMT_MODE(value)
        return None
    if isinstance(value, bool) or not isinstance(value, int | float):
        return None
    if kind in ("pct100", "pct1000", "ms"):
        limit = {"pct100": 100, "pct1000": 1000, "ms": 10000}[kind]
        return int(value) if float(value).is_integer() and 0 <= value <= limit else None
    v = float(value)
    if kind == "positive" and not v > 0:
        return None
    if kind == "non_negative" and not v >= 0:
        return None
    return v


class MC_Write(OneShotFB):
    DEF = FBDef(
        name="MC_Write",
        title="Write MC setting",
        summary="Overwrites one motion control parameter of an axis at run time (not saved).",
        kind="execute",
        inouts=(Var("Target", "_sAXIS_REF", None, "Axis whose parameter is written"),
                Var("SettingValue", "ANY_NUM", 0, "Value to write (type and range per ParameterNumber)")),
        inputs=(I_EXECUTE,
                Var("ParameterNumber", "_eMC_PARAMETER_NUMBER", 0, "Parameter to write", None, "0–12")),
        outputs=_OUT,
        spec="omron-group-and-cam.md §5.3 MC_Write (seed 000 line 17634)",
    )

    def resolve_axis(self, name_input: str = "Target", *, allow_unused: bool = False) -> Axis | None:
        return super().resolve_axis("Target")

    def execute(self, axis: Axis) -> None:
        num = self.inp["ParameterNumber"]
        if num not in _WRITABLE:
            self._common(E.E_PARAMETER_NUMBER)
            return
        group, member, kind = _WRITABLE[num]
        value = _setting(kind, self.inp["SettingValue"])
        if value is None:
            self._common(E.E_SETTING_VALUE)
            return
        data = axis.params.model_dump()
        data[group][member] = value
        try:
            params = AxisParameters.model_validate(data)
        except ValidationError:
            self._common(E.E_SETTING_VALUE)
            return
        if check_axis_parameters(params):
            self._common(E.E_SETTING_VALUE)  # e.g. a warning value above the over value
            return
        axis.apply_parameters(params)
        self.done_next()

    def reexecute(self, axis: Axis) -> None:
        self.execute(axis)  # re-execution uses the inputs at the new edge (§5.3)

    def _common(self, code: int) -> None:
        """MC common error (A-1 effect NOEXEC): nothing written, the axis is not affected."""
        self._set_error(code, None)
        self.mc.log_error(code, axis=None, source=self.label)


class MC_WriteAxisParameter(OneShotFB):
    DEF = FBDef(
        name="MC_WriteAxisParameter",
        title="Write axis parameters",
        summary="Writes a whole _sAXIS_PARAM to an unused axis (Read → modify → Write).",
        kind="execute",
        inouts=(IO_AXIS, Var("AxisParameter", "_sAXIS_PARAM", None, "The parameters to write")),
        inputs=(I_EXECUTE,),
        outputs=(*_OUT, Var("ErrorParameterCode", "WORD", 0, "573B detail code of the offending parameter")),
        spec="omron-group-and-cam.md §5.5 MC_WriteAxisParameter (seed 000 line 18689)",
    )

    def resolve_axis(self, name_input: str = "Axis", *, allow_unused: bool = True) -> Axis | None:
        return super().resolve_axis(name_input, allow_unused=True)

    def execute(self, axis: Axis) -> None:
        self.out["ErrorParameterCode"] = 0
        if axis.used:
            self._common(E.E_AXIS_PARAM_NOT_WRITABLE, 0)
            return
        try:
            params = AxisParameters.model_validate(self.inp["AxisParameter"] or {})
        except ValidationError as err:
            loc = err.errors()[0]["loc"]
            path = ".".join(str(x) for x in loc[:2])
            self._common(E.E_AXIS_PARAM_RANGE, RANGE_CODES.get(path, 0xFFFF), detail=f"{path}: out of range")
            return
        issues = check_axis_parameters(params)
        if issues:
            code, path, msg = issues[0]
            self._common(E.E_AXIS_PARAM_RANGE, code, detail=f"{path}: {msg}")
            return
        axis.apply_parameters(params)
        self.done_next()

    def _common(self, code: int, parameter_code: int, detail: str = "") -> None:
        self._set_error(code, None)
        self.out["ErrorParameterCode"] = parameter_code
        self.mc.log_error(code, axis=None, source=self.label,
                          detail=f"ErrorParameterCode {parameter_code:04X}" + (f" ({detail})" if detail else ""))


class MC_ReadAxisParameter(OneShotFB):
    DEF = FBDef(
        name="MC_ReadAxisParameter",
        title="Read axis parameters",
        summary="Reads the axis parameters in effect into AxisParameter (any axis use).",
        kind="execute",
        inouts=(IO_AXIS, Var("AxisParameter", "_sAXIS_PARAM", None, "Receives the parameters")),
        inputs=(I_EXECUTE,),
        outputs=_OUT,
        spec="omron-group-and-cam.md §5.6 MC_ReadAxisParameter (seed 000 line 19018)",
    )

    def resolve_axis(self, name_input: str = "Axis", *, allow_unused: bool = True) -> Axis | None:
        return super().resolve_axis(name_input, allow_unused=True)

    def execute(self, axis: Axis) -> None:
        # written once, at completion (the in-out variable then belongs to the program again)
        self.inp["AxisParameter"] = axis.params.model_dump(mode="json")
        self.done_next()


COMMON_CLASSES = (MC_Write, MC_WriteAxisParameter, MC_ReadAxisParameter)
