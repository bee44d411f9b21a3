"""``lightrocks studio``: the models' diagrams in a local page, with the findings of
``check`` on them, edited through the language's parser and pretty printer."""

from __future__ import annotations

import argparse
import contextlib
import sys
import threading

from lightrocks.app.commands.common import EXIT_OK, UsageError, command, existing_paths, require

PARTS = (
    "lightrocks.app.studio",
    "lightrocks.app.studio.page",
    "lightrocks.app.monitor",
    "lightrocks.app.web",
    "lightrocks.app.web.page",
)
"""The studio's code and page, the monitor, which serves the runs started from it, and the
web floor (guard, request checks, diagram script) they share."""


def _configure_studio(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser("studio", help="show and edit the models' diagrams in a local page")
    parser.add_argument(
        "paths", nargs="*", default=["."], metavar="MODEL_PATH", help="model-path folders"
    )
    parser.add_argument("--port", type=int, default=0, help="port on 127.0.0.1 (default: free)")


@command(_configure_studio)
def cmd_studio(args: argparse.Namespace) -> int:
    """Serve the page on the loopback interface until Ctrl-C."""
    require("the studio", PARTS, ("starlette", "uvicorn"), "monitor")
    folders = existing_paths(args.paths)
    if not all(folder.is_dir() for folder in folders):
        raise UsageError("studio takes model-path folders")
    if not 0 <= args.port < 65536:
        raise UsageError(f"--port {args.port} is no port")
    from lightrocks.app.studio.server import StudioServer
    from lightrocks.app.studio.workspace import Studio

    server = StudioServer(Studio(folders))
    try:
        url = server.serve(args.port)
    except OSError as error:
        raise UsageError(str(error)) from None
    print(f"studio: {url}", file=sys.stderr, flush=True)
    with contextlib.suppress(KeyboardInterrupt):
        threading.Event().wait()
    return EXIT_OK
