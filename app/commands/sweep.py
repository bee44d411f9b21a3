"""``lightrocks sweep``: every combination of parameters and noise levels over seeds, on Dask."""

from __future__ import annotations

import argparse
from importlib.util import find_spec
from pathlib import Path

from lightrocks.app.commands.common import (
    EXIT_FINDINGS,
    EXIT_OK,
    UsageError,
    command,
    existing_paths,
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


@command(_configure_sweep)
def cmd_sweep(args: argparse.Namespace) -> int:
    from lightrocks.app import display, pipeline, sweep, values
    from lightrocks.app.errors import ModelError, RunError
    from lightrocks.app.run import success_outcome
    from lightrocks.app.specs import run_spec
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
        cls = pipeline.load(model, search_path)
        wanted = success_outcome(cls, args.success)
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
            )
            for point in points
        ]
        seeds = range(args.seed, args.seed + args.seeds)
        with (
            display.progress_bar(cls.NAME, len(points) * len(seeds)) as advance,
            sweep.dask_client(args.scheduler, args.workers) as client,
        ):
            results = sweep.sweep(
                client, points, specs, seeds, done=lambda _, result: advance(result.success)
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
