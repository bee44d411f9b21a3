"""Seeded random plain statecharts that pass ``check``, for differential runs against sismic.

A chart is built top down. Every level (the statechart, a composite, a region) gets an
initial state and a few more states, some of them composite or orthogonal down to
``DEPTH``; final states, an end condition, a choice and history pseudostates are sprinkled
in. The CoCos are respected by construction rather than by filtering:

- names are unique in the whole chart (LR0101);
- every state of a level is the target of an event transition from a state reached before
  it, so all states are reachable (LR0207);
- a transition without stimulus only leaves a state that completes (LR0214), a choice is
  left by transitions without stimulus (LR0216), no transition leaves a final state
  (LR0208), a history target names a history of its state (LR0215);
- transitions stay on their level, so they never cross regions (LR0218), and an orthogonal
  body holds only regions, actions and internal transitions (LR0219).

Integer parameters are read by guards and written by entry, exit and transition actions.
Guards evaluated within the step that wrote them are favoured: a choice reads what the exit
actions of its level and the transitions into it write, a completion what the entry of a
final state and the exit of the completed state write. A choice sometimes has no *else*
branch, the statechart itself has internal transitions, a composite has self-transitions
(plain or through its history), and below a composite with deep history the states nest
one level deeper, so that its memory reaches three levels of states.
The regions of an orthogonal state read and write disjoint sets of them: sismic fires the
transitions of one step in an order of its own (docs/language.md §15.1), so a value that
one region writes and another uses in the same step would differ by design. The regions
of the statechart and of its states keep their parameters below them as well.
"""

from __future__ import annotations

import itertools
import random
import re
from collections.abc import Sequence
from dataclasses import dataclass, field

EVENTS = ("a", "b", "c", "d")
VARIABLES = ("n", "m", "k")
DEPTH = 3  # levels of states; one more below a composite with deep history
TICK = 0.25  # every delay is a multiple of it


@dataclass
class _Child:
    """A state of one level: its text and, when it completes, its outcomes."""

    name: str
    lines: list[str]
    outcomes: list[str] | None = None  # None: it never completes
    histories: list[str] = field(default_factory=list)
    composite: bool = False
    leaving: list[str] = field(default_factory=list)  # parameters its exit action writes
    completing: list[str] = field(default_factory=list)  # written as it completes


@dataclass
class _Level:
    """The body of a statechart, composite or region."""

    lines: list[str]
    outcomes: list[str] | None  # None: it never completes
    histories: list[str]
    completing: list[str]  # parameters the entry actions of its final states write


def _written(block: str) -> list[str]:
    """The parameters a block of assignments writes."""
    return re.findall(r"(\w+) = ", block)


class _Writer:
    def __init__(self, seed: int, timed: bool) -> None:
        self.rng = random.Random(seed)
        self.timed = timed
        self._numbers = itertools.count(1)

    def fresh(self, prefix: str) -> str:
        return f"{prefix}{next(self._numbers)}"

    # -- expressions ----------------------------------------------------------------------

    def guard(self, readable: list[str], favoured: Sequence[str] = ()) -> str:
        """A guard on ``readable``, mostly reading ``favoured`` when there are any."""
        rng = self.rng
        favoured = [v for v in favoured if v in readable]
        v = rng.choice(favoured if favoured and rng.random() < 0.8 else readable)
        w = rng.choice(readable)
        atoms = [
            f"{v} < {rng.randint(0, 3)}",
            f"{v} >= {rng.randint(0, 3)}",
            f"{v} % 2 == {rng.randint(0, 1)}",
            f"{v} != {w}",
            f"{v} + {w} <= {rng.randint(0, 4)}",
        ]
        first = rng.choice(atoms)
        roll = rng.random()
        if roll < 0.15:
            return f"!({first})"
        if roll < 0.3:
            return f"{first} {rng.choice(['&&', '||'])} {rng.choice(atoms)}"
        return first

    def assignment(self, owned: list[str]) -> str:
        rng = self.rng
        v, w = rng.choice(owned), rng.choice(owned)
        value = rng.choice(
            [f"{v} + 1", f"{v} - 1", f"{w} + 1", f"{v} * 2", f"{w} % 3", str(rng.randint(0, 2))]
        )
        return f"{v} = {value};"

    def block(self, owned: list[str]) -> str:
        count = self.rng.choice([1, 1, 2])
        return "{ " + " ".join(self.assignment(owned) for _ in range(count)) + " }"

    def stimulus(self, timed: bool = True) -> str:
        if timed and self.timed and self.rng.random() < 0.12:
            return f"after({250 * self.rng.randint(1, 4)} ms)"
        return self.rng.choice(EVENTS)

    def transition(
        self,
        source: str,
        target: str,
        stimulus: str,
        owned: list[str],
        favoured: Sequence[str] = (),
    ) -> str:
        rng = self.rng
        guard = f" [{self.guard(owned, favoured)}]" if owned and rng.random() < 0.3 else ""
        action = f" / {self.block(owned)}" if owned and rng.random() < 0.3 else ""
        stimulus = f" {stimulus}" if stimulus else ""
        return f"{source} -> {target}{guard}{stimulus}{action};"

    # -- states ---------------------------------------------------------------------------

    def behaviour(self, owned: list[str]) -> list[str]:
        """Entry and exit actions and internal transitions of a state."""
        rng = self.rng
        lines = []
        if owned and rng.random() < 0.3:
            lines.append(f"entry / {self.block(owned)}")
        if owned and rng.random() < 0.2:
            lines.append(f"exit / {self.block(owned)}")
        if rng.random() < 0.25:
            lines.append(self.internal(owned))
        return lines

    def internal(self, owned: list[str]) -> str:
        """An internal transition, of a state or of the statechart itself."""
        rng = self.rng
        guard = f" [{self.guard(owned)}]" if owned and rng.random() < 0.4 else ""
        action = f" / {self.block(owned)}" if owned else ""
        return f"internal{guard} {self.stimulus()}{action};"

    def child(self, depth: int, owned: list[str], initial: bool, limit: int) -> _Child:
        """A state of level ``depth``; composite or orthogonal only above ``limit``."""
        name = self.fresh("S")
        head = ("initial " if initial else "") + f"state {name}"
        roll = self.rng.random() if depth < limit else 1.0
        body = self.behaviour(owned)
        leaving = [v for line in body if line.startswith("exit") for v in _written(line)]
        inner = None
        if roll < 0.15:
            inner = self.regions(depth + 1, owned, limit)
        elif roll < 0.45:
            inner = self.level(depth + 1, owned, "composite", limit)
        if inner is not None:
            body += inner.lines
        if not body:
            return _Child(name, [f"{head};"])
        lines = [f"{head} {{", *_indent(body), "}"]
        if inner is None:
            return _Child(name, lines, leaving=leaving)
        return _Child(name, lines, inner.outcomes, inner.histories, True, leaving, inner.completing)

    def regions(self, depth: int, owned: list[str], limit: int = DEPTH) -> _Level:
        """Two or three regions that own disjoint parts of the parameters; the outcomes of the
        orthogonal state are the finals of its first region, when every region has one."""
        count = self.rng.choice([2, 2, 2, 3])
        shares: list[list[str]] = [[] for _ in range(count)]
        for variable in self.rng.sample(owned, len(owned)):
            shares[self.rng.randrange(count)].append(variable)
        lines, finals, completing = [], [], []
        for share in shares:
            body = self.level(depth, share, "region", limit)
            lines += [f"region {self.fresh('R')} {{", *_indent(body.lines), "}"]
            finals.append(body.outcomes)
            completing += body.completing
        return _Level(lines, finals[0] if all(finals) else None, [], completing)

    def level(self, depth: int, owned: list[str], kind: str, limit: int = DEPTH) -> _Level:
        """The body of a statechart, composite or region."""
        rng = self.rng
        histories = []
        if kind == "composite":
            histories = [
                f"{memory} {self.fresh('H')}"
                for memory in ("history", "deep history")
                if rng.random() < 0.3
            ]
        if any(h.startswith("deep") for h in histories):  # its memory reaches one level further
            limit = max(limit, DEPTH + 1)
        children = [self.child(depth, owned, i == 0, limit) for i in range(rng.randint(2, 3))]
        finals = [self.fresh("F") for _ in range(rng.choices([0, 1, 2], [4, 5, 1])[0])]
        ends = [self.fresh("o") for _ in range(kind == "composite" and rng.random() < 0.25)]
        choice = self.fresh("C") if rng.random() < 0.3 else None
        lines = [f"end condition {e};" for e in ends]
        for c in children:
            lines += c.lines
        completing = []
        for f in finals:
            if owned and rng.random() < 0.3:
                entry = self.block(owned)
                completing += _written(entry)
                lines.append(f"final state {f} {{ entry / {entry} }}")
            else:
                lines.append(f"final state {f};")
        lines += [f"choice {choice};"] if choice else []
        lines += [f"{h};" for h in histories]

        names = [c.name for c in children]
        targets = names + finals + ends + ([choice] if choice else [])
        targets += [f"{c.name}.{h.split()[-1]}" for c in children for h in c.histories]
        transitions = []
        reached = [names[0]]
        for target in names[1:] + finals + ends + ([choice] if choice else []):
            source = rng.choice(reached)
            transitions.append(self.transition(source, target, self.stimulus(), owned))
            if target in names:
                reached.append(target)
        for _ in range(rng.randint(0, len(names))):
            source, target = rng.choice(names), rng.choice(targets)
            transitions.append(self.transition(source, target, self.stimulus(), owned))
        for c in children:
            if c.composite and rng.random() < 0.4:  # external: left and entered again
                again = rng.choice([c.name, *(f"{c.name}.{h}" for h in c.histories)])
                transitions.append(self.transition(c.name, again, self.stimulus(), owned))
            if c.outcomes and rng.random() < 0.9:
                favoured = c.completing + c.leaving
                for outcome in c.outcomes:
                    if rng.random() < 0.4:
                        target = rng.choice(targets)
                        transitions.append(
                            self.transition(c.name, target, outcome, owned, favoured)
                        )
                if rng.random() < 0.8:
                    target = rng.choice(targets)
                    transitions.append(self.transition(c.name, target, "", owned, favoured))
        rng.shuffle(transitions)
        if choice:  # its guards run after the exit action of the source and the transition
            entering = [t for t in transitions if f"-> {choice} " in t]
            favoured = [v for c in children for v in c.leaving]
            favoured += [v for t in entering for v in _written(t)]
            transitions += self.branches(
                choice, [t for t in targets if t != choice], owned, favoured
            )
        lines += transitions
        outcomes = finals + ends
        return _Level(lines, outcomes or None, [h.split()[-1] for h in histories], completing)

    def branches(
        self, choice: str, targets: list[str], owned: list[str], favoured: list[str]
    ) -> list[str]:
        """Guarded branches in order, mostly reading what the step wrote before the choice,
        then the else branch, which is sometimes left out: then no branch may hold."""
        rng = self.rng
        lines = []
        for _ in range(rng.randint(1, 2) if owned else 0):
            action = f" / {self.block(owned)}" if rng.random() < 0.3 else ""
            guard = self.guard(owned, favoured)
            lines.append(f"{choice} -> {rng.choice(targets)} [{guard}]{action};")
        if not lines or rng.random() < 0.7:
            lines.append(f"{choice} -> {rng.choice(targets)};")
        return lines


def _indent(lines: list[str]) -> list[str]:
    return ["  " + line for line in lines]


def random_chart(seed: int, name: str = "R", timed: bool = True) -> str:
    """The text of a random plain statechart ``d.<name>``, the same for the same seed."""
    writer = _Writer(seed, timed)
    rng = writer.rng
    defaults = [f"Integer {v} = {rng.randint(0, 2)};" for v in VARIABLES]
    top = [writer.internal(list(VARIABLES)) for _ in range(rng.choice([0, 0, 1, 2]))]
    if rng.random() < 0.2:
        body = writer.regions(1, list(VARIABLES))
    else:
        body = writer.level(1, list(VARIABLES), "top")
    lines = ["parameters {", *_indent(defaults), "}", "", *top, *body.lines]
    return "\n".join(["package d;", "", f"statechart {name} {{", *_indent(lines), "}", ""])
