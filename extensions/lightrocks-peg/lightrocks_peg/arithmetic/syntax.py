"""``count`` statements and ``clamp`` expressions: their AST nodes and how parse nodes become
them. Each node says how it reads as text and how it types (``ast.ExtensionNode``)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from lightrocks.metamodel import ast
from lightrocks.metamodel.grammar import GrammarExtension

GRAMMAR = GrammarExtension(
    rules=Path(__file__).with_name("arithmetic.tx").read_text(encoding="utf-8"),
    hooks=(("StatementExtension", ("Count",)), ("ExpressionExtension", ("Clamp",))),
)


@dataclass(frozen=True)
class Count(ast.ExtensionNode):
    """``count target;``: one more, for retry and failure counters."""

    target: ast.Expression
    position: ast.Position = field(default=ast.NOWHERE, compare=False, repr=False)

    def text(self, expression: Callable[[ast.Expression], str]) -> str:
        return f"count {expression(self.target)};"

    def infer(self, infer: Callable[[ast.Expression], Any]) -> None:
        infer(self.target)


@dataclass(frozen=True)
class Clamp(ast.ExtensionNode):
    """``clamp(value, low, high)``: ``value`` limited to ``[low, high]``, of its type."""

    value: ast.Expression
    low: ast.Expression
    high: ast.Expression
    position: ast.Position = field(default=ast.NOWHERE, compare=False, repr=False)

    def text(self, expression: Callable[[ast.Expression], str]) -> str:
        parts = ", ".join(expression(e) for e in (self.value, self.low, self.high))
        return f"clamp({parts})"

    def infer(self, infer: Callable[[ast.Expression], Any]) -> Any:
        infer(self.low)
        infer(self.high)
        return infer(self.value)


def build_count(converter: Any, node: Any) -> Count:
    return Count(converter.convert(node.target), converter.position(node))


def build_clamp(converter: Any, node: Any) -> Clamp:
    value, low, high = (converter.convert(part) for part in (node.value, node.low, node.high))
    return Clamp(value, low, high, converter.position(node))
