"""The findings of ``check`` placed on the diagram: each on the level and the element (box
or arrow) it is about, so that a click on it opens that level and shows the element.

A finding is about the element of its file that starts last before it: a transition's
guard, a state's argument and a condition's expression all lie inside their element.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from lightrocks.metamodel import ast
from lightrocks.workbench.diagnostics import Diagnostic


@dataclass(frozen=True)
class Place:
    line: int
    column: int
    level: str
    """The key of the level the element is drawn on."""
    element: str
    """The element's id there (``Arm/Snap``), ``source->target`` for an arrow, '' for the
    level itself."""


def places(qualified: str, unit: ast.StatechartUnit) -> list[Place]:
    """Where each element of the chart starts, in the order of the file."""
    chart = unit.statechart
    found = [Place(chart.position.line, chart.position.column, qualified, "")]
    found += _within(chart.elements, qualified, "")
    return sorted(found, key=lambda p: (p.line, p.column))


def _within(elements: tuple, level: str, prefix: str) -> Iterator[Place]:
    """``prefix`` names the compartment of an orthogonal state's region (``Arm/``)."""
    for element in elements:
        where = element.position
        if isinstance(element, ast.Region):
            yield Place(where.line, where.column, level, f"{prefix}{element.name}")
            yield from _within(element.elements, level, f"{prefix}{element.name}/")
        elif isinstance(element, ast.State):
            yield Place(where.line, where.column, level, prefix + element.name)
            inner = element.body or ()
            if any(isinstance(e, (ast.State, ast.Pseudostate, ast.Region)) for e in inner):
                yield from _within(inner, f"{level}/{prefix}{element.name}", "")
        elif isinstance(element, ast.Transition):
            arrow = f"{prefix}{element.source}->{prefix}{element.target}"
            yield Place(where.line, where.column, level, arrow)
        elif isinstance(element, (ast.Condition, ast.Pseudostate)):
            yield Place(where.line, where.column, level, prefix + element.name)


def placed(diagnostics: list[Diagnostic], file: Path, marks: list[Place]) -> list[dict[str, Any]]:
    """The findings in ``file`` as the page shows them, each with its level and element."""
    result = []
    for finding in diagnostics:
        if Path(finding.file).resolve() != file:
            continue
        before = [p for p in marks if (p.line, p.column) <= (finding.line, finding.column)]
        place = before[-1] if before else marks[0]
        result.append(
            {
                "line": finding.line,
                "column": finding.column,
                "severity": finding.severity.value,
                "code": finding.code,
                "message": finding.message,
                "hint": finding.hint,
                "level": place.level,
                "element": place.element,
            }
        )
    return result
