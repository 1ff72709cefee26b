"""The MC function module: all axes, their arrays, and the inputs / motion / outputs stages of one period.

Data layout (settled for the performance issue): every continuous per-axis quantity is a numpy array indexed by the
axis row, so a period costs a fixed number of vector operations plus Python work only for axes with an event (a new
instruction, a profile end, a servo change, a supervision hit). `Axis` objects hold the discrete state machine.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import numpy as np

from ...drives.cia402 import (
    CW_FAULT_RESET,
    DI_EXT1,
    DI_EXT2,
    DI_HOME_SWITCH,
    DI_NEGATIVE_LIMIT,
    DI_POSITIVE_LIMIT,
    MODE_CSP,
    MODE_CST,
    MODE_CSV,
    TP1_ENABLE,
    TP1_POS_EDGE,
    TP1_SOURCE_Z,
    TS1_STORED,
    TS2_STORED,
)
from ...fastnp import copyto, count_nonzero
from ...fieldbus.network import ENCODER_REQUIRED, SERVO_REQUIRED
from . import errors as E
from .axis import Axis
from .cam.table import CamTable
from .enums import AxisState
from .group import AxesGroup
from .jobs import LAW_KINDS, JobKind, JobStatus
from .profile import Planner, PlanningError, ProfileTable
from .supervision import Supervision
from .sync_batch import CamBatch, batchable

if TYPE_CHECKING:
    from ...fieldbus.network import Network
    from ...project.models import Project
    from ..events import EventLog
    from .sync import Law

# DrvStatus bits (order of `_sAXIS_REF_STA_DRV`, omron-mc-basics.md §2.3)
DRV_BITS = ("ServoOn", "Ready", "MainPower", "P_OT", "N_OT", "HomeSw", "Home", "ImdStop", "Latch1", "Latch2",
            "DrvAlarm", "DrvWarning", "ILA", "CSP", "CSV", "CST")
_B = {name: 1 << k for k, name in enumerate(DRV_BITS)}

CW_SHUTDOWN, CW_SWITCH_ON, CW_ENABLE = 0x0006, 0x0007, 0x000F


def _drv_of_statusword(sw: int) -> int:
    oe = (sw & 0x6F) == 0x27
    fault = (sw & 0x4F) == 0x08
    bits = 0
    bits |= _B["ServoOn"] if oe else 0
    bits |= _B["Ready"] if (not fault and (sw & 0x4F) != 0) else 0
    bits |= _B["MainPower"] if sw & 0x10 else 0
    bits |= _B["DrvAlarm"] if fault else 0
    bits |= _B["DrvWarning"] if sw & 0x80 else 0
    bits |= _B["ILA"] if sw & 0x800 else 0
    return bits


# statusword → DrvStatus bits, and (servo on, modes display) → CSP/CSV/CST: lookup tables instead of per-bit
# array operations in every period
_DRV_OF_SW = np.array([_drv_of_statusword(sw) for sw in range(1 << 16)], dtype=np.uint32)
_MODE_BITS = np.zeros(256, dtype=np.uint32)
_MODE_BITS[8], _MODE_BITS[9], _MODE_BITS[10] = _B["CSP"], _B["CSV"], _B["CST"]
_SERVO_ON_BIT = _B["ServoOn"]
# 60FDh bits 0 (negative limit), 1 (positive limit), 2 (home switch), 16 (EXT1), 17 (EXT2) packed into 5 bits →
# DrvStatus bits
assert (DI_NEGATIVE_LIMIT, DI_POSITIVE_LIMIT, DI_HOME_SWITCH, DI_EXT1, DI_EXT2) == (1, 2, 4, 1 << 16, 1 << 17)
_DRV_OF_DIN = np.array([(_B["N_OT"] if k & 1 else 0) | (_B["P_OT"] if k & 2 else 0) | (_B["HomeSw"] if k & 4 else 0)
                        | ((_B["Latch1"] | _B["Home"]) if k & 8 else 0) | (_B["Latch2"] if k & 16 else 0)
                        for k in range(32)], dtype=np.uint32)
_VIRTUAL_ON = _B["ServoOn"] | _B["CSP"] | _B["Ready"] | _B["MainPower"]
_VIRTUAL_OFF = _B["Ready"] | _B["MainPower"]
_CW_FOR_STATE = np.full(0x70, CW_SHUTDOWN, dtype=np.uint16)
_CW_FOR_STATE[0x21] = CW_SWITCH_ON
_CW_FOR_STATE[0x23] = CW_ENABLE
_CW_FOR_STATE[0x27] = CW_ENABLE
_FB_LABEL = re.compile(r"fb \d+ \w+")  # an instance label inside an event source (FunctionBlock.label)
E_INTERNAL = 0xFFFF  # emulator-internal failure (never a manual code; see docs/decisions.md)


class MotionModule:
    def __init__(self, project: Project, *, period_s: float, events: EventLog, network: Network | None) -> None:
        self.period_s = period_s
        # 0-d array constants: numpy handles a Python scalar operand several times slower than an array
        self._T0 = np.array(period_s)
        self._TEN = np.array(10.0)
        self._ZERO = np.array(0.0)
        self.events = events
        self.network = network
        self.cycle = 0
        self.axes: list[Axis] = [Axis(self, i, cfg) for i, cfg in enumerate(project.axes)]
        self.by_name: dict[str, Axis] = {a.name: a for a in self.axes}
        n = self.n = len(self.axes)
        self.ppu = np.array([a.ppu for a in self.axes], dtype=float)
        self.rotary = np.array([a.rotary for a in self.axes], dtype=bool)
        self.mod_min = np.array([a.mod_min for a in self.axes], dtype=float)
        self.mod_len = np.array([a.mod_max - a.mod_min if a.rotary else 0.0 for a in self.axes], dtype=float)
        # command units: position = pulses / ppu + offset. Absolute encoders start home-defined with
        # [Absolute encoder home offset] applied (omron-axis-instructions.md line 100).
        self.pos_offset = np.array([a.config.drive.AbsoluteEncoderHomeOffset if a.homed else 0.0 for a in self.axes],
                                   dtype=float)
        self.cmd_pos = np.zeros(n)  # continuous (unwrapped) command position
        self.prof_vel = np.zeros(n)  # analytic profile velocity/acceleration: the state a re-plan starts from
        self.prof_acc = np.zeros(n)
        self.cmd_vel = np.zeros(n)  # Cmd.Vel: difference of command positions (manual §2.3)
        self.cmd_accdec = np.zeros(n)
        self.cmd_jerk = np.zeros(n)
        self._dv, self._da, self._dj, self._dw = np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n)  # work arrays
        self._moving = np.zeros(n, dtype=bool)
        self.prev_cmd_pos = np.zeros(n)
        self.act_pos = np.zeros(n)
        self.act_vel = np.zeros(n)
        self.act_count = np.zeros(n, dtype=np.int64)
        self.servo_on = np.zeros(n, dtype=bool)
        self.servo_req = np.zeros(n, dtype=bool)
        self.state = np.zeros(n, dtype=np.int8)
        self.drv = np.zeros(n, dtype=np.uint32)
        self.din = np.zeros(n, dtype=np.uint32)  # 60FDh after the input logic inversion settings
        self.tp_func = np.zeros(n, dtype=np.uint16)  # 60B8h written by the MC module (homing, touch probe)
        self.tp_status = np.zeros(n, dtype=np.uint16)
        self.tp_pos1 = np.zeros(n, dtype=np.int64)
        self.tp_pos2 = np.zeros(n, dtype=np.int64)
        self.step_accdec = np.zeros(n, dtype=bool)  # running instruction has acc/dec 0 → Cmd.AccDec/Jerk read 0
        self.stop_dec = np.zeros(n)  # deceleration a supervision stop uses (of the running instruction)
        self.target_checked = np.zeros(n, dtype=bool)  # running motion has a target checked against the limits
        self.notify = np.zeros(n, dtype=bool)  # profile end not yet reported to the axis
        self.override = np.ones(n)
        self.last_dir = np.ones(n, dtype=np.int8)  # direction of the last command motion (+1 after power-on)
        self.profiles = ProfileTable(n)
        self.planner = Planner(period_s)
        self._scheduled: dict[int, Axis] = {}  # jobs accepted (or changed) this period, planned in its motion stage
        self.changed: list[Any] = []  # jobs whose status changed this period (their instances are refreshed)
        self.homing_axes: dict[int, Axis] = {}
        self.cam_tables: dict[str, CamTable] = {}  # cam data variables by name (the kernel fills them)
        self.sync_laws: dict[int, Law] = {}  # slaves under synchronized control (sync.py), by axis number
        self._sync_order: list[int] = []  # per-law slaves in ascending axis number (masters with lower numbers first)
        # steady periodic cam followers computed together (sync_batch.py); rebuilt when `sync_version` moves
        self._batch: CamBatch | None = None
        self.sync_version = 0
        self._batch_version = -1
        # cam table instructions (fb/cam_fb.py): table name → instruction holding it, the running save/generation
        # (_MC_COM.Status.CamTableBusy / GenerateCamBusy), and how a save reaches the project folder
        self.cam_locks: dict[str, Any] = {}
        self.cam_saving: Any = None
        self.generate_cam_busy: Any = None
        self.cam_saver: Callable[[str, CamTable], None] | None = None
        self.fb_touched: set[int] = set()  # instances woken or put to sleep since the last snapshot
        self.fb_wakes = 0  # wake-ups so far (the kernel's program stage visits only awake instances while unchanged)
        self.watchers: dict[int, Any] = {}  # instances watching a latch / trigger each period (by instance id)
        self.common_reset_generation = 0  # ResetMCError: releases instances whose error has the MC common source
        self._inv_mask = np.zeros(n, dtype=np.uint32)  # 60FDh bits whose logic is inverted (axis parameters)
        # supervision parameters per axis (refreshed when parameters are written at run time)
        self.sw_mode = np.zeros(n, dtype=np.int8)
        self.posi_sw = np.full(n, np.inf)
        self.nega_sw = np.full(n, -np.inf)
        self.fe_over = np.zeros(n)
        self.fe_warn = np.zeros(n)
        self.vel_warn = np.zeros(n)
        self.acc_warn = np.zeros(n)
        self.dec_warn = np.zeros(n)
        self.max_dec = np.zeros(n)
        self.homed = np.array([a.homed for a in self.axes], dtype=bool)
        # Linear Mode: the command position spans signed 40 bits in pulses (Scale.MinPos … Scale.MaxPos); beyond, the
        # axis is in overflow (+1) / underflow (−1) until MC_SetPosition or homing (6442, decision D28)
        self.lin_max = np.zeros(n)
        self.lin_min = np.zeros(n)
        self.ovf = np.zeros(n, dtype=np.int8)
        self.fe_check = np.ones(n, dtype=bool)  # FALSE during the push phase of homing
        self.limit_check = np.ones(n, dtype=bool)  # FALSE while homing handles the limit inputs itself
        # torque control (MC_TorqueControl, MC_SetTorqueLimit); torques in % of the rated torque, signed
        self.trq_active = np.zeros(n, dtype=bool)  # a torque instruction controls the axis: the MC module sends CST
        self._n_trq = 0  # count of trq_active (changed only by _start_torque / leave_torque)
        self.trq_cmd = np.zeros(n)  # Cmd.Trq: the command torque (outside torque control: Act.Trq)
        self.act_trq = np.zeros(n)  # Act.Trq: 6077h torque actual value
        self.trq_target = np.zeros(n)  # target torque (sign = Direction)
        self.trq_rate = np.zeros(n)  # TorqueRamp [%/s], 0 = step change
        self.trq_from = np.zeros(n)  # the ramp starts at this torque …
        self.trq_from_cycle = np.zeros(n, dtype=np.int64)  # … in this period
        self.trq_vlim = np.zeros(n)  # velocity limit [unit/s] → 607Fh
        self.trq_reached = np.zeros(n, dtype=bool)  # InTorque reported
        self.trq_lim_pos = np.zeros(n)  # 60E0h positive torque limit value
        self.trq_lim_neg = np.zeros(n)  # 60E1h negative torque limit value
        self.trq_lim_dirty = True  # 60E0h/60E1h to be written in the next outputs stage
        self._trq_out = False  # the last outputs stage wrote torque-mode objects
        self._mode_check = False  # watch 6061h against the mode sent (a mode other than CSP was sent recently)
        # MC_SyncMoveVelocity: the drive in CSV with the velocity the program writes every period (60FFh)
        self.csv_active = np.zeros(n, dtype=bool)
        self.csv_vel = np.zeros(n)
        self._n_csv = 0
        self._csv_out = False
        self._trq_left = np.full(n, -1, dtype=np.int64)  # period in which torque control last ended
        self.drv_mode = np.full(n, MODE_CSP, dtype=np.int8)  # 6061h modes of operation display
        self.prev_act_pos = np.zeros(n)  # Act.Pos of the previous period (Cmd.Pos during torque control)
        self.sup_params_version = 0  # supervision parameters changed: the Supervision recompiles its thresholds
        for a in self.axes:
            self.refresh_params(a)
        # bus mapping: axes with a slave on the network
        rows, slaves = [], []
        if network is not None:
            for a in self.axes:
                addr = a.config.node_address
                if addr is not None and addr in network.index_of_node and not a.virtual:
                    rows.append(a.i)
                    slaves.append(network.index_of_node[addr])
        self.bus_rows = np.array(rows, dtype=np.intp)
        self.bus_slaves = np.array(slaves, dtype=np.intp)
        self.virtual_rows = np.array([a.i for a in self.axes if a.i not in set(rows)], dtype=np.intp)
        self.on_bus = np.zeros(n, dtype=bool)
        self.on_bus[self.bus_rows] = True
        # the common layout — every axis on the bus, axis i on slave i — is indexed with slices (views, no copies)
        self._rows_sel: Any = self.bus_rows
        self._sl_sel: Any = self.bus_slaves
        if network is not None and len(rows) == n and rows == list(range(n)) and slaves == list(range(len(slaves))) \
                and len(network.slaves) == n:
            self._rows_sel = self._sl_sel = slice(None)
        # objects in the PDO mapping of each axis's slave (None: no slave — virtual axes)
        self.pdo_objects: list[frozenset[int] | None] = [None] * n
        for row, slave in zip(rows, slaves, strict=True):
            self.pdo_objects[row] = network.mapped_objects(slave)  # type: ignore[union-attr]
        # network and drive faults (decision D29)
        self.pd_ok = np.ones(n, dtype=bool)  # process data communication of the axis's slave (virtual: TRUE)
        self.drv_fault = np.zeros(n, dtype=bool)  # statusword bit 3 of the previous period
        self.fault_reset_req = np.zeros(n, dtype=bool)  # MC_Reset: send CiA402 fault reset edges
        self.cfg_fault = np.zeros(n, dtype=np.int64)  # configuration error that keeps the axis from operating
        self._fault_resets = False
        self.supervise = Supervision(self)
        self.obs_set: dict[int, np.ndarray] = {}  # supervision: where each observation check set its observation
        # axes groups (group.py): the used groups of the project; those with a group motion step in the motion stage
        self.groups: list[AxesGroup] = [AxesGroup(self, cfg) for cfg in getattr(project, "groups", ())
                                         if cfg.use.name == "_mcUsedGroup"]
        self.groups_by_name: dict[str, AxesGroup] = {g.name: g for g in self.groups}
        self.moving_groups: dict[int, AxesGroup] = {}
        if network is not None:
            self.pd_ok[self.bus_rows] = network.pd_ok[self.bus_slaves]
            for row in rows:
                a = self.axes[row]
                mapped = self.pdo_objects[row] or frozenset()
                need = ENCODER_REQUIRED if a.encoder else SERVO_REQUIRED
                missing = [f"{o:04X}h" for o in need if o not in mapped]
                if missing:
                    self.cfg_fault[row] = E.E_PDO_REQUIRED
                    a.error_code = E.E_PDO_REQUIRED
                    a._set_state(AxisState.ErrorStop)
                    self.log_error(E.E_PDO_REQUIRED, axis=a, source="EtherCAT",
                                   detail=f"not in the PDO mapping of node {a.config.node_address}: "
                                   + ", ".join(missing))
        self._mode_wait = np.zeros(len(rows), dtype=np.int64)  # periods the drive has not taken the mode sent
        self._mode_limit = max(1, round(1.0 / period_s))  # 7439 after 1 s
        self._prev_pos32 = np.zeros(len(rows), dtype=np.int32)
        self._d32 = np.zeros(len(rows), dtype=np.int32)
        self._new_act = np.zeros(len(rows))
        self._discrete_key: bytes | None = None  # raw discrete inputs of the last period (statusword, 60FDh …)
        self._virtual_key: bytes | None = None
        self._n_off = n  # axes with the servo OFF (their command position reads the actual position)
        self._servo_seen = np.zeros(n, dtype=bool)  # servo states the axes were told of (on_servo_changed)
        self._out_w = np.zeros(len(rows))  # outputs stage: work arrays, and what the event-driven objects follow
        self._out_i64 = np.zeros(len(rows), dtype=np.int64)
        self._out_i32 = np.zeros(len(rows), dtype=np.int32)
        self._cw_key: bytes | None = None
        self._tp_key: bytes | None = None
        self._csp_sent = False
        if network is not None and len(rows):
            self._prev_pos32[:] = network.tx["position_actual"][self.bus_slaves]
            self.act_count[self.bus_rows] = self._prev_pos32
            self.act_pos[self.bus_rows] = self.act_count[self.bus_rows] / self.ppu[self.bus_rows]
            self.cmd_pos[:] = self.act_pos
            self.prev_cmd_pos[:] = self.act_pos

    # ------------------------------------------------------------------ helpers for axes
    def schedule(self, axis: Axis) -> None:
        self._scheduled[axis.i] = axis

    def job_changed(self, job: Any) -> None:
        self.changed.append(job)

    def refresh_params(self, axis: Axis) -> None:
        """Copy the parameters the period checks into the supervision arrays."""
        i, p = axis.i, axis.params
        op, lim = p.Operation, p.Limit
        self.sup_params_version += 1
        self.sw_mode[i] = int(lim.SwLimitMode)
        self.posi_sw[i] = lim.PosiSwLimit
        self.nega_sw[i] = lim.NegaSwLimit
        self.fe_over[i] = lim.FollowingErrorOverVal
        self.fe_warn[i] = lim.FollowingErrorWarningVal
        self.vel_warn[i] = op.MaxVel * op.VelWarningVal / 100.0
        self.acc_warn[i] = op.MaxAcc * op.AccWarningVal / 100.0
        self.dec_warn[i] = op.MaxDec * op.DecWarningVal / 100.0
        self.max_dec[i] = op.MaxDec
        self.lin_max[i] = (2**39 - 1) / self.ppu[i]
        self.lin_min[i] = -(2**39) / self.ppu[i]
        self.set_input_inversion(axis)
        axis.apply_torque_limits()

    def set_input_inversion(self, axis: Axis) -> None:
        oo = axis.params.OtherOperation
        mask = 0
        mask |= DI_POSITIVE_LIMIT if oo.PosiLimitInputLogicInversion else 0
        mask |= DI_NEGATIVE_LIMIT if oo.NegaLimitInputLogicInversion else 0
        mask |= DI_HOME_SWITCH if oo.HomeProximityInputLogicInversion else 0
        self._inv_mask[axis.i] = mask

    def shift_coordinates(self, i: int, delta: float) -> None:
        """Move axis i's coordinate system by `delta` (MC_SetPosition, home preset): command, actual and the running
        profile shift together, so motion continues unchanged and the following error is kept."""
        self.pos_offset[i] += delta
        self.cmd_pos[i] += delta
        self.prev_cmd_pos[i] += delta
        self.act_pos[i] += delta
        self.profiles.shift(i, delta)

    def reset_following_error(self, i: int) -> None:
        """Command := actual (immediate stop with following-error reset)."""
        self.cmd_pos[i] = self.act_pos[i]
        self.prev_cmd_pos[i] = self.act_pos[i]

    def wrapped(self, x: np.ndarray) -> np.ndarray:
        """Positions as reported (a copy): on the ring counter for Rotary Mode axes."""
        out = x.copy()
        if not count_nonzero(self.rotary):
            return out
        r = self.rotary
        out[r] = self.mod_min[r] + np.mod(x[r] - self.mod_min[r], self.mod_len[r])
        return out

    def log_error(self, code: int, *, axis: Axis | None, source: str | None, detail: str = "",
                  group: str | None = None) -> None:
        """An error or observation in the event log. The source kind (D125) is the axis, else the axes `group`, else
        the instruction instance named in `source` (MC common errors), else the MC module."""
        d = E.describe(code)
        where = axis.name if axis else "MC common"
        fb = _FB_LABEL.search(source or "")
        if axis is not None:
            kind, name = "axis", axis.name
        elif group is not None:
            kind, name = "group", group
        elif fb is not None:
            kind, name = "instruction", fb.group(0)
        else:
            kind, name = "controller", "MC common"
        self.events.add(
            cycle=self.cycle,
            time_s=self.cycle * self.period_s,
            source=f"{where} / {source}" if source else where,
            code=f"{code:04X}0000",
            level=d.level if d else "minor fault",  # type: ignore[arg-type]
            message=d.name if d else ("Emulator internal error" if code == E_INTERNAL else f"Error {code:04X}"),
            cause=d.cause if d else "",
            correction=d.correction if d else "",
            detail=detail,
            source_kind=kind,  # type: ignore[arg-type]
            source_name=name,
            instruction=fb.group(0) if fb else "",
        )

    def log_info(self, axis: Axis | None, message: str, *, group: str | None = None) -> None:
        kind, name = ("axis", axis.name) if axis else ("group", group) if group else ("controller", "MC")
        self.events.add(cycle=self.cycle, time_s=self.cycle * self.period_s, source=axis.name if axis else "MC",
                        code="00000000", level="information", message=message, source_kind=kind,  # type: ignore[arg-type]
                        source_name=name)

    # ------------------------------------------------------------------ torque control
    def _start_torque(self, i: int, job: Any, start_cycle: int | None) -> None:
        """A torque job starts or changes (re-execution): the command torque ramps from its current value."""
        self.profiles.clear(i)
        self.notify[i] = False
        self.step_accdec[i] = False
        self.target_checked[i] = False
        # from the current command torque: the last command if torque control runs (or ended in this period, e.g.
        # one MC_TorqueControl aborting another), else the actual torque (Cmd.Trq outside torque control)
        continuing = self.trq_active[i] or self._trq_left[i] == self.cycle
        self.trq_cmd[i] = self.trq_from[i] = self.trq_cmd[i] if continuing else self.act_trq[i]
        self.trq_from_cycle[i] = self.cycle if start_cycle is None else start_cycle
        if not self.trq_active[i]:
            # from position control: the command position is held until the drive reports CST
            self.prof_vel[i] = 0.0
            self.prof_acc[i] = 0.0
            self.trq_active[i] = True
            self._n_trq += 1
        self.trq_target[i] = job.info["torque"]
        self.trq_rate[i] = job.info["ramp"]
        self.trq_vlim[i] = job.velocity
        self.trq_reached[i] = False
        job.in_velocity = False
        job.status = JobStatus.ACTIVE
        job.replan = False
        job.cmd_done_cycle = -1

    def leave_torque(self, i: int) -> None:
        """The torque instruction ended: back to CSP with the command on the feedback position (servo lock), so a
        following profile starts where the shaft is, at its velocity (MC_TorqueControl rules, decision D25)."""
        if not self.trq_active[i]:
            return
        self.trq_active[i] = False
        self._n_trq -= 1
        self.trq_reached[i] = False
        self._trq_left[i] = self.cycle
        if not self.on_bus[i]:
            self.act_trq[i] = 0.0  # a virtual servo axis has no torque outside torque control
        self.cmd_pos[i] = self.act_pos[i]
        self.prof_vel[i] = self.act_vel[i] if self.on_bus[i] else 0.0
        self.prof_acc[i] = 0.0

    def _torque_stage(self, cycle: int, T: float) -> None:
        """Command torque of every axis in torque control (ramp to the target), Cmd.Pos, InTorque."""
        idx = np.flatnonzero(self.trq_active)
        tgt = self.trq_target[idx]
        sent = self.trq_cmd[idx]  # the command the drive received in this period's exchange
        start = self.trq_from[idx]
        rate = self.trq_rate[idx]
        sgn = np.sign(tgt - start)
        ramp = start + sgn * rate * ((cycle - self.trq_from_cycle[idx] + 1) * T)
        done = (rate <= 0) | (sgn * (ramp - tgt) >= -1e-9)
        self.trq_cmd[idx] = np.where(done, tgt, ramp)
        bus = self.on_bus[idx]
        in_mode = ~bus | (self.drv_mode[idx] == MODE_CST)  # virtual servo axes: no mode switch
        cst = bus & in_mode
        # Cmd.Pos = Act.Pos of one period earlier while the drive is in CST; held (position control) before
        self.cmd_pos[idx] = np.where(cst, self.prev_act_pos[idx], self.cmd_pos[idx])
        self.prof_vel[idx] = np.where(cst, self.act_vel[idx], 0.0)
        self.prof_acc[idx] = 0.0
        # InTorque: the drive is in CST and has received the target torque (one period after the command reached it,
        # like the ends of profiles, decision D1)
        reached = in_mode & (sent == tgt)
        new = idx[reached & ~self.trq_reached[idx]]
        self.trq_reached[idx] |= reached
        for i in new:
            axis = self.axes[i]
            job = axis.current
            if job is None or job.kind != JobKind.TORQUE or job.in_velocity:
                continue
            job.in_velocity = True  # InTorque: the target torque is output to the drive in CST
            self.job_changed(job)
            if axis.buffered is not None:
                axis._promote_buffered()  # a buffered instruction takes over at InTorque

    # ------------------------------------------------------------------ MC_SyncMoveVelocity (CSV)
    def _start_csv(self, i: int, job: Any) -> None:
        self.profiles.clear(i)
        self.notify[i] = False
        self.step_accdec[i] = False
        self.target_checked[i] = False
        if not self.csv_active[i]:
            self.csv_active[i] = True
            self._n_csv += 1
        self.csv_vel[i] = job.velocity
        job.in_velocity = False
        job.status = JobStatus.ACTIVE
        job.replan = False

    def leave_csv(self, i: int) -> None:
        """MC_SyncMoveVelocity ended: back to CSP with the command on the feedback position and the profile at the
        feedback velocity, so the instruction that took over (MC_Stop, a positioning) decelerates from there
        (decision D47)."""
        if not self.csv_active[i]:
            return
        self.csv_active[i] = False
        self._n_csv -= 1
        self.csv_vel[i] = 0.0
        if self.on_bus[i]:
            self.cmd_pos[i] = self.act_pos[i]
            self.prof_vel[i] = self.act_vel[i]
        self.prof_acc[i] = 0.0

    def _csv_stage(self) -> None:
        """Axes in MC_SyncMoveVelocity: Cmd.Pos follows the feedback of the previous period while the drive is in
        CSV (`_mcCount`), a virtual axis integrates the velocity; InVelocity once the drive runs the target."""
        for i in np.flatnonzero(self.csv_active).tolist():
            axis = self.axes[i]
            job = axis.current
            if job is None or job.kind != JobKind.CSV:
                continue
            v = job.velocity
            self.csv_vel[i] = v
            if self.on_bus[i]:
                in_mode = bool(self.drv_mode[i] == MODE_CSV)
                if in_mode:
                    self.cmd_pos[i] = self.prev_act_pos[i]
            else:
                in_mode = True
                self.cmd_pos[i] += v * self.period_s
            self.prof_vel[i] = v if in_mode else 0.0
            self.prof_acc[i] = 0.0
            # InVelocity: the drive is in CSV and has run the target velocity for a period (a step change)
            reached = in_mode and job.info.get("sent") == v
            job.info["sent"] = v if in_mode else None
            if reached != job.in_velocity:
                job.in_velocity = reached
                self.job_changed(job)
                if reached and axis.buffered is not None:
                    axis._promote_buffered()  # a buffered instruction takes over at InVelocity

    def _mode_switch_failed(self, i: int, reported: int) -> None:
        """The drive did not take the mode of operation sent within 1 s: 7439, servo OFF (free-run stop)."""
        axis = self.axes[i]
        job = axis.current
        source = None
        if job is not None and job.kind in (JobKind.TORQUE, JobKind.CSV):
            source = job.owner.label if job.owner is not None else None
            axis._end_job(job, JobStatus.ERROR, E.E_MODE_SWITCH)
        axis.raise_error(E.E_MODE_SWITCH, source=source, stop="free",
                         detail=f"the drive reports mode {reported} 1 s after the request")

    # ------------------------------------------------------------------ network and drive faults (D29)
    def _watch_communication(self, rows: np.ndarray, ok: np.ndarray) -> None:
        """A slave that leaves the process-data exchange: its axis error-stops with 3003 (the drive has lost its
        commands); the other axes carry on (invt-ivc5.md §2.4, R4)."""
        lost = self.pd_ok[rows] & ~ok
        self.pd_ok[rows] = ok
        for k in np.flatnonzero(lost):
            a = self.axes[int(rows[k])]
            a.raise_error(E.E_COMM_TIMEOUT, source="EtherCAT", stop="free",
                          detail=f"node {a.config.node_address} left the cyclic exchange")

    def _watch_drive_faults(self, rows: np.ndarray, fault: np.ndarray, sl: np.ndarray) -> None:
        """A drive alarm (statusword bit 3 rising): the axis error-stops with 3002; 603Fh in the detail."""
        new = fault & ~self.drv_fault[rows]
        self.drv_fault[rows] = fault
        for k in np.flatnonzero(new):
            a = self.axes[int(rows[k])]
            code = int(self.network.tx["error_code"][sl[k]])  # type: ignore[union-attr]
            mapped = 0x603F in (self.pdo_objects[a.i] or ())
            a.raise_error(E.E_SERVO_ALARM, source="drive", stop="free",
                          detail=f"603Fh error code {code:04X}h" if mapped else "603Fh not mapped")

    # ------------------------------------------------------------------ stage 2: inputs
    def inputs(self) -> None:
        """Stage 2. Continuous values (positions, velocities, torques) every period; the discrete signals (statusword,
        modes display, digital inputs, touch probes, process-data state) only when their raw values changed."""
        if self._n_trq or self._n_csv:
            # Cmd.Pos in torque control and MC_SyncMoveVelocity: Act.Pos of one period earlier
            self.prev_act_pos[:] = self.act_pos
        servo_changed = False
        if self.bus_rows.size:
            net = self.network
            tx = net.tx  # type: ignore[union-attr]
            rows, sl = self._rows_sel, self._sl_sel
            # actual position: the 32-bit count unwrapped (int32 differences wrap like the object)
            pos32 = tx["position_actual"][sl]
            d = np.subtract(pos32, self._prev_pos32, self._d32)
            self._prev_pos32[:] = pos32
            self.act_count[rows] += d
            new_act = np.divide(self.act_count[rows], self.ppu[rows], self._new_act)
            new_act += self.pos_offset[rows]
            self.act_vel[rows] = (new_act - self.act_pos[rows]) / self._T0
            self.act_pos[rows] = new_act
            self.act_trq[rows] = tx["torque_actual"][sl] / self._TEN  # 0.1 % units
            ok = net.pd_ok[sl]  # type: ignore[union-attr]
            key = b"".join((tx["statusword"][sl].tobytes(), tx["digital_inputs"][sl].tobytes(),
                            tx["modes_display"][sl].tobytes(), tx["touch_probe_status"][sl].tobytes(),
                            tx["touch_probe_pos1"][sl].tobytes(), tx["touch_probe_pos2"][sl].tobytes(),
                            ok.tobytes(), self._inv_mask.tobytes()))
            if key != self._discrete_key:
                self._discrete_key = key
                servo_changed = self._bus_discrete(tx, rows, sl, ok)
            if self._mode_check:
                # the drive must report the mode of operation sent within 1 s (7439, MC_TorqueControl rules)
                mode = self.drv_mode[rows]
                oe = self.servo_on[rows]
                pending = (net.rx["modes_of_operation"][sl] != mode) & oe  # type: ignore[union-attr]
                self._mode_wait = np.where(pending, self._mode_wait + 1, 0)
                self._mode_check = bool(pending.any()) or self._trq_out or self._csv_out
                for k in np.flatnonzero(self._mode_wait >= self._mode_limit):
                    self._mode_wait[k] = 0
                    self._mode_switch_failed(int(self.bus_rows[k]), int(mode[k]))
        if self.virtual_rows.size:
            v = self.virtual_rows
            key = self.servo_req.tobytes()
            if key != self._virtual_key:
                self._virtual_key = key
                on = self.servo_req[v]
                servo_changed |= bool((self.servo_on[v] != on).any())
                self.servo_on[v] = on
                self.drv[v] = np.where(on, _VIRTUAL_ON, _VIRTUAL_OFF)
            if self._n_trq:
                self.act_trq[v] = np.where(self.trq_active[v], self.trq_cmd[v], 0.0)  # no drive: as commanded
        if servo_changed:
            prev_on = self._servo_seen
            for i in np.flatnonzero(self.servo_on != prev_on):
                self.axes[i].on_servo_changed(bool(self.servo_on[i]))
            self._servo_seen = self.servo_on.copy()
            self._n_off = self.n - int(count_nonzero(self.servo_on))
        # Servo OFF: the command position reads the actual position (manual §2.3, Cmd.Pos).
        if self._n_off:
            copyto(self.cmd_pos, self.act_pos, where=~self.servo_on)

    def _bus_discrete(self, tx: np.ndarray, rows: Any, sl: Any, ok: np.ndarray) -> bool:
        """The discrete inputs of the axes on the bus changed: DrvStatus, servo state, inputs, latches, faults.
        Returns whether a servo state changed."""
        sw = tx["statusword"][sl]
        din = tx["digital_inputs"][sl] ^ self._inv_mask[rows]
        self.din[rows] = din
        drv = _DRV_OF_SW[sw]
        oe = (drv & _SERVO_ON_BIT) != 0
        if not ok.all() or not self.pd_ok[rows].all():
            self._watch_communication(self.bus_rows, ok)
            oe &= ok
        fault = (sw & 0x0008) != 0
        if fault.any() or self.drv_fault[rows].any():
            self._watch_drive_faults(self.bus_rows, fault & ok, self.bus_slaves)
        mode = tx["modes_display"][sl]
        drv |= _MODE_BITS[mode.view(np.uint8)] * oe
        self.drv_mode[rows] = mode
        drv |= _DRV_OF_DIN[(din & 0x7) | ((din >> 13) & 0x18)]
        self.drv[rows] = drv
        changed = bool((self.servo_on[rows] != oe).any())
        self.servo_on[rows] = oe
        self.tp_status[rows] = tx["touch_probe_status"][sl]
        self.tp_pos1[rows] = tx["touch_probe_pos1"][sl]
        self.tp_pos2[rows] = tx["touch_probe_pos2"][sl]
        return changed

    def reset_mc_errors(self) -> list[str]:
        """ResetMCError: reset MC common errors and the errors of every stopped axis. Returns axes still stopping."""
        self.common_reset_generation += 1
        busy = [a.name for a in self.axes if not a.reset()]
        self.log_info(None, "MC errors reset (ResetMCError)")
        return busy

    def arm_latch(self, i: int, slot: int, *, z_phase: bool) -> None:
        """Arm touch probe `slot` (1, 2) of axis i's drive on the Z phase or the external input (60B8h)."""
        bits = TP1_ENABLE | TP1_POS_EDGE | (TP1_SOURCE_Z if z_phase else 0)
        shift = 0 if slot == 1 else 8
        self.tp_func[i] = (int(self.tp_func[i]) & ~(0xFF << shift)) | (bits << shift)

    def disarm_latch(self, i: int, slot: int) -> None:
        shift = 0 if slot == 1 else 8
        self.tp_func[i] = int(self.tp_func[i]) & ~(0xFF << shift)

    def latch_stored(self, i: int, slot: int) -> bool:
        return bool(int(self.tp_status[i]) & (TS1_STORED if slot == 1 else TS2_STORED))

    def latch_position(self, i: int, slot: int) -> float:
        """A touch-probe latch of axis i converted to command units (unwrapped)."""
        count = self.tp_pos1[i] if slot == 1 else self.tp_pos2[i]
        # the latch is a 32-bit pulse count: place it next to the current 64-bit count
        base = int(self.act_count[i])
        d = (int(count) - base + 2**31) % 2**32 - 2**31
        return (base + d) / float(self.ppu[i]) + float(self.pos_offset[i])

    # ------------------------------------------------------------------ stage 4: motion
    def motion(self) -> None:
        T = self.period_s
        cycle = self.cycle
        if self._scheduled:
            scheduled, self._scheduled = self._scheduled, {}
            for i, axis in scheduled.items():
                self._plan(i, axis)
        if self.homing_axes:
            for axis in list(self.homing_axes.values()):
                if axis.homing is not None:
                    axis.homing.step()
        if self.watchers:
            for watcher in list(self.watchers.values()):
                watcher.watch()
        profiles = self.profiles
        if profiles.n_active:
            active = profiles.active
            if profiles.n_active == self.n:  # every axis runs a profile: evaluate straight into the command values
                _, _, _, fin = profiles.evaluate(cycle, T, (self.cmd_pos, self.prof_vel, self.prof_acc))
            else:
                pos, vel, acc, fin = profiles.evaluate(cycle, T)
                copyto(self.cmd_pos, pos, where=active)
                copyto(self.prof_vel, vel, where=active)
                copyto(self.prof_acc, acc, where=active)
                fin &= active
            fin &= self.notify
            report = np.flatnonzero(fin) if count_nonzero(fin) else ()
            for i in report:
                axis = self.axes[i]
                job = axis.current
                if job is None:
                    self.notify[i] = False
                    continue
                # keep reporting while the end is pending (final command in transit, in-position check)
                self.notify[i] = axis.on_profile_finished(job)
        if self._n_trq:
            self._torque_stage(cycle, T)
        if self._n_csv:
            self._csv_stage()
        if self.moving_groups:
            for group in list(self.moving_groups.values()):
                group.step(cycle)
        if self.sync_laws:
            self._sync_stage(T)
        # derived command values (manual §2.3: differences of command positions / velocities)
        vel, accdec, jerk, w = self._dv, self._da, self._dj, self._dw
        T0 = self._T0
        np.subtract(self.cmd_pos, self.prev_cmd_pos, vel)
        vel /= T0
        np.abs(vel, accdec)
        accdec -= np.abs(self.cmd_vel, w)
        accdec /= T0
        np.abs(accdec, jerk)
        jerk -= np.abs(self.cmd_accdec, w)
        jerk /= T0
        if count_nonzero(self.step_accdec):
            accdec[self.step_accdec] = 0.0
            jerk[self.step_accdec] = 0.0
        copyto(self.cmd_jerk, jerk)
        copyto(self.cmd_accdec, accdec)
        copyto(self.cmd_vel, vel)
        # direction of the last command motion: the sign of Cmd.Vel where it is not 0
        np.sign(vel, w)
        copyto(self.last_dir, w, where=np.not_equal(w, self._ZERO, self._moving), casting="unsafe")
        self.supervise()
        if self._scheduled:
            # started during this stage (a buffered instruction taking over, an error stop): from the next period
            scheduled, self._scheduled = self._scheduled, {}
            for i, axis in scheduled.items():
                self._plan(i, axis, start_cycle=cycle + 1)
                job = axis.current
                if job is not None and job.status == JobStatus.ACTIVE and job.owner is not None:
                    # a buffered instruction took over: its Active shows in the period the previous one is Done
                    self.changed.append(job)
        self.prev_cmd_pos[:] = self.cmd_pos
        # Push the MC module's status changes to the instances (Done, CommandAborted, InVelocity, Error) so they show
        # in the period the change happened, independent of program order. Active of an instruction started by its
        # own call is read at its next call (one period after Busy, as the manual's charts show); Active of a
        # buffered or blended successor is pushed here, in the period its predecessor reports Done.
        if self.changed:
            changed, self.changed = self.changed, []
            for job in changed:
                owner = job.owner
                if owner is not None:
                    owner.sync_job()

    def _plan(self, i: int, axis: Axis, start_cycle: int | None = None) -> None:
        job = axis.current
        if job is None or not job.running:
            return
        if job.status != JobStatus.STARTING and not job.replan and job.kind != JobKind.ERROR_STOP:
            return
        # from the last command value (with start_cycle: the new profile begins after this period's value)
        if job.kind == JobKind.TORQUE:
            self._start_torque(i, job, start_cycle)
            return
        if job.kind in LAW_KINDS:
            self._start_sync(i, axis, job, own_call=start_cycle is None)
            return
        if job.kind == JobKind.CSV:
            self._start_csv(i, job)
            return
        p0, v0, a0 = float(self.cmd_pos[i]), float(self.prof_vel[i]), float(self.prof_acc[i])
        try:
            seg = axis.plan_job(job, p0, v0, a0)
        except PlanningError as err:
            owner = job.owner
            axis.raise_error(E_INTERNAL, source="profile planner" + (f" / {owner.label}" if owner else ""),
                             detail=str(err))
            if owner is not None and job.status == JobStatus.ABORTED:
                job.status = JobStatus.ERROR  # the instruction that asked for the profile shows FFFF (D124)
                job.error_id = E_INTERNAL
            return
        if isinstance(seg, int):
            owner = job.owner
            axis.raise_error(seg, source=owner.label if owner is not None else None)
            if owner is not None and job.status == JobStatus.ABORTED:
                job.status = JobStatus.ERROR  # the instruction whose (re)planning failed shows the error
                job.error_id = seg
            return
        self.profiles.load(i, seg, self.cycle if start_cycle is None else start_cycle)
        split = job.info.get("split_time")
        if split is not None:
            self.profiles.duration[i] = split
        self.notify[i] = True
        self.step_accdec[i] = job.kind in (JobKind.POSITION, JobKind.VELOCITY, JobKind.JOG) and (
            job.acceleration == 0 or job.deceleration == 0 or job.rapid)
        self.stop_dec[i] = job.deceleration
        # positioning and homing targets are checked at start (6440/6441), the look-ahead guards the rest
        self.target_checked[i] = job.kind in (JobKind.POSITION, JobKind.HOMING, JobKind.RESET_FE)
        job.status = JobStatus.ACTIVE
        job.replan = False
        job.cmd_done_cycle = -1

    # ------------------------------------------------------------------ synchronized control (sync.py)
    def _start_sync(self, i: int, axis: Axis, job: Any, *, own_call: bool) -> None:
        law = job.info["law"]
        if own_call:
            job.info["quiet_cycle"] = self.cycle  # Active shows at the instance's next call (one period after Busy)
        if job.replan:  # re-execution (MC_CamIn switching tables, MC_GearIn a new ratio): the law was updated
            job.replan = False
            return
        code = law.begin()
        if code:
            owner = job.owner
            axis.raise_error(code, source=owner.label if owner is not None else None)
            if owner is not None and job.status == JobStatus.ABORTED:
                job.status = JobStatus.ERROR  # the instruction that could not start shows the error
                job.error_id = code
            return
        self.profiles.clear(i)
        self.notify[i] = False
        self.step_accdec[i] = False
        self.target_checked[i] = False
        self.stop_dec[i] = axis.params.Operation.MaxDec  # a slave error stops at the maximum deceleration
        self.sync_laws[i] = law
        self.sync_version += 1
        job.status = JobStatus.ACTIVE
        if law.flags_changed:
            law.flags_changed = False
            self.changed.append(job)

    def _sync_stage(self, T: float) -> None:
        """Slaves compute their command position from their masters, in ascending axis number (so that a slave
        using `_mcLatestCommand` sees its master's value of this period). The profile velocity is the difference
        of command positions; the profile acceleration is kept 0 (an instruction taking over starts from the
        slave's velocity; decision D38)."""
        laws = self.sync_laws
        if self._batch_version != self.sync_version:
            self._rebuild_batch()
        if self._batch is not None:
            self._batch.step(T)  # first: the batch's masters are not slaves, later per-law slaves may follow it
        cmd, pv, pa = self.cmd_pos, self.prof_vel, self.prof_acc
        finished: list[Law] = []
        stale: list[int] = []
        active = JobStatus.ACTIVE
        for i in self._sync_order:
            law = laws[i]
            job = law.job
            if law.slave.current is not job or job._status is not active:
                stale.append(i)
                continue
            pos = law.step()
            pv[i] = (pos - cmd.item(i)) / T
            pa[i] = 0.0
            cmd[i] = pos
            if law.flags_changed:
                law.flags_changed = False
                self.push_law_outputs(job, pulse=getattr(law, "eop_cycle", -1) == self.cycle)
            if law.finished:
                finished.append(law)
        if stale:
            for i in stale:
                del laws[i]  # aborted, stopped or replaced by another instruction
            self.sync_version += 1
        for law in finished:
            if laws.get(law.slave.i) is law:
                del laws[law.slave.i]
                self.sync_version += 1
            law.slave.sync_finished(law)

    def _rebuild_batch(self) -> None:
        """Split the slaves into the batch of steady cam followers and the per-law rest (sync_batch.py)."""
        old = self._batch
        if old is not None:
            old.write_back()
        laws = self.sync_laws
        active = JobStatus.ACTIVE
        for i in [i for i, law in laws.items() if law.slave.current is not law.job or law.job.status != active]:
            del laws[i]
        batch = [laws[i] for i in sorted(laws) if self.batch_enabled and batchable(laws[i], laws)]
        if len(batch) < self.batch_min:
            batch = []  # a few followers are cheaper one by one
        in_batch = {law.slave.i for law in batch}
        self._sync_order = [i for i in sorted(laws) if i not in in_batch]
        self._batch = CamBatch(self, batch) if batch else None  # type: ignore[arg-type]
        self._batch_version = self.sync_version

    batch_enabled = True  # tests compare the batch with the per-law path by turning it off
    batch_min = 12  # fewest steady followers worth a batch (measured: 14 µs for a batch, ≈ 1.1 µs per follower alone)

    def push_law_outputs(self, job: Any, *, pulse: bool) -> None:
        """A law's outputs changed (InSync, InGear, Index …): the instance shows them at the end of this period.
        It is woken only for a pulse it must end by its next call (EndOfProfile); otherwise it may stay asleep —
        it is only marked for the next snapshot, so the program stage keeps skipping the settled instances."""
        self.changed.append(job)
        owner = job.owner
        if owner is not None:
            if pulse:
                owner.wake()
            else:
                self.fb_touched.add(owner.id)

    def sync_changed(self) -> None:
        """Something the batch depends on changed (a law's table, phasing, offset, a buffered successor, InSync)."""
        self.sync_version += 1

    # ------------------------------------------------------------------ stage 5: outputs
    def outputs(self) -> None:
        """Stage 5. The target position every period; controlword, modes of operation and touch probe function only
        when what they follow changed."""
        if self.bus_rows.size:
            net = self.network
            rx = net.rx  # type: ignore[union-attr]
            rows, sl = self._rows_sel, self._sl_sel
            w, i64, i32 = self._out_w, self._out_i64, self._out_i32
            np.subtract(self.cmd_pos[rows], self.pos_offset[rows], w)
            w *= self.ppu[rows]
            np.rint(w, w)
            copyto(i64, w, casting="unsafe")
            copyto(i32, i64, casting="unsafe")  # the 32-bit object wraps
            rx["target_position"][sl] = i32
            sw = net.tx["statusword"][sl]  # type: ignore[union-attr]
            key = sw.tobytes() + self.servo_req.tobytes()
            if self._fault_resets or key != self._cw_key:
                self._cw_key = key
                # servo ON: Shutdown → Switch on → Enable operation as the drive reports each state; OFF: Shutdown
                cw = _CW_FOR_STATE[sw & 0x6F] * self.servo_req[rows]
                cw[cw == 0] = CW_SHUTDOWN
                if self._fault_resets:
                    # MC_Reset: CiA402 fault reset (rising edges of controlword bit 7, repeated every other period)
                    req = self.fault_reset_req[rows]
                    cw = np.where(req, CW_FAULT_RESET if self.cycle % 2 else 0, cw)
                    self._fault_resets = bool(self.fault_reset_req.any())
                    self._cw_key = None
                rx["controlword"][sl] = cw
            if self._n_trq or self._trq_out or self._n_csv or self._csv_out:
                # torque control: CST with the command torque and the velocity limit (6071h, 607Fh);
                # MC_SyncMoveVelocity: CSV with the target velocity (60FFh)
                ta = self.trq_active[rows]
                ca = self.csv_active[rows]
                rx["modes_of_operation"][sl] = np.where(ta, MODE_CST, np.where(ca, MODE_CSV, MODE_CSP))
                vel = np.clip(np.rint(self.csv_vel[rows] * self.ppu[rows]), -(2**31), 2**31 - 1)
                rx["target_velocity"][sl] = np.where(ca, vel, 0)
                self._csv_out = bool(ca.any())
                rx["target_torque"][sl] = np.where(ta, np.clip(np.rint(self.trq_cmd[rows] * 10.0), -32768, 32767), 0)
                vlim = np.clip(np.rint(self.trq_vlim[rows] * self.ppu[rows]), 0, 2**32 - 1)
                rx["max_profile_velocity"][sl] = np.where(ta, vlim, 0)
                self._trq_out = bool(ta.any())
                self._mode_check = True
                self._csp_sent = False
            elif not self._csp_sent:
                rx["modes_of_operation"][sl] = MODE_CSP
                self._csp_sent = True
            if self.trq_lim_dirty:
                self.trq_lim_dirty = False
                rx["positive_torque_limit"][sl] = np.clip(np.rint(self.trq_lim_pos[rows] * 10.0), 0, 65535)
                rx["negative_torque_limit"][sl] = np.clip(np.rint(self.trq_lim_neg[rows] * 10.0), 0, 65535)
            key = self.tp_func.tobytes()
            if key != self._tp_key:
                self._tp_key = key
                rx["touch_probe_function"][sl] = self.tp_func[rows]
        if self.virtual_rows.size:
            v = self.virtual_rows
            on = self.servo_on[v]
            self.act_vel[v] = np.where(on, self.cmd_vel[v], 0.0)
            self.act_pos[v] = self.cmd_pos[v]

    # ------------------------------------------------------------------ snapshot
    def capture(self) -> dict[str, Any]:
        return {
            "cmd_pos": self.wrapped(self.cmd_pos),
            "cmd_vel": self.cmd_vel.copy(),
            "cmd_accdec": self.cmd_accdec.copy(),
            "cmd_jerk": self.cmd_jerk.copy(),
            "act_pos": self.wrapped(self.act_pos),
            "act_vel": self.act_vel.copy(),
            "cmd_trq": np.where(self.trq_active, self.trq_cmd, self.act_trq),  # Cmd.Trq = Act.Trq outside
            "act_trq": self.act_trq.copy(),
            "drv": self.drv.copy(),
            "discrete": tuple(a.capture(st) for a, st in zip(self.axes, self.state.tolist(), strict=True)),
            "groups": tuple(g.capture() for g in self.groups),
        }


def drv_status(bits: int) -> dict[str, bool]:
    return {name: bool(bits & (1 << k)) for k, name in enumerate(DRV_BITS)}
