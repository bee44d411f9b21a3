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
        "--option",
        action="append",
        default=[],
        metavar="NAME=VALUE",
        help="generator option (see 'list generators')",
    )


@command(_configure_generate)
def cmd_generate(args: argparse.Namespace) -> int:
    from lightrocks.app import pipeline
    from lightrocks.app.errors import ModelError
    from lightrocks.app.specs import generate_spec
    from lightrocks.workbench.generators import (
        GenerationError,
        OptionError,
        TemplateProblem,
        write_all,
    )

    try:
        spec = generate_spec(
            existing_paths(args.models),
            existing_paths(args.path),
            args.target,
            dict(option(o) for o in args.option),
            existing_paths([args.templates])[0] if args.templates else None,
        )
    except OptionError as error:  # the user's option, not the command line's form
        print(f"lightrocks: error: {report.printable(str(error))}", file=sys.stderr)
        return EXIT_FINDINGS
    except GenerationError as error:
        raise UsageError(str(error)) from None
    try:
        written = write_all(Path(args.output), pipeline.generate(spec))
    except ModelError as error:
        print(error)  # the findings, already neutralised by report.text
        return EXIT_FINDINGS
    except TemplateProblem as error:
        raise UsageError(str(error)) from None
    except GenerationError as error:
        print(f"lightrocks: error: {report.printable(str(error))}", file=sys.stderr)
        return EXIT_FINDINGS
    print(f"{len(written)} file(s) written to {report.printable(args.output)}")
    return EXIT_OK
