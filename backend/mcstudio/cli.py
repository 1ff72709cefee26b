"""Command line: `mcstudio serve` starts the studio, `mcstudio validate` checks project folders, `mcstudio new` creates
one from a template, `mcstudio schema` writes the project document's JSON Schema (for editors)."""

from __future__ import annotations

import argparse
import logging
import os
import sys
from pathlib import Path
from typing import TYPE_CHECKING

from . import __version__

if TYPE_CHECKING:
    from .api.auth import AccessPolicy


def _cmd_validate(args: argparse.Namespace) -> int:
    from .project.cams import load_cam_tables
    from .project.io import ProjectError, load_project

    ok = True
    for folder in args.dirs:
        try:
            project = load_project(folder)
            cams = load_cam_tables(project, folder)
        except ProjectError as err:
            ok = False
            print(f"INVALID {folder}: {err.message}", file=sys.stderr)
            for issue in err.issues:
                code = f"  [{issue.code}]" if issue.code else ""
                print(f"  {issue.path}: {issue.message}{code}", file=sys.stderr)
            continue
        print(f"OK {folder}: '{project.name}', {len(project.axes)} axes, "
              f"primary period {project.controller.primary_period_us} µs"
              + (f", {len(cams)} cam tables" if cams else ""))
    return 0 if ok else 1


def _cmd_new(args: argparse.Namespace) -> int:
    from .project.folders import build_project_folder, check_project_name, copy_template, find_template, list_templates
    from .project.io import load_project, save_project

    target = Path(args.dir).resolve()
    template = find_template(args.template)
    if template is None:
        names = ", ".join(t.name for t in list_templates())
        print(f"no template named {args.template!r} (templates: {names})", file=sys.stderr)
        return 2
    try:
        check_project_name(target.name)
        tpl_project = load_project(template.folder)

        def fill(staging: Path) -> None:
            copy_template(template, staging)
            save_project(staging, tpl_project.model_copy(update={"name": args.name or target.name}))
            (staging / "project.json.bak").unlink(missing_ok=True)

        build_project_folder(target.parent, target.name, fill)
    except (ValueError, OSError) as err:
        print(f"cannot create {target}: {err}", file=sys.stderr)
        return 1
    print(f"created {target} from template {template.name!r}")
    return 0


def _cmd_schema(args: argparse.Namespace) -> int:
    import json

    from .api.routers.project import project_schema

    text = json.dumps(project_schema(), indent=2, ensure_ascii=False) + "\n"
    if args.output in (None, "-"):
        sys.stdout.write(text)
    else:
        Path(args.output).write_text(text, encoding="utf-8")
        print(f"wrote {args.output}", file=sys.stderr)
    return 0


def _cmd_serve(args: argparse.Namespace) -> int:
    import uvicorn

    from .api.app import create_app
    from .api.auth import is_loopback
    from .api.state import Studio
    from .controller.kernel import Controller
    from .controller.runner import Runner
    from .fieldbus.library import DeviceLibrary
    from .project.cams import load_cam_tables
    from .project.io import ProjectError, load_project

    logging.basicConfig(level=logging.INFO, format="%(levelname)s %(name)s: %(message)s")
    project_dir = Path(args.project).resolve()
    library = DeviceLibrary(project_dir)
    try:
        project = load_project(project_dir, library)
        cams = load_cam_tables(project, project_dir)
    except ProjectError as err:
        print(f"cannot start: {err}", file=sys.stderr)
        return 2
    access, token, problem = _access_settings(args)
    if problem:
        print(f"cannot start: {problem}", file=sys.stderr)
        return 2
    runner = Runner(Controller(project, library=library, cams=cams), mode=args.mode)
    viz = None
    if args.viser_port != 0:
        from .viz.scene import SceneServer

        try:
            viz = SceneServer(host="127.0.0.1" if args.viser_host is None else args.viser_host, port=args.viser_port)
        except OSError as err:
            print(f"WARNING: 3D view disabled, viser could not start on port {args.viser_port}: {err}",
                  file=sys.stderr)
    studio = Studio(runner=runner, project_dir=project_dir,
                    projects_root=Path(args.projects_root).resolve() if args.projects_root else project_dir.parent,
                    viz=viz)
    if viz is not None:
        viz.attach(runner)  # draws the project's robots and follows the published snapshots
    # the kernel starts once the server is up (uvicorn's start-up work would otherwise hold the GIL in its first periods
    # and count overruns that say nothing about the controller)
    app = create_app(studio, on_startup=runner.start, access=access, cors_origins=args.cors_origin or None)
    print(f"MC Studio {__version__}: project '{project.name}' ({project_dir}), mode {args.mode}")
    shown = f"[{args.host}]" if ":" in args.host else args.host
    print(f"  studio  http://{shown}:{args.port}/" + (f"?token={token}" if token else ""))
    print(f"  API     http://{shown}:{args.port}/docs")
    if viz is not None:
        print(f"  3D view http://{viz.host}:{viz.port}/")
    if token:
        print(f"  access token: {token}")
        print("  Every API request and the WebSocket need it ('Authorization: Bearer <token>', or the cookie the "
              "studio\n  sets when opened with ?token=…); the studio's files and /api/v1/health stay open.")
        if args.host in ("0.0.0.0", "::"):
            print("  (listening on every interface: replace the address with this machine's name or address)")
        if viz is not None and not is_loopback(viz.host):
            print(f"WARNING: the 3D view on {viz.host}:{viz.port} is not guarded by the token: whoever reaches it "
                  "sees the scene (it cannot command the controller).", file=sys.stderr)
    try:
        uvicorn.run(app, host=args.host, port=args.port, log_level="warning")
    finally:
        runner.stop()
        if viz is not None:
            viz.stop()
    return 0


def _access_settings(args: argparse.Namespace) -> tuple[AccessPolicy | None, str | None, str | None]:
    """The access policy of `serve` (decisions D118, D119): (policy, token to print, reason to refuse)."""
    from .api.auth import AccessPolicy, is_loopback, new_token

    token = args.token or os.environ.get("MCSTUDIO_TOKEN") or None
    if token is not None and (len(token) < 16 or any(c.isspace() for c in token) or not token.isascii()):
        return None, None, "the token must be at least 16 printable ASCII characters without spaces"
    loopback = is_loopback(args.host)
    if not loopback and token is None:
        token = new_token()
    if args.viser_host is not None and not is_loopback(args.viser_host) and token is None:
        return None, None, (f"--viser-host {args.viser_host} would show the 3D view to the network while the studio "
                            "itself is loopback-only; serve the studio on a network address too (it then needs a "
                            "token), or give --token")
    return AccessPolicy.for_bind(args.host, token, cors_origins=args.cors_origin), token, None


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="mcstudio", description="MC Studio — open engineering studio for motion control")
    p.add_argument("--version", action="version", version=f"mcstudio {__version__}")
    sub = p.add_subparsers(dest="command", required=True)

    s = sub.add_parser("serve", help="start the emulated controller and the studio")
    s.add_argument("--project", default="projects/demo", help="project folder (default: projects/demo)")
    s.add_argument("--projects-root", default=None, help="folder of project folders (default: the project's parent)")
    s.add_argument("--host", default="127.0.0.1",
                   help="address to serve on (default: 127.0.0.1, loopback only; any other address needs the access "
                   "token)")
    s.add_argument("--port", type=int, default=8000, help="HTTP port (default: 8000)")
    s.add_argument("--viser-port", type=int, default=8080, help="3D view port (default: 8080; 0 = no 3D view)")
    s.add_argument("--viser-host", default=None,
                   help="3D view address (default: 127.0.0.1; another address only with a token, and the 3D view "
                   "itself is not token-guarded)")
    s.add_argument("--token", default=None,
                   help="access token that API requests and the WebSocket must carry (default: $MCSTUDIO_TOKEN; "
                   "generated and printed when --host is not the loopback; on the loopback none is needed)")
    s.add_argument("--cors-origin", action="append", default=None, metavar="URL",
                   help="a web origin that may call the API from its pages (repeatable; default: none, the studio "
                   "and the Vite dev server only)")
    s.add_argument("--mode", choices=("realtime", "fast", "paused"), default="realtime",
                   help="controller mode at start (default: realtime)")
    s.set_defaults(func=_cmd_serve)

    v = sub.add_parser("validate", help="check project folders; exit code 0 if all are valid")
    v.add_argument("dirs", nargs="+", help="project folder(s)")
    v.set_defaults(func=_cmd_validate)

    n = sub.add_parser("new", help="create a project folder from a template")
    n.add_argument("dir", help="folder to create (must not exist)")
    n.add_argument("--template", default="empty", help="empty, single-axis or demo (default: empty)")
    n.add_argument("--name", default=None, help="project name in the document (default: the folder name)")
    n.set_defaults(func=_cmd_new)

    sc = sub.add_parser("schema", help="write the JSON Schema of project.json (for editors)")
    sc.add_argument("-o", "--output", default=None, help="file to write (default: standard output)")
    sc.set_defaults(func=_cmd_schema)
    return p


def main(argv: list[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    return int(args.func(args))


if __name__ == "__main__":
    sys.exit(main())
