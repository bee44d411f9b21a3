"""Time events ``after(d)``: an on-delay timer per time event and a flag that lets it fire
in one scan per entry of its state."""

from __future__ import annotations

from dataclasses import dataclass

from lightrocks.generators.sfc_iec61131.children import budget_seconds
from lightrocks.generators.sfc_iec61131.conditions import negate
from lightrocks.generators.sfc_iec61131.expressions import literal, time_literal
from lightrocks.generators.sfc_iec61131.hierarchy import Node
from lightrocks.generators.sfc_iec61131.ir import Variable
from lightrocks.generators.sfc_iec61131.network import Branch
from lightrocks.languages.domain.types import NUMBER
from lightrocks.metamodel import ast


@dataclass
class Timer:
    """A time event ``after(d)`` of one state, or the statechart's budget (``<<timeout>>``):
    an on-delay timer started on entry and a flag raised once its deadline has passed, so
    that it fires at most once per entry."""

    transition: ast.Transition | ast.InternalTransition | None  # None: the budget
    instance: str
    passed: str
    duration: str


class TimeEvents:
    """The part of :class:`~.component.ComponentBuilder` that declares and runs the timers."""

    timers: dict[int | None, list[Timer]]  # id(node), None: the statechart

    def _declare_timers(self) -> None:
        """A timer per time event: those of a state's own body and those leaving it."""
        owners: list[tuple[Node | None, list]] = [(None, list(self.region.internal))]
        for node in self._all(self.nodes):
            own = list(node.info.region.internal) if node.info.region else []
            leaving = [t for t in node.region.transitions if t.source == node.name]
            owners.append((node, own + leaving))
        for node, transitions in owners:
            for transition in transitions:
                if transition.delay is None:
                    continue
                where = "_".join(node.path) if node else self.component.name
                instance = self.names.claim(f"{where}_after")
                passed = self.names.claim(f"{instance}_passed")
                comment = f"after(…) at {transition.position.line}:{transition.position.column}"
                self.block.locals += [
                    Variable(instance, "TON", comment=comment),
                    Variable(passed, "BOOL", comment="its deadline has passed since the entry"),
                ]
                duration = literal(transition.delay)
                duration = (
                    time_literal(float(duration))
                    if duration is not None
                    else f"REAL_TO_TIME({self.scope.compile(transition.delay, NUMBER)})"
                )
                timer = Timer(transition, instance, passed, duration)
                self.timers.setdefault(id(node) if node else None, []).append(timer)
        budget = self.component.budget
        if budget is not None:
            instance = self.names.claim(f"{self.component.name}_budget")
            passed = self.names.claim(f"{instance}_passed")
            comment = f"<<timeout>> at {budget.position.line}:{budget.position.column}"
            self.block.locals += [
                Variable(instance, "TON", comment=comment),
                Variable(passed, "BOOL", comment="the budget is spent"),
            ]
            timer = Timer(None, instance, passed, time_literal(budget_seconds(budget)))
            self.timers.setdefault(None, []).append(timer)

    def _budget_branches(
        self, node: Node | None, stop: list[str], waiting: list[str]
    ) -> list[Branch]:
        """The statechart's budget spent, if it has one: what runs is stopped, every state
        left, and the statechart ends with ``timeout``. It is the outermost way out, so the
        last one a scan takes."""
        timer = next((t for t in self.timers.get(None, []) if t.transition is None), None)
        if timer is None:
            return []
        exits = stop + (self._exits(node.chain()) if node else [])
        condition = [f"{timer.instance}.Q", f"NOT {timer.passed}", *waiting]
        return [Branch(condition, [*exits, f"{timer.passed} := TRUE;"], self._exit("timeout"))]

    def _timer(
        self, owner: Node | None, transition: ast.Transition | ast.InternalTransition | None
    ) -> Timer:
        """The timer of ``transition``, a time event of ``owner`` (None: the statechart)."""
        timers = self.timers[id(owner) if owner else None]
        return next(t for t in timers if t.transition is transition)

    def _timed(self, node: Node | None) -> bool:
        """Whether the leaf ``node`` (or the watch of an orthogonal state) runs timers."""
        return any(self.timers.get(id(o) if o else None) for o in self._owners(node))

    def _ticks(self, step: str, node: Node | None, inner: str = "") -> list[str]:
        """N-action lines of a leaf's ``step`` that run the timers of its state and the states
        around it: the flag reads the timer's output of the scan before, so the scan in which
        the deadline shows is the one scan in which the time event fires. A time event keeps
        its deadline one scan longer when an earlier way out took that scan, as at run time,
        where the later event follows at the same instant: a time event of a state around
        the leaf when the leaf was entered in that scan (an inner transition took it), any
        time event after an internal transition of the step that took it, and a time event
        of the watch of orthogonal regions while one inside them is due (``inner``)."""
        lines = []
        took = self.took.get(step)
        for owner in self._owners(node):
            for timer in self.timers.get(id(owner) if owner else None, []):
                parts = [f"{timer.instance}.Q"]
                if owner is not node:
                    parts.append(self._resting(step))
                if took:  # held when a way out before its own took the scan
                    ways = self.ways[step]
                    place = next(
                        (i for i, way in enumerate(ways, 1) if parts[0] in way), len(ways) + 1
                    )
                    parts.append(f"({took} = 0 OR {took} > {place})")
                parts += [negate(inner)] if inner else []
                due = parts[0] if len(parts) == 1 else f"({' AND '.join(parts)})"
                lines += [f"{timer.passed} := {timer.passed} OR {due};",
                          f"{timer.instance}(IN := TRUE);"]  # fmt: skip
        return lines
