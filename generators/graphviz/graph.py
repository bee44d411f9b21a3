"""The picture of a statechart as plain data (clusters, nodes, edges), ready for a template."""

from __future__ import annotations

from dataclasses import dataclass, field

from lightrocks.languages.lightrocks.model import Component, Region, StateInfo
from lightrocks.metamodel import ast, printer


def quote(text: str) -> str:
    """A DOT string literal: every identifier and label goes through here."""
    escaped = text.replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n")
    return f'"{escaped}"'


def stereotypes(items: tuple[ast.Stereotype, ...]) -> str:
    return printer.stereotypes(items).strip() if items else ""


@dataclass
class Node:
    id: str
    label: str
    shape: str = "box"
    style: str = "rounded"
    peripheries: int = 1


@dataclass
class Edge:
    source: str
    target: str
    label: str = ""
    tail: str = ""  # cluster the edge leaves (compound edge)
    head: str = ""  # cluster the edge enters


@dataclass
class Cluster:
    id: str
    label: str
    nodes: list[Node] = field(default_factory=list)
    clusters: list[Cluster] = field(default_factory=list)
    anchor: str = ""  # a node inside, for edges to and from the cluster
    style: str = ""  # "dashed" for an orthogonal region, a compartment of its state


@dataclass
class Graph:
    name: str
    root: Cluster
    edges: list[Edge]

    @staticmethod
    def of(component: Component, depth: int) -> Graph:
        builder = _Builder(depth)
        label = f"{stereotypes(component.statechart.stereotypes)} {component.name}".strip()
        root = builder.region(component.region, component.name, label, depth)
        return Graph(component.qualified_name, root, builder.edges)


class _Builder:
    def __init__(self, depth: int) -> None:
        self.depth = depth
        self.edges: list[Edge] = []

    def region(self, region: Region, path: str, label: str, depth: int) -> Cluster:
        cluster = Cluster(quote(f"cluster_{path}"), label)
        ends: dict[str, str] = {}
        for condition in region.conditions.values():
            node_id = quote(f"{path}/{condition.name}")
            text = condition.name
            if condition.expression is not None:
                text += f" [{printer.expression(condition.expression)}]"
            rings = 1 if condition.kind == "start" else 2  # an end condition is a bullseye
            label = f"{condition.kind}: {text}"
            cluster.nodes.append(Node(node_id, label, "point", "filled", peripheries=rings))
            ends[condition.name] = node_id
        members: dict[str, tuple[str, str]] = {}
        for name, info in region.states.items():
            members[name] = self.state(cluster, info, f"{path}/{name}", depth)
            if info.state.is_initial:
                marker = quote(f"{path}/{name}/initial")
                cluster.nodes.append(Node(marker, "", "point", "filled"))
                anchor, inner = members[name]
                self.edges.append(Edge(marker, anchor, head=inner))
        for name, pseudostate in region.pseudostates.items():
            node_id = quote(f"{path}/{name}")
            if pseudostate.kind == "choice":
                cluster.nodes.append(Node(node_id, "", "diamond", "solid"))
            else:
                label = "H*" if pseudostate.kind == "deep history" else "H"
                cluster.nodes.append(Node(node_id, label, "circle", "solid"))
            ends[name] = node_id
        for transition in region.transitions:
            source, tail = members.get(transition.source, (ends.get(transition.source, ""), ""))
            target, head = members.get(transition.target, (ends.get(transition.target, ""), ""))
            if transition.target_history and head:  # into the history node inside the cluster
                target, head = quote(f"{path}/{transition.target}/{transition.target_history}"), ""
            if source and target:
                self.edges.append(Edge(source, target, _label(transition), tail, head))
        if region.orthogonal:
            for compartment in cluster.clusters:
                compartment.style = "dashed"
        first = cluster.nodes or [Node(quote(f"{path}/empty"), "", "point", "invis")]
        cluster.nodes = first
        cluster.anchor = first[0].id
        return cluster

    def state(self, parent: Cluster, info: StateInfo, path: str, depth: int) -> tuple[str, str]:
        """Add the state; answer the node edges attach to and the cluster they clip at."""
        state = info.state
        heading = " ".join(filter(None, [stereotypes(state.stereotypes), state.name]))
        if state.arguments:
            heading += "(" + ", ".join(printer.arguments(state.arguments)) + ")"
        region = info.region
        if region is not None:  # internal transitions are listed under the name, as in UML
            heading += "".join(f"\n{_label(t)}" for t in region.internal)
        if region is None and info.imported is not None and depth > 0:
            region = info.imported.region
            depth -= 1
        if region is None:
            final = 2 if state.is_final else 1
            node = Node(quote(path), heading, peripheries=final)
            parent.nodes.append(node)
            return node.id, ""
        cluster = self.region(region, path, heading, depth)
        parent.clusters.append(cluster)
        return cluster.anchor, cluster.id


def _label(transition: ast.Transition | ast.InternalTransition) -> str:
    arguments = ", ".join(printer.expression(a) for a in transition.stimulus_arguments)
    parts = [transition.stimulus + (f"({arguments})" if arguments else "")]
    if transition.guard is not None:
        parts.append(f"[{printer.expression(transition.guard)}]")
    if transition.action:
        parts.append("/ " + " ".join(" ".join(printer.statement(s)) for s in transition.action))
    return " ".join(p for p in parts if p)
