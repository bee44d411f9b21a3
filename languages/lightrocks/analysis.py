"""The shared analysis of one check run: resolved components and their typing, built once."""

from __future__ import annotations

from functools import cached_property

from lightrocks.languages.lightrocks.model import ModelSet
from lightrocks.languages.lightrocks.typing import Typing
from lightrocks.workbench.check import CheckContext
from lightrocks.workbench.passes import Pass
from lightrocks.workbench.workspace import Workspace


class Analysis(Pass):
    """The components of the run resolved, and typed, on first use; reports no codes itself
    (the typing findings are :class:`~.cocos_typing.TypingPass`'s)."""

    context: CheckContext

    @property
    def workspace(self) -> Workspace:
        return self.context.workspace

    @cached_property
    def models(self) -> ModelSet:
        return ModelSet(self.context.workspace, self.context.diagnostics)

    @cached_property
    def typing(self) -> Typing:
        return Typing(self.models)


def analysis(context: CheckContext) -> Analysis:
    """The analysis of this run, created by the first CoCo that asks for it."""
    return context.result(Analysis)
