"""One diagram per chart level: what a level shows, as plain data for a layout.

A level is the content of a statechart or of one of its composite states: its own states,
regions, pseudostates, start and end conditions and transitions. A child that is an
``<<import>>`` instance or a composite is one box naming the level it opens (its *drill*
key), so no level nests another and a layout never meets edges across nested clusters. An
action's level shows its ``do`` command and its end conditions as labelled exits.

Node ids are the paths the trace uses below the level's owner (``Snap``, ``Arm/Snap``), so a
page maps an active state to the box that shows it; ids of decorations (initial dots, final
bullseyes, the ``do`` box) carry a ``#`` that no state path has.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from lightrocks.generators.graphviz.labels import (
    WIDTH,
    action_lines,
    heading,
    state_lines,
    transition_label,
    wrap,
)
from lightrocks.generators.selection import is_action, reachable
from lightrocks.languages.lightrocks.model import Component, Region, StateInfo
from lightrocks.metamodel import ast, printer


@dataclass
class Node:
    id: str
    lines: list[str]
    kind: str
    """``state``, ``start``, ``end``, ``initial``, ``final``, ``choice``, ``history`` or ``do``."""
    region: str = ""
    """The compartment (orthogonal region) the node is drawn in; '' for the level itself."""
    drill: str = ""
    """The key of the level this box opens; '' when it opens none."""
    xlabel: str = ""


@dataclass
class Edge:
    source: str
    target: str
    label: str = ""
    kind: str = "transition"
    """``transition`` (a breakpoint can be set on it), ``marker`` or ``exit``."""
    head: str = ""
    """``H`` or ``H*`` where the transition enters its target's history."""


@dataclass
class Level:
    key: str
    """``pkg.Chart`` for a statechart, ``pkg.Chart/State`` (region names included) for a
    composite state in it."""
    title: str
    layer: str
    nodes: list[Node] = field(default_factory=list)
    edges: list[Edge] = field(default_factory=list)
    regions: list[str] = field(default_factory=list)
    """The orthogonal regions drawn as dashed compartments, in declaration order."""
    notes: list[str] = field(default_factory=list)
    """Lines under the title: the level's entry, exit and internal transitions."""

    @property
    def drills(self) -> dict[str, str]:
        """Node id -> the key of the level it opens."""
        return {n.id: n.drill for n in self.nodes if n.drill}


def all_levels(top: Component) -> dict[str, Level]:
    """Every level of ``top`` and of the statecharts it imports, at any depth, by key."""
    found: dict[str, Level] = {}
    for component in reachable(top):
        for level in chart_levels(component):
            found[level.key] = level
    return found


def chart_levels(component: Component) -> list[Level]:
    """The levels of one statechart: its own and one per composite state inside it."""
    title = heading(component.statechart.stereotypes, component.name)
    layer = component.layer or ""
    if is_action(component):
        return [_action(component, title, layer)]
    return _levels(component.region, component.qualified_name, title, layer)


def _action(component: Component, title: str, layer: str) -> Level:
    """The ``do`` box between the start conditions and one labelled exit per end condition."""
    region = component.region
    level = Level(component.qualified_name, title, layer)
    lines = [line for a in region.actions if a.kind == "do" for line in action_lines(a, 44)]
    level.nodes.append(Node("#do", lines or ["do"], "do"))
    level.notes = [line for a in region.actions if a.kind != "do" for line in action_lines(a)]
    for condition in region.start_conditions:
        level.nodes.append(Node(condition.name, [], "start", xlabel=_condition(condition)))
        level.edges.append(Edge(condition.name, "#do", kind="marker"))
    for condition in region.end_conditions:
        level.nodes.append(Node(condition.name, [], "end"))
        guard = f"[{printer.expression(condition.expression)}]" if condition.expression else ""
        level.edges.append(Edge("#do", condition.name, wrap([condition.name, guard]), "exit"))
    budget = ast.stereotype(component.statechart.stereotypes, "timeout")
    if budget is not None and budget.value:
        level.nodes.append(Node("#timeout", [], "end"))
        label = f"timeout: after({budget.value})"
        level.edges.append(Edge("#do", "#timeout", label, "exit"))
    return level


def _condition(condition: ast.Condition) -> str:
    if condition.expression is None:
        return condition.name
    return wrap([condition.name, f"[{printer.expression(condition.expression)}]"])


def is_composite(info: StateInfo) -> bool:
    """A state with states or pseudostates of its own (a body of internal transitions and
    actions only is drawn inside its box)."""
    region = info.region
    return region is not None and bool(region.states or region.pseudostates)


def _levels(region: Region, key: str, title: str, layer: str) -> list[Level]:
    """The level of ``region`` and one per composite state inside it."""
    level = Level(key, title, layer)
    level.notes = [line for a in region.actions for line in action_lines(a)]
    level.notes += [transition_label(t) for t in region.internal]
    _conditions(level, region, "", "")
    nested: list[Level] = []
    if region.orthogonal:
        for name, info in region.states.items():
            if info.region is None:
                continue
            level.regions.append(name)
            nested += _region(level, info.region, key, f"{name}/", name)
    else:
        nested += _region(level, region, key, "", "")
    level.edges = merged(level.edges)
    return [level, *nested]


def _conditions(level: Level, region: Region, prefix: str, compartment: str) -> None:
    for condition in region.conditions.values():
        kind = condition.kind
        text = _condition(condition) if kind == "start" else condition.name
        node = Node(prefix + condition.name, [], kind, compartment, xlabel=text)
        level.nodes.append(node)


def _region(level: Level, region: Region, key: str, prefix: str, compartment: str) -> list[Level]:
    """Draw ``region`` into ``level`` with ids under ``prefix``; the levels of its
    composite states."""
    nested: list[Level] = []
    if compartment:
        _conditions(level, region, prefix, compartment)
    for name, info in region.states.items():
        node_id = prefix + name
        drill = ""
        if info.imported is not None:
            drill = info.imported.qualified_name
        elif is_composite(info):
            drill = f"{key}/{node_id}"
            title = heading(info.state.stereotypes, name)
            nested += _levels(info.region, drill, title, "")
        lines = state_lines(info)
        level.nodes.append(Node(node_id, lines, "state", compartment, drill))
        if info.state.is_initial:
            level.nodes.append(Node(f"{node_id}#initial", [], "initial", compartment))
            level.edges.append(Edge(f"{node_id}#initial", node_id, kind="marker"))
        if info.state.is_final:
            level.nodes.append(Node(f"{node_id}#final", [], "final", compartment))
            level.edges.append(Edge(node_id, f"{node_id}#final", kind="marker"))
    for name, pseudostate in region.pseudostates.items():
        kind = "choice" if pseudostate.kind == "choice" else "history"
        text = {"history": "H", "deep history": "H*"}.get(pseudostate.kind, "")
        level.nodes.append(Node(prefix + name, [text] if text else [], kind, compartment))
    known = {n.id for n in level.nodes}
    for transition in region.transitions:
        source = _resolve(transition.source, prefix, known)
        target = _resolve(transition.target, prefix, known)
        if not source or not target:
            continue
        head = _history(region, transition)
        level.edges.append(Edge(source, target, transition_label(transition), head=head))
    return nested


def merged(edges: list[Edge]) -> list[Edge]:
    """One arrow per source and target: parallel transitions become one arrow with a label
    per transition (UML's list of triggers), so their labels never overlap; a breakpoint
    names a source and a target, so it is the same for all of them."""
    arrows: dict[tuple[str, str, str, str], Edge] = {}
    for edge in edges:
        key = (edge.source, edge.target, edge.kind, edge.head)
        first = arrows.setdefault(key, Edge(*key[:2], "", edge.kind, edge.head))
        labels = [t for t in (first.label, edge.label) if t]
        joined = ", ".join(labels)
        fits = "\n" not in joined and len(joined) <= WIDTH
        first.label = joined if fits else "\n".join(_listed(labels))
    return list(arrows.values())


def _listed(labels: list[str]) -> list[str]:
    """Each label but the last ends with a comma (an action's own semicolon does)."""
    return [t if t.endswith(";") or i == len(labels) - 1 else t + "," for i, t in enumerate(labels)]


def _resolve(name: str, prefix: str, known: set[str]) -> str:
    """The node a transition's end names: in its own region, else in the level itself."""
    for candidate in (prefix + name, name):
        if candidate in known:
            return candidate
    return ""


def _history(region: Region, transition: ast.Transition) -> str:
    if not transition.target_history:
        return ""
    target = region.states.get(transition.target)
    inner = target.region if target is not None else None
    pseudostate = inner.pseudostates.get(transition.target_history) if inner else None
    deep = pseudostate is not None and pseudostate.kind == "deep history"
    return "H*" if deep else "H"
