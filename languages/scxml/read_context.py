"""What the parts of the SCXML reader share: the findings of one document (with their
codes) and what is known of its states and data once they are indexed.

The reader is split by the parts of SCXML it reads; this is the state they all consult
and report to, so that each finding is made once, at its element.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from lightrocks.languages.scxml.xml_tree import Element
from lightrocks.metamodel import ast
from lightrocks.workbench.diagnostics import Diagnostic, Severity

OUTSIDE, EXPRESSION, DROPPED, RENAMED = "LR2130", "LR2131", "LR2132", "LR2133"
"""An element outside the subset (error); an expression without LightRocks counterpart
(error); something dropped that does not change what the chart does (warning); a name or a
type the reader chose (info)."""

_REASONS = {
    "script": "arbitrary code",
    "invoke": "another state machine as a service",
    "raise": "an internal event (LightRocks events come from outside)",
    "send": "an event sent elsewhere than a time event of its state",
    "cancel": "a cancel that is not the one of a time event of its state",
    "if": "conditional actions (LightRocks actions are assignments)",
    "foreach": "a loop (LightRocks actions are assignments)",
    "donedata": "data of an outcome",
    "content": "content",
    "param": "a parameter of an event or service",
}


class Refused(Exception):
    """An element the reader cannot convert, raised where the reading of it stops."""

    def __init__(self, element: Element, message: str, code: str = OUTSIDE) -> None:
        super().__init__(message)
        self.element, self.message, self.code = element, message, code


@dataclass(eq=False)
class ReadContext:
    """The findings of one document and its index, filled as the reader goes."""

    shown: str
    findings: list[Diagnostic] = field(default_factory=list)
    generated: bool = False  # written by the LightRocks SCXML target
    variables: dict[str, str] = field(default_factory=dict)  # data id -> parameter name
    flags: set[str] = field(default_factory=set)  # the generator's history variables
    states: dict[str, Element] = field(default_factory=dict)  # id -> element
    scope_of: dict[str, str] = field(default_factory=dict)  # id -> id of its parent's body
    name_of: dict[str, str] = field(default_factory=dict)  # id -> LightRocks name

    def at(self, element: Element | None) -> ast.Position:
        if element is None:
            return ast.Position(self.shown, 1, 1)
        return ast.Position(self.shown, element.line, element.column)

    def finding(self, element: Element | None, code: str, severity: Severity, text: str) -> None:
        self.findings.append(Diagnostic.at(self.at(element), code, severity, text))

    def refuse(self, element: Element, message: str, code: str = OUTSIDE) -> None:
        self.finding(element, code, Severity.ERROR, message)

    def refused(self, problem: Refused) -> None:
        """Report ``problem`` where it was raised."""
        self.refuse(problem.element, problem.message, problem.code)

    def outside(self, element: Element, where: str) -> None:
        """Refuse ``element`` found ``where``, saying why the subset leaves it out."""
        reason = _REASONS.get(element.tag, "outside the SCXML that LightRocks reads")
        self.refuse(element, f"<{element.tag}> {where}: {reason}")
