"""``lightrocks fmt``: models rewritten in canonical form, or ``--check`` that they are."""

from __future__ import annotations

import argparse
from pathlib import Path

from lightrocks.app.commands.common import (
    EXIT_FINDINGS,
    EXIT_OK,
    UsageError,
    command,
    existing_paths,
)
from lightrocks.workbench import report


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
    from lightrocks.workbench.depth import deepest
    from lightrocks.workbench.diagnostics import Diagnostics
    from lightrocks.workbench.files import write_atomic
    from lightrocks.workbench.languages import extensions, language_for
    from lightrocks.workbench.modelpath import model_files
    from lightrocks.workbench.reads import TooLarge, size_limit

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
        if file.stat().st_size > size_limit():
            too_large = TooLarge(file.stat().st_size, size_limit())
            diagnostics.error(Position(str(file), 1, 1), "LR0004", str(too_large))
            continue
        try:
            original[file] = file.read_text(encoding="utf-8")
            formatted[file] = language.format(original[file], str(file))
        except SyntaxProblem as problem:
            diagnostics.error(
                Position(str(file), problem.line, problem.column), "LR0001", problem.message
            )
        except RecursionError:
            where, message = deepest(original[file], str(file))
            diagnostics.error(where, "LR0001", message)
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
