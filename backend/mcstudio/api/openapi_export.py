"""Write the OpenAPI document of the REST API to a file (the frontend's types are generated from it).

    python -m mcstudio.api.openapi_export frontend/openapi.json

The document does not depend on the project, so a one-axis placeholder project is used.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path
from typing import Any

from ..controller.kernel import Controller
from ..controller.runner import Runner
from ..project.models import Project
from .app import create_app
from .state import Studio


def openapi_document() -> dict[str, Any]:
    studio = Studio(runner=Runner(Controller(Project(name="openapi"), cams={})), project_dir=None, projects_root=None)
    return create_app(studio, static_dir=Path("/nonexistent")).openapi()


def main(argv: list[str]) -> int:
    text = json.dumps(openapi_document(), indent=2, ensure_ascii=False, sort_keys=False) + "\n"
    if len(argv) > 1:
        Path(argv[1]).write_text(text, encoding="utf-8")
    else:
        sys.stdout.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
