from __future__ import annotations

from fastapi import APIRouter, Depends, Query, Response

from ...controller.events import Level, SourceKind
from ...controller.mc.errors import ERRORS
from ..deps import get_studio
from ..models import ErrorInfo, EventOut
from ..state import Studio

router = APIRouter(tags=["events"])


@router.get("/events", response_model=list[EventOut], summary="Event log (oldest first)")
def get_events(
    since: int = Query(0, ge=0, description="Only events with seq greater than this"),
    limit: int | None = Query(None, ge=1, le=10000, description="At most this many (the newest, after filtering)"),
    level: list[Level] | None = Query(None, description="Only these levels (repeat the parameter for several)"),
    source_kind: list[SourceKind] | None = Query(None, description="Only these source kinds (D125)"),
    studio: Studio = Depends(get_studio),
) -> list[EventOut]:
    events = studio.controller.events.list(since_seq=since)
    if level:
        events = [e for e in events if e.level in level]
    if source_kind:
        events = [e for e in events if e.source_kind in source_kind]
    if limit:
        events = events[-limit:]
    return [EventOut(**e.as_dict()) for e in events]


@router.delete("/events", status_code=204, summary="Clear the event log")
def clear_events(studio: Studio = Depends(get_studio)) -> Response:
    studio.controller.events.clear()
    return Response(status_code=204)


@router.get("/errors", response_model=list[ErrorInfo], summary="Every ErrorID with name, cause and correction")
def list_errors() -> list[ErrorInfo]:
    return [
        ErrorInfo(code=d.code, event_code=d.event_code, name=d.name, cause=d.cause, correction=d.correction,
                  level=d.level, source=d.source, ref=d.ref)
        for d in ERRORS.values()
    ]
