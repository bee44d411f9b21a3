"""Source text seen as LSP positions: 1-based model positions become 0-based ranges of names."""

from __future__ import annotations

import bisect
import re
from functools import cached_property

from lsprotocol import types as lsp

WORD = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
SKIPPED = (
    r"//[^\n]*"  # a line comment
    r"|/\*.*?(?:\*/|\Z)"  # a block comment, or an unclosed one
    r"|\"(?:[^\"\\\n]|\\.)*\"?"  # a string, or an unclosed one
    r"|'(?:[^'\\\n]|\\.)*'?"
)
BRACE_OR_SKIPPED = re.compile(SKIPPED + r"|[{}]", re.S)
BRACKET_OR_SKIPPED = re.compile(SKIPPED + r"|[()\[\]]", re.S)


class Text:
    """One file's text with the offset arithmetic the features need."""

    def __init__(self, source: str) -> None:
        self.source = source

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

    def offset(self, line: int, character: int) -> int:
        """The offset of a 0-based line and character, clamped into the text."""
        if line >= len(self.lines):
            return len(self.source)
        return self.starts[max(line, 0)] + min(max(character, 0), len(self.lines[max(line, 0)]))

    def position(self, offset: int) -> lsp.Position:
        line = bisect.bisect_right(self.starts, offset) - 1
        return lsp.Position(line, offset - self.starts[line])

    def range(self, start: int, end: int) -> lsp.Range:
        return lsp.Range(self.position(start), self.position(end))

    def name_range(self, line: int, column: int, name: str, declared: bool = False) -> lsp.Range:
        """The first whole-word ``name`` (its last dotted part) at or after a 1-based model
        position; the word there when ``name`` does not follow. A declared name is never
        inside a string or after a dot, where a stereotype value or an import may repeat it."""
        start = self.offset(line - 1, column - 1)
        last = name.rpartition(".")[2]
        if last:
            before = r"(?<![A-Za-z0-9_\".])" if declared else r"(?<![A-Za-z0-9_])"
            found = re.compile(rf"{before}{re.escape(last)}(?![A-Za-z0-9_])")
            match = found.search(self.source, start)
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
        for match in WORD.finditer(self.lines[position.line]):
            if match.start() <= position.character <= match.end():
                return match.group()
        return ""

    def prefix(self, position: lsp.Position) -> str:
        """The line up to the cursor."""
        if position.line >= len(self.lines):
            return ""
        return self.lines[position.line][: position.character]

    def block(self, line: int, column: int) -> lsp.Range:
        """The braces of the first block at or after a 1-based model position, or what the
        text holds of it while it is unclosed; comments and strings are skipped."""
        start = self.offset(line - 1, column - 1)
        depth, opened = 0, None
        for match in BRACE_OR_SKIPPED.finditer(self.source, start):
            if match.group() == "{":
                depth += 1
                opened = match.start() if opened is None else opened
            elif match.group() == "}" and opened is not None:
                depth -= 1
                if depth == 0:
                    return self.range(opened, match.end())
        return self.range(start if opened is None else opened, len(self.source))

    def end(self) -> lsp.Position:
        return lsp.Position(len(self.lines) - 1, len(self.lines[-1]))


def contains(outer: lsp.Range, position: lsp.Position) -> bool:
    start, end = outer.start, outer.end
    after = (position.line, position.character) >= (start.line, start.character)
    return after and (position.line, position.character) <= (end.line, end.character)
