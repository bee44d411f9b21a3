"""A level is drawn whatever Graphviz does: without its regions' compartments where Graphviz
refuses them, laid out in pure Python where no renderer works; and the nested picture of
``depth=N`` that failed with "trouble in init_rank" renders."""

from __future__ import annotations

import xml.etree.ElementTree as ElementTree

import pytest

import lightrocks.generators.graphviz.drawing as drawing
from diagram.models import EXAMPLES, ROOT, components
from lightrocks.generators.graphviz.levels import all_levels
from lightrocks.generators.graphviz.rendering import render
from lightrocks.workbench.check import check
from lightrocks.workbench.generators import GenerationError, GenerationRequest, load_generator

PLANT = ROOT / "tests" / "generators" / "models"
AHEAD = EXAMPLES / "din_rail_ahead" / "tasks" / "AssembleRailAhead.lr"
SVG = "{http://www.w3.org/2000/svg}"


@pytest.fixture(scope="module")
def crossing():
    component = next(c for c in components(PLANT) if c.qualified_name == "plant.Crossing")
    return all_levels(component)["plant.Crossing/Working"]


def titles(svg: bytes, kind: str) -> list[str]:
    root = ElementTree.fromstring(svg)
    return [
        g.find(f"{SVG}title").text
        for g in root.iter(f"{SVG}g")
        if kind in (g.get("class") or "").split()
    ]


def test_refused_compartments_are_left_out(crossing, monkeypatch) -> None:
    def refuse_clusters(dot: str, fmt: str) -> bytes:
        if "subgraph" in dot:
            raise GenerationError("graphviz-pure failed: Error: trouble in init_rank")
        return render(dot, fmt)

    monkeypatch.setattr(drawing, "render", refuse_clusters)
    drawn = drawing.draw(crossing, drawing.level_template())
    assert drawn.how.endswith("without regions")
    assert "Walker/Wait" in titles(drawn.svg, "node")


def test_without_any_renderer_the_grid_draws_the_level(crossing, monkeypatch) -> None:
    def missing(dot: str, fmt: str) -> bytes:
        raise GenerationError("render needs the Graphviz 'dot' program or 'graphviz-pure'")

    monkeypatch.setattr(drawing, "render", missing)
    drawn = drawing.draw(crossing, drawing.level_template())
    assert drawn.how == "grid" and drawn.dot == ""
    assert set(titles(drawn.svg, "node")) == {n.id for n in crossing.nodes}
    assert titles(drawn.svg, "region") == ["cluster_Traffic", "cluster_Walker"]
    assert titles(drawn.svg, "frame") == ["plant.Crossing/Working"]
    assert "Traffic/Red-&gt;Traffic/Green" in drawn.svg.decode()


def test_the_grid_draws_every_example_level(monkeypatch) -> None:
    monkeypatch.setattr(
        drawing, "render", lambda dot, fmt: (_ for _ in ()).throw(GenerationError())
    )
    template = drawing.level_template()
    for component in components(EXAMPLES):
        for key, level in all_levels(component).items():
            drawn = drawing.draw(level, template)
            assert set(titles(drawn.svg, "node")) == {n.id for n in level.nodes}, key


@pytest.mark.parametrize("depth", ["2", "3"])
def test_the_nested_picture_with_loops_two_levels_down_renders(depth: str) -> None:
    context = check([AHEAD], [EXAMPLES])
    request = GenerationRequest(context, [AHEAD.resolve()], {"depth": depth, "render": "svg"})
    files = load_generator("dot").generate(request)
    assert files["din_rail_ahead.tasks.AssembleRailAhead.svg"].startswith(b"<?xml")
