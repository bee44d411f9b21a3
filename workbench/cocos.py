"""The context-condition framework: small checks, each with a stable code and severity.

A CoCo is a function that inspects a loaded model set and reports findings. Languages
declare their CoCos with :func:`coco` and hand them to the registry with :func:`cocos_in`,
which collects them from the modules they are written in; the checker runs all of them and
collects every finding, so one run reports everything that is wrong. Findings that one
analysis makes for several codes come from a pass (:mod:`lightrocks.workbench.passes`).
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from functools import cached_property
from types import ModuleType
from typing import Any

from lightrocks.workbench.diagnostics import Diagnostic, Severity


@dataclass(frozen=True)
class Code:
    """A code that checks report, with the severity of its findings and what it demands."""

    code: str
    severity: Severity
    summary: str


@dataclass(frozen=True)
class CoCo(Code):
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


def cocos_in(*modules: ModuleType) -> tuple[CoCo, ...]:
    """The CoCos written in ``modules``, in the order they are defined there: a CoCo a
    module imports from another belongs to that other one."""
    return tuple(
        found
        for module in modules
        for found in vars(module).values()
        if isinstance(found, CoCo) and found.check.__module__ == module.__name__
    )


class Deferred(Sequence[Any]):
    """A language's CoCos or passes, loaded when a check first asks for them: every command
    reads the registered languages' light facts (extensions, library, implicit packages),
    and only a check needs their checks, whose modules import solvers and graph libraries."""

    def __init__(self, load: Callable[[], Sequence[Any]]) -> None:
        self._load = load

    @cached_property
    def _items(self) -> tuple[Any, ...]:
        return tuple(self._load())

    def __getitem__(self, index: Any) -> Any:
        return self._items[index]

    def __len__(self) -> int:
        return len(self._items)
