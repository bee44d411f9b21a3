"""SCXML (W3C State Chart XML): ``<Name>.scxml`` per selected plain statechart, with a Python
data model as python-statemachine reads it (docs/interchange.md, section SCXML).

The mapping is :mod:`generators.scxml.writer`, on the vocabulary it shares with the reader
(:mod:`languages.scxml.markup`); ``lightrocks convert X.scxml --to lr`` reads SCXML back
(:mod:`languages.scxml.reader`).
"""

from __future__ import annotations

from lightrocks.generators.outputs import chart_stems, distinct
from lightrocks.generators.scxml.chart_tree import Refusal
from lightrocks.generators.scxml.writer import Document, Writer
from lightrocks.generators.selection import selected
from lightrocks.languages.lightrocks.model import Component
from lightrocks.workbench.generators import GenerationError, GenerationRequest


def document(component: Component) -> Document:
    """The SCXML of a plain statechart; a :class:`GenerationError` at the first construct
    the target cannot express (file:line:col), naming how many more there are."""
    chart = component.statechart
    if component.layer is not None or component.base is not None:
        what = f"<<{component.layer}>>" if component.layer else "<<extends>>"
        raise GenerationError(
            f"{chart.position}: the scxml target takes plain statecharts; {component.name} is "
            f"a LightRocks component ({what}), whose children are other charts"
        )
    try:
        return Writer(component.unit, component.budget).document()
    except Refusal as refusal:
        others = len(getattr(refusal, "refusals", [refusal])) - 1
        more = f" ({others} more construct(s) the target cannot express)" if others else ""
        raise GenerationError(f"{refusal.position}: scxml: {refusal.message}{more}") from None


class ScxmlGenerator:
    name = "scxml"
    description = "SCXML (W3C) of plain statecharts, with python-statemachine's Python data model"
    options = ()

    def generate(self, request: GenerationRequest) -> dict[str, str]:
        components = selected(request)
        if not components:
            raise GenerationError("no statechart among the selected models")
        stems = chart_stems(components)
        owners = {f"{stems[c.qualified_name]}.scxml": c for c in components}
        distinct(dict(owners))
        return {name: document(component).text for name, component in owners.items()}


GENERATOR = ScxmlGenerator()
