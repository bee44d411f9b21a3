"""``lightrocks convert``: a model in another statechart language, or into one.

Each conversion lives in a module of its own and is found here by the suffix of the source
file and the target named by ``--to`` (:data:`CONVERSIONS`). A conversion is a function
``(path, text, shown) -> result`` where ``result`` has ``name`` (the file name to write),
``text`` (the converted text, ``None`` when an error refuses the conversion) and
``findings`` (``workbench.diagnostics.Diagnostic`` items); it raises
``metamodel.grammar.SyntaxProblem`` for a source that does not parse. To add one, add a
line to :data:`CONVERSIONS`.
"""

from __future__ import annotations

import argparse
import importlib
import sys
from pathlib import Path

from lightrocks.app.commands.common import (
    EXIT_FINDINGS,
    EXIT_OK,
    UsageError,
    command,
    existing_paths,
)
from lightrocks.workbench import report

CONVERSIONS: dict[tuple[str, str], str] = {
    (".sc", "lr"): "lightrocks.languages.umlp.interchange:convert_sc_to_lr",
    (".lr", "sc"): "lightrocks.languages.umlp.interchange:convert_lr_to_sc",
    (".scxml", "lr"): "lightrocks.generators.scxml.reader:convert_scxml_to_lr",
}
"""(source suffix, target) -> ``module:function`` of the conversion."""


def _targets() -> list[str]:
    return sorted({target for _, target in CONVERSIONS})


def _configure_convert(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser(
        "convert",
        help="convert models between statechart languages (UML/P .sc <-> .lr, …)",
        description="Convert each file; the conversion is chosen by the file's suffix and "
        "--to. Known: "
        + ", ".join(f"{source} -> .{target}" for source, target in sorted(CONVERSIONS)),
    )
    parser.add_argument("files", nargs="+", help="model files to convert")
    parser.add_argument("--to", required=True, help=f"target language: {', '.join(_targets())}")
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


def _conversion(suffix: str, target: str):
    key = (suffix, target.lstrip("."))
    if key not in CONVERSIONS:
        known = ", ".join(f"{s} -> .{t}" for s, t in sorted(CONVERSIONS))
        raise UsageError(
            f"no conversion from {suffix or 'a file without suffix'} to .{key[1]}; known: {known}"
        )
    module, _, function = CONVERSIONS[key].partition(":")
    return getattr(importlib.import_module(module), function)


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
