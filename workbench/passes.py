"""Passes: analyses computed once per check run and shared by everything that asks for them.

A pass is built from its check run the first time something asks for it
(``context.result(SomePass)``, typed by the class) and kept for the rest of that run, so
CoCos, generators and the language server share one computation. A pass that finds
problems declares the codes it reports; the checker reports its findings under those codes
(with their severities), and ``lightrocks list cocos`` lists them beside the CoCos'.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from types import ModuleType
from typing import TYPE_CHECKING, Any, ClassVar

from lightrocks.workbench.cocos import Code
from lightrocks.workbench.diagnostics import Diagnostic

if TYPE_CHECKING:
    from lightrocks.workbench.check import CheckContext

Finding = tuple[str, Any, str, str]
"""(code, position, message, hint) of one finding of a pass."""


class Pass:
    """An analysis of one check run; subclasses compute in ``__init__`` or lazily."""

    codes: ClassVar[tuple[Code, ...]] = ()
    """The codes this pass reports; none for an analysis that only answers questions."""

    def __init__(self, context: CheckContext) -> None:
        self.context = context

    def findings(self) -> Iterable[Finding]:
        """Every finding of this run, each under one of :attr:`codes`."""
        return ()


def report(kind: type[Pass], context: CheckContext) -> Iterator[Diagnostic]:
    """The findings of the pass ``kind`` in ``context``, each with its code's severity."""
    declared = {code.code: code for code in kind.codes}
    for code, position, message, hint in context.result(kind).findings():
        if code not in declared:
            raise ValueError(f"pass {kind.__qualname__} reports {code}, which it does not declare")
        yield Diagnostic.at(position, code, declared[code].severity, message, hint)


def passes_in(*modules: ModuleType) -> tuple[type[Pass], ...]:
    """The passes that report codes, defined in ``modules``, in the order they are defined."""
    return tuple(
        found
        for module in modules
        for found in vars(module).values()
        if isinstance(found, type)
        and issubclass(found, Pass)
        and found.codes
        and found.__module__ == module.__name__
    )
