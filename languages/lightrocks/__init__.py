"""The LightRocks language: action components as UML/P statecharts (``.lr``)."""

from __future__ import annotations

from typing import Any

from lightrocks.languages.lightrocks.cocos import COCOS, PASSES
from lightrocks.languages.lightrocks.syntax import parse_statechart
from lightrocks.metamodel import ast
from lightrocks.workbench.languages import Language


def _declarations(unit: ast.StatechartUnit) -> list[tuple[str, Any]]:
    return [(unit.statechart.name, unit.statechart)]


def _format(text: str, file: str) -> str:
    from lightrocks.languages.lightrocks.printer import format_statechart_text

    return format_statechart_text(text, file)


LANGUAGE = Language(
    name="lightrocks",
    extensions=(".lr",),
    parse=parse_statechart,
    format=_format,
    declarations=_declarations,
    cocos=COCOS,
    passes=PASSES,
    description="tasks, skills and elemental actions as UML/P statecharts",
)
