"""The base of MC Studio's pydantic models (REST bodies and the project format): unknown keys are refused, a JSON
`true`/`false` is not a number and a number is not a BOOL.

Pydantic's lax mode turns a boolean into 1/0 (or 1.0/0.0) for an int or float field, so `{"MaxVel": true}` was
accepted as 1.0 — a schema-violating request the API fuzzing found (docs/hardening.md, D129). Strict mode would also
refuse what JSON legitimately carries (a list for a tuple, a name for an enum), so only this one coercion is refused:
a before-validator on every field whose type is a number (int, float, an IntEnum, optional or not) or a list of
numbers (nested lists too). The other way round as well: a BOOL field takes only true/false (pydantic would read 0,
1, "yes", "off" …). Which fields those are is worked out once per class, not per validation.
"""

from __future__ import annotations

import types
from typing import Annotated, Any, ClassVar, Literal, Union, get_args, get_origin

import numpy as np
from pydantic import BaseModel, ConfigDict, ValidationInfo, field_validator

# What a field's type asks of a value: ("number", depth) — no boolean, ("bool", depth) — only a boolean, at `depth`
# levels of lists (0: the value itself); None — nothing beyond pydantic's own validation.
_Plan = tuple[str, int] | None


def _plan(annotation: Any) -> _Plan:
    origin = get_origin(annotation)
    if origin is Annotated:
        return _plan(get_args(annotation)[0])
    if origin in (Union, types.UnionType):
        args = [a for a in get_args(annotation) if a is not type(None)]
        if any(a is Any for a in args):
            return None
        plans = {_plan(a) for a in args}
        return plans.pop() if len(plans) == 1 else None  # a mixed union (BOOL or LREAL) is left to pydantic
    if origin in (list, tuple, set, frozenset):
        plans = {_plan(a) for a in get_args(annotation) if a is not Ellipsis}
        if len(plans) == 1 and (plan := plans.pop()) is not None and plan[1] < 2:
            return plan[0], plan[1] + 1
        return None
    if not isinstance(annotation, type) or origin is Literal:
        return None
    if issubclass(annotation, bool):
        return "bool", 0
    if issubclass(annotation, int | float):
        return "number", 0
    return None


def _wrong_at(value: Any, kind: str, depth: int) -> str | None:
    """Where `value` holds a boolean for a number, or something else for a boolean ('' for the value itself, '[1]'
    for an item, '[0][2]' …), or None."""
    if depth == 0:
        if kind == "number":
            return "" if isinstance(value, bool | np.bool_) else None
        return None if isinstance(value, bool | np.bool_) or value is None else ""
    if isinstance(value, list | tuple):
        for i, v in enumerate(value):
            if (at := _wrong_at(v, kind, depth - 1)) is not None:
                return f"[{i}]{at}"
    return None


class StrictModel(BaseModel):
    """Refuses unknown keys, booleans where a number is expected and anything but a boolean for a BOOL (D129)."""

    model_config = ConfigDict(extra="forbid")
    _type_plans: ClassVar[dict[str, tuple[str, int]]]

    @classmethod
    def __pydantic_init_subclass__(cls, **kwargs: Any) -> None:
        super().__pydantic_init_subclass__(**kwargs)
        plans = {name: _plan(f.annotation) for name, f in cls.model_fields.items()}
        cls._type_plans = {name: p for name, p in plans.items() if p is not None}

    @field_validator("*", mode="before")
    @classmethod
    def _booleans_are_booleans(cls, value: Any, info: ValidationInfo) -> Any:
        plan = cls._type_plans.get(info.field_name or "")
        if plan is not None and (at := _wrong_at(value, *plan)) is not None:
            where = f" at {info.field_name}{at}" if at else ""
            if plan[0] == "number":
                raise ValueError(f"expected a number, got a boolean (true/false){where}")
            raise ValueError(f"expected true or false{where}")
        return value
