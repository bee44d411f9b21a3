"""Nesting limits of syntax trees.

Later passes (typing, printing, generating) walk the tree recursively; a tree nested deeper
than they can walk is refused where it is parsed, with the place that nests deepest.
"""

from __future__ import annotations

from dataclasses import is_dataclass
from functools import cache
from typing import Any

from lightrocks.metamodel.ast import Position, field_names

MAX_DEPTH = 100
"""Nesting of the syntax tree that later passes (typing, printing, generating) may walk
recursively without running out of stack."""

TOO_DEEP = (
    f"nested too deeply (more than {MAX_DEPTH} levels): "
    "split the expression with intermediate parameters"
)


def deepest_node(root: Any) -> Position | None:
    """The position of the first node nested deeper than ``MAX_DEPTH``, found without
    recursion; None when the tree is shallow enough."""
    pending: list[tuple[Any, int, Position | None]] = [(root, 0, None)]
    while pending:
        node, depth, where = pending.pop()
        names = _field_names(type(node))
        if names is None:
            continue
        where = getattr(node, "position", where)
        if depth > MAX_DEPTH:
            return where
        for name in names:
            value = getattr(node, name)
            if isinstance(value, tuple):
                pending.extend((child, depth + 1, where) for child in value)
            else:
                pending.append((value, depth + 1, where))
    return None


@cache
def _field_names(cls: type) -> tuple[str, ...] | None:
    """The field names of a node class, None for any other class and for positions (which
    hold no nodes); decided once per class."""
    return field_names(cls) if is_dataclass(cls) and cls is not Position else None


def deepest(text: str, shown: str) -> Position:
    """Where the text nests deepest in brackets, else the start of its longest line: the
    best pointer to an expression too deep for the parser."""
    depth, best, where = 0, 0, None
    line, column = 1, 1
    for char in text:
        if char in "([{":
            depth += 1
            if depth > best:
                best, where = depth, (line, column)
        elif char in ")]}":
            depth -= 1
        line, column = (line + 1, 1) if char == "\n" else (line, column + 1)
    if where is None or best < 8:
        lines = text.splitlines() or [""]
        longest = max(range(len(lines)), key=lambda i: len(lines[i]))
        where = (longest + 1, len(lines[longest]) - len(lines[longest].lstrip()) + 1)
    return Position(shown, *where)
