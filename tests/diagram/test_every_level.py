"""Every chart of the examples, the extension's models and the test models is drawn at every
level by Graphviz, without an error and without falling back: nested loops two levels down,
regions, history and choice included. The largest level stays readable at 1280 x 800."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from diagram.models import EXAMPLES, FOLDERS, components
from lightrocks.generators.graphviz.drawing import PANEL, draw, level_template, size
from lightrocks.generators.graphviz.levels import Level, all_levels

SMALLEST = 8.0
"""CSS pixels the smallest text of a level has at least when the whole level is scaled into
the diagram panel of a 1280 x 800 window."""


def levels_under(folder: Path) -> dict[str, Level]:
    found: dict[str, Level] = {}
    for component in components(folder):
        found.update(all_levels(component))
    return found


@pytest.fixture(scope="module", params=FOLDERS, ids=lambda p: str(p.relative_to(EXAMPLES.parent)))
def drawn(request: pytest.FixtureRequest) -> dict[str, tuple[Level, object]]:
    template = level_template()
    return {
        key: (level, draw(level, template)) for key, level in levels_under(request.param).items()
    }


def test_every_level_is_drawn_by_graphviz(drawn) -> None:
    assert drawn
    for key, (level, drawing) in drawn.items():
        assert drawing.how.startswith("graphviz"), (key, drawing.how)
        svg = drawing.svg.decode()
        titles = set(re.findall(r"<title>([^<]*)</title>", svg))
        for node in level.nodes:
            assert escaped(node.id) in titles, (key, node.id)


def test_the_largest_example_level_is_readable_at_1280_by_800() -> None:
    template = level_template()
    smallest = {}
    for key, level in levels_under(EXAMPLES).items():
        svg = draw(level, template).svg
        width, height = size(svg)
        fonts = [float(f) for f in re.findall(rb'font-size="([\d.]+)"', svg)]
        scale = min(PANEL[0] / width, PANEL[1] / height, 1.0)
        smallest[key] = min(fonts) * 4 / 3 * scale
    worst = min(smallest, key=smallest.get)
    assert smallest[worst] >= SMALLEST, f"{worst}: text of {smallest[worst]:.1f} px"


def escaped(text: str) -> str:
    """As Graphviz writes text into SVG."""
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")
