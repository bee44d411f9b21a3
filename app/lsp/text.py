"""Source text seen as LSP positions.

Model positions count code points from 1; LSP positions count from 0 in the code units the
client and server agreed on at initialization (UTF-16 unless the client offers UTF-8 or
UTF-32), converted by pygls's position codec. Every range handed to the client comes from
here, so an emoji in a comment moves no finding off its name.
"""

from __future__ import annotations

import bisect
import re
from functools import cached_property

from lsprotocol import types as lsp
from pygls.workspace import PositionCodec

from lightrocks.metamodel import ast

WORD = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
UTF16 = PositionCodec()
"""LSP's default encoding, for a text no client has negotiated."""


class Text:
    """One file's text with the offset arithmetic the features need."""

    def __init__(self, source: str, codec: PositionCodec = UTF16) -> None:
        self.source = source
        self.codec = codec

    @cached_property
    def lines(self) -> list[str]:
        return self.source.split("\n")

    @cached_property
    def starts(self) -> list[int]:
        offsets, total = [], 0
        for line in self.lines:
            offsets.append(total)
            total += len(line) + 1
        return offsets

    # -- offsets and positions --------------------------------------------------------------

    def offset(self, line: int, character: int) -> int:
        """The offset of a 0-based line and character (in client units), clamped into the
        text."""
        if line >= len(self.lines):
            return len(self.source)
        line = max(line, 0)
        return self.starts[line] + self.column(line, character)

    def at(self, position: lsp.Position) -> int:
        return self.offset(position.line, position.character)

    def column(self, line: int, character: int) -> int:
        """The code points before a character (in client units) of a 0-based line."""
        text = self.lines[line] if 0 <= line < len(self.lines) else ""
        character = max(character, 0)
        if text.isascii():
            return min(character, len(text))
        units = 0
        for index, char in enumerate(text):
            if units >= character:
                return index
            units += self.codec.client_num_units(char)
        return len(text)

    def position(self, offset: int) -> lsp.Position:
        offset = min(max(offset, 0), len(self.source))
        line = bisect.bisect_right(self.starts, offset) - 1
        before = self.source[self.starts[line] : offset]
        return lsp.Position(line, len(before) if before.isascii() else self._units(before))

    def range(self, start: int, end: int) -> lsp.Range:
        return lsp.Range(self.position(start), self.position(end))

    def model_offset(self, line: int, column: int) -> int:
        """The offset of a 1-based model line and column (code points), clamped."""
        if line > len(self.lines):
            return len(self.source)
        line = max(line, 1)
        return self.starts[line - 1] + min(max(column - 1, 0), len(self.lines[line - 1]))

    def span(self, where: ast.Position) -> lsp.Range | None:
        """The range a model position spans, or ``None`` where its end is unknown."""
        if not where.has_end or where.line <= 0:
            return None
        start = self.model_offset(where.line, where.column)
        return self.range(start, self.model_offset(where.end_line, where.end_column))

    def _units(self, text: str) -> int:
        return self.codec.client_num_units(text)

    # -- names ------------------------------------------------------------------------------

    def name_in(self, where: ast.Position, name: str, declared: bool = False) -> lsp.Range:
        """``name`` inside the span of a model position (see :meth:`name_range`)."""
        start, end = self.model_offset(where.line, where.column), len(self.source)
        if where.has_end:
            end = self.model_offset(where.end_line, where.end_column)
        return self._name(start, end, name, declared)

    def name_range(self, line: int, column: int, name: str, declared: bool = False) -> lsp.Range:
        """The first whole-word ``name`` (its last dotted part) at or after a 1-based model
        position; the word there when ``name`` does not follow."""
        return self._name(self.model_offset(line, column), len(self.source), name, declared)

    def _name(self, start: int, end: int, name: str, declared: bool) -> lsp.Range:
        """The first whole-word ``name`` (its last dotted part) between two offsets, else
        the word at ``start``. A declared name is never inside a string or after a dot,
        where a stereotype value or an import may repeat it."""
        last = name.rpartition(".")[2]
        if last:
            before = r"(?<![A-Za-z0-9_\".])" if declared else r"(?<![A-Za-z0-9_])"
            found = re.compile(rf"{before}{re.escape(last)}(?![A-Za-z0-9_])")
            match = found.search(self.source, start, end)
            if match:
                return self.range(match.start(), match.end())
        return self.word_range(start)

    def word_range(self, offset: int) -> lsp.Range:
        match = WORD.match(self.source, offset)
        return self.range(offset, match.end() if match else offset)

    def word_at(self, position: lsp.Position) -> str:
        """The identifier touching a cursor position, or an empty string."""
        if position.line >= len(self.lines):
            return ""
        column = self.column(position.line, position.character)
        for match in WORD.finditer(self.lines[position.line]):
            if match.start() <= column <= match.end():
                return match.group()
        return ""

    def prefix(self, position: lsp.Position) -> str:
        """The line up to the cursor."""
        if position.line >= len(self.lines):
            return ""
        return self.lines[position.line][: self.column(position.line, position.character)]

    def end(self) -> lsp.Position:
        return self.position(len(self.source))


def contains(outer: lsp.Range, position: lsp.Position) -> bool:
    start, end = outer.start, outer.end
    after = (position.line, position.character) >= (start.line, start.character)
    return after and (position.line, position.character) <= (end.line, end.character)
