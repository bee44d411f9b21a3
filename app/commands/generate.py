"""``lightrocks generate``: checked models through a generator into an output folder."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from lightrocks.app.commands.common import (
    EXIT_FINDINGS,
    EXIT_OK,
    UsageError,
    command,
    existing_paths,
    option,
    path_option,
)
from lightrocks.workbench import report


def _configure_generate(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser("generate", help="generate code or pictures from checked models")
    parser.add_argument("models", nargs="+", help="model files or folders")
    parser.add_argument("--target", required=True, help="generator name (see 'list generators')")
    parser.add_argument(
        "-o", "--output", required=True, help="output folder (created when missing)"
    )
    path_option(parser)
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
    options = dict(option(o) for o in args.option)
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
