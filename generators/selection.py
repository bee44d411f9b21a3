"""Which components a generation request is about, shared by every target."""

from __future__ import annotations

from lightrocks.languages.lightrocks.analysis import analysis
from lightrocks.languages.lightrocks.model import Component, ModelSet
from lightrocks.workbench.generators import GenerationRequest


def model_set(request: GenerationRequest) -> ModelSet:
    return analysis(request.context).models


def selected(request: GenerationRequest) -> list[Component]:
    """The statecharts of the files the user named, sorted by qualified name."""
    files = {path.resolve() for path in request.files}
    chosen = [c for c in model_set(request).components if c.loaded.path in files]
    return sorted(chosen, key=lambda c: c.qualified_name)


def imported(component: Component) -> list[Component]:
    """Components imported by the states of ``component`` (any depth of regions), no repeats."""
    found: dict[str, Component] = {}
    for region in component.region.regions():
        for info in region.states.values():
            if info.imported is not None:
                found.setdefault(info.imported.qualified_name, info.imported)
    return list(found.values())


def reachable(top: Component) -> list[Component]:
    """``top`` and every component it imports, directly or not, children before parents."""
    order: list[Component] = []
    seen: set[str] = set()

    def visit(component: Component) -> None:
        if component.qualified_name in seen:
            return
        seen.add(component.qualified_name)
        for child in imported(component):
            visit(child)
        order.append(component)

    visit(top)
    return order


def is_action(component: Component) -> bool:
    """An elemental action: no child states, one device command in ``do``."""
    return component.layer == "action" or (
        not component.region.states and any(a.kind == "do" for a in component.region.actions)
    )
