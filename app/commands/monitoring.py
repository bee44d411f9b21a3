"""The monitor page's server for ``run --monitor`` and ``replay``: its address and start."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

from lightrocks.app.commands.common import UsageError, note, require

PARTS = (
    "lightrocks.app.monitor",
    "lightrocks.app.monitor.page",
    "lightrocks.app.web",
    "lightrocks.app.web.page",
)


def watch_for(args: argparse.Namespace, model: Path, search_path: list[Path], name: str) -> Any:
    """Start the page's server and tell where it is; the watch that feeds and controls it."""
    address = monitor_address(args.monitor, args.monitor_public)
    from lightrocks.app.monitor.watch import monitor_for

    monitor, watch = monitor_for(
        model, search_path, name, args.breakpoints, args.paused, args.aborts
    )
    serve(monitor, address)
    return watch


def monitor_options(parser: argparse.ArgumentParser, what: str) -> None:
    """``--monitor [HOST:]PORT`` and ``--monitor-public``; ``what`` the page shows."""
    parser.add_argument("--monitor", metavar="[HOST:]PORT", help=f"serve {what} (host 127.0.0.1)")
    parser.add_argument(
        "--monitor-public",
        action="store_true",
        help="let --monitor serve on an address other machines reach (plain HTTP)",
    )


def monitor_address(text: str, public: bool = False) -> tuple[str, int]:
    """Where the page is served. An address other machines can reach serves the run's
    controls to them over plain HTTP: only with ``--monitor-public``, and with a warning."""
    require("the monitor", PARTS, ("starlette", "uvicorn", "websockets"), "monitor")
    from lightrocks.app.monitor.server import parse_address
    from lightrocks.app.web.guard import is_loopback

    try:
        host, port = parse_address(text)
    except ValueError as error:
        raise UsageError(str(error)) from None
    if not is_loopback(host) and not public:
        raise UsageError(
            f"--monitor {text} serves the run's controls to other machines, over plain HTTP: "
            "add --monitor-public to mean it, or keep the default host 127.0.0.1 and use an "
            "SSH tunnel"
        )
    if not is_loopback(host):
        note(
            f"the monitor serves {host}:{port} to other machines over plain HTTP: whoever "
            "reads its URL (on the network, too) can pause and abort the run"
        )
    return host, port


def serve(monitor: Any, address: tuple[str, int]) -> None:
    """Start the page's server; its URL, with the token, on stderr."""
    try:
        url = monitor.serve(*address)
    except OSError as error:
        raise UsageError(str(error)) from None
    print(f"monitor: {url}", file=sys.stderr, flush=True)
