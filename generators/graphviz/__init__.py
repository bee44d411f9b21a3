"""Graphviz DOT pictures of statecharts: one ``.dot`` per selected statechart.

Options: ``depth=N`` also draws the content of imported statecharts N levels deep (as
clusters); ``render=svg|png`` runs the ``dot`` program next to each ``.dot`` file.
"""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

from generators.graphviz.graph import Graph, quote
from generators.selection import selected
from workbench.generators import GenerationError, GenerationRequest, template_environment

TEMPLATES = Path(__file__).parent / "templates"
FORMATS = ("svg", "png")


def render(dot: str, fmt: str) -> bytes:
    """The picture of ``dot`` drawn by Graphviz."""
    program = shutil.which("dot")
    if program is None:
        raise GenerationError(
            "render needs the Graphviz 'dot' program, which is not installed "
            "(Debian/Ubuntu: apt-get install graphviz; macOS: brew install graphviz)"
        )
    result = subprocess.run(
        [program, f"-T{fmt}"], input=dot.encode(), capture_output=True, check=False
    )
    if result.returncode != 0:
        raise GenerationError(f"dot failed: {result.stderr.decode(errors='replace').strip()}")
    return result.stdout


class DotGenerator:
    name = "dot"
    description = "Graphviz DOT of statecharts (options depth=N, render=svg|png)"

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
        files: dict[str, str | bytes] = {}
        for component in selected(request):
            graph = Graph.of(component, int(depth_text))
            text = template.render(graph=graph)
            files[f"{component.qualified_name}.dot"] = text
            if fmt:
                files[f"{component.qualified_name}.{fmt}"] = render(text, fmt)
        if not files:
            raise GenerationError("no statechart among the selected models")
        return files


GENERATOR = DotGenerator()
