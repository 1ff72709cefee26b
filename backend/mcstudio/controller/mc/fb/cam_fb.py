"""Cam table instructions: MC_SetCamTableProperty, MC_SaveCamTable, MC_GenerateCamTable
(`omron-group-and-cam.md` §5.0–§5.2, §5.4; seed 001 lines 17346–18689).

The cam data variables are the MC module's runtime copies (`MotionModule.cam_tables`). Mutual exclusion on one table
(§5.0.3) is kept in `MotionModule.cam_locks` (table name → instruction holding it): a second instruction on a locked
table, or MC_GenerateCamTable on a table an MC_CamIn is using, gets 543C. MC_GenerateCamTable computes in the period
after Busy (`GenerateCamBusy` TRUE in that period) and is Done one period later (decision D44). MC_SaveCamTable writes
the table to the project's `cams/<name>.csv` through `MotionModule.cam_saver` in a background thread (the controller
keeps its period) with `CamTableBusy` TRUE until the file is written; without a project folder it is Done next
period.
"""

from __future__ import annotations

import concurrent.futures
import logging
from typing import TYPE_CHECKING, Any

from .. import errors as E
from ..cam.generate import _sMC_CAM_NODE, _sMC_CAM_PROPERTY, generate_into
from ..sync import CamLaw
from .base import I_EXECUTE, O_ABORTED, O_BUSY, O_DONE, O_ERROR, O_ERRORID, FBDef, FunctionBlock, OneShotFB, Var

if TYPE_CHECKING:
    from ..cam.table import CamTable

log = logging.getLogger(__name__)

E_CAM_TABLE = 0x5439
E_CAM_DATA = 0x5480
E_ABORTED_TABLE = 0x5743
E_SAVE_IMPOSSIBLE = 0x743C

IO_CAM = Var("CamTable", "_sMC_CAM_REF", None, "Cam data variable (name of the cam table)")
_SAVER = concurrent.futures.ThreadPoolExecutor(max_workers=1, thread_name_prefix="cam-save")


class _CamTableFB(OneShotFB):
    """A common instruction on a cam data variable (no axis; errors have the MC common source)."""

    _locked: str | None = None

    def resolve_axis(self, name_input: str = "Axis", *, allow_unused: bool = False) -> Any:
        return None

    def _call(self, o: dict[str, Any], exe: bool, edge: bool) -> None:
        if o["Error"] and self._error_released():
            o["Error"] = False
            o["ErrorID"] = 0
        if not exe and self._end_cycle < self.mc.cycle:
            o["Done"] = o["CommandAborted"] = False
        self.sync_job()
        if edge and not o["Error"]:
            if o["Busy"]:
                # re-execution is not allowed (543B); the work in progress goes on (§5.4.5)
                FunctionBlock.fail(self, E.E_REEXEC_DISABLED, None)
            else:
                o["Done"] = o["CommandAborted"] = False
                o["Busy"] = True
                self._started_cycle = self.mc.cycle
                self.start()
        self.after_call(exe)

    _started_cycle = -1

    def execute(self, axis: Any) -> None:  # pragma: no cover - started by `start`
        raise NotImplementedError

    def start(self) -> None:
        raise NotImplementedError

    def table(self) -> tuple[CamTable | None, int]:
        name = self.inp.get("CamTable") or ""
        table = self.mc.cam_tables.get(name)
        if table is None:
            return None, E_CAM_TABLE
        return table, 0

    def lock(self) -> bool:
        """Take the table (§5.0.3); False (and 543C) when another cam instruction holds it."""
        name = self.inp["CamTable"]
        holder = self.mc.cam_locks.get(name)
        if holder is not None and holder is not self:
            self.fail(E.E_MULTIEXEC_DISABLED, None)
            return False
        self.mc.cam_locks[name] = self
        self._locked = name
        return True

    def unlock(self) -> None:
        if self._locked is not None and self.mc.cam_locks.get(self._locked) is self:
            del self.mc.cam_locks[self._locked]
        self._locked = None

    def fail(self, code: int, axis: Any, *, fault_axis: bool = True) -> None:
        self.unlock()
        super().fail(code, None)

    def on_delete(self) -> None:
        self.unlock()


# ----------------------------------------------------------------------------------------- MC_SetCamTableProperty
class MC_SetCamTableProperty(_CamTableFB):
    DEF = FBDef(
        name="MC_SetCamTableProperty",
        title="Cam table property setting",
        summary="Searches the cam table's end point (the element before the first Phase 0) after the program changed "
                "its data, and puts it in force.",
        kind="execute",
        inouts=(IO_CAM,),
        inputs=(I_EXECUTE,),
        outputs=(O_DONE, Var("EndPointIndex", "UINT", 0, "Index of the end point"),
                 Var("MaxDataNumber", "UINT", 0, "Number of elements of the cam data variable"),
                 O_BUSY, O_ABORTED, O_ERROR, O_ERRORID),
        spec="omron-group-and-cam.md §5.1 MC_SetCamTableProperty (seed 001 line 17346)",
    )

    def start(self) -> None:
        table, code = self.table()
        if table is None:
            self.fail(code, None)
            return
        if table.generation_aborted:
            self.fail(E_ABORTED_TABLE, None)
            return
        if not self.lock():
            return
        ep = table.set_cam_table_property()
        self.unlock()
        if not ep.ok:
            self.fail(E_CAM_DATA, None)
            return
        self.out["EndPointIndex"] = ep.end_point_index
        self.out["MaxDataNumber"] = table.max_data_number
        self.done_next()


# ----------------------------------------------------------------------------------------------- MC_SaveCamTable
class MC_SaveCamTable(_CamTableFB):
    DEF = FBDef(
        name="MC_SaveCamTable",
        title="Save cam table",
        summary="Saves the cam table to non-volatile memory: the project's cams/<name>.csv (CamTableBusy while "
                "saving).",
        kind="execute",
        inouts=(IO_CAM,),
        inputs=(I_EXECUTE,),
        outputs=(O_DONE, O_BUSY, O_ABORTED, O_ERROR, O_ERRORID),
        spec="omron-group-and-cam.md §5.2 MC_SaveCamTable (seed 001 line 17516)",
    )
    _future: concurrent.futures.Future[None] | None = None

    def start(self) -> None:
        mc = self.mc
        table, code = self.table()
        if table is None:
            self.fail(code, None)
            return
        if table.generation_aborted:
            self.fail(E_ABORTED_TABLE, None)
            return
        if mc.cam_saving is not None and mc.cam_saving is not self:
            self.fail(E.E_MULTIEXEC_DISABLED, None)  # only one save at a time, any table (§5.2)
            return
        if not self.lock():
            return
        mc.cam_saving = self
        saver = mc.cam_saver
        if saver is None:
            self._saved(None)
            return
        snapshot = table.copy()
        name = self.inp["CamTable"]
        self._future = _SAVER.submit(saver, name, snapshot)

    def _saved(self, error: BaseException | None) -> None:
        self._future = None
        self.mc.cam_saving = None
        self.unlock()
        if error is not None:
            log.error("MC_SaveCamTable %s: %s", self.inp["CamTable"], error)
            self.fail(E_SAVE_IMPOSSIBLE, None)
            return
        self.done_next()

    def sync_job(self) -> None:
        fut = self._future
        if fut is not None and fut.done():
            self._saved(fut.exception())
        super().sync_job()

    def on_delete(self) -> None:
        # deleting the instruction does not stop a save in progress (§5.2); the busy flag ends with it
        fut = self._future
        if fut is not None:
            fut.add_done_callback(lambda _f: setattr(self.mc, "cam_saving", None))
        else:
            super().on_delete()


# ------------------------------------------------------------------------------------------- MC_GenerateCamTable
NODE_MEMBERS = frozenset(("Phase", "Distance", "Curve", "ConnectingVelEnable", "ConnectingVel",
                          "ConnectingAccEnable", "ConnectingAcc", "PhasePitch"))


class MC_GenerateCamTable(_CamTableFB):
    DEF = FBDef(
        name="MC_GenerateCamTable",
        title="Generate cam table",
        summary="Computes cam data from a cam property and cam nodes (15 curve types, connecting conditions) into "
                "an existing cam data variable.",
        kind="execute",
        inouts=(
            IO_CAM,
            Var("CamProperty", "_sMC_CAM_PROPERTY", None, "Cam property: InitVel, InitAcc, CycleTime"),
            Var("CamNodes", "ARRAY OF _sMC_CAM_NODE", None, "Cam nodes (Phase, Distance, Curve, ConnectingVel…, "
                "PhasePitch); the first node with Phase 0 after element 0 ends the list"),
        ),
        inputs=(I_EXECUTE,),
        outputs=(O_DONE, Var("EndPointIndex", "UINT", 0, "End point index of the generated table"), O_BUSY, O_ABORTED,
                 O_ERROR, O_ERRORID,
                 Var("ErrorParameterCode", "WORD", 0, "Parameter of a 573C/573D error"),
                 Var("ErrorNodePointIndex", "UINT", 0, "Node of a 573D/5740/5741/5742 error")),
        spec="omron-group-and-cam.md §5.4 MC_GenerateCamTable (seed 001 line 17762)",
        notes="Generation runs in the period after Busy (GenerateCamBusy TRUE), Done one period later (D44).",
    )
    _pending = False

    def start(self) -> None:
        o = self.out
        o["ErrorParameterCode"] = 0
        o["ErrorNodePointIndex"] = 0
        mc = self.mc
        table, code = self.table()
        if table is None:
            self.fail(code, None)
            return
        if mc.generate_cam_busy is not None:
            self.fail(E.E_MULTIEXEC_DISABLED, None)  # one generation at a time (§5.4.5)
            return
        if any(isinstance(law, CamLaw) and law.table is table for law in mc.sync_laws.values()):
            self.fail(E.E_MULTIEXEC_DISABLED, None)  # MC_CamIn runs on this table (§5.0.3)
            return
        if not self.lock():
            return
        self._pending = True

    def after_call(self, exe: bool) -> None:
        """The period after Busy: GenerateCamBusy turns TRUE and the table is computed; Done shows in the next
        period, when GenerateCamBusy turns FALSE again."""
        mc = self.mc
        if self._pending and mc.cycle > self._started_cycle:
            self._pending = False
            mc.generate_cam_busy = self
            self._generate()

    def sync_job(self) -> None:
        if self._result and self.mc.generate_cam_busy is self:
            self.mc.generate_cam_busy = None
        super().sync_job()

    def _generate(self) -> None:
        table, _ = self.table()
        prop = _property(self.inp.get("CamProperty"))
        nodes = _nodes(self.inp.get("CamNodes"))
        if table is None or prop is None or nodes is None:
            code = E_CAM_TABLE if table is None else (0x573C if prop is None else 0x573E)
            self._end_error(code, 0, 0)
            return
        result = generate_into(table, nodes, prop)
        err = result.error
        if err is not None:
            self._end_error(err.ErrorID, err.ErrorParameterCode, err.ErrorNodePointIndex)
            return
        self.unlock()
        if not self.out["Error"]:  # (a re-execution error keeps the outputs; the table is generated anyway)
            self.out["EndPointIndex"] = result.end_point_index
            self.done_next()

    def _end_error(self, code: int, param: int, node: int) -> None:
        if self.mc.generate_cam_busy is self:
            self.mc.generate_cam_busy = None
        self.fail(code, None)
        self.out["ErrorParameterCode"] = param
        self.out["ErrorNodePointIndex"] = node

    def on_delete(self) -> None:
        if self.mc.generate_cam_busy is self:
            self.mc.generate_cam_busy = None
        super().on_delete()


def _property(value: Any) -> _sMC_CAM_PROPERTY | None:
    if not isinstance(value, dict):
        return None
    try:
        return _sMC_CAM_PROPERTY(**{k: float(value.get(k, 0.0)) for k in ("InitVel", "InitAcc", "CycleTime")})
    except (TypeError, ValueError):
        return None


def _nodes(value: Any) -> list[_sMC_CAM_NODE] | None:
    if not isinstance(value, list) or not value:
        return None
    out = []
    for item in value:
        if not isinstance(item, dict):
            return None
        out.append(_sMC_CAM_NODE(**item))
    return out


CAM_CLASSES: tuple[type[OneShotFB], ...] = (MC_SetCamTableProperty, MC_SaveCamTable, MC_GenerateCamTable)
