"""Ecore/XMI: ``lightrocks.ecore`` and one ``<qualified name>.xmi`` per selected statechart."""

from __future__ import annotations

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

    def generate(self, request: GenerationRequest) -> dict[str, str]:
        files = {"lightrocks.ecore": metamodel_text()}
        for component in selected(request):
            refuse_extensions("Ecore", component.unit)
            name = f"{component.qualified_name}.xmi"
            files[name] = model_text(component.unit, name)
        if len(files) == 1:
            raise GenerationError("no statechart among the selected models")
        return files


GENERATOR = EcoreGenerator()
