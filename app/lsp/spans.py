"""Where an expression lies in its text, from the spans its parts carry.

An expression reaches from the first start to the last end of its nodes: a member's own span
starts at its dot and a binary expression's at its left operand, so the parts are what tell
where the whole begins. Parentheses around an operand are not part of it. Hover uses the
spans to find the innermost expression under the cursor.
"""

from __future__ import annotations

from lsprotocol import types as lsp

from lightrocks.app.lsp.text import Text
from lightrocks.metamodel import ast


def span(text: Text, expression: ast.Expression) -> lsp.Range | None:
    """The range of an expression, or ``None`` where no part of it has a known span."""
    parts = [
        where
        for node in ast.walk(expression)
        if isinstance(where := getattr(node, "position", None), ast.Position) and where.has_end
    ]
    if not parts:
        return None
    first = min(parts, key=lambda p: (p.line, p.column))
    last = max(parts, key=lambda p: (p.end_line, p.end_column))
    return text.span(first.through(last))
