"""Graphviz DOT pictures of statecharts: one ``.dot`` per selected statechart.

Options: ``depth=N`` also draws the content of imported statecharts N levels deep (as
clusters); ``render=svg|png`` draws each ``.dot`` file beside it (see ``rendering``).
"""

from __future__ import annotations

from pathlib import Path

from lightrocks.generators.graphviz.graph import Graph, quote
from lightrocks.generators.graphviz.rendering import FORMATS, render, renderer
from lightrocks.generators.outputs import chart_stems, distinct
from lightrocks.generators.selection import selected
from lightrocks.workbench.generators import GenerationError, GenerationRequest, template_environment

TEMPLATES = Path(__file__).parent / "templates"


class DotGenerator:
    name = "dot"

    @property
    def description(self) -> str:
        found = renderer()
        drawn = f"rendered by {found}" if found else "no renderer installed"
        return f"Graphviz DOT of statecharts (options depth=N, render=svg|png; {drawn})"

    def generate(self, request: GenerationRequest) -> dict[str, str | bytes]:
        depth_text = request.options.get("depth", "0")
        if not depth_text.isdigit():
            raise GenerationError(f"option depth='{depth_text}' is not a whole number >= 0")
        fmt = request.options.get("render", "")
        if fmt and fmt not in FORMATS:
            raise GenerationError(f"option render='{fmt}': choose one of {', '.join(FORMATS)}")
        environment = template_environment(TEMPLATES, request.templates)
        environment.globals["quote"] = quote
        template = environment.get_template("statechart.dot.jinja")
        components = selected(request)
        if not components:
            raise GenerationError("no statechart among the selected models")
        stems = chart_stems(components, qualified=True)
        suffixes = ["dot", *([fmt] if fmt else [])]
        distinct({f"{stems[c.qualified_name]}.{s}": c for c in components for s in suffixes})
        files: dict[str, str | bytes] = {}
        for component in components:
            stem = stems[component.qualified_name]
            text = template.render(graph=Graph.of(component, int(depth_text)))
            files[f"{stem}.dot"] = text
            if fmt:
                files[f"{stem}.{fmt}"] = render(text, fmt)
        return files


GENERATOR = DotGenerator()
