"""Test-run control: who holds it, take and release (issue 8; api/control.py, decisions D115–D117)."""

from __future__ import annotations

from fastapi import APIRouter, Depends, HTTPException, Request

from ..control import (
    CLIENT_HEADER,
    ControlOut,
    ControlRefusedError,
    ControlTakeIn,
    client_address,
    client_id_of,
    drop_instances,
    registry_of,
)
from ..deps import get_studio
from ..state import Studio

router = APIRouter(prefix="/control", tags=["control"])

_NEEDS_ID = {400: {"description": f"No {CLIENT_HEADER} header"}}


def _out(request: Request, client_id: str | None) -> ControlOut:
    st = registry_of(request).state()
    return ControlOut(**st.model_dump(), you=client_id)


def _require_id(request: Request) -> str:
    client_id = client_id_of(request)
    if client_id is None:
        raise HTTPException(status_code=400, detail=[{
            "loc": ["header", CLIENT_HEADER], "type": "missing",
            "msg": f"send a client id in the {CLIENT_HEADER} header (any 1–64 letters, digits, '_', '.', '-')"}])
    return client_id


@router.get("", response_model=ControlOut, summary="Who holds test-run control")
def get_control(request: Request) -> ControlOut:
    return _out(request, client_id_of(request))


@router.post("/take", response_model=ControlOut, summary="Take test-run control",
             description=f"For the client in the {CLIENT_HEADER} header. While another client holds control this is "
             "refused with 409 unless `force`: the previous holder becomes read-only (it is told over its "
             "WebSocket) and its leased instances drop their Execute/Enable inputs (its jog stops).",
             responses={**_NEEDS_ID, 409: {"description": "Another client holds control (and force is false)"}})
def take_control(body: ControlTakeIn, request: Request, studio: Studio = Depends(get_studio)) -> ControlOut:
    client_id = _require_id(request)
    registry = registry_of(request)
    try:
        dropped = registry.take(client_id, client_address(request), force=body.force, name=body.name)
    except ControlRefusedError as err:
        raise HTTPException(status_code=409, detail=err.message) from None
    drop_instances(studio, dropped, f"control taken by '{registry.name_of(client_id)}'")
    return _out(request, client_id)


@router.post("/release", response_model=ControlOut, summary="Release test-run control",
             description="Nobody holds control afterwards; the releasing client's leased instances drop their "
             "Execute/Enable inputs. A client that does not hold control changes nothing.",
             responses=_NEEDS_ID)
def release_control(request: Request, studio: Studio = Depends(get_studio)) -> ControlOut:
    client_id = _require_id(request)
    registry = registry_of(request)
    dropped = registry.release(client_id)
    drop_instances(studio, dropped, f"control released by '{registry.name_of(client_id)}'")
    return _out(request, client_id)
