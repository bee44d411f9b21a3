"""Lines and columns of character offsets in a text, in memory that does not grow with the
number of lines: one checkpoint every :data:`STEP` characters (the line there and where
that line starts), and the newlines between a checkpoint and an offset counted by ``str``
itself. A table of every line start took 8 to 36 bytes a line (a model of five million
empty lines: up to 180 MB) and a Python loop over every character.
"""

from __future__ import annotations

import bisect
from array import array

STEP = 512
"""Characters between two checkpoints: a lookup scans at most this many."""


class Lines:
    """The lines of ``text`` (1-based lines and columns, lines ended by ``\\n``)."""

    def __init__(self, text: str) -> None:
        self.text = text
        self._lines = array("q")  # the line of each checkpoint
        self._starts = array("q")  # where that line starts
        line, start, previous = 1, 0, 0
        for at in range(0, len(text) + 1, STEP):
            newlines = text.count("\n", previous, at)
            if newlines:
                line += newlines
                start = text.rfind("\n", previous, at) + 1
            self._lines.append(line)
            self._starts.append(start)
            previous = at
        last = text.count("\n", previous)
        self.count = line + last
        """How many lines the text has (an empty text, or one ending in a newline, ends with
        an empty line, as ``text.split("\\n")`` counts)."""

    def line_column(self, offset: int) -> tuple[int, int]:
        """The line and column of ``offset`` (clamped to the text)."""
        offset = min(max(offset, 0), len(self.text))
        index = offset // STEP
        at = index * STEP
        line, start = self._lines[index], self._starts[index]
        newlines = self.text.count("\n", at, offset)
        if newlines:
            line += newlines
            start = self.text.rfind("\n", at, offset) + 1
        return line, offset - start + 1

    def start(self, line: int) -> int:
        """The offset at which ``line`` starts (the text's end for a line after the last)."""
        if line <= 1:
            return 0
        if line > self.count:
            return len(self.text)
        index = bisect.bisect_left(self._lines, line) - 1  # the last checkpoint before it
        offset, current = index * STEP, self._lines[index]
        while current < line:
            offset = self.text.index("\n", offset) + 1
            current += 1
        return offset

    def text_of(self, line: int) -> str:
        """The text of ``line`` without its newline ('' for a line after the last)."""
        if line < 1 or line > self.count:
            return ""
        start = self.start(line)
        end = self.text.find("\n", start)
        return self.text[start : len(self.text) if end < 0 else end]
