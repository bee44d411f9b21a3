"""The LightRocks language: action components as UML/P statecharts (``.lr``)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from lightrocks.workbench.cocos import Deferred
from lightrocks.workbench.languages import Language

if TYPE_CHECKING:
    from lightrocks.metamodel import ast


def _declarations(unit: ast.StatechartUnit) -> list[tuple[str, Any]]:
    return [(unit.statechart.name, unit.statechart)]


def _parse(text: str, file: str) -> ast.StatechartUnit:
    """Parsed on first use: every command reads the registered languages' descriptors, only
    some parse (an unchanged re-check answers from the findings cache)."""
    from lightrocks.languages.lightrocks.syntax import parse_statechart

    return parse_statechart(text, file)


def _format(text: str, file: str) -> str:
    from lightrocks.languages.lightrocks.printer import format_statechart_text

    return format_statechart_text(text, file)


def _cocos() -> tuple:
    from lightrocks.languages.lightrocks.cocos import COCOS

    return COCOS


def _passes() -> tuple:
    from lightrocks.languages.lightrocks.cocos import PASSES

    return PASSES


LANGUAGE = Language(
    name="lightrocks",
    extensions=(".lr",),
    parse=_parse,
    format=_format,
    declarations=_declarations,
    cocos=Deferred(_cocos),
    passes=Deferred(_passes),
    description="tasks, skills and elemental actions as UML/P statecharts",
)
