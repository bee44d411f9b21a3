"""The ``lightrocks`` command line: check, format and list; exit 0 clean, 1 findings, 2 usage."""

from __future__ import annotations

import argparse
import contextlib
import os
import sys
from collections.abc import Callable, Sequence
from importlib.metadata import version
from importlib.util import find_spec
from pathlib import Path
from typing import Any

from lightrocks.app import checkstore
from lightrocks.workbench import checkcache, report
from lightrocks.workbench.diagnostics import Severity

EXIT_OK, EXIT_FINDINGS, EXIT_USAGE = 0, 1, 2

Command = Callable[[argparse.Namespace], int]
COMMANDS: dict[str, tuple[Callable[[argparse._SubParsersAction], None], Command]] = {}


def command(
    configure: Callable[[argparse._SubParsersAction], None],
) -> Callable[[Command], Command]:
    """Register a sub-command: ``configure`` adds its parser, the function runs it."""

    def register(run: Command) -> Command:
        COMMANDS[run.__name__.removeprefix("cmd_")] = (configure, run)
        return run

    return register


class UsageError(Exception):
    """Wrong use of the command line: reported with exit code 2."""


def existing_paths(paths: Sequence[str]) -> list[Path]:
    """The given files and folders; anything else (a FIFO, a device) is never read."""
    missing = [p for p in paths if not Path(p).exists()]
    if missing:
        raise UsageError(f"no such file or folder: {', '.join(missing)}")
    special = [p for p in paths if not (Path(p).is_file() or Path(p).is_dir())]
    if special:
        raise UsageError(f"not a regular file or folder: {', '.join(special)}")
    return [Path(p) for p in paths]


def statechart_file(path: str) -> Path:
    """The one ``.lr`` file ``run`` takes."""
    [model] = existing_paths([path])
    if model.is_dir():
        raise UsageError(f"{path} is a folder: run takes one statechart file (.lr)")
    if model.suffix != ".lr":
        raise UsageError(f"{path} is not a statechart file (.lr): run takes one")
    return model.resolve()


def trace_file(path: str | None) -> Path | None:
    """Where ``--trace`` writes: a new or regular file in an existing folder."""
    if path is None:
        return None
    trace = Path(path)
    if trace.exists() and not trace.is_file():
        raise UsageError(f"--trace: {path} is not a regular file")
    if not trace.parent.is_dir():
        raise UsageError(f"--trace: no such folder: {trace.parent}")
    if not os.access(trace.parent, os.W_OK):
        raise UsageError(f"--trace: cannot write to folder {trace.parent}")
    return trace


def _path_option(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--path",
        action="append",
        default=[],
        metavar="DIR",
        help="model-path folder (package = sub-folder); repeatable",
    )


def _configure_check(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser("check", help="check models and report every finding")
    parser.add_argument("paths", nargs="+", help="model files or folders")
    _path_option(parser)
    parser.add_argument("--format", choices=sorted(report.FORMATS), default="text")
    parser.add_argument(
        "--strict", action="store_true", help="warnings fail the check too (exit 1), for CI"
    )


@command(_configure_check)
def cmd_check(args: argparse.Namespace) -> int:
    paths, model_path = existing_paths(args.paths), existing_paths(args.path)
    found = checkcache.stored(checkcache.key(paths, model_path, False))
    if found is None:
        from lightrocks.workbench.check import check

        keep_parses_on_disk()
        found = check(paths, model_path).diagnostics.items
    output = report.render(args.format, found, _all_cocos)
    if output:
        print(output)
    errors = any(d.severity is Severity.ERROR for d in found)
    warned = any(d.severity is Severity.WARNING for d in found)
    return EXIT_FINDINGS if errors or (args.strict and warned) else EXIT_OK


def _configure_fmt(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser("fmt", help="rewrite models in canonical form")
    parser.add_argument("paths", nargs="+", help="model files or folders")
    parser.add_argument(
        "--check", action="store_true", help="change nothing; exit 1 if a file would change"
    )


@command(_configure_fmt)
def cmd_fmt(args: argparse.Namespace) -> int:
    from lightrocks.metamodel.ast import Position
    from lightrocks.metamodel.grammar import SyntaxProblem
    from lightrocks.workbench.depth import TOO_DEEP, deepest
    from lightrocks.workbench.diagnostics import Diagnostics
    from lightrocks.workbench.files import write_atomic
    from lightrocks.workbench.languages import extensions, language_for
    from lightrocks.workbench.modelpath import model_files

    files = [f for p in existing_paths(args.paths) for f in model_files(p, extensions())]
    diagnostics = Diagnostics()
    original: dict[Path, str] = {}
    formatted: dict[Path, str] = {}
    for file in files:
        language = language_for(file.suffix)
        if language is None:
            raise UsageError(f"not a model file: {file}")
        if not file.is_file():
            diagnostics.error(Position(str(file), 1, 1), "LR0004", "not a regular file")
            continue
        try:
            original[file] = file.read_text(encoding="utf-8")
            formatted[file] = language.format(original[file], str(file))
        except SyntaxProblem as problem:
            diagnostics.error(
                Position(str(file), problem.line, problem.column), "LR0001", problem.message
            )
        except RecursionError:
            diagnostics.error(deepest(original[file], str(file)), "LR0001", TOO_DEEP)
        except (UnicodeDecodeError, ValueError):
            diagnostics.error(Position(str(file), 1, 1), "LR0002", "not a text file")
    if diagnostics.has_errors:
        print(report.text(diagnostics.items))
        return EXIT_FINDINGS
    changed = [f for f, text in formatted.items() if text != original[f]]
    if args.check:
        for file in changed:
            print(f"would reformat {report.printable(str(file))}")
        print(f"{len(changed)} of {len(files)} file(s) would change")
        return EXIT_FINDINGS if changed else EXIT_OK
    for file in changed:
        write_atomic(file, formatted[file])
        print(f"reformatted {report.printable(str(file))}")
    print(f"{len(changed)} of {len(files)} file(s) reformatted")
    return EXIT_OK


def _configure_generate(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser("generate", help="generate code or pictures from checked models")
    parser.add_argument("models", nargs="+", help="model files or folders")
    parser.add_argument("--target", required=True, help="generator name (see 'list generators')")
    parser.add_argument(
        "-o", "--output", required=True, help="output folder (created when missing)"
    )
    _path_option(parser)
    parser.add_argument("--templates", help="folder whose templates override the built-in ones")
    parser.add_argument(
        "--option", action="append", default=[], metavar="NAME=VALUE", help="generator option"
    )


@command(_configure_generate)
def cmd_generate(args: argparse.Namespace) -> int:
    from lightrocks.workbench.check import check
    from lightrocks.workbench.generators import (
        GenerationError,
        GenerationRequest,
        TemplateProblem,
        load_generator,
        run_generator,
        write_all,
    )
    from lightrocks.workbench.languages import extensions
    from lightrocks.workbench.modelpath import model_files

    try:
        generator = load_generator(args.target)
    except GenerationError as error:
        raise UsageError(str(error)) from None
    options = dict(_option(o) for o in args.option)
    templates = existing_paths([args.templates])[0] if args.templates else None
    paths = existing_paths(args.models)
    context = check(paths, existing_paths(args.path))
    if context.diagnostics.has_errors:
        print(report.text(context.diagnostics.items))
        return EXIT_FINDINGS
    files = [f.resolve() for p in paths for f in model_files(p, extensions())]
    request = GenerationRequest(context, files, options, templates)
    try:
        written = write_all(Path(args.output), run_generator(generator, request))
    except TemplateProblem as error:
        raise UsageError(str(error)) from None
    except GenerationError as error:
        print(f"lightrocks: error: {report.printable(str(error))}", file=sys.stderr)
        return EXIT_FINDINGS
    print(f"{len(written)} file(s) written to {report.printable(args.output)}")
    return EXIT_OK


def _option(text: str) -> tuple[str, str]:
    name, separator, value = text.partition("=")
    if not separator or not name:
        raise UsageError(f"option '{text}' is not NAME=VALUE")
    return name, value


def _configure_run(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser("run", help="generate Python for a statechart and run it")
    parser.add_argument("model", help="the .lr file of the statechart to run")
    parser.add_argument("--adapter", help="adapter name (see 'list adapters'); none for plain")
    parser.add_argument(
        "--param", action="append", default=[], metavar="NAME=VALUE", help="parameter value"
    )
    parser.add_argument("--trace", help="write the trace (JSON lines) to this file")
    parser.add_argument(
        "--events",
        default="",
        help="comma-separated events to send in order; +500ms advances the virtual clock",
    )
    parser.add_argument("--seed", type=int, default=0, help="the adapter's random seed")
    parser.add_argument(
        "--seeds", type=int, metavar="N", help="repeat with seeds SEED..SEED+N-1 and report"
    )
    parser.add_argument(
        "--workers", type=int, metavar="K", help="processes for --seeds (default: one per core)"
    )
    parser.add_argument(
        "--perception-noise",
        metavar="LENGTH,ANGLE",
        help="Gaussian sigmas of the camera's position and rotation, e.g. 2mm,2deg",
    )
    parser.add_argument("--video", metavar="FILE", help="record a video (.mp4) or PNG frames")
    parser.add_argument(
        "--script",
        metavar="FILE",
        help="JSON file of scripted outcomes and sensor values for the dry run",
    )
    parser.add_argument(
        "--success", metavar="OUTCOME", help="outcome that counts as success (default: the first)"
    )
    parser.add_argument(
        "--monitor", metavar="[HOST:]PORT", help="serve a live page of the run (host 127.0.0.1)"
    )
    parser.add_argument(
        "--break",
        dest="breakpoints",
        action="append",
        default=[],
        metavar="Q.NAME",
        help="pause on entering this state (with --monitor); repeatable",
    )
    parser.add_argument(
        "--paused", action="store_true", help="wait for Resume or Step on the page (--monitor)"
    )
    parser.add_argument(
        "--abort-at",
        dest="aborts",
        action="append",
        default=[],
        metavar="Q.NAME",
        help="abort safely on entering this state (with --monitor); repeatable",
    )
    _path_option(parser)


@command(_configure_run)
def cmd_run(args: argparse.Namespace) -> int:
    from functools import partial

    from lightrocks.app import display, values
    from lightrocks.app.adapter_factory import adapter_options
    from lightrocks.app.errors import ModelError, RunError
    from lightrocks.app.loading import load_component
    from lightrocks.app.run import run_component, run_header, success_outcome
    from lightrocks.app.script import read_script
    from lightrocks.app.seeds import run_seeds
    from lightrocks.workbench.generators import GenerationError

    model = statechart_file(args.model)
    search_path = existing_paths(args.path)
    trace = trace_file(args.trace)
    script_file = existing_paths([args.script])[0] if args.script else None
    events = [e.strip() for e in args.events.split(",") if e.strip()]
    if args.seeds is not None and args.seeds < 1:
        raise UsageError("--seeds must be at least 1")
    if args.workers is not None and (args.seeds is None or args.workers < 1):
        raise UsageError("--workers needs --seeds and must be at least 1")
    if args.seeds is not None and args.video:
        raise UsageError("--video records a single run: leave out --seeds")
    if (args.breakpoints or args.paused or args.aborts) and not args.monitor:
        raise UsageError("--break, --abort-at and --paused need --monitor")
    if args.monitor and args.seeds is not None:
        raise UsageError("--monitor watches a single run: leave out --seeds")
    try:
        noise = values.parse_noise(args.perception_noise) if args.perception_noise else (0.0, 0.0)
        cls = load_component(model, search_path)
        wanted = success_outcome(cls, args.success)
        values.parameters(cls, args.param)
        script = read_script(script_file, cls) if script_file else None
        adapter_options(args.adapter, args.seed, noise, args.video, script)
        if args.seeds is not None:
            seeds = range(args.seed, args.seed + args.seeds)
            many = partial(
                run_seeds,
                model,
                search_path,
                args.param,
                args.adapter,
                seeds,
                noise,
                trace,
                events=events,
                success=args.success,
                workers=args.workers,
                script=script,
            )
            return display.show_seeds(cls.NAME, wanted, len(seeds), many)
        watch = _monitor(args, model, search_path, cls.NAME) if args.monitor else None
        single = partial(
            run_component,
            cls,
            args.param,
            args.adapter,
            args.seed,
            noise,
            trace,
            args.video,
            events=events,
            success=args.success,
            script=script,
            watch=watch,
            header=run_header(model, search_path),
        )
        return display.show(cls.NAME, single)
    except ModelError as error:
        print(error)  # the findings, already neutralised by report.text
        return EXIT_FINDINGS
    except (RunError, GenerationError) as error:
        raise UsageError(str(error)) from None
    except OSError as error:
        raise UsageError(f"cannot write {error.filename or 'output'}: {error.strerror}") from None


def _configure_sweep(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser(
        "sweep", help="run every combination of parameters and noise levels over seeds on Dask"
    )
    parser.add_argument("model", help="the .lr file of the statechart to run")
    parser.add_argument("--adapter", help="adapter name (see 'list adapters'); none for plain")
    parser.add_argument("--seeds", type=int, required=True, metavar="N", help="runs per point")
    parser.add_argument("--seed", type=int, default=0, help="the first seed (default 0)")
    parser.add_argument(
        "--grid",
        action="append",
        default=[],
        metavar="NAME=V1,V2,…",
        help="values of a parameter to sweep (repeat for more parameters)",
    )
    parser.add_argument(
        "--param", action="append", default=[], metavar="NAME=VALUE", help="fixed parameter value"
    )
    parser.add_argument(
        "--perception-noise",
        default="0mm,0deg",
        metavar="L,A[;L,A…]",
        help="noise levels to sweep, e.g. '0mm,0deg;2mm,2deg;3mm,3deg'",
    )
    parser.add_argument(
        "--success", metavar="OUTCOME", help="outcome that counts as success (default: the first)"
    )
    parser.add_argument(
        "--scheduler", metavar="ADDRESS", help="a running Dask scheduler (default: a local cluster)"
    )
    parser.add_argument(
        "--workers", type=int, metavar="K", help="worker processes of the local cluster"
    )
    parser.add_argument(
        "-o", "--output", default="sweep", help="folder for the tables and the plot (sweep)"
    )
    _path_option(parser)


@command(_configure_sweep)
def cmd_sweep(args: argparse.Namespace) -> int:
    from lightrocks.app import display, sweep, values
    from lightrocks.app.adapter_factory import adapter_options
    from lightrocks.app.errors import ModelError, RunError
    from lightrocks.app.loading import load_component
    from lightrocks.app.run import success_outcome
    from lightrocks.workbench.files import write_tree
    from lightrocks.workbench.generators import GenerationError

    missing = [m for m in ("distributed", "pyarrow", "matplotlib") if not find_spec(m)]
    if missing:
        raise UsageError(f"sweep needs {', '.join(missing)}: pip install 'lightrocks[sweep]'")
    model = statechart_file(args.model)
    search_path = existing_paths(args.path)
    output = Path(args.output)
    if output.exists() and not output.is_dir():
        raise UsageError(f"--output {output} is not a folder")
    if args.seeds < 1:
        raise UsageError("--seeds must be at least 1")
    if args.workers is not None and (args.workers < 1 or args.scheduler is not None):
        raise UsageError("--workers sizes the local cluster: at least 1, without --scheduler")
    try:
        noises = [values.parse_noise(level) for level in args.perception_noise.split(";")]
        grid = sweep.parse_grid(args.grid)
        cls = load_component(model, search_path)
        wanted = success_outcome(cls, args.success)
        points = sweep.grid_points(grid, noises)
        for point in points:  # every value is checked before the first run starts
            values.parameters(cls, [*args.param, *point.params])
            adapter_options(args.adapter, args.seed, point.noise, None)
        seeds = range(args.seed, args.seed + args.seeds)
        with (
            display.progress_bar(cls.NAME, len(points) * len(seeds)) as advance,
            sweep.dask_client(args.scheduler, args.workers) as client,
        ):
            results = sweep.sweep(
                client,
                model,
                search_path,
                args.adapter,
                points,
                seeds,
                params=args.param,
                success=args.success,
                done=lambda _, result: advance(result.success),
            )
        summaries = sweep.summarize(points, results)
        write_tree(output, sweep.result_files(cls.NAME, summaries, results))
    except ModelError as error:
        print(error)
        return EXIT_FINDINGS
    except (RunError, GenerationError) as error:
        raise UsageError(str(error)) from None
    display.show_sweep(cls.NAME, wanted, sweep.point_rows(summaries), str(output))
    return EXIT_OK


def _monitor(args: argparse.Namespace, model: Path, search_path: list[Path], name: str) -> Any:
    """Start the page's server and tell where it is; the watch that feeds and controls it."""
    from lightrocks.app.monitor.watch import monitor_for

    address = _monitor_address(args.monitor)
    monitor, watch = monitor_for(
        model, search_path, name, args.breakpoints, args.paused, args.aborts
    )
    _serve(monitor, address)
    return watch


def _monitor_address(text: str) -> tuple[str, int]:
    from lightrocks.app.monitor.server import parse_address

    if any(find_spec(m) is None for m in ("starlette", "uvicorn", "websockets")):
        raise UsageError("--monitor needs its web server: pip install 'lightrocks[monitor]'")
    try:
        return parse_address(text)
    except ValueError as error:
        raise UsageError(str(error)) from None


def _serve(monitor: Any, address: tuple[str, int]) -> None:
    try:
        url = monitor.serve(*address)
    except OSError as error:
        raise UsageError(str(error)) from None
    print(f"monitor: {url}", file=sys.stderr, flush=True)


def _configure_replay(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser("replay", help="replay a recorded run in the monitor page")
    parser.add_argument("trace", help="a trace written by 'run --trace'")
    parser.add_argument(
        "--monitor", required=True, metavar="[HOST:]PORT", help="serve the page (host 127.0.0.1)"
    )
    parser.add_argument("--model", help="the .lr file the run ran (default: named in the trace)")
    _path_option(parser)


@command(_configure_replay)
def cmd_replay(args: argparse.Namespace) -> int:
    """Serve the page with a time slider over the recorded run until Ctrl-C."""
    import threading

    from lightrocks.app.monitor.traces import TraceError, header, read_trace, task_name
    from lightrocks.app.monitor.watch import replay_for
    from lightrocks.workbench.generators import GenerationError

    trace = existing_paths([args.trace])[0]
    address = _monitor_address(args.monitor)
    try:
        records = read_trace(trace)
        name = task_name(records)
    except TraceError as error:
        print(f"lightrocks: error: {error}", file=sys.stderr)
        return EXIT_FINDINGS
    named, named_path = header(records)
    if args.model is None and named is None:
        raise UsageError(f"{trace} names no model (an older trace): give --model")
    model = statechart_file(args.model or str(named))
    search_path = existing_paths(args.path) if args.model else existing_paths(named_path)
    try:
        monitor = replay_for(model, search_path, name, records)
    except GenerationError as error:
        raise UsageError(str(error)) from None
    _serve(monitor, address)
    print(f"replaying {trace} ({records[-1]['time']:.3f} s); Ctrl-C ends", file=sys.stderr)
    with contextlib.suppress(KeyboardInterrupt):
        threading.Event().wait()
    return EXIT_OK


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
        recorded = plot(trace, output)
    except TraceError as error:
        print(f"lightrocks: error: {error}", file=sys.stderr)
        return EXIT_FINDINGS
    print(f"{output} written: {len(recorded.times)} samples, outcome {recorded.outcome}")
    return EXIT_OK


def _configure_list(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser("list", help="list languages, CoCos, generators, adapters or scenes")
    parser.add_argument("what", choices=("languages", "cocos", "generators", "adapters", "scenes"))


@command(_configure_list)
def cmd_list(args: argparse.Namespace) -> int:
    from importlib.metadata import entry_points

    from lightrocks.workbench.extensions import language_extensions
    from lightrocks.workbench.generators import load_generator
    from lightrocks.workbench.languages import languages

    if args.what == "languages":
        rows = [(lang.name, " ".join(lang.extensions), lang.description) for lang in languages()]
        rows += [(e.name, f"extends {e.extends}", e.description) for e in language_extensions()]
    elif args.what == "cocos":
        rows = [(c.code, c.severity.value, c.summary) for c in _all_cocos()]
    elif args.what == "generators":
        rows = [
            (e.name, e.value, load_generator(e.name).description)
            for e in sorted(entry_points(group="lightrocks.generators"), key=str)
        ]
    else:
        group = f"lightrocks.{args.what}"
        rows = [(e.name, e.value, "") for e in sorted(entry_points(group=group), key=str)]
    for row in rows:
        print("  ".join(part for part in row if part))
    return EXIT_OK


def _configure_lsp(sub: argparse._SubParsersAction) -> None:
    sub.add_parser("lsp", help="serve the language server protocol over stdio (for editors)")


@command(_configure_lsp)
def cmd_lsp(args: argparse.Namespace) -> int:
    from lightrocks.app.lsp.server import main as serve  # only editors need pygls

    return serve()


def parser() -> argparse.ArgumentParser:
    main_parser = argparse.ArgumentParser(
        prog="lightrocks", description="LightRocks language workbench"
    )
    main_parser.add_argument("--version", action="version", version=version("lightrocks"))
    sub = main_parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for configure, _ in COMMANDS.values():
        configure(sub)
    return main_parser


def _all_cocos() -> list[Any]:
    from lightrocks.workbench.check import all_cocos

    return all_cocos()


def main(argv: Sequence[str] | None = None) -> int:
    args = parser().parse_args(argv)
    checkcache.use_store(checkstore.DiskStore())  # an unchanged workspace is not checked again
    if args.command != "check":  # check loads the parser only when its findings are not on disk
        keep_parses_on_disk()
    try:
        return COMMANDS[args.command][1](args)
    except UsageError as error:
        _complain(f"error: {error}")
        return EXIT_USAGE
    except KeyboardInterrupt:
        _complain("interrupted")
        return 130
    except Exception as error:
        if os.environ.get("LIGHTROCKS_DEBUG"):
            raise
        _complain(f"internal error: {error!r} (set LIGHTROCKS_DEBUG=1 for the traceback)")
        return EXIT_FINDINGS


def keep_parses_on_disk() -> None:
    """Parse results outlive the process: the next run does not parse an unchanged file."""
    from lightrocks.app import parsestore
    from lightrocks.workbench import parsecache

    parsecache.use_store(parsestore.DiskStore())


def _complain(message: str) -> None:
    print(f"lightrocks: {report.printable(message)}", file=sys.stderr)


if __name__ == "__main__":
    sys.exit(main())
