"""Unit conversion between command units and pulses (electronic gear), and the 40-bit pulse range.

Without reducer: pulses = units × CmdPlsCountPerMotorRotation / WorkTravelDistancePerMotorRotation.
With reducer:    pulses = units × CmdPlsCountPerMotorRotation × MotorSideGearRatio
                          / (WorkTravelDistancePerWorkSideRotation × WorkSideGearRatio),
where, in Rotary Mode, the work-side travel is |ModuloMaxPosVal − ModuloMinPosVal| (`omron-group-and-cam.md` §5.5.2).
The MC module keeps positions in a signed 40-bit pulse range (`omron-mc-basics.md` §2.6).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from .enums import _eMC_COUNT_MODE

if TYPE_CHECKING:
    from ...project.models import AxisParameters

POS_MIN_PULSES = -(2**39)
POS_MAX_PULSES = 2**39 - 1
DIST_MAX_PULSES = 2**40 - 1


def pulses_per_unit(params: AxisParameters) -> float:
    uc = params.UnitConversion
    if uc.ReducerUse:
        if params.PosCount.CountMode == _eMC_COUNT_MODE._mcCountModeRotary:
            work_travel = abs(params.PosCount.ModuloMaxPosVal - params.PosCount.ModuloMinPosVal)
        else:
            work_travel = uc.WorkTravelDistancePerWorkSideRotation
        return uc.CmdPlsCountPerMotorRotation * uc.MotorSideGearRatio / (work_travel * uc.WorkSideGearRatio)
    return uc.CmdPlsCountPerMotorRotation / uc.WorkTravelDistancePerMotorRotation


def fits_position(value_units: float, ppu: float) -> bool:
    p = value_units * ppu
    return POS_MIN_PULSES <= p <= POS_MAX_PULSES


def fits_distance(value_units: float, ppu: float) -> bool:
    return abs(value_units * ppu) <= DIST_MAX_PULSES
