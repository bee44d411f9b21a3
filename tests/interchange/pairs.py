"""A checked plain chart generated twice: to Python, on the LightRocks runtime, and to SCXML."""

from __future__ import annotations

from pathlib import Path

from lightrocks.app.loading import component_class, generated_package
from lightrocks.generators.scxml import document
from lightrocks.generators.scxml.writer import Document
from lightrocks.languages.lightrocks.analysis import analysis
from lightrocks.workbench.check import CheckContext


def generated(context: CheckContext, file: Path, name: str, cache: Path) -> tuple[type, Document]:
    """The runtime class and the SCXML document of the chart ``name`` of a checked model."""
    component = analysis(context).models.component(name)
    assert component is not None, name
    package = generated_package(context, [file], cache)
    return component_class(package, name), document(component)
