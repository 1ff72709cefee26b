"""Error codes of the MC function module and their descriptions (manual appendix A-1/A-2).

`ErrorID` is a WORD: the upper four hex digits of the 32-bit event code (`54220000` → `16#5422`). The API writes
ErrorIDs as four upper-case hex digits and event codes as eight.
"""

from __future__ import annotations

from dataclasses import dataclass

from .errors_table import ERROR_ROWS


@dataclass(frozen=True, slots=True)
class ErrorDef:
    code: str  # ErrorID, 4 upper-case hex digits
    name: str
    cause: str
    correction: str
    level: str  # "minor fault" | "observation"
    source: str
    effect: str
    ref: str

    @property
    def event_code(self) -> str:
        return self.code + "0000"

    @property
    def value(self) -> int:
        return int(self.code, 16)


ERRORS: dict[str, ErrorDef] = {row[0]: ErrorDef(*row) for row in ERROR_ROWS}


def describe(code: int | str) -> ErrorDef | None:
    """Look up an ErrorID given as int (0x5422) or hex string ("5422" / "54220000")."""
    key = f"{code:04X}" if isinstance(code, int) else code.upper()[:4]
    return ERRORS.get(key)


def hex4(code: int) -> str:
    return f"{code:04X}"


# Named constants for the codes the MC layer raises (keeps call sites readable).
E_PDO_MISSING = 0x3461
E_PDO_REQUIRED = 0x3460
E_SERVO_ALARM = 0x3002
E_COMM_TIMEOUT = 0x3003
E_CONNECTION = 0x600D
E_VELOCITY = 0x5422
E_ACCELERATION = 0x5423
E_DECELERATION = 0x5424
E_JERK = 0x5425
E_TORQUE_RAMP = 0x5427
E_BUFFER_MODE = 0x542B
E_DIRECTION = 0x542E
E_MOVE_MODE = 0x5431
E_REEXEC_DISABLED = 0x543B
E_MULTIEXEC_DISABLED = 0x543C
E_AXIS_TYPE = 0x543D
E_COORDINATED = 0x543E  # instruction not allowed during multi-axes coordinated motion (A-1 #31)
E_SERVO_OFF = 0x5441
E_BUFFER_LIMIT = 0x5443
E_TRAVEL_SHORT = 0x5444
E_BLEND_DISTANCE = 0x5445
E_REEXEC_BUFFER_MODE = 0x5454
E_REEXEC_DIRECTION = 0x5455
E_REEXEC_JERK = 0x5458
E_ILLEGAL_AXIS = 0x5460
E_TARGET_POSITION = 0x5478
E_TRAVEL_DISTANCE = 0x5479
E_STOP_MODE = 0x544D
E_IMMEDIATE_STOP = 0x5485
E_POSI_SW_LIMIT = 0x6440
E_NEGA_SW_LIMIT = 0x6441
E_POSI_LIMIT_INPUT = 0x6443
E_NEGA_LIMIT_INPUT = 0x6444
E_MAIN_POWER_OFF = 0x7422
E_MODE_SWITCH = 0x7439
E_POSITION_TYPE = 0x5430
E_HOME_UNDEFINED = 0x5466
E_RING_NO_ZERO = 0x549C
E_POSITION_OVERFLOW = 0x6442
E_MASK_DISTANCE = 0x742B
E_HOMING_PARAMETER = 0x5700
E_PARAMETER_NUMBER = 0x544C
E_DUPLICATE_LATCH = 0x546E
E_SETTING_VALUE = 0x544F
E_AXIS_PARAM_NOT_WRITABLE = 0x573A
E_AXIS_PARAM_RANGE = 0x573B
# Run-time axis faults and warnings that the instruction manual leaves to the Troubleshooting Manual (not in the
# seeds): codes assigned by MC Studio, see errors_table.py and docs/decisions.md D19.
E_SW_LIMIT_POSI = 0x6450
E_SW_LIMIT_NEGA = 0x6451
E_FOLLOWING_ERROR = 0x6452
E_POSI_LIMIT_DETECTED = 0x6453
E_NEGA_LIMIT_DETECTED = 0x6454
E_INPOS_TIME = 0x6455
E_HOMING_LIMIT = 0x6456
E_HOMING_NO_HOME_INPUT = 0x6457
O_FOLLOWING_ERROR_WARNING = 0x6460
O_VELOCITY_WARNING = 0x6461
O_ACCELERATION_WARNING = 0x6462
O_DECELERATION_WARNING = 0x6463
