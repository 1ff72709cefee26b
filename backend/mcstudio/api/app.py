"""FastAPI application factory: REST under /api/v1, the WebSocket, OpenAPI docs at /docs, the studio at /."""

from __future__ import annotations

import contextlib
from collections.abc import AsyncIterator, Callable
from pathlib import Path
from typing import Any

from fastapi import APIRouter, Depends, FastAPI, Request
from fastapi.middleware.cors import CORSMiddleware
from fastapi.openapi.utils import get_openapi
from fastapi.responses import FileResponse, JSONResponse
from fastapi.staticfiles import StaticFiles

from .. import __version__
from . import errors
from .auth import AccessMiddleware, AccessPolicy
from .control import ControlRegistry, control_guard
from .limits import BodyLimitMiddleware
from .models import WsHeartbeat, WsPing, WsSubscribe
from .routers import (
    axes,
    cams,
    control,
    controller,
    ethercat,
    events,
    fb,
    groups,
    health,
    live,
    project,
    robots,
    traces,
)
from .state import Studio

API_PREFIX = "/api/v1"


def default_static_dir() -> Path | None:
    """The built studio: `frontend/dist` of a source checkout, or `mcstudio/web` of an installed package."""
    here = Path(__file__).resolve()
    for candidate in (here.parents[3] / "frontend" / "dist", here.parents[1] / "web"):
        if (candidate / "index.html").is_file():
            return candidate
    return None


def create_app(studio: Studio, *, static_dir: Path | None = None, cors_origins: list[str] | None = None,
               on_startup: Callable[[], None] | None = None, access: AccessPolicy | None = None,
               control_registry: ControlRegistry | None = None) -> FastAPI:
    """The application; `on_startup` runs once the server has started (the CLI starts the kernel thread there).

    `access`: the token / Host / Origin checks (auth.py; default: Origin checks only — `mcstudio serve` passes
    `AccessPolicy.for_bind`). `control_registry`: who holds test-run control (control.py; default: a new one)."""

    @contextlib.asynccontextmanager
    async def lifespan(_: FastAPI) -> AsyncIterator[None]:
        if on_startup is not None:
            on_startup()
        yield

    app = FastAPI(
        lifespan=lifespan,
        title="MC Studio",
        version=__version__,
        description="REST API of MC Studio: an emulated NJ/NX-style machine controller (MC function module, "
        "EtherCAT, CiA402 drives) you commission from the browser or from scripts. Names of instructions and "
        "variables are those of the vendor manual.",
        openapi_url=f"{API_PREFIX}/openapi.json",
        docs_url="/docs",
        redoc_url=None,
    )
    app.state.studio = studio
    app.state.control = control_registry if control_registry is not None else ControlRegistry()
    policy = access if access is not None else AccessPolicy(
        origins=frozenset(o.rstrip("/") for o in cors_origins or []))
    app.state.access = policy
    errors.install(app)
    # Only the studio's own origin (and the Vite dev server, through its proxy) is served unless CORS origins are
    # given; the access middleware is added last, so it is the outermost layer (preflights pass it, D119).
    if cors_origins:
        app.add_middleware(CORSMiddleware, allow_origins=cors_origins, allow_methods=["*"], allow_headers=["*"],
                           allow_credentials=True)
    app.add_middleware(BodyLimitMiddleware)  # 413 while the body streams (limits.py, D57)
    app.add_middleware(AccessMiddleware, policy=policy)

    api = APIRouter(prefix=API_PREFIX)
    guarded = [Depends(control_guard)]  # requests that need test-run control (control.py TEST_RUN, CONFIGURATION)
    for r in (health.router, controller.router, project.router, axes.router, groups.router, fb.router, events.router,
              ethercat.router, cams.router, robots.router, traces.router):
        api.include_router(r, dependencies=guarded)
    api.include_router(live.router)
    api.include_router(control.router)
    app.include_router(api)

    @app.get("/openapi.json", include_in_schema=False)
    def openapi_alias() -> JSONResponse:
        return JSONResponse(app.openapi())

    def custom_openapi() -> dict[str, Any]:
        if app.openapi_schema:
            return app.openapi_schema
        schema = get_openapi(title=app.title, version=app.version, description=app.description, routes=app.routes)
        comps = schema.setdefault("components", {}).setdefault("schemas", {})
        # WebSocket client messages are not routes; publish their schemas for the generated client types.
        for model in (WsSubscribe, WsHeartbeat, WsPing):
            comps[model.__name__] = model.model_json_schema(ref_template="#/components/schemas/{model}")
        app.openapi_schema = schema
        return schema

    app.openapi = custom_openapi  # type: ignore[method-assign]

    static = static_dir if static_dir is not None else default_static_dir()
    if static is not None and (static / "index.html").is_file():
        assets = static / "assets"
        if assets.is_dir():
            app.mount("/assets", StaticFiles(directory=assets), name="assets")
        index = static / "index.html"

        @app.get("/", include_in_schema=False, response_model=None)
        def index_page() -> FileResponse:
            return FileResponse(index, headers={"Cache-Control": "no-cache"})

        @app.get("/{path:path}", include_in_schema=False, response_model=None)
        def spa(path: str, request: Request) -> FileResponse | JSONResponse:
            if path.startswith(("api/", "docs")):
                # a GET on an API path that serves only other methods is a 405 (D128), an unknown one a 404
                if errors.allowed_methods(app, request.url.path):
                    return errors.method_not_allowed(request)
                return JSONResponse({"detail": "Not Found"}, status_code=404)
            target = (static / path).resolve()
            if target.is_file() and static.resolve() in target.parents:
                return FileResponse(target)
            return FileResponse(index, headers={"Cache-Control": "no-cache"})
    else:

        @app.get("/", include_in_schema=False, response_model=None)
        def no_frontend() -> JSONResponse:
            return JSONResponse(
                {"detail": "the studio frontend is not built; run 'make run' (or 'npm run build' in frontend/)",
                 "api": f"{API_PREFIX}/health", "docs": "/docs"},
                status_code=503,
            )

    return app
