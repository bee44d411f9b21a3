"""``lightrocks replay``: a recorded run served in the monitor page with a time slider."""

from __future__ import annotations

import argparse
import contextlib
import sys
from pathlib import Path

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

    from lightrocks.app.errors import ModelError, RunError
    from lightrocks.app.monitor.traces import TraceError, check_states, read_trace, task_name
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
    model, search_path = _model(args, trace, records)
    try:
        check_states(records, model_states(model, search_path), model)
        monitor = replay_for(model, search_path, name, records)
    except TraceError as error:
        print(f"lightrocks: error: {printable(str(error))}", file=sys.stderr)
        return EXIT_FINDINGS
    except ModelError as error:
        print(error)  # the findings, already neutralised by report.text
        return EXIT_FINDINGS
    except (GenerationError, RunError) as error:
        raise UsageError(str(error)) from None
    serve(monitor, address)
    shown = printable(str(trace))
    print(f"replaying {shown} ({records[-1]['time']:.3f} s); Ctrl-C ends", file=sys.stderr)
    with contextlib.suppress(KeyboardInterrupt):
        while not threading.Event().wait(1.0):  # wakes to take Ctrl-C from any thread
            pass
    return EXIT_OK


def _model(args: argparse.Namespace, trace: Path, records: list[dict]) -> tuple[Path, list[Path]]:
    """The model the run ran: ``--model`` (with ``--path``), else the one the trace names,
    when it is on this machine."""
    from lightrocks.app.monitor.traces import header

    if args.model is not None:
        return statechart_file(args.model), existing_paths(args.path)
    named, named_path = header(records)
    if named is None:
        raise UsageError(f"{trace} names no model (an older trace): give --model")
    missing = [str(p) for p in (named, *named_path) if not p.exists()]
    if missing:
        raise UsageError(
            f"{trace} was recorded with {named} (model path: "
            f"{', '.join(map(str, named_path)) or 'none'}), but {', '.join(missing)} is not "
            "on this machine: give the model with --model FILE (and its folders with --path DIR)"
        )
    return statechart_file(str(named)), existing_paths([str(p) for p in named_path])


def model_states(model: Path, search_path: list[Path]) -> set[str]:
    """The paths of every state of the statechart in ``model``, as a trace names them."""
    from lightrocks.app import pipeline
    from lightrocks.runtime.tree import states_below

    return {state.path for state in states_below(pipeline.load(model, search_path)())}
