"""``after(d)`` and the chart's ``<<timeout>>`` budget in SCXML: a delayed ``<send>`` on
entry of the state, its ``<cancel>`` on exit, and the relays that keep LightRocks' order of
time events due at one deadline (see :meth:`TimeEvents.ties`).

A delay must be known when generating; finding it (a constant, or the defaults of parameters
the chart never assigns) and refusing any other is part of this module's job.
"""

from __future__ import annotations

import math
import re
import xml.etree.ElementTree as ET
from collections.abc import Callable, Iterator, Mapping
from typing import NamedTuple

from lightrocks.generators.scxml import elements
from lightrocks.generators.scxml.chart_tree import Node
from lightrocks.generators.scxml.names import Names
from lightrocks.languages.lightrocks.access import assigned
from lightrocks.languages.scxml.markup import q
from lightrocks.metamodel import ast, units
from lightrocks.metamodel.constants import fold
from lightrocks.metamodel.printer import expression as lightrocks_text

BUDGET = "budget"
"""The source of the chart's ``<<timeout>>`` time event (the others are transitions)."""


class Timer(NamedTuple):
    """A time event armed on entering a state: the transition (or :data:`BUDGET`) it
    stands for, its delay in seconds (``None`` when refused) and a comment for the reader
    of the document."""

    source: object
    seconds: float | None
    comment: str


class TimeEvents:
    """The time events of one chart, armed per node, and the events each is taken on."""

    def __init__(
        self,
        statechart: ast.Statechart,
        chart: Node,
        names: Names,
        parameters: Mapping[str, ast.Parameter],
        budget: ast.Stereotype | None,
        refuse: Callable[[ast.Position, str], None],
    ) -> None:
        self.names = names
        self.parameters = parameters
        self.budget = budget
        self.refuse = refuse
        self.chart_id = names.state(chart.path)
        self.assigned = assigned(statechart)
        self.armed = {n: self._armed(n) for n in [chart, *chart.descendants()]}
        timed = [len(n.path) for n, found in self.armed.items() if found]
        self.deepest = max(timed, default=0)
        self._events: dict[int, str] = {}

    def event_of(self, source: object) -> str | None:
        """The event the transitions of ``source`` take (once its ``<send>`` is written)."""
        return self._events.get(id(source))

    # -- on entry and exit ----------------------------------------------------------------

    def sends(self, node: Node) -> Iterator[ET.Element]:
        """The ``<send>`` s (with their comments) of ``node``'s ``<onentry>``."""
        for index, (source, delay, comment) in enumerate(self.armed[node]):
            event = self._event(node, index, source)
            if comment:
                yield ET.Comment(comment)
            yield ET.Element(
                q("send"),
                {
                    "event": event,
                    "id": self._send_id(node, index),
                    "delay": self._delay(delay, source),
                },
            )

    def cancels(self, node: Node) -> Iterator[ET.Element]:
        """The ``<cancel>`` s of ``node``'s ``<onexit>``."""
        for index, _ in enumerate(self.armed[node]):
            yield ET.Element(q("cancel"), {"sendid": self._send_id(node, index)})

    def ties(self, node: Node) -> Iterator[ET.Element]:
        """Of several time events due at one deadline LightRocks fires the innermost state's
        first; SCXML delivers delayed events in the order they were sent, and an enclosing
        state is entered (and sends) first. So each time event of a state above the deepest
        one that has time events is sent on with delay 0 once per level it lies above: the
        events of deeper states due at that deadline come first."""
        hops = self.deepest - len(node.path)
        if hops <= 0:
            return
        for index, (source, _, _) in enumerate(self.armed[node]):
            base = self._base_event(node, index, source)
            for hop in range(hops):
                event = f"{base}-{hop}" if hop else base
                element = elements.transition(event, None, None, [], helper="tie")
                ET.SubElement(
                    element,
                    q("send"),
                    {
                        "event": f"{base}-{hop + 1}",
                        "id": self._send_id(node, index),
                        "delay": "0ms",
                    },
                )
                yield element

    def _base_event(self, node: Node, index: int, source: object) -> str:
        if source == BUDGET:
            return f"timeout-{self.chart_id}"
        return f"after-{self.names.state(node.path)}-{index}"

    def _event(self, node: Node, index: int, source: object) -> str:
        """The event the delayed ``<send>`` sends; the transitions take it after
        :meth:`ties` has sent it on as often as the state lies above the deepest."""
        event = self._base_event(node, index, source)
        hops = self.deepest - len(node.path)
        self._events[id(source)] = f"{event}-{hops}" if hops > 0 else event
        return event

    def _send_id(self, node: Node, index: int) -> str:
        return f"{self.names.state(node.path)}.after{index}"

    def _delay(self, seconds: float, source: object) -> str:
        """The CSS2 time SCXML takes: in the unit the model wrote, else milliseconds."""
        if source == BUDGET:
            written = re.fullmatch(r"\s*(\d+(?:\.\d+)?)\s*(ms|s)\s*", self.budget.value or "")
            if written is not None:
                return written.group(1) + written.group(2)
        argument = getattr(source, "stimulus_arguments", ())
        single = len(argument) == 1 and isinstance(argument[0], ast.Quantity)
        unit = argument[0].unit if single else ""
        if unit == "s":
            return _number(seconds) + "s"
        return _number(seconds * 1000) + "ms"

    # -- finding the delays ---------------------------------------------------------------

    def _armed(self, node: Node) -> list[Timer]:
        """The time events armed on entering ``node``: its internal ones, the chart's budget,
        then those leaving it (the order in which LightRocks fires them at one deadline)."""
        found: list[Timer] = []
        for transition in node.internal:
            if transition.stimulus == "after":
                found.append(self._timed(transition, transition.stimulus_arguments))
        if node.kind == "chart" and self.budget is not None:
            found.append(self._budget())
        for transition in node.leaving():
            if transition.stimulus == "after":
                found.append(self._timed(transition, transition.stimulus_arguments))
        return [f for f in found if f.seconds is not None]

    def _timed(self, transition: object, arguments: tuple[ast.Expression, ...]) -> Timer:
        if len(arguments) != 1:
            self.refuse(transition.position, "after() takes one delay")
            return Timer(transition, None, "")
        delay = arguments[0]
        value = fold(delay)
        comment = ""
        if value is None:
            reads = {n.name for n in ast.walk(delay) if isinstance(n, ast.Name)}
            defaults = {
                name: self.parameters[name].default
                for name in reads
                if name in self.parameters
                and name not in self.assigned
                and self.parameters[name].default is not None
            }
            value = fold(_substituted(delay, defaults)) if defaults.keys() == reads else None
            if value is not None:
                comment = (
                    f" after({lightrocks_text(delay)}) at {delay.position}: the chart never "
                    f"assigns {', '.join(sorted(reads))}, so the delay is computed from the "
                    "defaults "
                ).replace("--", "- -")
        if not isinstance(value, int | float) or isinstance(value, bool) or value < 0:
            self.refuse(
                delay.position,
                f"after({lightrocks_text(delay)}): SCXML's delay must be known when the event "
                "is sent, and python-statemachine's data model cannot write a number as a "
                "time (delayexpr needs a string such as '300ms'); use a constant, or "
                "parameters the chart never assigns",
            )
            return Timer(transition, None, "")
        if not math.isfinite(value):
            self.refuse(delay.position, "an infinite delay")
            return Timer(transition, None, "")
        return Timer(transition, float(value), comment)

    def _budget(self) -> Timer:
        seconds = units.seconds(self.budget.value)
        if seconds is None:
            self.refuse(self.budget.position, "a <<timeout>> that is not a duration")
            return Timer(BUDGET, None, "")
        return Timer(BUDGET, float(seconds), "")


def _substituted(node: ast.Expression, values: dict[str, ast.Expression]) -> ast.Expression:
    """``node`` with names replaced by expressions (defaults of parameters)."""
    match node:
        case ast.Name(name=name) if name in values:
            return values[name]
        case ast.Binary(operator=operator, left=left, right=right):
            return ast.Binary(operator, _substituted(left, values), _substituted(right, values))
        case ast.Unary(operator=operator, operand=operand):
            return ast.Unary(operator, _substituted(operand, values))
        case ast.Call(function=function, arguments=arguments):
            return ast.Call(
                function,
                tuple(ast.Argument(_substituted(a.value, values), a.name) for a in arguments),
            )
    return node


def _number(value: float) -> str:
    """12 significant digits: ``3 * 100 ms`` is 300 ms, not the 300.00000000000006 ms that
    the product of the doubles 3 and 0.1 s gives."""
    text = format(value, ".12g")
    return text if "e" not in text else repr(value)
