"""Events per second of generated code against three Python statechart libraries.

Three charts, each built once as a neutral tree and then as LightRocks text (run as
generated Python), sismic YAML, a python-statemachine definition and a ``transitions``
hierarchical machine:

- ``flat``: a ring of ``N`` simple states; ``next`` moves one on, ``hop`` half-way round.
- ``ring``: a ring of ``N`` composite states with two sub-states each; ``next`` moves the
  inner state, ``hop`` moves to the next composite (exit and entry of two levels).
- ``deep``: two towers of ``D`` nested composites with two leaves at the bottom; ``next``
  toggles the leaves, ``hop`` leaves one tower for the other (``D + 2`` exits and entries).

Every engine runs the same events (two ``next`` for one ``hop``) in one process, in
interleaved rounds, timed in CPU seconds of the process (a shared machine's other load does
not count); the median rate of each is reported, and every engine must end in the
same leaf state. LightRocks runs twice: with the trace kept in memory (the default) and with
a disabled trace (``Trace(keep=False)``), which is what the other libraries do. The goal:
generated code at least 20x sismic on the ring chart. Needs the ``bench`` extra
(``pip install -e '.[bench]'``).

    .venv/bin/python benchmarks/bench_runtime.py [N] [EVENTS] [ROUNDS] [D]
"""

from __future__ import annotations

import json
import statistics
import sys
import tempfile
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

from sismic.interpreter import Interpreter
from sismic.io import import_from_yaml
from statemachine.io import create_machine_class_from_definition
from transitions.extensions import HierarchicalMachine

from lightrocks.app.loading import component_class, generated_package
from lightrocks.runtime import Trace
from lightrocks.workbench.check import check

GOAL = 20.0
"""Generated code (disabled trace) over sismic on the ring chart."""
BASELINE_SHARE = 4
"""The libraries run a quarter of the events: they are much slower, and a rate is a rate."""


@dataclass
class Node:
    """A state of a neutral chart; a composite when it has children."""

    name: str
    children: list[Node] = field(default_factory=list)
    moves: list[tuple[str, str, str]] = field(default_factory=list)  # source, target, event

    @property
    def initial(self) -> str:
        return self.children[0].name


def flat(n: int) -> Node:
    moves = [(f"S{i}", f"S{(i + 1) % n}", "next") for i in range(n)]
    moves += [(f"S{i}", f"S{(i + n // 2) % n}", "hop") for i in range(n)]
    return Node("Flat", [Node(f"S{i}") for i in range(n)], moves)


def ring(n: int) -> Node:
    def composite(i: int) -> Node:
        a, b = f"A{i}", f"B{i}"
        return Node(f"S{i}", [Node(a), Node(b)], [(a, b, "next"), (b, a, "next")])

    moves = [(f"S{i}", f"S{(i + 1) % n}", "hop") for i in range(n)]
    return Node("Ring", [composite(i) for i in range(n)], moves)


def deep(depth: int) -> Node:
    def tower(t: str) -> Node:
        a, b = f"{t}A", f"{t}B"
        node = Node(f"{t}L{depth}", [Node(a), Node(b)], [(a, b, "next"), (b, a, "next")])
        for level in range(depth - 1, 0, -1):
            node = Node(f"{t}L{level}", [node])
        return node

    return Node("Deep", [tower("T0"), tower("T1")], [("T0L1", "T1L1", "hop"),
                                                     ("T1L1", "T0L1", "hop")])  # fmt: skip


# -- the chart in each engine's terms ------------------------------------------------------


def lightrocks_text(chart: Node) -> str:
    def body(node: Node, indent: str) -> str:
        lines = []
        for k, child in enumerate(node.children):
            initial = "initial " if k == 0 else ""
            if child.children:
                lines.append(f"{indent}{initial}state {child.name} {{")
                lines.append(body(child, indent + "  "))
                lines.append(f"{indent}}}")
            else:
                lines.append(f"{indent}{initial}state {child.name};")
        lines += [f"{indent}{source} -> {target} {event};" for source, target, event in node.moves]
        return "\n".join(lines)

    return f"package bench;\n\nstatechart {chart.name} {{\n{body(chart, '  ')}\n}}\n"


def sismic_yaml(chart: Node) -> str:
    """The chart as sismic's YAML (written as JSON, which YAML includes)."""

    def state(node: Node, moves: list[tuple[str, str, str]]) -> dict:
        found: dict = {"name": node.name}
        leaving = [{"target": t, "event": e} for s, t, e in moves if s == node.name]
        if leaving:
            found["transitions"] = leaving
        if node.children:
            found["initial"] = node.initial
            found["states"] = [state(child, node.moves) for child in node.children]
        return found

    return json.dumps({"statechart": {"name": chart.name, "root state": state(chart, [])}})


def statemachine_class(chart: Node) -> type:
    def states(node: Node) -> dict:
        found = {}
        for k, child in enumerate(node.children):
            definition: dict = {"initial": k == 0}
            on: dict[str, list] = {}
            for source, target, event in node.moves:
                if source == child.name:
                    on.setdefault(event, []).append({"target": target})
            if on:
                definition["on"] = on
            if child.children:
                definition["states"] = states(child)
            found[child.name] = definition
        return found

    return create_machine_class_from_definition(chart.name, states=states(chart))


def transitions_machine(chart: Node) -> HierarchicalMachine:
    def states(node: Node) -> list:
        return [
            {"name": c.name, "children": states(c), "initial": c.initial} if c.children else c.name
            for c in node.children
        ]

    def moves(node: Node, prefix: str) -> list[dict]:
        found = [{"trigger": e, "source": prefix + s, "dest": prefix + t} for s, t, e in node.moves]
        for child in node.children:
            found += moves(child, f"{prefix}{child.name}_")
        return found

    return HierarchicalMachine(
        states=states(chart),
        transitions=moves(chart, ""),
        initial=chart.initial,
        auto_transitions=False,
    )


# -- runs ----------------------------------------------------------------------------------


Started = tuple[Callable[[str], object], Callable[[], str]]
"""A chart just started: how to send it one event, and the name of its active leaf."""
Engine = Callable[[], Started]


def lightrocks_engines(chart: Node, folder: Path) -> tuple[Engine, Engine]:
    models = folder / "models" / "bench"
    models.mkdir(parents=True)
    (models / f"{chart.name}.lr").write_text(lightrocks_text(chart))
    context = check([models.parent])
    assert not context.diagnostics.has_errors, context.diagnostics.items[:3]
    component = component_class(generated_package(context, [], folder / "cache"),
                                f"bench.{chart.name}")  # fmt: skip

    def engine(keep: bool) -> Engine:
        def start() -> Started:
            instance = component().start(trace=Trace(keep=keep))
            return instance.send, lambda: instance.active_configuration[-1]

        return start

    return engine(True), engine(False)


def sismic_engine(chart: Node) -> Engine:
    statechart = import_from_yaml(sismic_yaml(chart))

    def start() -> Started:
        interpreter = Interpreter(statechart)
        interpreter.execute_once()

        def send(event: str) -> None:
            interpreter.queue(event)
            interpreter.execute_once()

        return send, lambda: max(interpreter.configuration, key=statechart.depth_for)

    return start


def statemachine_engine(chart: Node) -> Engine:
    kind = statemachine_class(chart)

    def start() -> Started:
        machine = kind()
        return machine.send, lambda: next(s.id for s in machine.configuration if not s.states)

    return start


def transitions_engine(chart: Node) -> Engine:
    def start() -> Started:
        machine = transitions_machine(chart)
        return machine.trigger, lambda: machine.state.split("_")[-1]

    return start


def rate(engine: Engine, sequence: list[str]) -> tuple[float, str]:
    """Events per CPU second after the start, and the leaf the chart ends in."""
    send, leaf = engine()
    begin = time.process_time()
    for event in sequence:
        send(event)
    return len(sequence) / (time.process_time() - begin), leaf()


def events(count: int) -> list[str]:
    return ["hop" if k % 3 == 2 else "next" for k in range(count)]


def measure(chart: Node, count: int, rounds: int) -> dict[str, float]:
    """Median events/s of every engine on ``chart``; all must end in the same leaf."""
    with tempfile.TemporaryDirectory() as folder:
        kept, disabled = lightrocks_engines(chart, Path(folder))
        engines = {
            "LightRocks (trace kept)": (kept, count),
            "LightRocks (trace disabled)": (disabled, count),
            "sismic": (sismic_engine(chart), count // BASELINE_SHARE),
            "python-statemachine": (statemachine_engine(chart), count // BASELINE_SHARE),
            "transitions": (transitions_engine(chart), count // BASELINE_SHARE),
        }
        rates: dict[str, list[float]] = {name: [] for name in engines}
        leaves: dict[int, set[str]] = {}
        for _ in range(rounds):
            for name, (engine, n) in engines.items():
                value, leaf = rate(engine, events(n))
                rates[name].append(value)
                leaves.setdefault(n, set()).add(leaf)
    assert all(len(found) == 1 for found in leaves.values()), f"engines disagree: {leaves}"
    return {name: statistics.median(values) for name, values in rates.items()}


def main() -> None:
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 100
    count = int(sys.argv[2]) if len(sys.argv) > 2 else 20000
    rounds = int(sys.argv[3]) if len(sys.argv) > 3 else 3
    depth = int(sys.argv[4]) if len(sys.argv) > 4 else 20
    charts = {
        f"flat ({n} states)": flat(n),
        f"ring ({3 * n + 1} states)": ring(n),
        f"deep ({2 * depth + 5} states, {depth} levels)": deep(depth),
    }
    print(f"{count} events for LightRocks, {count // BASELINE_SHARE} for the others; "
          f"median of {rounds} rounds")  # fmt: skip
    for title, chart in charts.items():
        rates = measure(chart, count, rounds)
        ours = rates["LightRocks (trace disabled)"]
        print(f"\n{title}")
        for name, value in rates.items():
            ratio = "" if name.startswith("LightRocks") else f"  generated is {ours / value:5.1f}x"
            print(f"  {name:28s} {value:10.0f} events/s{ratio}")
        if chart.name == "Ring":
            achieved = ours / rates["sismic"]
            kept = rates["LightRocks (trace kept)"] / rates["sismic"]
            verdict = "met" if achieved >= GOAL else "NOT met"
            print(f"  goal: >= {GOAL:.0f}x sismic; measured {achieved:.1f}x ({verdict}), "
                  f"{kept:.1f}x with the trace kept")  # fmt: skip


if __name__ == "__main__":
    main()
