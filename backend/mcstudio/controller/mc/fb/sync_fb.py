"""Synchronized control instructions: MC_CamIn, MC_CamOut, MC_GearIn, MC_GearInPos, MC_GearOut, MC_MoveLink,
MC_CombineAxes — inputs, outputs and rules as in `omron-axis-instructions.md` (seed 000 chapter 3, lines 6635–10417).

Each instruction checks its inputs (the manual's ErrorIDs, input errors before state errors as for the other motion
instructions, decision D2) and submits a `JobKind.SYNC` job carrying a law from `sync.py`; the MC module's sync
stage computes the slave's command position from the master every period. MC_CamOut and MC_GearOut submit a
`JobKind.SYNC_OUT` deceleration (the slave goes Synchronized → Discrete, A-3.4).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from .. import errors as E
from ..jobs import Job, JobKind, JobStatus
from ..sync import REF_FEEDBACK, REF_LATEST, CamLaw, CombineLaw, CyclicPositionLaw, GearLaw, GearPosLaw, LinkLaw
from ..units import fits_distance, fits_position
from .base import I_EXECUTE, O_ABORTED, O_ACTIVE, O_BUSY, O_DONE, O_ERROR, O_ERRORID, ExecuteFB, FBDef, Var
from .latch import IO_TRIGGER, IO_TRIGGER_VAR, _Latcher, latch_pdo_missing, parse_trigger
from .single_axis import _clamp_profile, start_limit_error

if TYPE_CHECKING:
    from ..axis import Axis

E_MASTER_ILLEGAL = 0x5462
E_MASTER_UNUSED = 0x5468
E_SAME_AXIS = 0x5436
E_AUX_SAME_AXIS = 0x5437
E_AUX_SLAVE_SAME = 0x548E
E_NOT_ASCENDING = 0x5438
E_AUX_NOT_ASCENDING = 0x547F
E_CAM_TABLE = 0x5439
E_CAM_ABORTED_TABLE = 0x5743
E_SYNC_STOPPED = 0x543A
E_RATIO_NUM = 0x5420
E_RATIO_DEN = 0x5421
E_MASTER_SCALING = 0x5428
E_SLAVE_SCALING = 0x5429
E_START_MODE = 0x5471
E_CAM_TRANSITION = 0x5490
E_OUT_MODE = 0x5491
E_START_POSITION = 0x547A
E_MASTER_START_DISTANCE = 0x547B
E_MASTER_OFFSET = 0x5493
E_SLAVE_OFFSET = 0x5494
E_MASTER_SYNC_POS = 0x546C
E_SLAVE_SYNC_POS = 0x546D
E_LINK_OPTION = 0x5435
E_LINK_SHORT = 0x5446
E_MASTER_DISTANCE = 0x5482
E_MASTER_DIST_ACC = 0x5483
E_MASTER_DIST_DEC = 0x5484
E_SLAVE_DISTANCE = 0x548B
E_COMBINE_MODE = 0x5434
# re-execution: an input that may not change (A-1 #56–67)
E_REEXEC_MASTER = 0x5459
E_REEXEC_MASTER_OFFSET = 0x545A
E_REEXEC_MASTER_SCALING = 0x545B
E_REEXEC_MASTER_START_DISTANCE = 0x545C
E_REEXEC_SLAVE_OFFSET = 0x5463
E_REEXEC_SLAVE_SCALING = 0x5464
E_REEXEC_START_MODE = 0x5472

IO_MASTER = Var("Master", "_sAXIS_REF", None, "Master axis")
IO_SLAVE = Var("Slave", "_sAXIS_REF", None, "Slave axis")
I_REFTYPE = Var("ReferenceType", "_eMC_REFERENCE_TYPE", 0, "Master position used: 0 command of the previous period, "
                "1 feedback of this period, 2 command of this period (master axis number < slave axis number)",
                None, "0–2")
I_ACC = Var("Acceleration", "LREAL", 0.0, "Acceleration (0 = no ramp)", "unit/s²", "positive or 0")
I_DEC = Var("Deceleration", "LREAL", 0.0, "Deceleration (0 = no ramp)", "unit/s²", "positive or 0")
I_JERK = Var("Jerk", "LREAL", 0.0, "Reserved", "unit/s³", "0")
I_RATIO_NUM = Var("RatioNumerator", "DINT", 10000, "Gear ratio numerator (negative: opposite direction)", None,
                  "positive or negative")
I_RATIO_DEN = Var("RatioDenominator", "UDINT", 10000, "Gear ratio denominator", None, "positive")
I_OUT_MODE = Var("OutMode", "_eMC_OUT_MODE", 0, "Reserved: _mcStop", None, "0", allowed=(0,))


def _may_start(fb: ExecuteFB, axis: Axis, accept: str, check: Callable[[Axis], int], *,
               direction_less: bool = False) -> bool:
    """The acceptance in the axis state (A-3, `acceptance.py`) and the instruction's input checks — input errors
    before state errors (D2); False once the instance shows CommandAborted or Error.

    `direction_less`: a motion instruction that specifies no direction of motion (synchronized control and the
    cyclic synchronous instructions, decision D132) is refused with 6443/6444 while either limit input of the axis is
    ON (A-1 #145/#146, seed 000 lines 21279–21300) — after the input and state checks, as the limit checks of the
    direction-defined instructions come after theirs (`_MotionFB.execute`)."""
    verdict, code = axis.check_start(accept)
    if verdict == "abort":
        fb._finish("CommandAborted")
        return False
    if code != E.E_AXIS_TYPE:  # an encoder axis is refused before anything else
        code = check(axis) or code
    if not code and direction_less:
        code = start_limit_error(axis, 0)  # direction 0, no target: the limit inputs only
    if code:
        fb.fail(code, axis)
        return False
    return True


class _SyncFB(ExecuteFB):
    """A synchronized-control instruction: the slave is the axis the job runs on."""

    ACCEPT = "move"
    LATCHED: tuple[tuple[str, int], ...] = ()  # inputs re-execution may not change, with their ErrorID

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        # The law's outputs (InCam, InSync, InGear, Index …) are pushed by the sync stage, which also wakes the
        # instance; its call may sleep like a plain instruction's (a pulse to clear forces the next call, below)
        cls._plain = "call" not in vars(cls) and "after_call" not in vars(cls) and not cls.EVERY_PERIOD

    EVERY_PERIOD = False  # the instruction reads its inputs every period (it must never sleep)

    def resolve_axis(self, name_input: str = "Slave", *, allow_unused: bool = False) -> Axis | None:
        return super().resolve_axis(name_input, allow_unused=allow_unused)

    # -- checks shared by the instructions with a master
    def _master(self, slave: Axis, name: str = "Master", ref_input: str = "ReferenceType") -> tuple[Axis | None, int]:
        mc = self.mc
        master = mc.by_name.get(self.inp.get(name) or "")
        if master is None:
            return None, E_MASTER_ILLEGAL
        if not master.used:
            return None, E_MASTER_UNUSED
        if master is slave:
            return None, E_SAME_AXIS if name == "Master" else E_AUX_SLAVE_SAME
        ref = self.inp.get(ref_input, 0)
        if ref not in (0, 1, 2) or (master.encoder and ref != REF_FEEDBACK):
            return None, E.E_POSITION_TYPE  # 5430: out of range, or a command position of an encoder axis
        if ref == REF_LATEST and master.i >= slave.i:
            return None, E_NOT_ASCENDING if name == "Master" else E_AUX_NOT_ASCENDING
        return master, 0

    def _check(self, slave: Axis) -> int:
        raise NotImplementedError

    def _law(self, slave: Axis, job: Job) -> Any:
        raise NotImplementedError

    def execute(self, axis: Axis) -> None:
        if not _may_start(self, axis, self.ACCEPT, self._check, direction_less=True):
            return
        job = Job(JobKind.SYNC, self, buffer_mode=self.inp.get("BufferMode", 0))
        job.info["law"] = self._law(axis, job)
        job.info["latched"] = {k: self.inp[k] for k, _ in self.LATCHED}
        self._clear_sync_outputs()
        self._submit(axis, job, "ok", 0)

    def _reexec_latched(self, axis: Axis) -> bool:
        job = self.job
        if job is None:
            return False
        latched = job.info["latched"]
        for name, code in self.LATCHED:
            if self.inp[name] != latched[name]:
                self.fail(code, axis)
                return False
        return True

    # -- outputs
    SYNC_OUTPUTS: tuple[str, ...] = ()

    def _clear_sync_outputs(self) -> None:
        o = self.out
        for k in self.SYNC_OUTPUTS:
            o[k] = 0 if k == "Index" else False

    def _show(self, law: Any) -> None:
        """Copy the law's flags to the outputs (subclasses)."""

    def sync_job(self) -> None:
        job = self.job
        if job is None:
            return
        st = job.status
        if st == JobStatus.ACTIVE:
            self._show(job.info["law"])
            if job.info.get("quiet_cycle") == self.mc.cycle:
                return  # started by this period's call: Active from the next call (outputs of the law show now)
        elif st in (JobStatus.ABORTED, JobStatus.ERROR, JobStatus.DONE):
            self._clear_sync_outputs()
            for dep in list(getattr(job.info.get("law"), "dependents", ())):
                dep.sync_ended()  # MC_Phasing / MC_SyncOffsetPosition on it: CommandAborted in the same period
        super().sync_job()

    def _set_error(self, code: int, axis: Axis | None) -> None:
        super()._set_error(code, axis)
        self._clear_sync_outputs()


# --------------------------------------------------------------------------------------------------- MC_CamIn
class MC_CamIn(_SyncFB):
    DEF = FBDef(
        name="MC_CamIn",
        title="Start cam operation",
        summary="The slave follows the master through a cam table (phase → displacement), once or periodically.",
        kind="execute",
        inouts=(IO_MASTER, IO_SLAVE,
                Var("CamTable", "_sMC_CAM_REF", None, "Cam data variable (name of the cam table)")),
        inputs=(
            I_EXECUTE,
            Var("Periodic", "BOOL", False, "TRUE: repeat the cam table; FALSE: execute it once"),
            Var("StartMode", "_eMC_START_MODE", 0, "MasterStartDistance is absolute or relative to StartPosition",
                None, "0, 1"),
            Var("StartPosition", "LREAL", 0.0, "Master absolute position of the cam table start point (phase 0)",
                "unit", "negative, positive, 0"),
            Var("MasterStartDistance", "LREAL", 0.0, "Master position where the slave starts camming", "unit",
                "negative, positive, 0"),
            Var("MasterScaling", "LREAL", 1.0, "Scales the master phase", None, "positive"),
            Var("SlaveScaling", "LREAL", 1.0, "Scales the slave displacement", None, "positive"),
            Var("MasterOffset", "LREAL", 0.0, "Shifts the master phase", "unit", "negative, positive, 0"),
            Var("SlaveOffset", "LREAL", 0.0, "Shifts the slave displacement", "unit", "negative, positive, 0"),
            I_REFTYPE,
            Var("Direction", "_eMC_DIRECTION", 4, "Cam only while the master moves in this direction", None,
                "0, 2, 4", allowed=(0, 2, 4)),
            Var("CamTransition", "_eMC_CAM_TRANSITION", 0, "Reserved: _mcCTNone", None, "0", allowed=(0,)),
            Var("BufferMode", "_eMC_BUFFER_MODE", 0, "Behaviour on multi-execution (blending only onto MC_CamIn)",
                None, "0–5"),
        ),
        outputs=(
            Var("InCam", "BOOL", False, "TRUE once the master passed StartPosition (cam table start point executed)"),
            Var("InSync", "BOOL", False, "TRUE while the slave cams (master passed the cam start position)"),
            Var("EndOfProfile", "BOOL", False, "Pulses for one period when the cam table end point is output"),
            Var("Index", "UINT", 0, "Index of the cam data point in use (the lower of the two interpolated)"),
            O_BUSY, O_ACTIVE, O_ABORTED, O_ERROR, O_ERRORID,
        ),
        spec="omron-axis-instructions.md MC_CamIn (seed 000 line 6635)",
        notes="No Done: a non-periodic cam ends with EndOfProfile and Busy/Active/InCam/InSync dropping. "
              "Re-execution switches the cam table only.",
    )
    SYNC_OUTPUTS = ("InCam", "InSync", "EndOfProfile", "Index")
    LATCHED = (("Master", E_REEXEC_MASTER), ("StartMode", E_REEXEC_START_MODE),
               ("MasterStartDistance", E_REEXEC_MASTER_START_DISTANCE), ("MasterScaling", E_REEXEC_MASTER_SCALING),
               ("SlaveScaling", E_REEXEC_SLAVE_SCALING), ("MasterOffset", E_REEXEC_MASTER_OFFSET),
               ("SlaveOffset", E_REEXEC_SLAVE_OFFSET))

    def __init__(self, mc: Any, fb_id: int, inputs: dict[str, Any] | None = None) -> None:
        super().__init__(mc, fb_id, inputs)
        self._cam: CamLaw | None = None

    def _table(self) -> tuple[Any, int]:
        table = self.mc.cam_tables.get(self.inp.get("CamTable") or "")
        if table is None:
            return None, E_CAM_TABLE
        if table.generation_aborted:
            return None, E_CAM_ABORTED_TABLE
        if table.end_point_index is None:
            return None, E_CAM_TABLE  # no valid end point: not a usable cam data variable (decision D43)
        holder = self.mc.cam_locks.get(self.inp["CamTable"])
        if holder is not None and holder.DEF.name == "MC_GenerateCamTable":
            return None, E.E_MULTIEXEC_DISABLED  # the table is being generated (§5.0.3)
        return table, 0

    def _check(self, slave: Axis) -> int:
        i = self.inp
        master, code = self._master(slave)
        if code:
            return code
        assert master is not None
        _, code = self._table()
        if code:
            return code
        if i["StartMode"] not in (0, 1):
            return E_START_MODE
        if not i["MasterScaling"] > 0:
            return E_MASTER_SCALING
        if not i["SlaveScaling"] > 0:
            return E_SLAVE_SCALING
        if i["Direction"] not in (0, 2, 4):
            return E.E_DIRECTION
        if i["CamTransition"] != 0:
            return E_CAM_TRANSITION
        if i["BufferMode"] not in range(6):
            return E.E_BUFFER_MODE
        if not fits_position(i["StartPosition"], master.ppu):
            return E_START_POSITION
        if not fits_position(i["MasterStartDistance"], master.ppu):
            return E_MASTER_START_DISTANCE
        if not fits_position(i["MasterOffset"], master.ppu):
            return E_MASTER_OFFSET
        if not fits_position(i["SlaveOffset"], slave.ppu):
            return E_SLAVE_OFFSET
        return 0

    def _law(self, slave: Axis, job: Job) -> CamLaw:
        i = self.inp
        master, _ = self._master(slave)
        table, _ = self._table()
        assert master is not None
        law = CamLaw(self.mc, job, slave, master, table, ref=i["ReferenceType"], periodic=i["Periodic"],
                     start_mode=i["StartMode"], start_position=i["StartPosition"],
                     master_start_distance=i["MasterStartDistance"], master_scaling=i["MasterScaling"],
                     slave_scaling=i["SlaveScaling"], master_offset=i["MasterOffset"],
                     slave_offset=i["SlaveOffset"], direction=i["Direction"])
        self._cam = law
        return law

    def reexecute(self, axis: Axis) -> None:
        """Re-execution switches the cam table (the other inputs may not change): InCam/InSync keep their states
        and camming continues in the new table from the phase the master is at (MC_CamIn re-execution rules)."""
        if not self._reexec_latched(axis):
            return
        job = self.job
        assert job is not None
        table, code = self._table()
        if code:
            self.fail(code, axis)
            return
        job.info["law"].set_table(table)

    def _show(self, law: CamLaw) -> None:
        o = self.out
        o["InCam"] = law.in_cam
        o["InSync"] = law.in_sync
        o["Index"] = law.index if law.in_cam else 0

    def sync_job(self) -> None:
        law = self._cam
        o = self.out
        if law is not None:
            o["EndOfProfile"] = law.eop_cycle == self.mc.cycle
        job = self.job
        if job is not None and job.status == JobStatus.DONE:
            # the end point of a non-periodic cam was output (or a buffered instruction took over at the end of the
            # cycle): Busy, Active, InCam and InSync drop with the EndOfProfile pulse; MC_CamIn has no Done
            self.job = None
            self.wake()
            o["Busy"] = o["Active"] = o["InCam"] = o["InSync"] = False
            o["Index"] = 0
            self._end_cycle = self.mc.cycle
            return
        eop = o["EndOfProfile"]
        super().sync_job()
        o["EndOfProfile"] = eop and not o["Error"]
        if eop:
            self.__dict__["_seen_status"] = None  # call again next period to end the pulse


# --------------------------------------------------------------------------------------------------- MC_CamOut
_OUT_INPUTS = (I_EXECUTE, Var("Deceleration", "LREAL", 0.0, "Deceleration (0 = stop at once)", "unit/s²",
                              "positive or 0"), I_JERK, I_OUT_MODE)


class _OutFB(_SyncFB):
    KINDS: tuple[str, ...] = ()
    ACCEPT = "sync_out"
    sync_job = ExecuteFB.sync_job  # a deceleration job: Done at velocity 0, no law outputs

    def _check(self, slave: Axis) -> int:
        i = self.inp
        if not i["Deceleration"] >= 0:
            return E.E_DECELERATION
        if not i["Jerk"] >= 0:
            return E.E_JERK
        if i["OutMode"] != 0:
            return E_OUT_MODE
        cur = slave.current
        law = cur.info.get("law") if cur is not None and cur.kind == JobKind.SYNC and cur.running else None
        if (law is None or law.kind not in self.KINDS) and slave.state.name == "Synchronized":
            return E_SYNC_STOPPED
        return 0

    def execute(self, axis: Axis) -> None:
        if not _may_start(self, axis, self.ACCEPT, self._check):
            return
        dec = self.inp["Deceleration"]
        _, _, dec = _clamp_profile(axis, 0.0, 0.0, dec)
        job = Job(JobKind.SYNC_OUT, self, deceleration=dec)
        self._submit(axis, job, "ok", 0)


class MC_CamOut(_OutFB):
    DEF = FBDef(
        name="MC_CamOut",
        title="End cam operation",
        summary="Ends camming of the slave: it decelerates to a stop; the master is not affected.",
        kind="execute",
        inouts=(IO_SLAVE,),
        inputs=_OUT_INPUTS,
        outputs=(O_DONE, O_BUSY, O_ABORTED, O_ERROR, O_ERRORID),
        spec="omron-axis-instructions.md MC_CamOut (seed 000 line 8217)",
    )
    HAS_ACTIVE = False
    KINDS = ("cam",)


class MC_GearOut(_OutFB):
    DEF = FBDef(
        name="MC_GearOut",
        title="End gear operation",
        summary="Ends MC_GearIn / MC_GearInPos on the slave: it decelerates to a stop; the master is not affected.",
        kind="execute",
        inouts=(IO_SLAVE,),
        inputs=_OUT_INPUTS,
        outputs=(O_DONE, O_BUSY, O_ABORTED, O_ERROR, O_ERRORID),
        spec="omron-axis-instructions.md MC_GearOut (seed 000 line 9429)",
    )
    HAS_ACTIVE = False
    KINDS = ("gear", "gearpos")


# --------------------------------------------------------------------------------------------------- MC_GearIn
def _ratio_error(i: dict[str, Any]) -> int:
    if i["RatioNumerator"] == 0:
        return E_RATIO_NUM
    if not i["RatioDenominator"] > 0:
        return E_RATIO_DEN
    return 0


def _acc_dec_error(i: dict[str, Any]) -> int:
    if not i["Acceleration"] >= 0:
        return E.E_ACCELERATION
    if not i["Deceleration"] >= 0:
        return E.E_DECELERATION
    if not i["Jerk"] >= 0:
        return E.E_JERK
    return 0


class MC_GearIn(_SyncFB):
    DEF = FBDef(
        name="MC_GearIn",
        title="Start gear operation",
        summary="The slave catches up to master velocity × ratio (Acceleration/Deceleration), then follows the "
                "master's position increments × ratio (InGear).",
        kind="execute",
        inouts=(IO_MASTER, IO_SLAVE),
        inputs=(
            I_EXECUTE, I_RATIO_NUM, I_RATIO_DEN, I_REFTYPE, I_ACC, I_DEC, I_JERK,
            Var("BufferMode", "_eMC_BUFFER_MODE", 0, "Behaviour on multi-execution", None, "0, 1", allowed=(0, 1)),
        ),
        outputs=(
            Var("InGear", "BOOL", False, "TRUE when the slave reached the target velocity (master velocity × ratio)"),
            O_BUSY, O_ACTIVE, O_ABORTED, O_ERROR, O_ERRORID,
        ),
        spec="omron-axis-instructions.md MC_GearIn (seed 000 line 8324)",
        notes="Re-execution may change RatioNumerator, RatioDenominator, Acceleration and Deceleration.",
    )
    SYNC_OUTPUTS = ("InGear",)
    LATCHED = (("Master", E_REEXEC_MASTER), ("BufferMode", E.E_REEXEC_BUFFER_MODE))

    def _check(self, slave: Axis) -> int:
        i = self.inp
        _, code = self._master(slave)
        if code:
            return code
        code = _ratio_error(i) or _acc_dec_error(i)
        if code:
            return code
        if i["BufferMode"] not in (0, 1):
            return E.E_BUFFER_MODE
        return 0

    def _params(self, slave: Axis) -> tuple[float, float, float]:
        i = self.inp
        _, acc, dec = _clamp_profile(slave, 0.0, i["Acceleration"], i["Deceleration"])
        return i["RatioNumerator"] / i["RatioDenominator"], acc, dec

    def _law(self, slave: Axis, job: Job) -> GearLaw:
        master, _ = self._master(slave)
        assert master is not None
        ratio, acc, dec = self._params(slave)
        return GearLaw(self.mc, job, slave, master, ratio=ratio, ref=self.inp["ReferenceType"], acceleration=acc,
                       deceleration=dec)

    def reexecute(self, axis: Axis) -> None:
        if not self._reexec_latched(axis):
            return
        code = _ratio_error(self.inp) or _acc_dec_error(self.inp)
        if code:
            self.fail(code, axis)
            return
        job = self.job
        assert job is not None
        ratio, acc, dec = self._params(axis)
        job.info["law"].set_ratio(ratio, acc, dec)

    def _show(self, law: GearLaw) -> None:
        self.out["InGear"] = law.in_gear


class MC_GearInPos(_SyncFB):
    DEF = FBDef(
        name="MC_GearInPos",
        title="Positioning gear operation",
        summary="The slave catches up so that it is at SlaveSyncPosition when the master is at MasterSyncPosition, "
                "then follows the master × ratio.",
        kind="execute",
        inouts=(IO_MASTER, IO_SLAVE),
        inputs=(
            I_EXECUTE, I_RATIO_NUM, I_RATIO_DEN, I_REFTYPE,
            Var("MasterSyncPosition", "LREAL", 0.0, "Master position of synchronization (absolute)", "unit"),
            Var("SlaveSyncPosition", "LREAL", 0.0, "Slave position of synchronization (absolute)", "unit"),
            Var("Velocity", "LREAL", 0.0, "Target velocity of the catch-up", "unit/s", "positive"),
            I_ACC, I_DEC, I_JERK,
            Var("BufferMode", "_eMC_BUFFER_MODE", 0, "Reserved: _mcAborting", None, "0", allowed=(0,)),
        ),
        outputs=(
            Var("StartSync", "BOOL", False, "TRUE once the slave started the catch-up"),
            Var("InSync", "BOOL", False, "TRUE once the slave reached SlaveSyncPosition with the master at "
                "MasterSyncPosition"),
            O_BUSY, O_ACTIVE, O_ABORTED, O_ERROR, O_ERRORID,
        ),
        spec="omron-axis-instructions.md MC_GearInPos (seed 000 line 8880)",
    )
    ACCEPT = "standstill_only"
    SYNC_OUTPUTS = ("StartSync", "InSync")

    def _check(self, slave: Axis) -> int:
        i = self.inp
        master, code = self._master(slave)
        if code:
            return code
        assert master is not None
        code = _ratio_error(i)
        if code:
            return code
        if not i["Velocity"] > 0:
            return E.E_VELOCITY
        code = _acc_dec_error(i)
        if code:
            return code
        if i["BufferMode"] != 0:
            return E.E_BUFFER_MODE
        if not fits_position(i["MasterSyncPosition"], master.ppu):
            return E_MASTER_SYNC_POS
        if not fits_position(i["SlaveSyncPosition"], slave.ppu):
            return E_SLAVE_SYNC_POS
        return 0

    def _law(self, slave: Axis, job: Job) -> GearPosLaw:
        i = self.inp
        master, _ = self._master(slave)
        assert master is not None
        v, acc, dec = _clamp_profile(slave, i["Velocity"], i["Acceleration"], i["Deceleration"])
        return GearPosLaw(self.mc, job, slave, master, ratio=i["RatioNumerator"] / i["RatioDenominator"],
                          ref=i["ReferenceType"], master_sync=i["MasterSyncPosition"],
                          slave_sync=i["SlaveSyncPosition"], velocity=v, acceleration=acc, deceleration=dec)

    def _show(self, law: GearPosLaw) -> None:
        self.out["StartSync"] = law.start_sync
        self.out["InSync"] = law.in_sync


# --------------------------------------------------------------------------------------------------- MC_MoveLink
class MC_MoveLink(_Latcher, _SyncFB):
    DEF = FBDef(
        name="MC_MoveLink",
        title="Synchronous positioning",
        summary="The slave moves SlaveDistance as a trapezoid over MasterDistance of master travel (acceleration "
                "over MasterDistanceInACC, deceleration over MasterDistanceInDEC), after the start condition.",
        kind="execute",
        inouts=(IO_MASTER, IO_SLAVE, IO_TRIGGER, IO_TRIGGER_VAR),
        inputs=(
            I_EXECUTE, I_REFTYPE,
            Var("SlaveDistance", "LREAL", 0.0, "Slave travel distance", "unit", "negative, positive, 0"),
            Var("MasterDistance", "LREAL", 0.0, "Master travel distance", "unit", "positive or 0"),
            Var("MasterDistanceInACC", "LREAL", 0.0, "Master travel while the slave accelerates", "unit",
                "positive or 0"),
            Var("MasterDistanceInDEC", "LREAL", 0.0, "Master travel while the slave decelerates", "unit",
                "positive or 0"),
            Var("LinkOption", "_eMC_LINKOPTION", 0, "Start condition: 0 at once, 1 on the trigger (the slave's "
                "latch or TriggerVariable), 2 when the master reaches MasterStartDistance", None, "0–2"),
            Var("MasterStartDistance", "LREAL", 0.0, "Master position where the link starts (LinkOption 2)",
                "unit"),
            Var("BufferMode", "_eMC_BUFFER_MODE", 0, "Behaviour on multi-execution", None, "0, 1", allowed=(0, 1)),
        ),
        outputs=(
            O_DONE,
            Var("InSync", "BOOL", False, "TRUE while the slave moves synchronized to the master"),
            O_BUSY, O_ACTIVE, O_ABORTED, O_ERROR, O_ERRORID,
        ),
        spec="omron-axis-instructions.md MC_MoveLink (seed 000 line 9537)",
    )
    SYNC_OUTPUTS = ("InSync",)

    def latch_active(self) -> bool:
        return bool(self.out["Busy"]) and self._waiting_trigger

    _waiting_trigger = False
    _fired = False

    def execute(self, axis: Axis) -> None:
        super().execute(axis)
        job = self.job
        if job is None or self.inp["LinkOption"] != 1:
            return
        code = self._claim(axis, self._slot)
        if code:
            self.fail(code, axis)
            return
        self._fired = False
        self._waiting_trigger = True
        job.info["law"].trigger = lambda: self._fired
        self._arm()

    def watch(self) -> None:
        """Each period while waiting for the trigger (the slave's drive latch or TriggerVariable)."""
        job = self.job
        if job is None or not job.running or job.status != JobStatus.ACTIVE:
            return
        if self._poll() is not None:
            self._fired = True
            self._waiting_trigger = False
            self._release()

    def on_job_end(self) -> None:
        self._waiting_trigger = False
        if hasattr(self, "_slot"):
            self._release()

    def on_delete(self) -> None:
        self.on_job_end()

    def _check(self, slave: Axis) -> int:
        i = self.inp
        master, code = self._master(slave)
        if code:
            return code
        assert master is not None
        if not fits_distance(i["SlaveDistance"], slave.ppu):
            return E_SLAVE_DISTANCE
        if not i["MasterDistance"] >= 0 or not fits_distance(i["MasterDistance"], master.ppu):
            return E_MASTER_DISTANCE
        if not i["MasterDistanceInACC"] >= 0:
            return E_MASTER_DIST_ACC
        if not i["MasterDistanceInDEC"] >= 0:
            return E_MASTER_DIST_DEC
        if i["MasterDistanceInACC"] + i["MasterDistanceInDEC"] > i["MasterDistance"]:
            return E_LINK_SHORT
        if i["LinkOption"] not in (0, 1, 2):
            return E_LINK_OPTION
        if i["LinkOption"] == 1:
            err, self._mode, self._slot, self._z = parse_trigger(i.get("TriggerInput"))
            code = err or latch_pdo_missing(slave, self._mode, self._slot)  # the slave's latch (drive mode)
            if code:
                return code
        if i["BufferMode"] not in (0, 1):
            return E.E_BUFFER_MODE
        return 0

    def _law(self, slave: Axis, job: Job) -> LinkLaw:
        i = self.inp
        master, _ = self._master(slave)
        assert master is not None
        return LinkLaw(self.mc, job, slave, master, ref=i["ReferenceType"], slave_distance=i["SlaveDistance"],
                       master_distance=i["MasterDistance"], acc_distance=i["MasterDistanceInACC"],
                       dec_distance=i["MasterDistanceInDEC"], option=i["LinkOption"],
                       master_start=i["MasterStartDistance"])

    def _show(self, law: LinkLaw) -> None:
        self.out["InSync"] = law.in_sync and not law.done


# --------------------------------------------------------------------------------------------------- MC_CombineAxes
class MC_CombineAxes(_SyncFB):
    DEF = FBDef(
        name="MC_CombineAxes",
        title="Combine axes",
        summary="The slave follows the sum (or difference) of the master's and the auxiliary axis's travel.",
        kind="execute",
        inouts=(IO_MASTER, Var("Auxiliary", "_sAXIS_REF", None, "Auxiliary axis"), IO_SLAVE),
        inputs=(
            I_EXECUTE,
            Var("CombineMode", "_eMC_COMBINE_MODE", 0, "0 addition, 1 subtraction", None, "0, 1", allowed=(0, 1)),
            Var("RatioNumeratorMaster", "DINT", 10000, "Reserved"),
            Var("RatioDenominatorMaster", "UDINT", 10000, "Reserved", None, "positive"),
            Var("RatioNumeratorAuxiliary", "DINT", 10000, "Reserved"),
            Var("RatioDenominatorAuxiliary", "UDINT", 10000, "Reserved", None, "positive"),
            Var("ReferenceTypeMaster", "_eMC_REFERENCE_TYPE", 2, "Master position type: 1 feedback, 2 latest command",
                None, "1, 2", allowed=(1, 2)),
            Var("ReferenceTypeAuxiliary", "_eMC_REFERENCE_TYPE", 2, "Auxiliary position type: 1 feedback, 2 latest "
                "command", None, "1, 2", allowed=(1, 2)),
            Var("BufferMode", "_eMC_BUFFER_MODE", 0, "Reserved: _mcAborting", None, "0", allowed=(0,)),
        ),
        outputs=(
            Var("InCombination", "BOOL", False, "TRUE while the slave follows the combined position"),
            O_BUSY, O_ACTIVE, O_ABORTED, O_ERROR, O_ERRORID,
        ),
        spec="omron-axis-instructions.md MC_CombineAxes (seed 000 line 10194)",
    )
    SYNC_OUTPUTS = ("InCombination",)

    def _check(self, slave: Axis) -> int:
        i = self.inp
        if i["ReferenceTypeMaster"] not in (1, 2):
            return 0x549A  # Master Axis Position Type Selection Out of Range (A-1 #117)
        if i["ReferenceTypeAuxiliary"] not in (1, 2):
            return 0x549B  # Auxiliary Axis Position Type Selection Out of Range (A-1 #118)
        master, code = self._master(slave, "Master", "ReferenceTypeMaster")
        if code:
            return code
        aux, code = self._master(slave, "Auxiliary", "ReferenceTypeAuxiliary")
        if code:
            return code
        if aux is master:
            return E_AUX_SAME_AXIS
        if i["CombineMode"] not in (0, 1):
            return E_COMBINE_MODE
        if i["RatioNumeratorMaster"] == 0:
            return 0x5496
        if not i["RatioDenominatorMaster"] > 0:
            return 0x5497
        if i["RatioNumeratorAuxiliary"] == 0:
            return 0x5498
        if not i["RatioDenominatorAuxiliary"] > 0:
            return 0x5499
        if i["BufferMode"] != 0:
            return E.E_BUFFER_MODE
        return 0

    def _law(self, slave: Axis, job: Job) -> CombineLaw:
        i = self.inp
        master, _ = self._master(slave, "Master", "ReferenceTypeMaster")
        aux, _ = self._master(slave, "Auxiliary", "ReferenceTypeAuxiliary")
        assert master is not None and aux is not None
        return CombineLaw(self.mc, job, slave, master, aux, subtract=i["CombineMode"] == 1,
                          ref_master=i["ReferenceTypeMaster"], ref_aux=i["ReferenceTypeAuxiliary"])

    def _show(self, law: CombineLaw) -> None:
        self.out["InCombination"] = law.in_sync


# --------------------------------------------------------------------------------------------------- compensation
class _CompensationFB(ExecuteFB):
    """MC_Phasing / MC_SyncOffsetPosition: no motion job of their own; they act on the law of the synchronized
    instruction running on the slave (the axis stays Synchronized, A-3.4 E*8) and end with CommandAborted when
    that instruction ends (their rules)."""

    KINDS: tuple[str, ...] = ("cam", "gear", "gearpos", "link")

    def __init__(self, mc: Any, fb_id: int, inputs: dict[str, Any] | None = None) -> None:
        super().__init__(mc, fb_id, inputs)
        self._law: Any = None

    def resolve_axis(self, name_input: str = "Slave", *, allow_unused: bool = False) -> Axis | None:
        return super().resolve_axis(name_input if name_input in self.inp else "Axis", allow_unused=allow_unused)

    def running_law(self, slave: Axis) -> Any:
        cur = slave.current
        if cur is None or cur.kind != JobKind.SYNC or not cur.running:
            return None
        law = cur.info.get("law")
        return law if law is not None and law.kind in self.KINDS else None

    def _attached(self) -> bool:
        """Still working on the synchronized instruction it was started on."""
        law = self._law
        return law is not None and law.job.running and law.slave.current is law.job

    def _abort(self) -> None:
        law, self._law = self._law, None
        deps = getattr(law, "dependents", None)
        if deps is not None and self in deps:
            deps.remove(self)
        self._finish("CommandAborted")

    def _attach(self, law: Any) -> None:
        self._law = law
        self.mc.sync_changed()  # compensation: the follower leaves the batch (sync_batch.py)
        if not hasattr(law, "dependents"):
            law.dependents = []
        if self not in law.dependents:
            law.dependents.append(self)

    def sync_ended(self) -> None:
        if self._law is not None:
            self._abort()

    def sync_job(self) -> None:
        if self._law is None:
            return
        if not self._attached():
            self._abort()
            return
        self.out["Active"] = True
        self.track()

    def track(self) -> None:
        """Per-call work while Active."""


class MC_Phasing(_CompensationFB):
    DEF = FBDef(
        name="MC_Phasing",
        title="Shift master axis phase",
        summary="Shifts the master phase the slave follows by PhaseShift (a relative profile at Velocity, "
                "Acceleration, Deceleration) without moving the master.",
        kind="execute",
        inouts=(IO_MASTER, IO_SLAVE),
        inputs=(
            I_EXECUTE,
            Var("PhaseShift", "LREAL", 0.0, "Master phase compensation (relative)", "unit", "negative, positive, 0"),
            Var("Velocity", "LREAL", 0.0, "Compensation velocity (relative to the master)", "unit/s", "positive"),
            I_ACC, I_DEC,
            Var("Jerk", "LREAL", 0.0, "Jerk (0 = trapezoid)", "unit/s³", "positive or 0"),
            Var("BufferMode", "_eMC_BUFFER_MODE", 0, "Reserved: _mcAborting", None, "0", allowed=(0,)),
        ),
        outputs=(O_DONE, O_BUSY, O_ACTIVE, O_ABORTED, O_ERROR, O_ERRORID),
        spec="omron-axis-instructions.md MC_Phasing (seed 000 line 10418)",
        notes="Re-execution starts a new compensation profile for the changed PhaseShift from where the running one "
              "is (decision D42).",
    )

    def _check(self, slave: Axis) -> tuple[Any, int]:
        i = self.inp
        master = self.mc.by_name.get(i.get("Master") or "")
        if master is None:
            return None, E_MASTER_ILLEGAL
        if master is slave:
            return None, E_SAME_AXIS
        law = self.running_law(slave)
        if law is None:
            return None, E_SYNC_STOPPED
        if master.i not in law.masters:
            return None, E_MASTER_ILLEGAL  # not the master of the running synchronized instruction (A-1 #65)
        if not fits_distance(i["PhaseShift"], master.ppu):
            return None, 0x548C
        if not i["Velocity"] > 0:
            return None, E.E_VELOCITY
        code = _acc_dec_error(i)
        if code:
            return None, code
        if i["BufferMode"] != 0:
            return None, E.E_BUFFER_MODE
        return law, 0

    def execute(self, axis: Axis) -> None:
        _, code = axis.check_start("admin")
        law, code2 = self._check(axis)
        code = code2 or code
        if code:
            self.fail(code, axis)
            return
        self._start_profile(law)

    def _start_profile(self, law: Any) -> None:
        from ..sync import PhaseShift

        i = self.inp
        m = self.mc
        base = law.shift()  # the compensation already applied (a running MC_Phasing is taken over: Aborting)
        seg = m.planner.position(p0=0.0, v0=0.0, a0=0.0, target=i["PhaseShift"], velocity=i["Velocity"],
                                 acceleration=i["Acceleration"], deceleration=i["Deceleration"], jerk=i["Jerk"])
        old = law.phasing
        law.phasing = PhaseShift(seg, m.cycle + 1, base)
        law.phase_base = base
        owner = getattr(old, "owner", None)
        law.phasing.owner = self
        if owner is not None and owner is not self and owner._law is law:
            owner._abort()  # the previous MC_Phasing is replaced (Aborting): CommandAborted
        self._attach(law)

    def reexecute(self, axis: Axis) -> None:
        law, code = self._check(axis)
        if code:
            self.fail(code, axis)
            return
        self._start_profile(law)

    def track(self) -> None:
        law = self._law
        ph = law.phasing
        if ph is None or getattr(ph, "owner", None) is not self:
            self._abort()  # another MC_Phasing took over
            return
        if ph.done:
            self._law = None
            self._finish("Done")


class MC_SyncOffsetPosition(_CompensationFB):
    DEF = FBDef(
        name="MC_SyncOffsetPosition",
        title="Cyclic synchronous position offset compensation",
        summary="Adds OffsetPosition (relative to the start, may change every period) to the command position of "
                "a slave in synchronized control.",
        kind="execute",
        inouts=(Var("Axis", "_sAXIS_REF", None, "Slave axis in synchronized control"),),
        inputs=(
            I_EXECUTE,
            Var("OffsetPosition", "LREAL", 0.0, "Offset added to the command position (relative to the start)",
                "unit"),
            Var("BufferMode", "_eMC_BUFFER_MODE", 0, "Reserved: _mcAborting", None, "0", allowed=(0,)),
            Var("MoveMode", "_eMC_MOVE_MODE", 1, "Reserved: _mcRelative", None, "1", allowed=(1,)),
        ),
        outputs=(Var("OutputtedOffsetPosition", "LREAL", 0.0, "Offset added to the command position", "unit"),
                 O_BUSY, O_ACTIVE, O_ABORTED, O_ERROR, O_ERRORID),
        spec="omron-axis-instructions.md MC_SyncOffsetPosition (seed 000 line 14193)",
        notes="MoveMode defaults to _mcRelative, the only valid value (decision D43).",
    )
    KINDS = ("cam", "gear", "gearpos", "link")  # not MC_CombineAxes

    def __init__(self, mc: Any, fb_id: int, inputs: dict[str, Any] | None = None) -> None:
        super().__init__(mc, fb_id, inputs)
        self._base = 0.0

    def execute(self, axis: Axis) -> None:
        i = self.inp
        law = self.running_law(axis)
        code = 0
        if i["BufferMode"] != 0:
            code = E.E_BUFFER_MODE
        elif i["MoveMode"] != 1:
            code = E.E_MOVE_MODE
        elif law is None:
            code = E_SYNC_STOPPED
        if code:
            self.fail(code, axis)
            return
        old = getattr(law, "offset_owner", None)
        law.offset_owner = self
        if old is not None and old is not self and old._law is law:
            old._abort()  # the running instance is replaced: CommandAborted, its offset stays
        self._base = law.offset  # the offset already output stays; this instance adds to it
        self._attach(law)
        self.track()

    def sync_job(self) -> None:
        law = self._law
        if law is not None and getattr(law, "offset_owner", None) is not self:
            self._abort()  # another MC_SyncOffsetPosition took over
            return
        super().sync_job()

    def track(self) -> None:
        off = self.inp["OffsetPosition"]
        self._law.offset = self._base + off
        self.out["OutputtedOffsetPosition"] = off


# --------------------------------------------------------------------------------------------------- cyclic
class MC_SyncMoveAbsolute(_SyncFB):
    DEF = FBDef(
        name="MC_SyncMoveAbsolute",
        title="Cyclic synchronous absolute positioning",
        summary="Outputs the target position the program writes every period (no profile; the step limited to "
                "Maximum Velocity); InPosition when the feedback is within the in-position range of an unchanged "
                "target.",
        kind="execute",
        inouts=(Var("Axis", "_sAXIS_REF", None, "Axis"),),
        inputs=(
            I_EXECUTE,
            Var("Position", "LREAL", 0.0, "Absolute target position (may change every period)", "unit"),
            Var("Direction", "_eMC_DIRECTION", 1, "Direction in Rotary Mode (as MC_MoveAbsolute)", None, "0–4"),
            Var("BufferMode", "_eMC_BUFFER_MODE", 0, "Reserved: _mcAborting", None, "0", allowed=(0,)),
        ),
        outputs=(
            Var("InPosition", "BOOL", False, "TRUE while the feedback is within the in-position range of the target"),
            O_BUSY, O_ACTIVE, O_ABORTED, O_ERROR, O_ERRORID,
        ),
        spec="omron-axis-instructions.md MC_SyncMoveAbsolute (seed 000 line 12478)",
        notes="MC_Stop and errors stop the axis immediately. Override is ignored.",
    )
    SYNC_OUTPUTS = ("InPosition",)
    EVERY_PERIOD = True  # Position and the feedback are read every period

    def __init__(self, mc: Any, fb_id: int, inputs: dict[str, Any] | None = None) -> None:
        super().__init__(mc, fb_id, inputs)
        self._last_target: float | None = None

    def resolve_axis(self, name_input: str = "Axis", *, allow_unused: bool = False) -> Axis | None:
        return ExecuteFB.resolve_axis(self, "Axis", allow_unused=allow_unused)

    def _check(self, slave: Axis) -> int:
        i = self.inp
        if i["Direction"] not in range(5):
            return E.E_DIRECTION
        if i["BufferMode"] != 0:
            return E.E_BUFFER_MODE
        if not fits_position(i["Position"], slave.ppu):
            return E.E_TARGET_POSITION
        return 0

    def _resolve(self, slave: Axis) -> float:
        _, target = slave.resolve_target(self.inp["Position"], self.inp["Direction"])
        return target

    def execute(self, axis: Axis) -> None:
        if not _may_start(self, axis, self.ACCEPT, self._check, direction_less=True):
            return
        job = Job(JobKind.CYCLIC, self, buffer_mode=0)
        job.info["law"] = CyclicPositionLaw(self.mc, job, axis, self._resolve(axis))
        self._last_target = self.inp["Position"]
        self.out["InPosition"] = False
        self._submit(axis, job, "ok", 0)

    def sync_job(self) -> None:
        job = self.job
        axis = self.axis
        if job is not None and axis is not None and job.status in (JobStatus.ACTIVE, JobStatus.STARTING):
            law = job.info["law"]
            pos = self.inp["Position"]
            changed = pos != self._last_target
            if changed:
                self._last_target = pos
                law.target = self._resolve(axis)
                code = self._check(axis)
                if code:
                    self.fail(code, axis)
                    return
            in_range = abs(axis.m.act_pos.item(axis.i) - law.target) <= axis.params.Operation.InPosRange
            # a target change while InPosition keeps it TRUE this period, FALSE from the next (its rules)
            self.out["InPosition"] = (in_range and not changed) or (changed and self.out["InPosition"])
        super().sync_job()


SYNC_MOVE_VELOCITY_PDO = (0x60FF, 0x6060, 0x6061)  # target velocity, modes of operation (display)


class MC_SyncMoveVelocity(ExecuteFB):
    DEF = FBDef(
        name="MC_SyncMoveVelocity",
        title="Cyclic synchronous velocity control",
        summary="Puts the drive in CSV and outputs the velocity the program writes every period (no ramp); the "
                "command position follows the feedback.",
        kind="execute",
        inouts=(Var("Axis", "_sAXIS_REF", None, "Axis"),),
        inputs=(
            I_EXECUTE,
            Var("Velocity", "LREAL", 0.0, "Target velocity (signed; may change every period)", "unit/s",
                "negative, positive, 0"),
            Var("CmdPosMode", "_eMC_CMDPOS_MODE", 0, "_mcCount: the command position follows the feedback", None,
                "0", allowed=(0,)),
            Var("BufferMode", "_eMC_BUFFER_MODE", 0, "Behaviour on multi-execution", None, "0, 1", allowed=(0, 1)),
        ),
        outputs=(Var("InVelocity", "BOOL", False, "TRUE when the command velocity reached the target velocity"),
                 O_BUSY, O_ACTIVE, O_ABORTED, O_ERROR, O_ERRORID),
        spec="omron-axis-instructions.md MC_SyncMoveVelocity (seed 000 line 12163)",
        notes="Ends back in CSP with the servo locked at the feedback position (generic CiA402 drive, decision D47).",
    )

    def _check(self, axis: Axis) -> int:
        i = self.inp
        if i["CmdPosMode"] != 0:
            return 0x5495  # Command Current Position Count Selection Out of Range
        if i["BufferMode"] not in (0, 1):
            return E.E_BUFFER_MODE
        if axis.pdo_missing(SYNC_MOVE_VELOCITY_PDO):
            return 0x3461
        return 0

    def _velocity(self, axis: Axis) -> float:
        v = self.inp["Velocity"]
        vmax = axis.params.Operation.MaxVel
        return max(-vmax, min(vmax, v))

    def execute(self, axis: Axis) -> None:
        if not _may_start(self, axis, "move", self._check, direction_less=True):
            return
        job = Job(JobKind.CSV, self, buffer_mode=self.inp["BufferMode"])
        job.velocity = self._velocity(axis)
        self._submit(axis, job, "ok", 0)

    def sync_job(self) -> None:
        job, axis = self.job, self.axis
        if job is not None and axis is not None and job.running:
            job.velocity = self._velocity(axis)  # a new value applies at once (its rules)
        super().sync_job()


SYNC_CLASSES: tuple[type[ExecuteFB], ...] = (MC_CamIn, MC_CamOut, MC_GearIn, MC_GearInPos, MC_GearOut, MC_MoveLink,
                                             MC_CombineAxes, MC_Phasing, MC_SyncOffsetPosition, MC_SyncMoveAbsolute,
                                             MC_SyncMoveVelocity)
