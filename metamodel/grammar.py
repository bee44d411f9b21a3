"""Composition of textX grammars from fragments, and parsing with positions.

A language's grammar is its own root fragment followed by the shared fragments of this
package (common rules, expressions, statecharts). The root fragment comes first because
textX takes the first rule as the root of the model.
"""

from __future__ import annotations

import gc
from collections.abc import Iterator
from contextlib import contextmanager
from functools import cache
from pathlib import Path

from textx import TextXSyntaxError, metamodel_from_str

FRAGMENTS = Path(__file__).parent


class SyntaxProblem(Exception):
    """A text that does not match the grammar, located at line and column."""

    def __init__(self, message: str, line: int, column: int) -> None:
        super().__init__(f"{line}:{column}: {message}")
        self.message = message
        self.line = line
        self.column = column


def compose(root: Path, *fragments: str) -> str:
    """Grammar text of ``root`` followed by the named fragments of this package."""
    parts = [root.read_text(encoding="utf-8")]
    parts += [(FRAGMENTS / f"{name}.tx").read_text(encoding="utf-8") for name in fragments]
    return "\n".join(parts)


@cache
def textx_metamodel(root: Path, fragments: tuple[str, ...]):
    """The textX metamodel of a composed grammar, built once per process."""
    return metamodel_from_str(compose(root, *fragments), autokwd=True, skipws=True)


def parse(root: Path, fragments: tuple[str, ...], text: str, file: str):
    """Parse ``text``; raise :class:`SyntaxProblem` with a readable message on mismatch."""
    metamodel = textx_metamodel(root, fragments)
    try:
        return metamodel.model_from_str(text, file_name=file)
    except TextXSyntaxError as error:
        raise SyntaxProblem(_describe(error), error.line or 1, error.col or 1) from None


@contextmanager
def paused_gc() -> Iterator[None]:
    """Pause the cyclic garbage collector while building trees.

    Parsing and conversion allocate hundreds of thousands of acyclic objects; the collector
    would rescan the growing tree again and again, which made large models grow
    super-linearly (6.5 s instead of 3 s for 10,000 states).
    """
    collecting = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if collecting:
            gc.enable()


def _describe(error: TextXSyntaxError) -> str:
    expected = sorted({_rule_text(rule) for rule in (error.expected_rules or [])})
    found = error.context.split("*")[-1].strip().split()[:1] if error.context else []
    if expected:
        shown = ", ".join(expected[:6]) + (", …" if len(expected) > 6 else "")
        where = f" but found '{found[0]}'" if found else " but the file ends here"
        return f"syntax error: expected {shown}{where}"
    return f"syntax error: {error.message}"


def _rule_text(rule: object) -> str:
    text = getattr(rule, "to_match", None)
    if isinstance(text, str) and not getattr(rule, "regex", None):
        return f"'{text}'"
    name = getattr(rule, "rule_name", "") or getattr(rule, "name", "")
    return _FRIENDLY.get(name, name or str(rule))


_FRIENDLY = {
    "ID": "a name",
    "STRING": "a string",
    "INT": "an integer",
    "Number": "a number",
    "UnitSymbol": "a unit",
    "Comment": "a comment",
}
