"""Nesting limits of syntax trees.

Later passes (typing, printing, generating) walk the tree recursively; a tree nested deeper
than they can walk is refused where it is parsed, with the place that nests deepest.
"""

from __future__ import annotations

from dataclasses import is_dataclass
from functools import cache
from typing import Any

from lightrocks.metamodel import ast
from lightrocks.metamodel.ast import Position, field_names

MAX_DEPTH = 200
"""Nesting of the syntax tree that later passes (typing, printing, generating) may walk
recursively without running out of stack: the typing pass takes three frames a level, so
200 levels stay well inside Python's 1,000 wherever a check runs (a command, the language
server's threads, a sweep's workers). A flat sum of terms nests one level per operator."""

EXPRESSIONS = (
    ast.Quantity,
    ast.BooleanLiteral,
    ast.StringLiteral,
    ast.VectorLiteral,
    ast.Name,
    ast.Member,
    ast.Argument,
    ast.Call,
    ast.Index,
    ast.Unary,
    ast.Binary,
    ast.ExtensionNode,
)
"""Nodes of expressions: a tree too deep mostly inside them is an expression's fault."""

TOO_DEEP_EXPRESSION = (
    f"expression nested too deeply (more than {MAX_DEPTH} levels of operators and brackets): "
    "split it with intermediate parameters"
)
TOO_DEEP_STATES = (
    f"states nested too deeply (more than {MAX_DEPTH} levels): move inner states into a "
    "statechart of their own and <<import>> it"
)


def deepest_node(root: Any) -> tuple[Position, str] | None:
    """Where the tree first nests deeper than ``MAX_DEPTH`` and what says so (expressions
    or states, by what most of the levels are), found without recursion; None when the
    tree is shallow enough."""
    pending: list[tuple[Any, int, int, Position | None]] = [(root, 0, 0, None)]
    while pending:
        node, depth, in_expressions, where = pending.pop()
        names = _field_names(type(node))
        if names is None:
            continue
        where = getattr(node, "position", where)
        in_expressions += isinstance(node, EXPRESSIONS)
        if depth > MAX_DEPTH:
            expression = 2 * in_expressions > depth
            return where, TOO_DEEP_EXPRESSION if expression else TOO_DEEP_STATES
        for name in names:
            value = getattr(node, name)
            if isinstance(value, tuple):
                pending.extend((child, depth + 1, in_expressions, where) for child in value)
            else:
                pending.append((value, depth + 1, in_expressions, where))
    return None


@cache
def _field_names(cls: type) -> tuple[str, ...] | None:
    """The field names of a node class, None for any other class and for positions (which
    hold no nodes); decided once per class."""
    return field_names(cls) if is_dataclass(cls) and cls is not Position else None


def deepest(text: str, shown: str) -> tuple[Position, str]:
    """Where the text nests deepest in brackets, else the start of its longest line: the
    best pointer to nesting too deep for the parser; states when the deepest bracket is a
    block's ``{``, else an expression."""
    depth, best, where, opened = 0, 0, None, ""
    line, column = 1, 1
    for char in text:
        if char in "([{":
            depth += 1
            if depth > best:
                best, where, opened = depth, (line, column), char
        elif char in ")]}":
            depth -= 1
        line, column = (line + 1, 1) if char == "\n" else (line, column + 1)
    if where is None or best < 8:
        lines = text.splitlines() or [""]
        longest = max(range(len(lines)), key=lambda i: len(lines[i]))
        where = (longest + 1, len(lines[longest]) - len(lines[longest].lstrip()) + 1)
        opened = ""
    message = TOO_DEEP_STATES if opened == "{" else TOO_DEEP_EXPRESSION
    return Position(shown, *where), message
