"""``lightrocks sweep``: every combination of parameters and noise levels over seeds, on Dask."""

from __future__ import annotations

import argparse
from importlib.util import find_spec
from pathlib import Path
from typing import Any

from lightrocks.app.commands.common import (
    EXIT_FINDINGS,
    EXIT_OK,
    UsageError,
    command,
    complain,
    existing_paths,
    note,
    run_arguments,
    statechart_file,
)


def _configure_sweep(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser(
        "sweep", help="run every combination of parameters and noise levels over seeds on Dask"
    )
    run_arguments(parser, "fixed parameter value")
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
        "--perception-noise",
        default="0mm,0deg",
        metavar="L,A[;L,A…]",
        help="noise levels to sweep, e.g. '0mm,0deg;2mm,2deg;3mm,3deg'",
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
    parser.add_argument(
        "--resume",
        action="store_true",
        help="run only what a stopped sweep with the same arguments into -o did not finish",
    )


def _arguments(args: argparse.Namespace, model: Path, models: str) -> dict[str, Any]:
    """What decides a sweep's runs (not where they run): a resumed sweep must match them.
    ``models`` names the generated code, a digest of every model the run loads."""
    robot = {"robot": args.robot} if args.robot is not None else {}
    return {
        "model": str(model),
        "models": models,
        "path": [str(p.resolve()) for p in existing_paths(args.path)],
        "adapter": args.adapter,
        "param": args.param,
        "success": args.success,
        "grid": args.grid,
        "perception_noise": args.perception_noise,
        "seed": args.seed,
        "seeds": args.seeds,
        **robot,
    }


@command(_configure_sweep)
def cmd_sweep(args: argparse.Namespace) -> int:
    from lightrocks.app import display, pipeline, sweep, sweeplog, values
    from lightrocks.app.errors import ModelError, RunError, SceneError
    from lightrocks.app.robots import choose
    from lightrocks.app.specs import run_spec
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
        robot = choose(args.robot) if args.robot is not None else None
        cls = pipeline.load(model, search_path, robot)
        points = sweep.grid_points(grid, noises)
        specs = [  # every value is parsed and checked before the first run starts
            run_spec(
                cls,
                model,
                search_path,
                [*args.param, *point.params],
                args.adapter,
                seed=args.seed,
                noise=point.noise,
                success=args.success,
                robot=robot,
            )
            for point in points
        ]
        wanted = specs[0].success  # the same outcome at every point
        arguments = _arguments(args, model, cls.__module__.partition(".")[0])
        finished = sweeplog.finished_runs(output, arguments, note) if args.resume else {}
        journal = sweeplog.Journal(output, arguments, points, finished)
        seeds = range(args.seed, args.seed + args.seeds)
        try:
            results = _run(args, cls.NAME, points, specs, seeds, journal)
        except KeyboardInterrupt:
            _keep_finished(cls.NAME, wanted, points, seeds, journal, output)
            raise
    except ModelError as error:
        print(error)
        return EXIT_FINDINGS
    except SceneError as error:
        complain(str(error))
        return EXIT_FINDINGS
    except (RunError, GenerationError) as error:
        raise UsageError(str(error)) from None
    summaries = sweep.summarize(points, results, len(seeds))
    _write(output, sweep.result_files(cls.NAME, summaries, results))
    display.show_sweep(cls.NAME, wanted, sweep.point_rows(summaries), str(output))
    faults = list(dict.fromkeys(r.scene_fault for _, r in results if r.scene_fault))
    for fault in faults:
        complain(fault)
    return EXIT_FINDINGS if faults else EXIT_OK


def _run(
    args: argparse.Namespace,
    name: str,
    points: list[Any],
    specs: list[Any],
    seeds: range,
    journal: Any,
) -> list[tuple[Any, Any]]:
    """Every run not finished before, each journaled as it finishes."""
    from lightrocks.app import display, sweep

    def finished(point: Any, result: Any) -> None:
        journal.add(point, result)
        advance(result.success)

    try:
        with (
            display.progress_bar(name, len(points) * len(seeds)) as advance,
            sweep.dask_client(args.scheduler, args.workers) as client,
        ):
            for result in journal.done.values():
                advance(result.success)
            return sweep.sweep(
                client, points, specs, seeds, done=finished, finished=dict(journal.done)
            )
    finally:
        journal.close()


def _keep_finished(
    name: str, wanted: str | None, points: list[Any], seeds: range, journal: Any, output: Path
) -> None:
    """After Ctrl-C: the tables of the runs that finished, marked incomplete, and how to go
    on; nothing when no run finished."""
    from lightrocks.app import display, sweep

    if not journal.done:
        return
    index = {i: point for i, point in enumerate(points)}
    results = [
        (index[i], journal.done[i, s]) for i in index for s in seeds if (i, s) in journal.done
    ]
    summaries = sweep.summarize(points, results, len(seeds))
    _write(output, sweep.result_files(name, summaries, results))
    display.show_sweep(name, wanted, sweep.point_rows(summaries), str(output))
    note(
        f"the sweep is incomplete: {len(results)} of {len(points) * len(seeds)} runs; "
        "the same command with --resume runs the others"
    )


def _write(output: Path, files: dict[str, str | bytes]) -> None:
    from lightrocks.workbench.files import write_tree

    write_tree(output, files)
