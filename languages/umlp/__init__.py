"""UML/P statecharts as MontiCore writes them (``.sc``), registered through the
``lightrocks.languages`` entry point like any language a separate package adds.

The language reads MontiCore's ``UMLStatecharts`` (with the Java expressions and statements
of actions and guards), prints it back, and checks MontiCore's 14 context conditions
(:mod:`languages.umlp.cocos`). Its charts declare no symbols of the workbench: a ``.sc``
chart and the ``.lr`` chart converted from it may live side by side
(:mod:`languages.umlp.interchange`).
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from lightrocks.workbench.cocos import Deferred, cocos_in
from lightrocks.workbench.diagnostics import Diagnostics
from lightrocks.workbench.languages import Language

if TYPE_CHECKING:
    from lightrocks.languages.umlp.nodes import SCArtifact


def _cocos() -> tuple:
    from lightrocks.languages.umlp import cocos

    return cocos_in(cocos)


def _declarations(unit: SCArtifact) -> list[tuple[str, Any]]:
    return []


def _parse(text: str, file: str) -> SCArtifact:
    """Parsed on first use, as the LightRocks language does (see its ``_parse``)."""
    from lightrocks.languages.umlp.syntax import parse_sc

    return parse_sc(text, file)


def _format(text: str, file: str) -> str:
    from lightrocks.languages.umlp.printer import format_sc_text

    return format_sc_text(text, file)


LANGUAGE = Language(
    name="umlp",
    extensions=(".sc", ".aut"),  # .aut: MontiCore's former suffix, read with LR2106
    parse=_parse,
    format=_format,
    declarations=_declarations,
    cocos=Deferred(_cocos),
    description="UML/P statecharts as MontiCore writes them (UMLStatecharts)",
)


@dataclass
class _Loaded:
    path: Path
    unit: SCArtifact


@dataclass
class _Units:
    units: list[_Loaded]

    def checked_units(self) -> list[_Loaded]:
        return self.units


@dataclass
class SCCheck:
    """What the CoCos of this language see: the parsed files, whatever their suffix."""

    workspace: _Units
    diagnostics: Diagnostics
    units: dict[Path, SCArtifact] = field(default_factory=dict)


def check_sc(files: Iterable[Path], shown: Sequence[str] | None = None) -> SCCheck:
    """Parse each file as a UML/P statechart, whatever its suffix (as MontiCore's parser
    takes any file it is given; SCFileExtension, LR2106, then warns), and run the CoCos of
    this language. ``shown`` names the files in findings (default: as given)."""
    from lightrocks.languages.umlp.syntax import parse_sc
    from lightrocks.metamodel.ast import Position
    from lightrocks.metamodel.grammar import SyntaxProblem

    files = list(files)
    names = list(shown) if shown is not None else [str(f) for f in files]
    diagnostics = Diagnostics()
    loaded = []
    units: dict[Path, SCArtifact] = {}
    for file, name in zip(files, names, strict=True):
        try:
            unit = parse_sc(file.read_text(encoding="utf-8"), name)
        except SyntaxProblem as problem:
            where = Position(name, problem.line, problem.column)
            diagnostics.error(where, "LR0001", problem.message)
            continue
        except (OSError, UnicodeDecodeError) as error:
            diagnostics.error(Position(name, 1, 1), "LR0004", f"cannot read file: {error}")
            continue
        loaded.append(_Loaded(file.resolve(), unit))
        units[file] = unit
    context = SCCheck(_Units(loaded), diagnostics, units=units)
    for check in LANGUAGE.cocos:
        diagnostics.extend(check.run(context))
    return context
