"""The ``markdown`` target: one Markdown page per statechart the user names, with its
parameters, outcomes, requirements and a Mermaid state diagram of its top region.

It uses only the public generator API: the request (checked models, named files, options,
template folder), :func:`generators.selection.selected` and the resolved model
(:class:`languages.lightrocks.model.Component`).
"""

from __future__ import annotations

import re
from pathlib import Path

from lightrocks.generators.selection import selected
from lightrocks.languages.lightrocks.model import Component
from lightrocks.metamodel.printer import expression
from lightrocks.workbench.generators import GenerationRequest, template_environment
from lightrocks_peg.requirements.syntax import Requirement

TEMPLATES = Path(__file__).parent / "templates" / "markdown"


def cell(text: str) -> str:
    """Model text inside a Markdown table cell: one line, pipes escaped."""
    return " ".join(text.split()).replace("\\", "\\\\").replace("|", "\\|")


def node(name: str) -> str:
    """A state name as a Mermaid node id (model names are identifiers already)."""
    return re.sub(r"\W", "_", name)


def page(component: Component) -> dict:
    """Everything the page template shows, as plain values."""
    region = component.region
    starts = {c.name for c in region.start_conditions}
    ends = {c.name for c in region.end_conditions}
    edges = []
    for t in region.transitions:
        source = "[*]" if t.source in starts else node(t.source)
        edges.append(
            (source, node(t.target), t.stimulus or (t.source if t.source in starts else ""))
        )
    return {
        "name": component.name,
        "qualified_name": component.qualified_name,
        "layer": component.layer or "statechart",
        "parameters": [
            (p.name, p.type, expression(p.default) if p.default is not None else "")
            for p in region.parameters.values()
        ],
        "outcomes": list(region.outcomes),
        "requirements": [r for r in region.extensions if isinstance(r, Requirement)],
        "states": [node(name) for name in region.states],
        "ends": sorted(node(name) for name in ends),
        "edges": edges,
    }


class MarkdownGenerator:
    name = "markdown"
    description = "Markdown pages with a Mermaid state diagram (lightrocks-peg)"

    def generate(self, request: GenerationRequest) -> dict[str, str]:
        environment = template_environment(TEMPLATES, request.templates)
        environment.filters["cell"] = cell
        template = environment.get_template("page.md.jinja")
        return {
            f"{c.qualified_name.replace('.', '/')}.md": template.render(page=page(c))
            for c in selected(request)
        }


GENERATOR = MarkdownGenerator()
