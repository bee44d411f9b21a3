"""Boolean conditions as Structured Text strings: grouping, negation and conjunction.

Conditions are built from compiled expressions, so they are combined as text. A parenthesis
inside an ST string literal (``'a(b'``, with ``$`` escapes) is a character of the
string, never structure: a group is found by reading the text outside the literals.
"""

from __future__ import annotations

from lightrocks.generators.sfc_iec61131.expressions import outside_strings


def balanced(text: str) -> bool:
    """Every parenthesis of ``text`` outside its string literals is closed, in order."""
    depth = 0
    for _, character in outside_strings(text):
        depth += {"(": 1, ")": -1}.get(character, 0)
        if depth < 0:
            return False
    return depth == 0


def group(condition: str) -> str:
    """``condition`` safe to negate or combine."""
    if (
        not condition
        or condition.isidentifier()
        or (condition.startswith("(") and condition.endswith(")") and balanced(condition[1:-1]))
    ):
        return condition
    return f"({condition})"


def negate(condition: str) -> str:
    """``NOT condition``, without a double negation."""
    if condition.startswith("NOT "):
        rest = condition[4:]
        if group(rest) == rest:
            return rest
    return f"NOT {group(condition)}"


def conjunction(conditions: list[str]) -> str:
    """The conditions joined by ``AND``; empty and ``TRUE`` ones left out."""
    parts = [c for c in conditions if c and c != "TRUE"]
    if not parts:
        return "TRUE"
    if len(parts) == 1:
        return parts[0]
    return " AND ".join(group(p) for p in parts)
