"""Time events ``after(d)``: an on-delay timer per time event and a flag that lets it fire
in one scan per entry of its state."""

from __future__ import annotations

from dataclasses import dataclass

from lightrocks.generators.sfc_iec61131.expressions import literal, time_literal
from lightrocks.generators.sfc_iec61131.hierarchy import Node
from lightrocks.generators.sfc_iec61131.ir import Variable
from lightrocks.languages.domain.types import NUMBER
from lightrocks.metamodel import ast


@dataclass
class Timer:
    """A time event ``after(d)`` of one state: an on-delay timer started on entry and a flag
    raised once its deadline has passed, so that it fires at most once per entry."""

    transition: ast.Transition | ast.InternalTransition
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

    def _ticks(self, step: str, node: Node) -> list[str]:
        """N-action lines of a leaf's ``step`` that run the timers of its state and the states
        around it: the flag reads the timer's output of the scan before, so the scan in which
        the deadline shows is the one scan in which the time event fires. A transition leaving
        a state around the leaf keeps its event one scan longer when the leaf was entered in
        that scan: an inner transition due at the same deadline took it, and at run time the
        outer event follows at the same instant."""
        lines = []
        for owner in self._owners(node):
            for timer in self.timers.get(id(owner) if owner else None, []):
                due = f"{timer.instance}.Q"
                if owner is not node and isinstance(timer.transition, ast.Transition):
                    due = f"({due} AND {self._resting(step)})"
                lines += [f"{timer.passed} := {timer.passed} OR {due};",
                          f"{timer.instance}(IN := TRUE);"]  # fmt: skip
        return lines
