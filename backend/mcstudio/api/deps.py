"""Dependencies injected into the routers (FastAPI "bigger applications" style)."""

from __future__ import annotations

from fastapi import Request

from .state import Studio


def get_studio(request: Request) -> Studio:
    return request.app.state.studio  # type: ignore[no-any-return]
