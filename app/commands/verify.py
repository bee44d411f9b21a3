"""``lightrocks verify``: ``check``, then the model checker over the outcome flow of every task
and skill; each refuted property with the run that shows it, and that run as a dry-run script
(``--counterexamples DIR``) to watch with ``run --adapter dryrun --script FILE --monitor``."""

from __future__ import annotations

import argparse
from pathlib import Path

from lightrocks.app.commands.common import (
    EXIT_FINDINGS,
    EXIT_OK,
    UsageError,
    all_cocos,
    command,
    existing_paths,
    keep_parses_on_disk,
    path_option,
)
from lightrocks.workbench import report


def _configure_verify(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser(
        "verify", help="check, then prove or refute what every task and skill can reach"
    )
    parser.add_argument("paths", nargs="+", help="model files or folders")
    path_option(parser)
    parser.add_argument("--format", choices=sorted(report.FORMATS), default="text")
    parser.add_argument(
        "--strict", action="store_true", help="warnings fail the verification too (exit 1)"
    )
    parser.add_argument(
        "--max-configurations",
        type=_positive,
        default=None,
        metavar="N",
        help="explore at most N configurations of each statechart (default 200,000)",
    )
    parser.add_argument(
        "--counterexamples",
        metavar="DIR",
        help="write each refuted property's run as a dry-run script (--script) into DIR",
    )


def _script_name(taken: dict[str, str], stem: str) -> str:
    """``stem.dryrun.json``, numbered from 2 where two findings share chart, code and line."""
    name, number = f"{stem}.dryrun.json", 1
    while name in taken:
        number += 1
        name = f"{stem}-{number}.dryrun.json"
    return name


def _positive(text: str) -> int:
    if not text.isdigit() or int(text) == 0:
        raise argparse.ArgumentTypeError(f"{text!r} is not a positive whole number")
    return int(text)


@command(_configure_verify)
def cmd_verify(args: argparse.Namespace) -> int:
    from lightrocks.languages.lightrocks.behaviour.script import describe, script_text
    from lightrocks.languages.lightrocks.behaviour.verify import verify
    from lightrocks.workbench.files import write_tree

    paths, model_path = existing_paths(args.paths), existing_paths(args.path)
    folder = Path(args.counterexamples) if args.counterexamples else None
    if folder is not None and folder.exists() and not folder.is_dir():
        raise UsageError(f"--counterexamples {folder} is not a folder")
    keep_parses_on_disk()
    limit = {"max_configurations": args.max_configurations} if args.max_configurations else {}
    result = verify(paths, model_path, strict=args.strict, **limit)
    output = report.render(args.format, result.diagnostics, all_cocos)
    if output:
        print(output)
    scripts: dict[str, str] = {}
    for finding, counterexample in result.counterexamples:
        name = _script_name(scripts, f"{counterexample.chart}-{finding.code}-{finding.line}")
        scripts[name] = script_text(counterexample)
        if args.format == "text":
            print(
                f"\n{report.printable(finding.code)} in {report.printable(counterexample.chart)}:"
            )
            for line in describe(counterexample):
                print(f"  {report.printable(line)}")
            if folder is not None:
                print(f"  script: {report.printable(str(folder / name))}")
    if folder is not None and scripts:
        write_tree(folder, scripts)
    return EXIT_FINDINGS if result.failed else EXIT_OK
