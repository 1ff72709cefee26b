"""Pydantic field types for the manual's enumerations.

api.md: enumerations are accepted as the enumerator name (`"_mcBuffered"`) or its number (`1`) and returned as the
name. `ManualEnum(_eMC_UNITS)` builds an `Annotated` type that does exactly that and documents the allowed names in
the JSON Schema.
"""

from __future__ import annotations

import enum
from typing import Annotated, Any

from pydantic import BeforeValidator, PlainSerializer, WithJsonSchema


def parse_enum(cls: type[enum.IntEnum], value: Any, allowed: tuple[int, ...] | None = None) -> enum.IntEnum:
    """Accept a member, its name or its number; raise ValueError naming the valid enumerators otherwise."""
    member: enum.IntEnum | None = None
    if isinstance(value, cls):
        member = value
    elif isinstance(value, bool):
        member = None
    elif isinstance(value, int):
        try:
            member = cls(value)
        except ValueError:
            member = None
    elif isinstance(value, str):
        member = cls.__members__.get(value)
        if member is None and value.lstrip("-").isdigit():
            try:
                member = cls(int(value))
            except ValueError:
                member = None
    if member is None or (allowed is not None and int(member) not in allowed):
        names = [m.name for m in cls if allowed is None or int(m) in allowed]
        raise ValueError(f"{value!r} is not a valid {cls.__name__}; use one of {', '.join(names)} (or its number)")
    return member


def ManualEnum(cls: type[enum.IntEnum], allowed: tuple[int, ...] | None = None) -> Any:
    names = [m.name for m in cls if allowed is None or int(m) in allowed]
    numbers = [int(m) for m in cls if allowed is None or int(m) in allowed]
    return Annotated[
        cls,
        BeforeValidator(lambda v: parse_enum(cls, v, allowed)),
        PlainSerializer(lambda m: m.name, return_type=str),
        WithJsonSchema(
            {
                "anyOf": [{"type": "string", "enum": names}, {"type": "integer", "enum": numbers}],
                "title": cls.__name__,
                "description": f"{cls.__name__}: enumerator name (returned) or its number",
            },
            mode="validation",
        ),
        WithJsonSchema({"type": "string", "enum": names, "title": cls.__name__}, mode="serialization"),
    ]
