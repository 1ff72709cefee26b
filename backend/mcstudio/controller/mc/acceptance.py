"""Which instruction may start in which axis state: the A-3 multi-execution table for axis instructions.

Source: `omron-mc-basics.md` §A-3.4 (state after each instruction, seed 000 lines 21576–21675) with the acceptance of
each cell reconstructed in §A-3.8 — the original encodes it by cell colour, lost in the extraction. Each cell is
"ok" (accepted), "abort" (CommandAborted, no error) or an ErrorID (the instruction errors and the axis error-stops).
Codes for refused cells: 5441 on a servo-OFF axis (A-1 #34), 546E for the latch instructions during homing (A-1 #77),
543C "multi-execution disabled" elsewhere (A-1 #29; decision D6), 543E on a coordinated axis (A-1 #31).
"""

from __future__ import annotations

from typing import Literal

from . import errors as E
from .enums import AxisState

S = AxisState
Verdict = Literal["ok", "abort"] | int

# instruction class → verdict per state, in the order Disabled, Standstill, Discrete, Continuous, Synchronized,
# Homing, Stopping, ErrorStop, Coordinated (A-3.4 columns A–I)
_OK, _AB, _SV, _MX, _CO = "ok", "abort", E.E_SERVO_OFF, E.E_MULTIEXEC_DISABLED, E.E_COORDINATED
TABLE: dict[str, tuple[Verdict, ...]] = {
    # MC_Move, MC_MoveAbsolute, MC_MoveRelative, MC_MoveZeroPosition, MC_MoveVelocity, MC_MoveFeed,
    # MC_TorqueControl, MC_SyncMoveVelocity, MC_SyncMoveAbsolute, MC_CamIn, MC_GearIn, MC_MoveLink, MC_CombineAxes
    "move": (_SV, _OK, _OK, _OK, _OK, _MX, _AB, _AB, _CO),
    # MC_MoveJog, MC_Home, MC_HomeWithParameter, MC_GearInPos: only from Standstill
    "standstill_only": (_SV, _OK, _MX, _MX, _MX, _MX, _AB, _AB, _CO),
    # MC_CamOut, MC_GearOut: only while synchronized (the running instruction is checked by the instruction);
    # elsewhere 543A "Synchronization Stopped" (A-1 #27; rows *6/*7)
    "sync_out": (_SV, 0x543A, 0x543A, 0x543A, _OK, 0x543A, _AB, _AB, _CO),
    # MC_Stop: A → A (accepted, Done), ErrorStop → CommandAborted
    "stop": (_OK, _OK, _OK, _OK, _OK, _OK, _OK, _AB, _CO),
    # MC_ImmediateStop: any state (→ ErrorStop)
    "immediate_stop": (_OK, _OK, _OK, _OK, _OK, _OK, _OK, _OK, _CO),
    # MC_SetPosition: Discrete/Continuous accepted unless a listed instruction runs (checked by the axis)
    "set_position": (_OK, _OK, _OK, _OK, _MX, _MX, _OK, _OK, _CO),
    # MC_ResetFollowingError: B → B, C/D/E → G, G accepted, F/A errors, H CommandAborted
    "reset_fe": (_SV, _OK, _OK, _OK, _OK, _MX, _OK, _AB, _CO),
    # MC_TouchProbe, MC_AbortTrigger: not during homing — both latches are in use there, 546E "Duplicate Latch ID"
    # (A-1 #77, decision D22) — not coordinated
    "latch": (_OK, _OK, _OK, _OK, _OK, E.E_DUPLICATE_LATCH, _OK, _OK, _CO),
    # MC_SetOverride, MC_SetTorqueLimit, MC_ZoneSwitch, MC_AxesObserve, MC_Reset, MC_Power: every state
    "admin": (_OK, _OK, _OK, _OK, _OK, _OK, _OK, _OK, _OK),
}


def verdict(kind: str, state: AxisState) -> Verdict:
    return TABLE[kind][int(state)]
