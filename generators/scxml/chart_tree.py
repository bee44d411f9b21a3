"""A plain LightRocks statechart as a tree of :class:`Node` s, the shape the SCXML writer
walks: every state, region, final state, end condition, choice and history with its
transitions, actions and invariants gathered in one place.

Building the tree is also where the constructs SCXML has no place for (a ``do`` action, a
start condition, a component's stereotypes …) are refused, each at its position.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from dataclasses import dataclass, field

from lightrocks.languages.lightrocks.model import COMPONENT_STEREOTYPES
from lightrocks.metamodel import ast


class Refusal(Exception):
    """A construct the SCXML target cannot express."""

    def __init__(self, position: ast.Position, message: str) -> None:
        super().__init__(f"{position}: {message}")
        self.position = position
        self.message = message


@dataclass(eq=False)
class Node:
    """A state, region, final state, end condition, choice or history of the chart."""

    kind: str  # chart | state | region | final | end | choice | history
    name: str
    path: tuple[str, ...]
    position: ast.Position
    parent: Node | None = None
    state: ast.State | None = None
    children: dict[str, Node] = field(default_factory=dict)
    regions: list[Node] = field(default_factory=list)
    transitions: list[ast.Transition] = field(default_factory=list)
    internal: list[ast.InternalTransition] = field(default_factory=list)
    entry: list[ast.Statement] = field(default_factory=list)
    exit: list[ast.Statement] = field(default_factory=list)
    invariants: list[ast.Expression] = field(default_factory=list)
    initial: str | None = None
    deep: bool = False
    stereotypes: tuple[ast.Stereotype, ...] = ()

    @property
    def composite(self) -> bool:
        return any(c.kind in ("state", "final", "end", "choice") for c in self.children.values())

    def finals(self) -> list[Node]:
        return [c for c in self.children.values() if c.kind in ("final", "end")]

    def leaving(self) -> list[ast.Transition]:
        """The transitions whose source is this node, in declaration order."""
        if self.parent is None or self.kind == "region":
            return []
        return [t for t in self.parent.transitions if t.source == self.name]

    def completes(self) -> bool:
        if self.regions:
            return all(r.finals() for r in self.regions)
        return bool(self.finals())

    def outcomes(self) -> dict[str, Node]:
        """Outcome -> the final state (or end condition) that ends this node with it."""
        if self.regions:
            return {f.name: f for f in self.regions[0].finals() if f.kind == "final"}
        ends = [f for f in self.finals() if f.kind == "end"]
        finals = [f for f in self.finals() if f.kind == "final"]
        return {f.name: f for f in ends + finals}

    def descendants(self) -> Iterator[Node]:
        for child in [*self.regions, *self.children.values()]:
            yield child
            yield from child.descendants()


class ChartBuilder:
    """Builds the tree of a chart, collecting what it refuses in ``refusals``."""

    def __init__(self, refusals: list[Refusal]) -> None:
        self.refusals = refusals

    def refuse(self, position: ast.Position, message: str) -> None:
        self.refusals.append(Refusal(position, message))

    def chart(self, chart: ast.Statechart) -> Node:
        node = Node("chart", chart.name, (chart.name,), chart.position)
        self.body(node, chart.elements)
        return node

    def body(self, node: Node, elements: Sequence[object]) -> None:
        for element in elements:
            match element:
                case ast.ParameterBlock() | ast.EventBlock() if node.kind == "chart":
                    pass
                case ast.State():
                    self.state(node, element)
                case ast.Pseudostate(kind=kind, name=name):
                    child = Node(
                        "choice" if kind == "choice" else "history",
                        name,
                        (*node.path, name),
                        element.position,
                        node,
                    )
                    child.deep = kind == "deep history"
                    node.children[name] = child
                case ast.Transition():
                    node.transitions.append(element)
                case ast.InternalTransition():
                    node.internal.append(element)
                case ast.Action(kind="do"):
                    self.refuse(
                        element.position,
                        "a 'do' action: SCXML has no activity that runs while a state is "
                        "active (a plain statechart's 'do' calls no device command either)",
                    )
                case ast.Action(kind=kind, statements=statements):
                    (node.entry if kind == "entry" else node.exit).extend(statements)
                case ast.Invariant(expression=expression):
                    node.invariants.append(expression)
                case ast.Region(name=name, elements=inner):
                    region = Node("region", name, (*node.path, name), element.position, node)
                    self.body(region, inner)
                    node.regions.append(region)
                case ast.Condition(kind="start"):
                    self.refuse(
                        element.position,
                        "a start condition: SCXML enters a state at its initial state only "
                        "(an <initial> transition has no condition)",
                    )
                case ast.Condition(kind="end", name=name, expression=expression):
                    if expression is not None:
                        self.refuse(
                            element.position,
                            "an end condition with a condition: SCXML has no condition that "
                            "ends a state by itself holding",
                        )
                    end = Node("end", name, (*node.path, name), element.position, node)
                    node.children[name] = end
                case _:
                    self.refuse(
                        getattr(element, "position", node.position),
                        f"'{type(element).__name__}' (syntax of a language extension) has no "
                        "mapping to SCXML",
                    )
        if node.kind == "region" and (node.internal or node.entry or node.exit):
            self.refuse(node.position, "a region's own actions or internal transitions")
        if node.regions and any(c.kind in ("final", "end") for c in node.children.values()):
            end = next(c for c in node.children.values() if c.kind in ("final", "end"))
            self.refuse(
                end.position,
                "an end condition beside regions: SCXML's <parallel> holds no <final>",
            )

    def state(self, parent: Node, state: ast.State) -> None:
        final = "final" in state.modifiers
        node = Node(
            "final" if final else "state",
            state.name,
            (*parent.path, state.name),
            state.position,
            parent,
            state,
        )
        for stereotype in state.stereotypes:
            if stereotype.name in COMPONENT_STEREOTYPES:
                self.refuse(
                    stereotype.position,
                    f"<<{stereotype.name}>>: a LightRocks component, not a plain statechart; "
                    "SCXML has no instance of another chart",
                )
        node.stereotypes = tuple(
            s for s in state.stereotypes if s.name not in COMPONENT_STEREOTYPES
        )
        if state.arguments:
            self.refuse(state.arguments[0].position, "arguments of a state (<<import>>)")
        if state.invariant is not None:
            node.invariants.append(state.invariant)
        self.body(node, state.body or ())
        if final and (node.children or node.regions or node.transitions or node.internal):
            self.refuse(state.position, "a final state with states, regions or transitions")
        if "initial" in state.modifiers:
            parent.initial = state.name
        parent.children[state.name] = node


def may_fail(node: Node) -> bool:
    """Whether a child of ``node`` may end with error (over-approximated)."""
    for inner in node.descendants():
        if inner.kind == "choice" or inner.invariants or inner.completes():
            return True
        if any(t.postcondition is not None for t in inner.transitions):
            return True
    return any(t.postcondition is not None for t in node.transitions)
