"""What the studio's composition forms write, compared with a shipped chart: the properties
a robot expert states in text (``property name: formula;``) are no part of composing."""

from __future__ import annotations

from dataclasses import replace

from lightrocks.languages.lightrocks.syntax import parse_statechart
from lightrocks.metamodel import ast


def composed_part(text: str) -> ast.Statechart:
    """The statechart of ``text`` without its properties."""
    chart = parse_statechart(text, "x.lr").statechart
    kept = tuple(e for e in chart.elements if not isinstance(e, ast.Property))
    return replace(chart, elements=kept)
