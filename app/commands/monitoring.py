"""The monitor page's server for ``run --monitor`` and ``replay``: its address and start."""

from __future__ import annotations

import argparse
import sys
from importlib.util import find_spec
from pathlib import Path
from typing import Any

from lightrocks.app.commands.common import UsageError


def watch_for(args: argparse.Namespace, model: Path, search_path: list[Path], name: str) -> Any:
    """Start the page's server and tell where it is; the watch that feeds and controls it."""
    from lightrocks.app.monitor.watch import monitor_for

    address = monitor_address(args.monitor)
    monitor, watch = monitor_for(
        model, search_path, name, args.breakpoints, args.paused, args.aborts
    )
    serve(monitor, address)
    return watch


def monitor_address(text: str) -> tuple[str, int]:
    from lightrocks.app.monitor.server import parse_address

    if any(find_spec(m) is None for m in ("starlette", "uvicorn", "websockets")):
        raise UsageError("--monitor needs its web server: pip install 'lightrocks[monitor]'")
    try:
        return parse_address(text)
    except ValueError as error:
        raise UsageError(str(error)) from None


def serve(monitor: Any, address: tuple[str, int]) -> None:
    try:
        url = monitor.serve(*address)
    except OSError as error:
        raise UsageError(str(error)) from None
    print(f"monitor: {url}", file=sys.stderr, flush=True)
