"""``lightrocks replay``: a recorded run served in the monitor page with a time slider."""

from __future__ import annotations

import argparse
import contextlib
import sys

from lightrocks.app.commands.common import (
    EXIT_FINDINGS,
    EXIT_OK,
    UsageError,
    command,
    existing_paths,
    note,
    path_option,
    statechart_file,
)
from lightrocks.app.commands.monitoring import monitor_address, monitor_options, serve
from lightrocks.workbench.report import printable


def _configure_replay(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser("replay", help="replay a recorded run in the monitor page")
    parser.add_argument("trace", help="a trace written by 'run --trace'")
    monitor_options(parser, "the page")
    parser.add_argument("--model", help="the .lr file the run ran (default: named in the trace)")
    path_option(parser)


@command(_configure_replay)
def cmd_replay(args: argparse.Namespace) -> int:
    """Serve the page with a time slider over the recorded run until Ctrl-C."""
    import threading

    from lightrocks.app.errors import ModelError
    from lightrocks.app.monitor.traces import TraceError, header, read_trace, task_name
    from lightrocks.app.monitor.watch import replay_for
    from lightrocks.workbench.generators import GenerationError

    trace = existing_paths([args.trace])[0]
    if args.monitor is None:
        raise UsageError("replay serves its page: give --monitor [HOST:]PORT")
    address = monitor_address(args.monitor, args.monitor_public)
    try:
        records = read_trace(trace, note)
        name = task_name(records)
    except TraceError as error:
        print(f"lightrocks: error: {printable(str(error))}", file=sys.stderr)
        return EXIT_FINDINGS
    named, named_path = header(records)
    if args.model is None and named is None:
        raise UsageError(f"{trace} names no model (an older trace): give --model")
    model = statechart_file(args.model or str(named))
    search_path = existing_paths(args.path) if args.model else existing_paths(named_path)
    try:
        monitor = replay_for(model, search_path, name, records)
    except ModelError as error:
        print(error)  # the findings, already neutralised by report.text
        return EXIT_FINDINGS
    except GenerationError as error:
        raise UsageError(str(error)) from None
    serve(monitor, address)
    shown = printable(str(trace))
    print(f"replaying {shown} ({records[-1]['time']:.3f} s); Ctrl-C ends", file=sys.stderr)
    with contextlib.suppress(KeyboardInterrupt):
        threading.Event().wait()
    return EXIT_OK
