"""Catalog of supported instructions: name → FunctionBlock class (feeds the kernel and GET /api/v1/fb-types)."""

from __future__ import annotations

from .base import FunctionBlock
from .single_axis import FB_CLASSES

FB_TYPES: dict[str, type[FunctionBlock]] = {cls.DEF.name: cls for cls in FB_CLASSES}
