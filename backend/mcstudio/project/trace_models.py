"""Data trace settings (issue 8): what a trace records, how often, when it triggers.

One model for the project document (`Project.traces`), the REST request (`POST /api/v1/traces`) and the kernel's
trace engine (`controller/trace.py`), like Sysmac Studio's data trace settings: sampling every N primary periods,
up to `MAX_VARIABLES` variables, a trigger on one variable with a condition and a pre-trigger share, and the mode
single / continuous / repeat. Limits are checked here (shape) and by the engine (names, memory budget).
"""

from __future__ import annotations

from typing import Literal

from pydantic import ConfigDict, Field, model_validator

from ..modelbase import StrictModel

MAX_TRACES = 8  # traces running at once in one controller
MAX_VARIABLES = 32  # variables per trace
MAX_SAMPLES = 1_000_000  # samples per variable of one trace (the ring's length)
DEFAULT_SAMPLES = 100_000

VariableKind = Literal["axis", "group", "fb", "pdo"]
Condition = Literal["rising", "falling", "gt", "lt", "eq", "ne"]
Mode = Literal["single", "continuous", "repeat"]


class _Strict(StrictModel):
    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)


class TraceVariable(_Strict):
    """One traced variable.

    * `axis`: `target` = axis name, `name` = a member of the axis variable (`Cmd.Pos`, `Cmd.Vel`, `Cmd.AccDec`,
      `Cmd.Jerk`, `Cmd.Trq`, `Act.Pos`, `Act.Vel`, `Act.Trq`, `Status.Standstill`, `DrvStatus.ServoOn`, …);
    * `group`: `target` = axes group name, `name` = `Cmd.Vel`, `Cmd.AccDec`, `CmdPos[0]` … `CmdPos[3]`, `Status.*`,
      `MFaultLvl.Active`;
    * `fb`: `target` = the instance id, `name` = one of its outputs of a scalar type (`Busy`, `Done`, `ErrorID` …);
    * `pdo`: `target` = the slave's node address, `name` = a mapped object by index (`6064:00`, `0x6064`, `6064h`) or
      by name (`Position actual value`).
    """

    kind: VariableKind
    target: str = Field(min_length=1, max_length=100, description="Axis / group name, instance id or node address")
    name: str = Field(min_length=1, max_length=100, description="Member, output or PDO object")

    @property
    def label(self) -> str:
        if self.kind == "fb":
            return f"FB{self.target}.{self.name}"
        if self.kind == "pdo":
            return f"Node{self.target}.{self.name}"
        return f"{self.target}.{self.name}"


class TraceTrigger(_Strict):
    """Start condition: `rising` (value goes from below `level` to at or above it; a BOOL from FALSE to TRUE),
    `falling` (from above to at or below; TRUE to FALSE), or a level condition `gt`, `lt`, `eq`, `ne` against
    `level`. The trigger is armed once the pre-trigger samples are recorded, so the share is exact."""

    variable: TraceVariable
    condition: Condition = "rising"
    level: float = 0.5
    pre_trigger_percent: float = Field(10.0, ge=0.0, le=100.0, description="Share of the samples before the trigger")


class TraceSettings(_Strict):
    """A data trace's settings (saved in the project, sent to start a trace)."""

    name: str = Field("Trace", min_length=1, max_length=60)
    variables: list[TraceVariable] = Field(min_length=1, max_length=MAX_VARIABLES)
    sampling_periods: int = Field(1, ge=1, le=10_000, description="Sample every N primary periods (1 = each)")
    samples: int = Field(DEFAULT_SAMPLES, ge=2, le=MAX_SAMPLES, description="Samples per variable (record length)")
    mode: Mode = Field("single", description="single: one record; continuous: a ring of the last `samples` until "
                       "stopped (no trigger); repeat: re-arm after each record, the last complete one is readable")
    trigger: TraceTrigger | None = Field(None, description="None: record from the start")

    @model_validator(mode="after")
    def _continuous_has_no_trigger(self) -> TraceSettings:
        if self.mode == "continuous" and self.trigger is not None:
            raise ValueError("mode 'continuous' records a ring without a trigger; use 'single' or 'repeat' with "
                             "a trigger")
        if self.mode == "repeat" and self.trigger is None:
            raise ValueError("mode 'repeat' needs a trigger (without one, use 'continuous')")
        return self
