"""``lightrocks run``: a statechart generated, bound to an adapter and run, or run over seeds."""

from __future__ import annotations

import argparse

from lightrocks.app.commands.common import (
    EXIT_FINDINGS,
    UsageError,
    command,
    complain,
    existing_paths,
    run_arguments,
    statechart_file,
    trace_file,
)
from lightrocks.app.commands.monitoring import monitor_options, watch_for


def _configure_run(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser("run", help="generate Python for a statechart and run it")
    run_arguments(parser, "parameter value")
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
        "--robot-ip", metavar="ADDRESS", help="the address of a real arm (--adapter franka)"
    )
    parser.add_argument(
        "--confirm", action="store_true", help="ask once before a real arm's first motion"
    )
    parser.add_argument(
        "--script",
        metavar="FILE",
        help="JSON file of scripted outcomes and sensor values for the dry run",
    )
    monitor_options(parser, "a live page of the run")
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


@command(_configure_run)
def cmd_run(args: argparse.Namespace) -> int:
    from lightrocks.app import display, pipeline, values
    from lightrocks.app.errors import ModelError, RunError, SceneError
    from lightrocks.app.robots import choose
    from lightrocks.app.script import read_script
    from lightrocks.app.seeds import run_seeds
    from lightrocks.app.specs import run_spec
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
    if (args.breakpoints or args.paused or args.aborts or args.monitor_public) and not args.monitor:
        raise UsageError("--break, --abort-at, --paused and --monitor-public need --monitor")
    if (args.robot_ip or args.confirm) and args.adapter is None:
        raise UsageError("--robot-ip and --confirm are for a real arm: give --adapter franka")
    if args.robot_ip and args.seeds is not None:
        raise UsageError("a real arm runs one run at a time: leave out --seeds")
    if args.monitor and args.seeds is not None:
        raise UsageError("--monitor watches a single run: leave out --seeds")
    try:
        noise = values.parse_noise(args.perception_noise) if args.perception_noise else (0.0, 0.0)
        robot = choose(args.robot) if args.robot is not None else None
        cls = pipeline.load(model, search_path, robot)
        script = read_script(script_file, cls) if script_file else None
        spec = run_spec(
            cls,
            model,
            search_path,
            args.param,
            args.adapter,
            seed=args.seed,
            noise=noise,
            video=args.video,
            script=script,
            trace=trace,
            events=events,
            success=args.success,
            robot=robot,
            robot_ip=args.robot_ip,
            confirm=args.confirm,
        )
        if args.seeds is not None:
            seeds = range(args.seed, args.seed + args.seeds)
            with display.progress_bar(cls.NAME, len(seeds)) as advance:
                results = run_seeds(
                    spec, seeds, workers=args.workers, done=lambda r: advance(r.success)
                )
            return display.show_seeds(cls.NAME, spec.success, results)
        watch = watch_for(args, model, search_path, cls.NAME) if args.monitor else None
        with display.live_status() as progress:
            result = pipeline.run(spec, cls, progress=progress, watch=watch)
        return display.show(cls.NAME, result)
    except ModelError as error:
        print(error)  # the findings, already neutralised by report.text
        return EXIT_FINDINGS
    except SceneError as error:
        complain(str(error))
        return EXIT_FINDINGS
    except (RunError, GenerationError) as error:
        raise UsageError(str(error)) from None
    except OSError as error:
        raise UsageError(f"cannot write {error.filename or 'output'}: {error.strerror}") from None
