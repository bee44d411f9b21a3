"""SCXML executable content (``<onentry>``, ``<onexit>``, a transition's content) as
LightRocks statements: an ``<assign>`` to a ``<data>`` is an assignment, a ``<log>`` is
dropped (LR2132); the ``<send>`` and ``<cancel>`` of a state's time events belong to
:mod:`languages.scxml.read_time_events`, anything else is outside the subset.
"""

from __future__ import annotations

from collections.abc import Sequence

from lightrocks.languages.scxml.markup import SCXML
from lightrocks.languages.scxml.read_context import DROPPED, ReadContext, Refused
from lightrocks.languages.scxml.read_expressions import ExpressionReader
from lightrocks.languages.scxml.read_time_events import Timer
from lightrocks.languages.scxml.xml_tree import Element
from lightrocks.metamodel import ast
from lightrocks.workbench.diagnostics import Severity


class ActionReader:
    """The statements of one document's executable content."""

    def __init__(self, context: ReadContext, expressions: ExpressionReader) -> None:
        self.context = context
        self.expressions = expressions

    def statements(
        self, element: Element, ignore_flags: bool = False, timers: Sequence[Timer] = ()
    ) -> tuple[ast.Assignment, ...]:
        """The assignments of ``element``'s executable content; ``ignore_flags`` leaves out
        the generator's history variables, ``timers`` the sends and cancels of time events."""
        statements = []
        sends = {t.event for t in timers}
        ids = {t.send_id for t in timers}
        for child in element.children:
            if child.namespace not in (SCXML, ""):
                message = f"<{child.tag}> of another namespace is dropped"
                self.context.finding(child, DROPPED, Severity.WARNING, message)
                continue
            try:
                if child.tag == "assign":
                    if ignore_flags and child.get("location") in self.context.flags:
                        continue
                    statements.append(self._assignment(child))
                elif (child.tag == "send" and child.get("event") in sends) or (
                    child.tag == "cancel" and child.get("sendid") in ids
                ):
                    continue
                elif child.tag == "log":
                    message = "<log> is dropped: LightRocks actions print nothing"
                    self.context.finding(child, DROPPED, Severity.WARNING, message)
                else:
                    self.context.outside(child, f"in <{element.tag}>")
            except Refused as problem:
                self.context.refused(problem)
        return tuple(statements)

    def _assignment(self, element: Element) -> ast.Assignment:
        location = element.get("location") or ""
        if location not in self.context.variables:
            raise Refused(element, f"<assign> to '{location}', which is no <data> of the chart")
        text = element.get("expr")
        if text is None:
            raise Refused(element, "<assign> without expr (content is not read)")
        value = self.expressions.expression(text, element)
        return ast.Assignment(ast.Name(self.context.variables[location]), value)
