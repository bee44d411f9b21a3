"""Ecore/XMI: ``lightrocks.ecore`` and one ``<qualified name>.xmi`` per selected statechart
(shortened where too long for a file name, see ``generators.outputs``)."""

from __future__ import annotations

from lightrocks.generators.outputs import chart_stems, distinct
from lightrocks.generators.selection import selected
from lightrocks.metamodel.ecore import metamodel_text, model_text
from lightrocks.workbench.generators import (
    GenerationError,
    GenerationRequest,
    refuse_extensions,
)


class EcoreGenerator:
    name = "ecore"
    description = "the Ecore metamodel (lightrocks.ecore) and each statechart as XMI"
    options = ()

    def generate(self, request: GenerationRequest) -> dict[str, str]:
        components = selected(request)
        if not components:
            raise GenerationError("no statechart among the selected models")
        stems = chart_stems(components, qualified=True)
        owners = {f"{stems[c.qualified_name]}.xmi": c for c in components}
        distinct({"lightrocks.ecore": None, **owners})
        files = {"lightrocks.ecore": metamodel_text()}
        for name, component in owners.items():
            refuse_extensions("Ecore", component.unit)
            files[name] = model_text(component.unit, name)
        return files


GENERATOR = EcoreGenerator()
