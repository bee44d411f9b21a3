"""Context conditions on components as a whole and how they use one another (LR02xx): one
layer stereotype, the layering of tasks, skills and actions, the one command of an action,
no cycle of ``<<import>>`` and ``<<extends>>``, known stereotypes."""

from __future__ import annotations

from collections.abc import Iterator

import networkx as nx

from lightrocks.languages.lightrocks.analysis import analysis
from lightrocks.languages.lightrocks.model import MAY_USE, STEREOTYPES, Region, may_use
from lightrocks.languages.lightrocks.regions import own_regions
from lightrocks.metamodel import ast
from lightrocks.workbench.cocos import coco
from lightrocks.workbench.diagnostics import Severity, did_you_mean

Finding = tuple[ast.Position, str, str]


@coco("LR0201", Severity.ERROR, "a component has exactly one layer stereotype")
def one_layer(context: object) -> Iterator[Finding]:
    for component in analysis(context).models.components:
        layers = component.layers
        if len(layers) > 1:
            yield (layers[1].position, "a statechart has exactly one layer stereotype", "")
        elif not layers and component.base is None and _uses_lightrocks(component.region):
            yield (
                component.statechart.position,
                f"'{component.name}' uses conditions, commands or <<import>> "
                "but has no layer stereotype",
                "add <<task>>, <<skill>> or <<action>>",
            )


def _uses_lightrocks(region: Region) -> bool:
    return bool(
        region.conditions
        or any(a.kind == "do" for a in region.actions)
        or any(s.imported is not None for s in region.states.values())
    )


@coco("LR0202", Severity.ERROR, "layering: tasks use skills, skills use actions or skills")
def layering(context: object) -> Iterator[Finding]:
    for component, region in own_regions(analysis(context)):
        layer = component.layer
        if layer not in MAY_USE:
            continue
        for info in region.states.values():
            child = info.imported.layer if info.imported is not None else None
            if layer == "action":
                yield (info.state.position, "an action has no child states", "")
            elif child is not None and not may_use(layer, child):
                yield (
                    info.state.position,
                    f"a {layer} cannot use the {child} '{info.imported.name}'",
                    f"a {layer} uses {' and '.join(f'{m}s' for m in sorted(MAY_USE[layer]))}",
                )


@coco("LR0203", Severity.ERROR, "an action has exactly one do command")
def action_has_one_command(context: object) -> Iterator[Finding]:
    for component in analysis(context).models.components:
        if component.layer != "action":
            continue
        commands = [s for a in component.region.actions if a.kind == "do" for s in a.statements]
        if len(commands) != 1:
            where = commands[1].position if len(commands) > 1 else component.statechart.position
            yield (
                where,
                f"action '{component.name}' must have exactly one do command, "
                f"found {len(commands)}",
                "",
            )


@coco("LR0204", Severity.ERROR, "a composite has no do command")
def composite_has_no_command(context: object) -> Iterator[Finding]:
    for component, region in own_regions(analysis(context)):
        if component.layer in ("task", "skill") and region.states:
            for action in region.actions:
                if action.kind == "do":
                    yield (action.position, "a composite runs its children, not a command", "")


@coco("LR0210", Severity.ERROR, "no cycle of <<import>> and <<extends>>")
def no_reference_cycle(context: object) -> Iterator[Finding]:
    a = analysis(context)
    graph = nx.DiGraph()
    where: dict[tuple[str, str], ast.Position] = {}
    for source, target, _, position in a.models.references:
        graph.add_edge(source, target)
        where.setdefault((source, target), position)
    for cycle in nx.simple_cycles(graph):
        first = cycle.index(min(cycle))  # start at the smallest name: same report every run
        cycle = cycle[first:] + cycle[:first]
        edge = (cycle[0], cycle[1 % len(cycle)])
        path = " -> ".join([*cycle, cycle[0]])
        yield (where[edge], f"cyclic <<import>>/<<extends>>: {path}", "")


@coco("LR0212", Severity.WARNING, "stereotypes are known")
def known_stereotypes(context: object) -> Iterator[Finding]:
    for component, region in own_regions(analysis(context)):
        stereotypes = list(component.statechart.stereotypes) if region.parent is None else []
        for info in region.states.values():
            stereotypes += info.state.stereotypes
        for stereotype in stereotypes:
            if stereotype.name not in STEREOTYPES:
                yield (
                    stereotype.position,
                    f"unknown stereotype <<{stereotype.name}>>",
                    did_you_mean(stereotype.name, STEREOTYPES),
                )
