"""Uniform 4xx responses: `{"detail": [...]}` with a `loc` naming the offending field, like FastAPI's own 422s."""

from __future__ import annotations

import math
import re
from typing import Any

from fastapi import FastAPI, Request
from fastapi.encoders import jsonable_encoder
from fastapi.exception_handlers import http_exception_handler
from fastapi.exceptions import RequestValidationError
from fastapi.responses import JSONResponse, Response
from starlette.exceptions import HTTPException as StarletteHTTPException
from starlette.formparsers import MultiPartException

from ..controller.kernel import KernelError
from ..controller.mc.fb.base import FBInputError
from ..controller.trace import TraceError
from ..project.io import ProjectError
from .state import ConflictError


def _err(loc: list[Any], msg: str, typ: str = "value_error", **extra: Any) -> dict[str, Any]:
    return {"loc": loc, "msg": msg, "type": typ, **extra}


def _finite(v: Any) -> Any:
    """NaN/±inf (Python's json accepts the literals) echoed back as strings: JSON cannot carry them."""
    if isinstance(v, float) and not math.isfinite(v):
        return str(v)
    if isinstance(v, dict):
        return {k: _finite(x) for k, x in v.items()}
    if isinstance(v, list | tuple):
        return [_finite(x) for x in v]
    return v


# FastAPI's answer to a JSON body it cannot decode (not UTF-8, …); it carries no `loc`.
_BODY_PARSE_ERROR = "There was an error parsing the body"


def _body_unreadable(exc: StarletteHTTPException) -> bool:
    """A 400 raised while FastAPI/Starlette read the body (undecodable JSON, malformed multipart), not by a route."""
    return exc.status_code == 400 and (
        exc.detail == _BODY_PARSE_ERROR or isinstance(exc.__context__, MultiPartException)
    )


def install(app: FastAPI) -> None:
    @app.exception_handler(StarletteHTTPException)
    async def _http(request: Request, exc: StarletteHTTPException) -> Response:
        # An unreadable body is a 422 naming the body, like FastAPI's own answer to malformed JSON (found by the
        # API fuzzing, docs/hardening.md); every other HTTPException keeps FastAPI's handling.
        if _body_unreadable(exc):
            msg = "the body cannot be read" + ("" if exc.detail == _BODY_PARSE_ERROR else f": {exc.detail}")
            return JSONResponse(status_code=422, content={"detail": [_err(["body"], msg, "body_unreadable")]})
        if exc.status_code == 405:
            return method_not_allowed(request)
        return await http_exception_handler(request, exc)

    @app.exception_handler(RequestValidationError)
    async def _validation(_: Request, exc: RequestValidationError) -> JSONResponse:
        # FastAPI's own 422, except that a non-finite input no longer turns it into a 500
        return JSONResponse(status_code=422, content={"detail": _finite(jsonable_encoder(exc.errors()))})

    @app.exception_handler(FBInputError)
    async def _fb_input(_: Request, exc: FBInputError) -> JSONResponse:
        loc = ["body", "inputs", exc.field]
        return JSONResponse(status_code=422, content={"detail": [_err(loc, exc.message)]})

    @app.exception_handler(KernelError)
    async def _kernel(_: Request, exc: KernelError) -> JSONResponse:
        if exc.status == 404:
            return JSONResponse(status_code=404, content={"detail": exc.message})
        loc = ["body", *exc.field.split(".")]
        return JSONResponse(status_code=exc.status, content={"detail": [_err(loc, exc.message)]})

    @app.exception_handler(TraceError)
    async def _trace(_: Request, exc: TraceError) -> JSONResponse:
        if exc.status == 404:
            return JSONResponse(status_code=404, content={"detail": exc.message})
        return JSONResponse(status_code=exc.status,
                            content={"detail": [_err(["body", *_split_path(exc.field)], exc.message)]})

    @app.exception_handler(ProjectError)
    async def _project(_: Request, exc: ProjectError) -> JSONResponse:
        if not exc.issues:
            return JSONResponse(status_code=422, content={"detail": [_err(["body"], exc.message)]})
        detail = [
            _err(["body", *_split_path(i.path)], i.message, "project_error", path=i.path, code=i.code)
            for i in exc.issues
        ]
        return JSONResponse(status_code=422, content={"detail": detail, "message": exc.message})

    @app.exception_handler(ConflictError)
    async def _conflict(_: Request, exc: ConflictError) -> JSONResponse:
        return JSONResponse(status_code=409, content={"detail": str(exc)})


_HTTP_METHODS = ("get", "put", "post", "patch", "delete", "head", "options", "trace")


def _documented_paths(app: Any) -> list[tuple[re.Pattern[str], list[str]]]:
    """The OpenAPI paths as regexes with their documented methods; built once per app. A `{param}` is one path
    segment, digits only for an integer parameter (as the route's `:int` convertor)."""
    cached = getattr(app.state, "documented_paths", None)
    if cached is None:
        cached = []
        for template, item in app.openapi().get("paths", {}).items():
            integers = {p["name"] for op in item.values() if isinstance(op, dict)
                        for p in op.get("parameters", []) if p.get("in") == "path"
                        and p.get("schema", {}).get("type") == "integer"}
            pattern = re.sub(r"\\\{([^/]+?)\\\}", lambda m, ints=integers: "[0-9]+" if m[1] in ints else "[^/]+",
                             re.escape(template))
            cached.append((re.compile(f"^{pattern}$"), sorted(m.upper() for m in item if m in _HTTP_METHODS)))
        app.state.documented_paths = cached
    return cached


def allowed_methods(app: Any, path: str) -> list[str]:
    """Every method the API serves at this path, over all the operations whose path matches it (/cams/generate is
    also the cam table "generate"). Starlette's own 405 named only the first matching route's methods, so a path
    with GET and PUT on two routes answered `Allow: GET` (found by schemathesis, D128)."""
    return sorted({m for pattern, documented in _documented_paths(app) if pattern.match(path) for m in documented})


def method_not_allowed(request: Request) -> JSONResponse:
    allow = allowed_methods(request.app, request.url.path)
    if not allow:  # no operation has this path (only the page fallback's GET matched it): nothing is here
        return JSONResponse({"detail": "Not Found"}, status_code=404)
    return JSONResponse({"detail": f"{request.method} is not allowed here; allowed: {', '.join(allow)}"},
                        status_code=405, headers={"Allow": ", ".join(allow)})


def _split_path(path: str) -> list[Any]:
    """'axes[1].parameters.Operation.MaxVel' → ['axes', 1, 'parameters', 'Operation', 'MaxVel']."""
    out: list[Any] = []
    for part in path.split("."):
        # (a key of the document may itself contain '[' or ']', e.g. an unknown key "[": kept as text)
        while "[" in part and "]" in part.split("[", 1)[1]:
            head, rest = part.split("[", 1)
            if head:
                out.append(head)
            idx, part = rest.split("]", 1)
            out.append(int(idx) if idx.isascii() and idx.isdigit() else idx)
        if part:
            out.append(part)
    return out
