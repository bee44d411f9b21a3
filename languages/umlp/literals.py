"""The literals whose texts differ between Java and LightRocks, for both directions of the
``.sc ↔ .lr`` conversion: Java string literals (escapes) and their values, and the number
texts LightRocks writes as they are.
"""

from __future__ import annotations

import re

LR_NUMBER = re.compile(r"(\d+(\.\d+)?|\.\d+)([eE][-+]?\d+)?")
"""A number LightRocks and Java both write alike (no sign, no suffix)."""

_ESCAPES = {"b": "\b", "t": "\t", "n": "\n", "f": "\f", "r": "\r", '"': '"', "'": "'", "\\": "\\"}
_ESCAPED = {value: letter for letter, value in _ESCAPES.items() if letter != "'"}


def java_string_value(literal: str) -> str:
    """The value of a Java string literal (with its quotes)."""
    body = literal[1:-1]

    def unescape(match: re.Match[str]) -> str:
        text = match.group(0)
        if text[1] == "u":
            return chr(int(text.lstrip("\\u")[:4], 16))
        if text[1] in "01234567":
            return chr(int(text[1:], 8))
        return _ESCAPES.get(text[1], text[1])

    return re.sub(r"\\(u+[0-9a-fA-F]{4}|[0-3][0-7]{0,2}|[4-7][0-7]?|.)", unescape, body)


def java_string_literal(value: str) -> str:
    """A Java string literal whose value is ``value``."""
    out = []
    for char in value:
        if char in _ESCAPED:
            out.append("\\" + _ESCAPED[char])
        elif ord(char) < 0x20:
            out.append(f"\\u{ord(char):04x}")
        else:
            out.append(char)
    return '"' + "".join(out) + '"'
