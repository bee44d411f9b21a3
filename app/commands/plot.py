"""``lightrocks plot``: force, torque and TCP of a recorded trace as PNG or HTML."""

from __future__ import annotations

import argparse
import sys
from importlib.util import find_spec
from pathlib import Path

from lightrocks.app.commands.common import (
    EXIT_FINDINGS,
    EXIT_OK,
    UsageError,
    command,
    existing_paths,
    note,
)
from lightrocks.workbench.report import printable


def _configure_plot(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser("plot", help="plot force, torque and TCP of a recorded trace")
    parser.add_argument("trace", help="a trace written by 'run --trace'")
    parser.add_argument("-o", "--output", required=True, help="FILE.png or FILE.html")


@command(_configure_plot)
def cmd_plot(args: argparse.Namespace) -> int:
    from lightrocks.app.monitor.plot import FORMATS, plot
    from lightrocks.app.monitor.traces import TraceError

    if find_spec("matplotlib") is None:
        raise UsageError("plot needs matplotlib: pip install 'lightrocks[plot]'")
    trace = existing_paths([args.trace])[0]
    output = Path(args.output)
    if output.suffix not in FORMATS:
        raise UsageError(f"-o must end in {' or '.join(FORMATS)}: {output}")
    if not output.parent.is_dir():
        raise UsageError(f"-o: no such folder: {output.parent}")
    try:
        recorded = plot(trace, output, note)
    except TraceError as error:
        print(f"lightrocks: error: {printable(str(error))}", file=sys.stderr)
        return EXIT_FINDINGS
    outcome = printable(recorded.outcome or "unfinished")
    print(f"{printable(str(output))} written: {len(recorded.times)} samples, outcome {outcome}")
    return EXIT_OK
