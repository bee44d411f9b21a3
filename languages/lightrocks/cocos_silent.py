"""Context conditions against silent no-ops: what a model says and the tools quietly ignore.

A name that two wildcard imports both provide resolves to whichever import comes last; a
stereotype written where nothing reads it (``<<timeout>>`` on a skill, ``<<scene>>`` on a
state) and a history or choice pseudostate in an action (which has no child states) change
nothing. Each is an error naming what was meant to happen and did not.
"""

from __future__ import annotations

from collections.abc import Iterator

from lightrocks.languages.lightrocks.analysis import analysis
from lightrocks.languages.lightrocks.model import (
    REFERENCE_STEREOTYPES,
    STEREOTYPES,
    Component,
    takes_effect,
)
from lightrocks.metamodel import ast
from lightrocks.workbench.cocos import coco
from lightrocks.workbench.diagnostics import Severity
from lightrocks.workbench.workspace import Loaded, Workspace

Finding = tuple[ast.Position, str, str]


@coco("LR0112", Severity.ERROR, "no name is provided by two wildcard imports")
def ambiguous_imports(context: object) -> Iterator[Finding]:
    workspace: Workspace = context.workspace
    for loaded in workspace.checked_units():
        if sum(1 for i in loaded.unit.imports if i.wildcard) < 2:
            continue  # one wildcard import (and the explicit ones) cannot be ambiguous
        providers = _wildcard_providers(workspace, loaded)
        if not providers:
            continue
        for name, position in _used_names(loaded.unit):
            found = providers.get(name, [])
            if len(found) < 2:
                continue
            listed = " and ".join(f"import {i.name}.* ({s.node.position.file})" for i, s in found)
            yield (
                position,
                f"'{name}' is ambiguous: {listed} both provide it; the last import wins",
                "import it by its qualified name, or write the qualified name",
            )


def _wildcard_providers(workspace: Workspace, loaded: Loaded) -> dict[str, list]:
    """Simple names that wildcard imports provide, with every import that provides them;
    a name imported by its qualified name is not ambiguous."""
    explicit = {i.name.rpartition(".")[2] for i in loaded.unit.imports if not i.wildcard}
    providers: dict[str, list] = {}
    for imported in loaded.unit.imports:
        if not imported.wildcard:
            continue
        for name, symbol in workspace.load_package(imported.name).items():
            if name not in explicit:
                providers.setdefault(name, []).append((imported, symbol))
    return {n: p for n, p in providers.items() if len({s.qualified_name for _, s in p}) > 1}


def _used_names(unit: object) -> Iterator[tuple[str, ast.Position]]:
    """Simple names a unit refers to: imported and extended statecharts, types."""
    for node in ast.walk(unit):
        if isinstance(node, ast.Stereotype) and node.name in REFERENCE_STEREOTYPES:
            if node.value and "." not in node.value:
                yield node.value, node.position
        elif isinstance(node, ast.Parameter | ast.Sensor | ast.CommandParameter | ast.Field):
            if "." not in node.type:
                yield node.type, node.position
        elif isinstance(node, ast.DeviceInstance) and "." not in node.type:
            yield node.type, node.position


@coco("LR0221", Severity.ERROR, "stereotypes and pseudostates stand where they have an effect")
def stereotype_has_effect(context: object) -> Iterator[Finding]:
    a = analysis(context)
    for loaded in a.workspace.checked_units():
        unit = loaded.unit
        if isinstance(unit, ast.DomainUnit):
            for declaration in unit.declarations:
                kind = "device" if isinstance(declaration, ast.Device) else "cell"
                yield from _misplaced(getattr(declaration, "stereotypes", ()), kind)
            continue
        component = a.models.component(_qualified(unit))
        if component is None:
            continue
        yield from _misplaced(unit.statechart.stereotypes, "statechart", component)
        own = [r for r in component.region.regions() if r.loaded is component.loaded]
        for region in own:
            for info in region.states.values():
                if info.state.position.file == unit.package_position.file:
                    yield from _misplaced(info.state.stereotypes, "state")
        if component.layer == "action":
            pseudostates = [p for region in own for p in region.pseudostates.values()]
            for node in pseudostates:
                if node.position.file == unit.package_position.file:
                    yield (
                        node.position,
                        f"{node.kind} '{node.name}' in an action has no effect: an action "
                        "has no child states to choose or remember",
                        "remove it, or make the statechart a skill",
                    )


def _misplaced(
    stereotypes: tuple[ast.Stereotype, ...], kind: str, component: Component | None = None
) -> Iterator[Finding]:
    for stereotype in stereotypes:
        if stereotype.name not in STEREOTYPES:
            continue  # unknown stereotypes are LR0212's
        if not takes_effect(stereotype.name, kind):
            layer = component.layer if component is not None else None
            where = f"a {layer or kind}"
            yield (
                stereotype.position,
                f"<<{stereotype.name}>> has no effect on {where}",
                STEREOTYPES[stereotype.name].belongs,
            )


def _qualified(unit: ast.StatechartUnit) -> str:
    name = unit.statechart.name
    return f"{unit.package}.{name}" if unit.package else name
