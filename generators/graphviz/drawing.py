"""Laying out a level so that it always gets drawn.

Graphviz lays a level out top-down and left-to-right; the one that shows its text larger in
the page's diagram panel wins. Where Graphviz refuses a level (its classic ranking of
clusters fails on some graphs with "trouble in init_rank"; ``newrank`` avoids the known
cases), the level is drawn again without its regions' compartments, and where no renderer
works at all, :mod:`grid` lays it out in pure Python. The drawing says which way it took.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import jinja2

from lightrocks.generators.graphviz import grid
from lightrocks.generators.graphviz.graph import quote
from lightrocks.generators.graphviz.levels import Level
from lightrocks.generators.graphviz.rendering import render
from lightrocks.workbench.generators import GenerationError, template_environment

TEMPLATES = Path(__file__).parent / "templates"
PANEL = (860.0, 680.0)
"""CSS pixels of the pages' diagram panel in a 1280 x 800 window: a level is laid out in the
direction that shows it larger there."""
ORIENTATIONS = ("TB", "LR")


@dataclass(frozen=True)
class Drawing:
    dot: str
    """The DOT the picture was drawn from ('' for the grid)."""
    svg: bytes
    how: str
    """``graphviz TB``, ``graphviz LR``, ``graphviz TB without regions`` or ``grid``."""


def dot_lines(items: Sequence[str], end: str = "\\n", left: Sequence[str] = ()) -> str:
    """A DOT label of lines: ``items`` ended by ``end`` (``\\n`` centres, ``\\l`` aligns
    left), then ``left`` aligned left."""

    def escaped(text: str, terminator: str) -> str:
        text = text.replace("\\", "\\\\").replace('"', '\\"')
        return text.replace("\n", terminator) + terminator

    body = "".join(escaped(i, end) for i in items) + "".join(escaped(t, "\\l") for t in left)
    return f'"{body}"'


def level_template(templates: Path | None = None) -> jinja2.Template:
    environment = template_environment(TEMPLATES, templates)
    environment.globals.update(quote=quote, lines=dot_lines)
    return environment.get_template("level.dot.jinja")


def draw(level: Level, template: jinja2.Template) -> Drawing:
    """The level as SVG; never fails."""
    for clusters in (True, False) if level.regions else (True,):
        drawings = []
        for rankdir in ORIENTATIONS:
            dot = template.render(level=level, rankdir=rankdir, clusters=clusters)
            try:
                svg = render(dot, "svg")
            except GenerationError:
                continue
            how = f"graphviz {rankdir}" + ("" if clusters else " without regions")
            drawings.append((scale(svg), Drawing(dot, svg, how)))
        if drawings:
            return max(drawings, key=lambda d: d[0])[1]
    return Drawing("", grid.svg(level).encode(), "grid")


def scale(svg: bytes) -> float:
    """How much the panel shrinks (< 1) or could enlarge the picture to fit it."""
    width, height = size(svg)
    return min(PANEL[0] / width, PANEL[1] / height)


def size(svg: bytes) -> tuple[float, float]:
    """The picture's width and height in CSS pixels (Graphviz writes points)."""
    found = re.search(rb'<svg width="([\d.]+)(pt|px)?" height="([\d.]+)(pt|px)?"', svg)
    if found is None:
        return PANEL
    factor = 4 / 3 if found.group(2) == b"pt" else 1.0
    return float(found.group(1)) * factor, float(found.group(3)) * factor
