"""Response models of the data trace API (routers/traces.py); the request is the project's `TraceSettings`."""

from __future__ import annotations

from typing import Literal

from pydantic import Field

from ..modelbase import StrictModel
from ..project.trace_models import TraceSettings, VariableKind

TraceState = Literal["waiting", "triggered", "done", "running", "stopped"]


_Model = StrictModel


class TraceSummary(_Model):
    id: int
    name: str
    state: TraceState = Field(description="waiting (for the trigger, or filling the pre-trigger samples), triggered "
                              "(recording the post-trigger samples), done (single record complete), running "
                              "(continuous ring), stopped")
    armed: bool = Field(description="The trigger is armed: the pre-trigger samples of the record being filled are "
                        "in (a trigger before that is not taken, so the pre-trigger share is exact)")
    records: int = Field(description="Complete records so far (repeat mode)")
    sample_count: int = Field(description="Samples in the readable record")
    start_cycle: int = Field(description="Cycle of the first sample (the period in which the trace was started)")
    trigger_cycle: int | None = Field(description="Cycle of the trigger sample of the readable record")
    settings: TraceSettings


class TraceSeries(_Model):
    label: str = Field(description="Variable name as shown: MC_Axis000.Cmd.Vel, MC_MoveAbsolute#3.Busy, "
                       "Node1.6064:00 …")
    unit: str = Field(description="mm, mm/s, mm/s², %, bool … ('' for PDO entries: raw object values)")
    type: Literal["REAL", "INT", "BOOL"]
    values: list[float] = Field(description="One value per returned sample; BOOL as 0/1")


class TraceData(TraceSummary):
    period_s: float
    decimation: int = Field(description="Every decimation-th sample of the record is returned")
    pre_trigger_samples: int
    trigger_index: int | None = Field(description="Index of the trigger sample in the (undecimated) record")
    trigger_time_s: float | None
    cycles: list[int] = Field(description="Cycle of each returned sample (sampled at the end of that period)")
    time_s: list[float] = Field(description="cycle × period")
    series: list[TraceSeries]


class TraceVariableInfo(_Model):
    name: str
    unit: str
    type: Literal["REAL", "INT", "BOOL"]
    description: str = Field("", description="PDO entries: the object's name")


class TraceTarget(_Model):
    kind: VariableKind
    target: str = Field(description="Axis / group name, instance id or node address, as TraceVariable.target")
    label: str
    variables: list[TraceVariableInfo]


class TraceCatalog(_Model):
    """What can be traced in the running controller, grouped as in the studio's variable list."""

    axes: list[TraceTarget]
    groups: list[TraceTarget]
    instances: list[TraceTarget]
    slaves: list[TraceTarget]
    max_traces: int
    max_variables: int
    max_samples: int
    memory_budget_bytes: int
