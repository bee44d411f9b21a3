"""``lightrocks check``: every finding of the models, in the chosen format; exit 1 on errors."""

from __future__ import annotations

import argparse

from lightrocks.app.commands.common import (
    EXIT_FINDINGS,
    EXIT_OK,
    all_cocos,
    command,
    existing_paths,
    keep_parses_on_disk,
    path_option,
)
from lightrocks.workbench import checkcache, report
from lightrocks.workbench.diagnostics import Severity


def _configure_check(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser("check", help="check models and report every finding")
    parser.add_argument("paths", nargs="+", help="model files or folders")
    path_option(parser)
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
    output = report.render(args.format, found, all_cocos)
    if output:
        print(output)
    errors = any(d.severity is Severity.ERROR for d in found)
    warned = any(d.severity is Severity.WARNING for d in found)
    return EXIT_FINDINGS if errors or (args.strict and warned) else EXIT_OK
