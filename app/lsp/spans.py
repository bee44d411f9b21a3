"""Where an expression ends in its text: syntax trees carry start positions only.

An expression ends where its rightmost part ends: a name, a literal, the closing bracket of
a call, an index or a vector, or the member name after a dot. Parentheses around an operand
are not part of it. Hover uses the spans to find the innermost expression under the cursor.
"""

from __future__ import annotations

import re

from lsprotocol import types as lsp

from lightrocks.app.lsp.text import BRACKET_OR_SKIPPED, WORD, Text
from lightrocks.metamodel import ast

NUMBER = re.compile(r"\d+(?:\.\d+)?(?:[eE][-+]?\d+)?")
STRING = re.compile(r"\"(?:[^\"\\\n]|\\.)*\"?|'(?:[^'\\\n]|\\.)*'?")
CLOSING = {"(": ")", "[": "]"}


def span(text: Text, expression: ast.Expression) -> lsp.Range | None:
    """The range of an expression, or ``None`` where the text does not hold it (a buffer
    changed since the check)."""
    if expression.position.line <= 0:
        return None
    end = _end(text, expression)
    return None if end is None else text.range(_start(text, expression), end)


def _start(text: Text, node: ast.Expression) -> int:
    return text.offset(node.position.line - 1, node.position.column - 1)


def _end(text: Text, node: ast.Expression) -> int | None:
    source, start = text.source, _start(text, node)
    match node:
        case ast.Binary(right=last) | ast.Unary(operand=last):
            return _end(text, last)
        case ast.Member(target=target, name=name):
            return _after(text, target, rf"\s*\.\s*{re.escape(name)}\b")
        case ast.Call(function=target) | ast.Index(target=target):
            opening = "(" if isinstance(node, ast.Call) else "["
            after = _after(text, target, rf"\s*{re.escape(opening)}")
            return None if after is None else _closing(source, after - 1)
        case ast.VectorLiteral():
            return _closing(source, start)
        case ast.StringLiteral():
            return _matched(STRING, source, start)
        case ast.Quantity(unit=unit):
            end = _matched(NUMBER, source, start)
            if end is None or not unit:
                return end
            with_unit = re.compile(rf"\s*{re.escape(unit)}(?![\w/])").match(source, end)
            return with_unit.end() if with_unit else end
        case ast.Name() | ast.BooleanLiteral():
            return _matched(WORD, source, start)
    return None


def _after(text: Text, target: ast.Expression, pattern: str) -> int | None:
    """The end of ``pattern`` right after ``target``."""
    end = _end(text, target)
    found = None if end is None else re.compile(pattern).match(text.source, end)
    return found.end() if found else None


def _matched(pattern: re.Pattern[str], source: str, start: int) -> int | None:
    found = pattern.match(source, start)
    return found.end() if found else None


def _closing(source: str, opening: int) -> int | None:
    """The end of the bracket group whose opening bracket is at ``opening``."""
    if source[opening : opening + 1] not in CLOSING:
        return None
    depth = 0
    for found in BRACKET_OR_SKIPPED.finditer(source, opening):
        token = found.group()
        if token in CLOSING:
            depth += 1
        elif token in CLOSING.values():
            depth -= 1
            if depth == 0:
                return found.end()
    return None
