"""Command line: `mcstudio serve` starts the studio, `mcstudio validate` checks a project folder."""

from __future__ import annotations

import argparse
import logging
import sys
from pathlib import Path

from . import __version__


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


def _cmd_serve(args: argparse.Namespace) -> int:
    import uvicorn

    from .api.app import create_app
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
    if args.host not in ("127.0.0.1", "localhost", "::1"):
        print(f"WARNING: serving on {args.host}: anyone who reaches this address can move the axes.", file=sys.stderr)
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
    app = create_app(studio, on_startup=runner.start)
    print(f"MC Studio {__version__}: project '{project.name}' ({project_dir}), mode {args.mode}")
    print(f"  studio  http://{args.host}:{args.port}/")
    print(f"  API     http://{args.host}:{args.port}/docs")
    if viz is not None:
        print(f"  3D view http://{viz.host}:{viz.port}/")
    try:
        uvicorn.run(app, host=args.host, port=args.port, log_level="warning")
    finally:
        runner.stop()
        if viz is not None:
            viz.stop()
    return 0


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="mcstudio", description="MC Studio — open engineering studio for motion control")
    p.add_argument("--version", action="version", version=f"mcstudio {__version__}")
    sub = p.add_subparsers(dest="command", required=True)

    s = sub.add_parser("serve", help="start the emulated controller and the studio")
    s.add_argument("--project", default="projects/demo", help="project folder (default: projects/demo)")
    s.add_argument("--projects-root", default=None, help="folder of project folders (default: the project's parent)")
    s.add_argument("--host", default="127.0.0.1", help="address to serve on (default: 127.0.0.1, loopback only)")
    s.add_argument("--port", type=int, default=8000, help="HTTP port (default: 8000)")
    s.add_argument("--viser-port", type=int, default=8080, help="3D view port (default: 8080; 0 = no 3D view)")
    s.add_argument("--viser-host", default=None, help="3D view address (default: 127.0.0.1)")
    s.add_argument("--mode", choices=("realtime", "fast", "paused"), default="realtime",
                   help="controller mode at start (default: realtime)")
    s.set_defaults(func=_cmd_serve)

    v = sub.add_parser("validate", help="check project folders; exit code 0 if all are valid")
    v.add_argument("dirs", nargs="+", help="project folder(s)")
    v.set_defaults(func=_cmd_validate)
    return p


def main(argv: list[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    return int(args.func(args))


if __name__ == "__main__":
    sys.exit(main())
