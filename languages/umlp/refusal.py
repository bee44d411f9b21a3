"""What the ``.sc ↔ .lr`` conversions report: the exception that refuses one construct, and
the findings of one conversion (the codes LR2120 to LR2124, docs/interchange.md).

Both directions convert what they can and go on after a refused construct, so that one run
reports every place the target language cannot say; :meth:`Findings.guarded` is where a
refusal becomes a finding.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TypeVar

from lightrocks.metamodel import ast
from lightrocks.workbench.diagnostics import Diagnostic, Severity

Converted = TypeVar("Converted")


class Refused(Exception):
    """A construct without counterpart; ``code`` LR2120 or LR2121."""

    def __init__(self, position: ast.Position, message: str, code: str = "LR2120") -> None:
        super().__init__(message)
        self.position = position
        self.message = message
        self.code = code


class Findings:
    """The findings of one conversion, in the order they were found."""

    def __init__(self) -> None:
        self.items: list[Diagnostic] = []

    def add(self, position: ast.Position, code: str, severity: Severity, message: str) -> None:
        self.items.append(Diagnostic.at(position, code, severity, message))

    def refused(self, problem: Refused) -> None:
        self.add(problem.position, problem.code, Severity.ERROR, problem.message)

    def lacks(self, position: ast.Position, message: str) -> None:
        """A construct the target language lacks (LR2121)."""
        self.refused(Refused(position, message, "LR2121"))

    def dropped(self, position: ast.Position, message: str) -> None:
        self.add(position, "LR2122", Severity.WARNING, message)

    def guarded(self, convert: Callable[..., Converted], *arguments: object) -> Converted | None:
        """``convert(*arguments)``, or None after recording why it is refused."""
        try:
            return convert(*arguments)
        except Refused as problem:
            self.refused(problem)
            return None
