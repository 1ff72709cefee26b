"""Controller status, mode, stepping and reset (api.md "Controller")."""

from __future__ import annotations

from fastapi import APIRouter, Depends

from ...controller.kernel import Controller, Until
from ..deps import get_studio
from ..models import ControllerStatus, ModeIn, StepIn, StepOut
from ..state import ConflictError, Studio

router = APIRouter(prefix="/controller", tags=["controller"])


@router.get("", response_model=ControllerStatus, summary="Mode, cycle, simulated time, RTF and overruns")
def get_status(studio: Studio = Depends(get_studio)) -> ControllerStatus:
    return studio.status()


@router.put("/mode", response_model=ControllerStatus, summary="Switch between realtime, fast and paused")
def put_mode(body: ModeIn, studio: Studio = Depends(get_studio)) -> ControllerStatus:
    studio.runner.set_mode(body.mode)
    return studio.status()


@router.post(
    "/step",
    response_model=StepOut,
    summary="Run cycles while paused",
    description="Runs `cycles` control periods (only while paused) and stops early after the first cycle in which "
    "`until` holds (an instance output equals the given value). Returns the status after the last cycle.",
    responses={404: {"description": "`until.fb` names no instance"},
               409: {"description": "The controller is not paused"}},
)
def post_step(body: StepIn, studio: Studio = Depends(get_studio)) -> StepOut:
    if studio.runner.mode != "paused":
        raise ConflictError(f"step is only possible while paused (mode is {studio.runner.mode}); "
                            "PUT /api/v1/controller/mode {\"mode\": \"paused\"} first")
    until = Until(body.until.fb, body.until.output, body.until.equals) if body.until else None

    def run(c: Controller) -> tuple[int, bool | None]:
        n = c.step(body.cycles, until)
        return n, (c.until_holds(until) if until else None)

    stepped, met = studio.runner.call(run, timeout=None)
    status = studio.status()
    return StepOut(**status.model_dump(), stepped=stepped, until_met=met)


@router.post("/reset-errors", response_model=ControllerStatus,
             summary="Reset MC errors (ResetMCError): MC common errors and the errors of all stopped axes")
def post_reset_errors(studio: Studio = Depends(get_studio)) -> ControllerStatus:
    studio.runner.call(lambda c: c.mc.reset_mc_errors())
    return studio.status()


@router.post("/reset", response_model=ControllerStatus,
             summary="Reload the project into a fresh controller (cycle 0)")
def post_reset(studio: Studio = Depends(get_studio)) -> ControllerStatus:
    project = studio.project
    controller = Controller(project, library=studio.library, cams=studio.controller.cams)
    studio.attach(controller)
    studio.runner.replace_controller(controller)
    if studio.viz is not None:
        studio.viz.rebuild(controller)
    return studio.status()
