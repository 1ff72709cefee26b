"""Data traces (api.md "EtherCAT, ESI, faults, events, trace"): configure + start, read, export as CSV, stop, restart,
delete; the catalog of traceable variables; trace settings saved in the project.

Everything that touches a trace runs in the kernel thread (`Runner.call`) between two periods: reading a recording
trace copies the requested samples there (a decimated read copies only the returned rows); a finished one is read in
the request's thread. The JSON/CSV is built afterwards in the request's thread.
"""

from __future__ import annotations

import io
from typing import Any

from fastapi import APIRouter, Body, Depends, Query, Response

from ...controller.kernel import Controller
from ...controller.trace import MEMORY_BUDGET_BYTES, Trace, catalog
from ...project.trace_models import MAX_SAMPLES, MAX_TRACES, MAX_VARIABLES, TraceSettings
from ..deps import get_studio
from ..state import Studio
from ..trace_models import TraceCatalog, TraceData, TraceSummary

router = APIRouter(tags=["traces"])

NOT_FOUND = {404: {"description": "No such trace"}}


def _summary(t: Trace) -> TraceSummary:
    d = t.read(decimation=max(1, t.samples))  # one row at most: the record's counters without its samples
    return TraceSummary(id=t.id, name=t.settings.name, state=d["state"], armed=d["armed"], records=d["records"],
                        sample_count=d["sample_count"], start_cycle=d["start_cycle"],
                        trigger_cycle=d["trigger_cycle"], settings=t.settings)


def _read(studio: Studio, trace_id: int, **kw: Any) -> tuple[dict[str, Any], TraceSettings]:
    """The record, copied in the kernel thread while the trace records; a trace that no longer records (done,
    stopped) is read in the request's thread, so a long CSV export does not hold up the control period."""

    def get(c: Controller) -> tuple[Trace, dict[str, Any] | None]:
        t = c.traces.get(trace_id)
        return t, (t.read(**kw) if t.active else None)

    trace, data = studio.runner.call(get)
    return (data if data is not None else trace.read(**kw)), trace.settings


@router.get("/traces/variables", response_model=TraceCatalog, summary="Traceable variables, grouped")
def trace_variables(studio: Studio = Depends(get_studio)) -> TraceCatalog:
    cat = studio.runner.call(catalog)
    return TraceCatalog(**cat, max_traces=MAX_TRACES, max_variables=MAX_VARIABLES, max_samples=MAX_SAMPLES,
                        memory_budget_bytes=MEMORY_BUDGET_BYTES)


@router.get("/traces", response_model=list[TraceSummary], summary="The controller's traces")
def list_traces(studio: Studio = Depends(get_studio)) -> list[TraceSummary]:
    return studio.runner.call(lambda c: [_summary(t) for t in c.traces.traces.values()])


@router.post(
    "/traces", response_model=TraceSummary, status_code=201, summary="Configure and start a trace",
    description="The first sample is taken at the end of the next period the controller runs. An unknown axis, group, "
    "instance, slave or member is a 422 whose `loc` names the field (`variables[1].target`); more than "
    f"{MAX_TRACES} traces at once is a 409; rings beyond the memory budget are a 422 on `samples`.",
    responses={409: {"description": "Too many traces"}},
)
def create_trace(body: TraceSettings, studio: Studio = Depends(get_studio)) -> TraceSummary:
    return studio.runner.call(lambda c: _summary(c.traces.configure(body)))


@router.get("/traces/{trace_id:int}", response_model=TraceData, summary="State and samples of a trace",
            description="The record (in repeat mode the last complete one, once there is one), oldest sample first. "
            "`max_points` decimates for plotting (every k-th sample, the smallest k giving at most that many); "
            "`decimation` sets k directly.", responses=NOT_FOUND)
def get_trace(trace_id: int, studio: Studio = Depends(get_studio),
              max_points: int | None = Query(None, ge=2, le=1_000_000, description="At most this many samples"),
              decimation: int | None = Query(None, ge=1, le=1_000_000, description="Every k-th sample")
              ) -> TraceData:
    d, settings = _read(studio, trace_id, max_points=max_points, decimation=decimation)
    return TraceData(
        id=d["id"], name=d["name"], state=d["state"], armed=d["armed"], records=d["records"],
        sample_count=d["sample_count"],
        start_cycle=d["start_cycle"], trigger_cycle=d["trigger_cycle"], settings=settings, period_s=d["period_s"],
        decimation=d["decimation"], pre_trigger_samples=d["pre_trigger_samples"], trigger_index=d["trigger_index"],
        trigger_time_s=d["trigger_time_s"], cycles=d["cycles"].tolist(), time_s=d["time_s"].tolist(),
        series=[{**s, "values": s["values"].tolist()} for s in d["series"]],
    )


@router.get("/traces/{trace_id:int}/csv", summary="The record as CSV (every sample)",
            response_class=Response, responses={200: {"content": {"text/csv": {}}}, **NOT_FOUND})
def trace_csv(trace_id: int, studio: Studio = Depends(get_studio)) -> Response:
    d, _ = _read(studio, trace_id)
    buf = io.StringIO()
    head = ["cycle", "time_s"] + [f"{s['label']} [{s['unit']}]" if s["unit"] else s["label"] for s in d["series"]]
    buf.write(",".join(head) + "\n")
    cols = [list(map(str, d["cycles"].tolist())), list(map(repr, d["time_s"].tolist()))]
    for s in d["series"]:
        vals = s["values"].tolist()
        cols.append([str(int(v)) for v in vals] if s["type"] != "REAL" else list(map(repr, vals)))
    buf.writelines(",".join(row) + "\n" for row in zip(*cols, strict=True))
    name = "".join(ch if ch.isalnum() or ch in "-_" else "_" for ch in d["name"]) or "trace"
    return Response(buf.getvalue(), media_type="text/csv",
                    headers={"Content-Disposition": f'attachment; filename="{name}.csv"'})


@router.post("/traces/{trace_id:int}/stop", response_model=TraceSummary, summary="Stop recording (samples are kept)",
             responses=NOT_FOUND)
def stop_trace(trace_id: int, studio: Studio = Depends(get_studio)) -> TraceSummary:
    return studio.runner.call(lambda c: _summary(c.traces.stop(trace_id)))


@router.post("/traces/{trace_id:int}/restart", response_model=TraceSummary,
             summary="Discard the samples and start again with the same settings", responses=NOT_FOUND)
def restart_trace(trace_id: int, studio: Studio = Depends(get_studio)) -> TraceSummary:
    return studio.runner.call(lambda c: _summary(c.traces.restart(trace_id)))


@router.delete("/traces/{trace_id:int}", status_code=204, summary="Delete a trace and free its rings",
               responses=NOT_FOUND)
def delete_trace(trace_id: int, studio: Studio = Depends(get_studio)) -> Response:
    studio.runner.call(lambda c: c.traces.delete(trace_id))
    return Response(status_code=204)


@router.get("/project/traces", response_model=list[TraceSettings], tags=["project"],
            summary="Trace settings saved in the project")
def get_project_traces(studio: Studio = Depends(get_studio)) -> list[TraceSettings]:
    return list(studio.project.traces)


@router.put("/project/traces", response_model=list[TraceSettings], tags=["project"],
            summary="Replace the project's trace settings",
            description="Changes the project document without restarting the controller (traces are not part of "
            "the download); the document is written by POST /project/save.")
def put_project_traces(body: list[TraceSettings] = Body(..., max_length=4 * MAX_TRACES),
                       studio: Studio = Depends(get_studio)) -> list[TraceSettings]:
    def apply(c: Controller) -> None:
        c.project = c.project.model_copy(update={"traces": list(body)})

    studio.runner.call(apply)
    return list(studio.project.traces)
