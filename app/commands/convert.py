"""``lightrocks convert``: a model in another statechart language, or into one.

The conversion is chosen by the suffix of the source file (or ``--from``) and the target
named by ``--to``, among those registered through the ``lightrocks.conversions`` entry
points (:mod:`workbench.conversions`); only the one chosen is imported.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import TYPE_CHECKING

from lightrocks.app.commands.common import (
    EXIT_FINDINGS,
    EXIT_OK,
    UsageError,
    command,
    existing_paths,
)
from lightrocks.workbench import report

if TYPE_CHECKING:
    from lightrocks.workbench.conversions import Convert


def _configure_convert(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser(
        "convert",
        help="convert models between statechart languages (UML/P .sc <-> .lr, …)",
        description="Convert each file; the conversion is chosen by the file's suffix and "
        "--to among the registered ones (see 'list conversions').",
    )
    parser.add_argument("files", nargs="+", help="model files to convert")
    parser.add_argument("--to", required=True, help="target language (see 'list conversions')")
    parser.add_argument(
        "--from",
        dest="source",
        metavar="SUFFIX",
        help="read every file as this language whatever its suffix (e.g. --from sc for a "
        "MontiCore model named .aut)",
    )
    where = parser.add_mutually_exclusive_group()
    where.add_argument("-o", "--output", help="folder to write into (default: beside the file)")
    where.add_argument("--stdout", action="store_true", help="print instead of writing")
    parser.add_argument("--force", action="store_true", help="replace files that exist")


def _conversion(suffix: str, target: str) -> Convert:
    from lightrocks.workbench.conversions import ConversionError, load_conversion

    try:
        return load_conversion(suffix, target).convert
    except ConversionError as error:
        raise UsageError(str(error)) from None


@command(_configure_convert)
def cmd_convert(args: argparse.Namespace) -> int:
    from lightrocks.metamodel.ast import Position
    from lightrocks.metamodel.grammar import SyntaxProblem
    from lightrocks.workbench.diagnostics import Diagnostic, Severity
    from lightrocks.workbench.files import write_atomic

    files = existing_paths(args.files)
    folders = [str(f) for f in files if f.is_dir()]
    if folders:
        raise UsageError(f"convert takes files, not folders: {', '.join(folders)}")
    output = Path(args.output) if args.output else None
    if output is not None and not output.is_dir():
        raise UsageError(f"--output: no such folder: {args.output}")
    source = f".{args.source.lstrip('.')}" if args.source else None
    conversions = [(file, _conversion(source or file.suffix, args.to)) for file in files]
    findings: list[Diagnostic] = []
    written: list[tuple[Path, str]] = []
    for file, convert in conversions:
        shown = str(file)
        try:
            text = file.read_text(encoding="utf-8")
            result = convert(file, text, shown)
        except SyntaxProblem as problem:
            where = Position(shown, problem.line, problem.column)
            findings.append(Diagnostic.at(where, "LR0001", Severity.ERROR, problem.message))
            continue
        except UnicodeDecodeError:
            where = Position(shown, 1, 1)
            findings.append(Diagnostic.at(where, "LR0002", Severity.ERROR, "not a text file"))
            continue
        findings += result.findings
        if result.text is None:
            continue
        target = (output or file.parent) / result.name
        if not args.stdout and target.exists() and not args.force:
            message = f"{target} exists; --force replaces it"
            findings.append(Diagnostic.at(Position(shown, 1, 1), "LR0004", Severity.ERROR, message))
            continue
        written.append((target, result.text))
    failed = any(f.severity is Severity.ERROR for f in findings)
    if findings:
        print(report.text(sorted(set(findings))), file=sys.stderr if args.stdout else sys.stdout)
    if failed:
        return EXIT_FINDINGS
    for target, text in written:
        if args.stdout:
            sys.stdout.write(text)
        else:
            write_atomic(target, text)
            print(f"wrote {report.printable(str(target))}")
    return EXIT_OK
