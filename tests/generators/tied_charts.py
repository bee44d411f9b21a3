"""Seeded random plain statecharts whose time events tend to fall due together.

Composites and orthogonal states nest a few levels deep; their states leave by ``after(…)``
with few distinct delays and by events, so a time event of a state and one of a state around
it (entered by another stimulus, or at the same instant), or of a state in another region,
are due at one instant of the runtime's clock. Every transition records that it fired in an
Integer of its region and some guards read it, so two time events taken in another order
lead elsewhere. Regions write Integers of their own (regions run side by side on a PLC).
The charts pass ``check`` and use no construct the SFC target refuses.
"""

from __future__ import annotations

import itertools
import random

DELAYS = (250, 500, 750)  # ms; every script lets time pass in steps of 250 ms
EVENTS = ("a", "b")
DEPTH = 3


class _Writer:
    def __init__(self, seed: int) -> None:
        self.rng = random.Random(seed)
        self.numbers = itertools.count(1)
        self.variables: list[str] = []

    def name(self, prefix: str) -> str:
        return f"{prefix}{next(self.numbers)}"

    def variable(self) -> str:
        self.variables.append(f"v{len(self.variables) + 1}")
        return self.variables[-1]

    def record(self, variable: str) -> str:
        return f"{{ {variable} = ({variable} * 7 + {self.rng.randint(1, 6)}) % 1000; }}"

    def delay(self) -> str:
        return f"after({self.rng.choice(DELAYS)} ms)"

    def level(self, depth: int, variable: str, orthogonal: bool) -> list[str]:
        """The states of a statechart, composite or region, left in a ring: each by a time
        event or an event to the next, some also by an event elsewhere."""
        states = [self.name("S") for _ in range(self.rng.choice((2, 3)))]
        lines = []
        for index, state in enumerate(states):
            head = f"{'initial ' if index == 0 else ''}state {state}"
            body = self.body(depth, variable, orthogonal)
            lines += [f"{head} {{", *_indent(body), "}"] if body else [f"{head};"]
        for index, state in enumerate(states):
            lines.append(self.transition(state, states[(index + 1) % len(states)], variable))
            if self.rng.random() < 0.4:
                target = self.rng.choice(states)
                lines.append(f"{state} -> {target} {self.rng.choice(EVENTS)};")
        return lines

    def transition(self, source: str, target: str, variable: str) -> str:
        timed = self.rng.random() < 0.7
        stimulus = self.delay() if timed else self.rng.choice(EVENTS)
        guard = f"[{variable} % 2 == 0] " if self.rng.random() < 0.25 else ""
        return f"{source} -> {target} {guard}{stimulus} / {self.record(variable)};"

    def body(self, depth: int, variable: str, orthogonal: bool) -> list[str]:
        """A state's body: maybe an internal time event, maybe nested states or regions."""
        lines = []
        if self.rng.random() < 0.3:
            lines.append(f"internal {self.delay()} / {self.record(variable)};")
        roll = self.rng.random()
        if depth < DEPTH and roll < 0.4:
            lines += self.level(depth + 1, variable, orthogonal)
        elif depth < DEPTH and orthogonal and roll < 0.65:
            for _ in range(2):
                region = self.level(depth + 1, self.variable(), False)
                lines += [f"region {self.name('R')} {{", *_indent(region), "}"]
        return lines


def _indent(lines: list[str]) -> list[str]:
    return [f"  {line}" for line in lines]


def tied_chart(seed: int) -> str:
    """The chart ``d.T`` of ``seed``."""
    writer = _Writer(seed)
    body = writer.level(1, writer.variable(), True)
    parameters = [f"    Integer {v} = 0;" for v in writer.variables]
    return "\n".join(
        ["package d;", "", "statechart T {", "  parameters {", *parameters, "  }", "",
         *_indent(body), "}", ""]
    )  # fmt: skip
