"""The base protocol's frames on a byte stream: ``Content-Length: N`` (and ``Content-Type``)
header lines, a blank line, N bytes of body.

A frame whose header is broken (no length, one that is no number or over ``MAX_BODY``, a line
that is no header) is reported as such, and the reader finds the next frame by its header
line: a broken frame costs that frame, never the session. Nothing is read into memory beyond
``MAX_BODY`` bytes.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import BinaryIO

MAX_BODY = 64 * 1024 * 1024
"""The largest message body read (bytes): a model far over the size a model may have."""
LINE = 64 * 1024
"""The longest header line read at once; a longer one is no header."""
KEPT = 1024 * 1024
"""What is kept of the bytes skipped after a broken header, to answer the request in them."""

_HEADER = re.compile(rb"(?i)(content-length|content-type)[ \t]*:[ \t]*([^\r\n]*?)[ \t]*\r?\n\Z")


@dataclass
class Frame:
    """A message body, or what was wrong with a frame (``problem``). ``skipped`` holds the
    bytes between a broken header and the next frame: the body of the broken frame, which
    may still name the request to answer."""

    body: bytes = b""
    problem: str = ""
    skipped: bytes = b""


class FrameReader:
    def __init__(self, stream: BinaryIO) -> None:
        self.stream = stream
        self._next_line = b""
        """A header line already read: the start of the next frame."""
        self._resync = False
        """After a broken header: skip to the next header line first."""

    def next(self) -> Frame | None:
        """The next frame; ``None`` at the end of the stream."""
        if self._resync:
            self._resync = False
            skipped = self._skip()
            if skipped is None:
                return None
            if skipped.strip():
                return Frame(problem="bytes outside any frame", skipped=skipped)
        length: int | None = None
        seen = False
        while True:
            line = self._line()
            if not line:
                return None
            if line in (b"\r\n", b"\n"):
                if seen:
                    break
                continue  # blank lines between frames
            seen = True
            header = _HEADER.search(line)
            if header is None:
                return self._broken("a line that is no header (Content-Length: N expected)")
            if header.start() > 0:  # the end of a body longer than its Content-Length said
                self._next_line = line[header.start() :]
                return Frame(problem="bytes outside any frame", skipped=line[: header.start()])
            if header.group(1).lower() == b"content-length":
                value = header.group(2)
                if not value.isdigit():
                    return self._broken(f"Content-Length {value[:40]!r} is no number of bytes")
                if int(value) > MAX_BODY:
                    return self._broken(f"Content-Length {int(value)} is over {MAX_BODY}")
                length = int(value)
        if length is None:
            return self._broken("the header has no Content-Length")
        body = self._read(length)
        return None if body is None else Frame(body=body)

    def _broken(self, problem: str) -> Frame:
        """A broken header: the reader goes on at the next header line."""
        self._resync = True
        return Frame(problem=problem)

    def _line(self) -> bytes:
        if self._next_line:
            line, self._next_line = self._next_line, b""
            return line
        return self.stream.readline(LINE)

    def _read(self, length: int) -> bytes | None:
        body = self.stream.read(length) if length else b""
        return body if len(body) == length else None

    def _skip(self) -> bytes | None:
        """Read up to the next header line (kept for ``next``); what came before it."""
        kept = bytearray()
        while True:
            chunk = self.stream.readline(LINE)
            if not chunk:
                return None
            header = _HEADER.search(chunk)
            if header is not None:
                self._next_line = chunk[header.start() :]
                chunk = chunk[: header.start()]
            if len(kept) < KEPT:
                kept += chunk[: KEPT - len(kept)]
            if header is not None:
                return bytes(kept)
