"""Properties of the outcome flow, proved or refuted on the explored configurations.

The configurations reachable from a statechart's start are explored breadth first into a
networkx graph (the control part is finite; tracked values are bounded by the guards that
read them, or forgotten). On that graph:

- LR0701: a run can end with the success outcome (the first end condition);
- LR0702: no reachable configuration is a trap, from which no declared end is reachable;
- LR0703: every cycle is broken by a value that changes on it (a counter moving toward its
  bound leaves the cycle in the graph's past; one past the window of exact values must move
  one way on every round and pass a bound on that side), else it is a possible endless
  retry, reported at the transition whose guard reads a value nothing on the loop moves.

Every refutation carries the path that shows it, shortest first.
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass, field
from itertools import pairwise

import networkx as nx

from lightrocks.languages.lightrocks.access import access
from lightrocks.languages.lightrocks.behaviour.flow import Flow, Step
from lightrocks.languages.lightrocks.behaviour.store import BOUNDED, MOVED
from lightrocks.metamodel import ast

MAX_CONFIGURATIONS = 200_000
RAISE_LIMIT = (
    "raise the limit with lightrocks verify --max-configurations N, or bound what its "
    "guards count with a declared range or a guard on the loop"
)
START = ("START",)


@dataclass(frozen=True)
class Counterexample:
    """A run of ``chart``: ``steps`` from its start, then ``loop`` repeated (for an endless
    retry); ``end`` is the outcome the run ends with ('' when it does not end)."""

    chart: str
    steps: tuple[Step, ...]
    loop: tuple[Step, ...] = ()
    end: str = ""


@dataclass(frozen=True)
class Refutation:
    code: str
    position: ast.Position
    message: str
    hint: str
    counterexample: Counterexample | None


@dataclass
class Exploration:
    graph: nx.DiGraph
    configurations: list[tuple]
    complete: bool
    limit: int = MAX_CONFIGURATIONS  # the configurations it was allowed
    endings: dict[int, list[tuple[Step, str, tuple]]] = field(default_factory=dict)
    """The steps from a configuration that end the run: the step, the outcome and the store
    after it (the graph's end nodes keep no store)."""

    def tree(self, node: object) -> tuple:
        return ("START",) if node == START else self.configurations[node][0]


def explore(flow: Flow, limit: int = MAX_CONFIGURATIONS) -> Exploration:
    """Every configuration reachable from the start, breadth first, up to ``limit`` of them;
    a configuration is a graph node by its number (hashing the nested configuration once)."""
    graph = nx.DiGraph()
    graph.add_node(START)
    endings: dict[int, list[tuple[Step, str, tuple]]] = {}
    numbers: dict[tuple, int] = {}
    configurations: list[tuple] = []
    pending: deque[int] = deque()

    def number(configuration: tuple) -> tuple[int, bool]:
        known = numbers.get(configuration)
        if known is not None:
            return known, False
        numbers[configuration] = len(configurations)
        configurations.append(configuration)
        return len(configurations) - 1, True

    for tree, store in flow.initial():
        node, _ = number((tree, store))
        graph.add_edge(START, node, step=Step((), "", "start"))
        pending.append(node)
    while pending:
        if len(configurations) > limit:
            return Exploration(graph, configurations, False, limit, endings)
        node = pending.popleft()
        tree, store = configurations[node]
        if tree[0] == "END":
            continue
        for step, after, kept in flow.successors(tree, store):
            if after[0] == "END":
                endings.setdefault(node, []).append((step, after[1], kept))
            target, new = number((after, () if after[0] == "END" else kept))
            if new:
                pending.append(target)
            if not graph.has_edge(node, target):
                graph.add_edge(node, target, step=step)
    return Exploration(graph, configurations, True, limit, endings)


def refute(flow: Flow, exploration: Exploration, loops: bool) -> list[Refutation]:
    """The properties of the chart at the root of ``flow`` that the exploration refutes."""
    graph = exploration.graph
    root = flow.root
    ends = [c.name for c in root.region.end_conditions] or [
        n for n, i in root.region.states.items() if i.state.is_final
    ]
    if not ends:
        return []
    tree = exploration.tree
    terminals = {n for n in graph if tree(n)[0] == "END"}
    declared = {n for n in terminals if tree(n)[1] in ends}
    found = []
    success = [n for n in declared if tree(n)[1] == ends[0]]
    if not success and exploration.complete:
        shown = _path(graph, sorted(declared) or sorted(terminals))
        end = tree(shown[-1])[1] if shown else ""
        found.append(
            Refutation(
                "LR0701",
                root.statechart.position,
                f"no run of '{root.name}' ends with '{ends[0]}'"
                + (f": the closest runs end with '{end}'" if end else ""),
                "check the guards and outcomes on the way to it",
                _counterexample(root.qualified_name, graph, shown, end),
            )
        )
    good = set(declared)
    for node in declared:
        good |= nx.ancestors(graph, node)
    traps = [n for n in graph if n != START and n not in good and n not in terminals]
    if traps and exploration.complete:
        path = _path(graph, traps)
        trap = path[-1]
        ends_there = {tree(n)[1] for n in nx.descendants(graph, trap) if n in terminals}
        fate = "can only end with 'error'" if ends_there else "never ends"
        step = graph.edges[path[-2], path[-1]]["step"]
        where = "/".join(step.where) or root.name
        found.append(
            Refutation(
                "LR0702",
                _position(step, root),
                f"after {where} ({step.stimulus}), '{root.name}' {fate}: no declared end "
                "is reachable from there",
                "handle the outcomes that lead there, or add a way out",
                _counterexample(root.qualified_name, graph, path, "error" if ends_there else ""),
            )
        )
    if loops:
        attributes = {path.partition(".")[2] for path, _ in flow.initial_store()}
        found += _endless(root, graph, terminals, attributes)
    return found


def _endless(root, graph: nx.DiGraph, terminals: set, attributes: set[str]) -> list[Refutation]:
    """One finding per set of states that can repeat forever: the loop reached first, at
    the transition that closes it (the one back to the state reached earliest)."""
    inner = graph.subgraph(n for n in graph if n != START and n not in terminals)
    distance = nx.single_source_shortest_path_length(graph, START)
    loops = []
    for component in nx.strongly_connected_components(inner):
        some = min(component, key=lambda n: distance[n])
        if len(component) == 1 and not inner.has_edge(some, some):
            continue
        if _leaves(inner.subgraph(component)):
            continue
        cycle = nx.find_cycle(inner.subgraph(component), some)
        loops.append((distance[some], some, cycle))
    found = []
    shown: set[frozenset] = set()
    for _, head, cycle in sorted(loops, key=lambda loop: loop[:2]):
        steps = [inner.edges[u, v]["step"] for u, v in cycle]
        states = frozenset("/".join(s.where) for s in steps)
        if states in shown:
            continue
        shown.add(states)
        back = min(cycle, key=lambda edge: (distance[edge[1]], distance[edge[0]]))
        closing = inner.edges[back]["step"]
        names = " -> ".join(dict.fromkeys("/".join(s.where) for s in steps))
        path = _counterexample(root.qualified_name, graph, _path(graph, [head]), "")
        guarded = _unmoved_guard(steps, attributes)
        if guarded is None:
            where, why = _position(closing, root), "no counter on the way moves toward a bound"
        else:
            transition, read = guarded
            where = transition.position  # the transition that should move it
            why = f"its guard reads '{read}', which nothing on the loop moves toward its bound"
        found.append(
            Refutation(
                "LR0703",
                where,
                f"possible endless retry in '{root.name}': {names} can repeat forever, {why}",
                "count the attempts in an attribute and guard the retry with a bound",
                Counterexample(path.chart, path.steps, tuple(steps)),
            )
        )
    return found


def _leaves(component: nx.DiGraph) -> bool:
    """Some counter past the window must leave the strongly connected ``component``: no step
    in it moves the counter the other way, every round raises (or lowers) it, and every
    round passes a guard or its range that bounds it on that side."""
    marked = [(u, v, dict(step.marks)) for u, v, step in component.edges(data="step")]
    sides = {(p[1:], m) for _, _, marks in marked for p, m in marks.items() if p[0] == MOVED}
    for path, sign in sides:
        if sign == 0 or any(marks.get(MOVED + path, sign) != sign for *_, marks in marked):
            continue
        rising = [(u, v) for u, v, marks in marked if marks.get(MOVED + path) == sign]
        bounding = [(u, v) for u, v, marks in marked if marks.get(BOUNDED + path) == sign]
        if _acyclic_without(component, rising) and _acyclic_without(component, bounding):
            return True
    return False


def _acyclic_without(component: nx.DiGraph, edges: list) -> bool:
    rest = nx.DiGraph(component.edges)
    rest.remove_edges_from(edges)
    return nx.is_directed_acyclic_graph(rest)


def _unmoved_guard(steps: list[Step], attributes: set[str]) -> tuple[ast.Transition, str] | None:
    """A transition fired on the loop whose guard reads an attribute of a scene object that
    the loop never assigns: where the value that should bound the loop is read."""
    written = set()
    for step in steps:
        for transition in step.fired:
            written |= access(transition.action).writes
    for step in steps:
        for transition in step.fired:
            if transition.guard is None:
                continue
            reads = access(transition.guard).reads
            unmoved = sorted(
                r for r in reads if r.partition(".")[2] in attributes and r not in written
            )
            if unmoved:
                return transition, unmoved[0]
    return None


def _path(graph: nx.DiGraph, targets: list) -> list:
    """The shortest path from the start to any of ``targets``."""
    lengths, paths = nx.single_source_dijkstra(graph, START)
    reachable = [t for t in targets if t in lengths]
    if not reachable:
        return []
    best = min(reachable, key=lambda t: (lengths[t], str(t)))
    return paths[best]


def _counterexample(chart: str, graph: nx.DiGraph, path: list, end: str) -> Counterexample:
    steps = tuple(graph.edges[u, v]["step"] for u, v in pairwise(path))
    return Counterexample(chart, tuple(s for s in steps if s.stimulus != "start"), (), end)


def _position(step: Step, root) -> ast.Position:
    """Where the transition the step fired on its outermost level is written (it leaves
    the outermost state that acted), else the chart."""
    for name in step.where:
        for transition in step.fired:
            if transition.source == name:
                return transition.position
    return step.fired[-1].position if step.fired else root.statechart.position
