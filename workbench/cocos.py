"""The context-condition framework: small checks, each with a stable code and severity.

A CoCo is a function that inspects a loaded model set and reports findings. Languages
declare their CoCos with :func:`coco`; the checker runs all of them and collects every
finding, so one run reports everything that is wrong.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from dataclasses import dataclass
from typing import Any

from lightrocks.workbench.diagnostics import Diagnostic, Severity


@dataclass(frozen=True)
class CoCo:
    code: str
    severity: Severity
    summary: str
    check: Callable[[Any], Iterable[tuple[Any, str, str]]]

    def run(self, model: Any) -> Iterable[Diagnostic]:
        """Findings of this CoCo; ``check`` yields (position, message, hint) triples."""
        for position, message, hint in self.check(model):
            yield Diagnostic.at(position, self.code, self.severity, message, hint)


def coco(code: str, severity: Severity, summary: str) -> Callable[[Callable], CoCo]:
    """Declare a check function as a CoCo with its code, severity and one-line summary."""

    def wrap(check: Callable[[Any], Iterable[tuple[Any, str, str]]]) -> CoCo:
        return CoCo(code, severity, summary, check)

    return wrap
