"""Function-block instances: any MC instruction with PLC call semantics (api.md "Function-block instances")."""

from __future__ import annotations

from fastapi import APIRouter, Depends, HTTPException, Request, Response

from ...controller.kernel import Controller
from ...controller.mc.fb.registry import FB_TYPES
from ..control import note_created
from ..deps import get_studio
from ..models import FBCreate, FBOut, FBPatch, FBType
from ..state import Studio

router = APIRouter(tags=["function blocks"])


@router.get("/fb-types", response_model=list[FBType], summary="Catalog of supported instructions")
def fb_types() -> list[FBType]:
    return [FBType(**cls.DEF.catalog()) for cls in FB_TYPES.values()]


@router.get("/fb", response_model=list[FBOut], summary="All instances, in call order")
def list_fbs(studio: Studio = Depends(get_studio)) -> list[FBOut]:
    snap = studio.runner.snapshot
    return [out for fid in snap.fbs if (out := studio.fb_out(snap, fid)) is not None]


@router.post(
    "/fb",
    response_model=FBOut,
    status_code=201,
    summary="Create an instance",
    description="The instance is called once per control period, in creation order, from the next cycle on; unless "
    "the controller is paused, the response comes after that first call and shows its outputs. In-outs "
    "(`Axis`) are given by name. With `lease_s` the instance is a dead-man: unless renewed (PATCH or a WebSocket "
    "heartbeat) within `lease_s`, its Execute/Enable-type inputs drop to FALSE.",
)
def create_fb(body: FBCreate, request: Request, studio: Studio = Depends(get_studio)) -> FBOut:
    def create(c: Controller) -> int:
        return c.fb(body.type, lease_s=body.lease_s, **body.inputs).id

    fb_id = studio.runner.call(create, see_cycle=True)
    note_created(request, fb_id)  # its dead-man inputs drop when the creating client loses control (D117)
    out = studio.fb_out(studio.runner.snapshot, fb_id)
    assert out is not None
    return out


@router.get("/fb/{fb_id}", response_model=FBOut, summary="Inputs and outputs as of the last call",
            responses={404: {"description": "No such instance"}})
def get_fb(fb_id: int, studio: Studio = Depends(get_studio)) -> FBOut:
    out = studio.fb_out(studio.runner.snapshot, fb_id)
    if out is None:
        raise HTTPException(status_code=404, detail=f"no function-block instance {fb_id}")
    return out


@router.patch("/fb/{fb_id}", response_model=FBOut, summary="Change inputs (applied at the next cycle boundary)",
              description="Unless the controller is paused, the response comes after the instance was called once "
              "with the new inputs, so consecutive PATCHes are always seen in different cycles (no lost edges).",
              responses={404: {"description": "No such instance"}})
def patch_fb(fb_id: int, body: FBPatch, studio: Studio = Depends(get_studio)) -> FBOut:
    studio.runner.call(lambda c: c.set_inputs(fb_id, body.inputs), see_cycle=True)
    out = studio.fb_out(studio.runner.snapshot, fb_id)
    assert out is not None
    return out


@router.delete("/fb/{fb_id}", status_code=204, summary="Remove an instance",
               responses={404: {"description": "No such instance"}})
def delete_fb(fb_id: int, studio: Studio = Depends(get_studio)) -> Response:
    studio.runner.call(lambda c: c.delete_fb(fb_id))
    return Response(status_code=204)
