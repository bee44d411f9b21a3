"""Events per second of generated code against sismic, on one chart of a few hundred states.

The chart is a ring of ``N`` composite states with two sub-states each; event ``next`` moves
the inner state, ``hop`` moves to the next composite. The same chart is generated as
LightRocks text (then Python) and as sismic YAML, and both run the same events in one
process. Needs the ``bench`` extra (``pip install -e '.[bench]'``).

    .venv/bin/python benchmarks/bench_runtime.py [N] [EVENTS]
"""

from __future__ import annotations

import sys
import tempfile
import time
from pathlib import Path

from sismic.interpreter import Interpreter
from sismic.io import import_from_yaml

from lightrocks.workbench.app.loading import component_class, generated_package
from lightrocks.workbench.check import check


def lightrocks_text(n: int) -> str:
    states = []
    for i in range(n):
        states.append(
            f"  {'initial ' if i == 0 else ''}state S{i} {{\n"
            f"    initial state A{i};\n    state B{i};\n"
            f"    A{i} -> B{i} next;\n    B{i} -> A{i} next;\n  }}\n"
        )
    hops = "".join(f"  S{i} -> S{(i + 1) % n} hop;\n" for i in range(n))
    return f"package bench;\n\nstatechart Ring {{\n{''.join(states)}{hops}}}\n"


def sismic_yaml(n: int) -> str:
    lines = ["statechart:", "  name: Ring", "  root state:", "    name: root",
             "    initial: S0", "    states:"]  # fmt: skip
    for i in range(n):
        lines += [
            f"    - name: S{i}",
            f"      initial: A{i}",
            "      transitions:",
            f"      - target: S{(i + 1) % n}",
            "        event: hop",
            "      states:",
            f"      - name: A{i}",
            "        transitions:",
            f"        - target: B{i}",
            "          event: next",
            f"      - name: B{i}",
            "        transitions:",
            f"        - target: A{i}",
            "          event: next",
        ]
    return "\n".join(lines) + "\n"


def events(count: int) -> list[str]:
    return ["hop" if k % 3 == 2 else "next" for k in range(count)]


def rate(run, sequence: list[str]) -> float:
    start = time.perf_counter()
    run(sequence)
    return len(sequence) / (time.perf_counter() - start)


def main() -> None:
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 100
    count = int(sys.argv[2]) if len(sys.argv) > 2 else 20000
    sequence = events(count)
    with tempfile.TemporaryDirectory() as folder:
        models = Path(folder) / "models" / "bench"
        models.mkdir(parents=True)
        (models / "Ring.lr").write_text(lightrocks_text(n))
        context = check([models.parent])
        assert not context.diagnostics.has_errors, context.diagnostics.items[:3]
        package = generated_package(context, [], Path(folder) / "cache")
        ring = component_class(package, "bench.Ring")

        def generated(sequence: list[str]) -> None:
            chart = ring().start()
            for event in sequence:
                chart.send(event)

        interpreter = Interpreter(import_from_yaml(sismic_yaml(n)))

        def sismic(sequence: list[str]) -> None:
            for event in sequence:
                interpreter.queue(event)
                interpreter.execute_once()

        ours = rate(generated, sequence)
        theirs = rate(sismic, sequence)
    print(f"chart: {3 * n + 1} states, {count} events")
    print(f"generated LightRocks: {ours:10.0f} events/s")
    print(f"sismic:               {theirs:10.0f} events/s")
    print(f"ratio:                {ours / theirs:10.1f}x")


if __name__ == "__main__":
    main()
