"""Graphviz DOT pictures of statecharts: one ``.dot`` per selected statechart.

Options: ``depth=N`` also draws the content of imported statecharts N levels deep (as
clusters); ``render=svg|png`` draws each ``.dot`` file beside it (see ``rendering``).
``levels=yes`` draws one picture per chart level instead (see ``levels``): for each selected
statechart ``<stem>/levels.json`` and, per level of it and of what it imports, a ``.dot``
and an ``.svg`` that is drawn even where Graphviz fails (see ``drawing``).
"""

from __future__ import annotations

import json
import os
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

from lightrocks.generators.graphviz.drawing import draw, level_template
from lightrocks.generators.graphviz.graph import Graph, quote
from lightrocks.generators.graphviz.levels import all_levels
from lightrocks.generators.graphviz.rendering import FORMATS, render, renderer
from lightrocks.generators.outputs import chart_stems, distinct, shortened
from lightrocks.generators.selection import selected
from lightrocks.languages.lightrocks.model import Component
from lightrocks.workbench.generators import (
    GenerationError,
    GenerationRequest,
    one_of,
    template_environment,
    whole_number,
)

TEMPLATES = Path(__file__).parent / "templates"

DEPTH = whole_number("depth", 0, "also draw the content of imported statecharts N levels deep")
RENDER = one_of("render", FORMATS, "also draw each .dot file as a picture beside it")
LEVELS = one_of("levels", ("yes",), "one picture per chart level, with levels.json")


class DotGenerator:
    name = "dot"
    options = (DEPTH, RENDER, LEVELS)

    @property
    def description(self) -> str:
        found = renderer()
        drawn = f"rendered by {found}" if found else "no renderer installed"
        return f"Graphviz DOT of statecharts ({drawn})"

    def generate(self, request: GenerationRequest) -> dict[str, str | bytes]:
        depth, fmt, levels = request.value(DEPTH), request.value(RENDER), request.value(LEVELS)
        environment = template_environment(TEMPLATES, request.templates)
        environment.globals["quote"] = quote
        template = environment.get_template("statechart.dot.jinja")
        components = selected(request)
        if not components:
            raise GenerationError("no statechart among the selected models")
        stems = chart_stems(components, qualified=True)
        if levels:
            return _levels(components, stems, request)
        suffixes = ["dot", *([fmt] if fmt else [])]
        distinct({f"{stems[c.qualified_name]}.{s}": c for c in components for s in suffixes})
        files: dict[str, str | bytes] = {}
        for component in components:
            stem = stems[component.qualified_name]
            text = template.render(graph=Graph.of(component, depth))
            files[f"{stem}.dot"] = text
            if fmt:
                files[f"{stem}.{fmt}"] = render(text, fmt)
        return files


def _levels(
    components: list[Component], stems: dict[str, str], request: GenerationRequest
) -> dict[str, str | bytes]:
    """Per selected chart: every level it shows, drawn, and the index of them. A level that
    several charts show is drawn once; levels are drawn side by side, each waiting on a
    renderer process of its own."""
    template = level_template(request.templates)
    charts = {c.qualified_name: all_levels(c) for c in components}
    unique = {key: level for levels in charts.values() for key, level in levels.items()}
    with ThreadPoolExecutor(max_workers=os.cpu_count() or 2) as pool:
        drawn = pool.map(lambda level: draw(level, template), unique.values())
        drawings = dict(zip(unique, drawn, strict=True))
    files: dict[str, str | bytes] = {}
    owners: dict[str, Component | None] = {}
    for component in components:
        stem = stems[component.qualified_name]
        index = []
        for key, level in charts[component.qualified_name].items():
            name = "/".join(shortened(part) for part in key.split("/"))
            drawing = drawings[key]
            files[f"{stem}/{name}.dot"] = drawing.dot
            files[f"{stem}/{name}.svg"] = drawing.svg
            owners.update({f"{stem}/{name}.dot": component, f"{stem}/{name}.svg": component})
            entry = {"key": key, "title": level.title, "layer": level.layer}
            entry.update(file=f"{name}.svg", layout=drawing.how, drills=level.drills)
            index.append(entry)
        document = {"root": component.qualified_name, "levels": index}
        files[f"{stem}/levels.json"] = json.dumps(document, indent=1, ensure_ascii=False)
        owners[f"{stem}/levels.json"] = component
    distinct(owners)
    return files


GENERATOR = DotGenerator()
