"""Comments of a source text, found again after parsing, because textX drops them.

A formatter that loses comments loses user work, so the printers re-attach every comment
found here by its position (see :class:`metamodel.printer.Writer`). The scan mirrors the
lexer of the grammars: ``//`` to the end of the line and ``/* … */``, except inside string
literals. It also records the braces outside strings and comments (to locate the closing
brace of a block, which the AST does not record) and which lines are blank.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from lightrocks.metamodel import ast
from lightrocks.metamodel.grammar import LINEAR_STRING
from lightrocks.metamodel.lines import Lines

# textX's STRING rule: a double- or single-quoted literal where only the quote is escaped.
STRING = re.compile(LINEAR_STRING)  # as the grammar matches a string, in constant memory


@dataclass(frozen=True)
class Comment:
    """One comment with its text as written, from ``//`` or ``/*`` to its end."""

    text: str
    line: int
    column: int
    end_line: int
    own_line: bool  # nothing but whitespace before it on its line

    @property
    def start(self) -> tuple[int, int]:
        return (self.line, self.column)


class Comments:
    """The comments, braces and blank lines of one text: what the AST does not record."""

    def __init__(self, text: str) -> None:
        self._lines = Lines(text)
        self._braces: list[tuple[int, str]] = []
        found: list[Comment] = []
        index = 0
        while index < len(text):
            char = text[index]
            if char in "\"'":
                literal = STRING.match(text, index)
                index = literal.end() if literal else index + 1
            elif text.startswith("//", index):
                end = text.find("\n", index)
                end = len(text) if end < 0 else end
                found.append(self._comment(text, index, end, text[index:end].rstrip()))
                index = end
            elif text.startswith("/*", index):
                end = text.find("*/", index + 2)
                end = len(text) if end < 0 else end + 2
                found.append(self._comment(text, index, end, text[index:end]))
                index = end
            else:
                if char in "{}":
                    self._braces.append((index, char))
                index += 1
        self.comments = tuple(found)

    def _comment(self, text: str, start: int, end: int, body: str) -> Comment:
        line, column = self._line_column(start)
        own_line = not text[start - column + 1 : start].strip()
        return Comment(body, line, column, self._line_column(max(start, end - 1))[0], own_line)

    def _line_column(self, offset: int) -> tuple[int, int]:
        return self._lines.line_column(offset)

    def closing_brace(self, position: ast.Position) -> tuple[int, int]:
        """Where the ``}`` matching the first ``{`` at or after ``position`` is."""
        offset = self._lines.start(position.line) + position.column - 1
        depth = 0
        for where, char in self._braces:
            if where < offset:
                continue
            depth += 1 if char == "{" else -1
            if depth == 0:
                return self._line_column(where)
        return (self._lines.count + 1, 0)

    def blank(self, line: int) -> bool:
        """Whether source line ``line`` holds nothing but whitespace."""
        return 1 <= line <= self._lines.count and not self._lines.text_of(line).strip()
