from __future__ import annotations

from fastapi import APIRouter, Depends

from ..deps import get_studio
from ..models import Health, VizInfo
from ..state import Studio

router = APIRouter(tags=["health"])


@router.get("/health", response_model=Health, summary="Liveness and version")
def health(studio: Studio = Depends(get_studio)) -> Health:
    return Health(status="ok", version=studio.version)


@router.get("/viz", response_model=VizInfo, summary="Where the 3D view (viser) is served")
def viz(studio: Studio = Depends(get_studio)) -> VizInfo:
    if studio.viz is None:
        return VizInfo(enabled=False)
    return VizInfo(enabled=True, port=studio.viz.port, host=studio.viz.host)
