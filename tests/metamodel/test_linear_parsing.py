"""Parsing in memory linear in the text: textX's ``STRING`` rule is matched by a pattern that
keeps no state per character but finds the same matches (every text, every position), the
skipper of whitespace and comments repeats possessively, and lines and columns come from
checkpoints instead of a table of every line (the same positions as that table)."""

from __future__ import annotations

import bisect
import re

from hypothesis import given, settings
from hypothesis import strategies as st

from lightrocks.metamodel import lines
from lightrocks.metamodel.grammar import LINEAR_STRING, TEXTX_STRING
from lightrocks.metamodel.lines import Lines

ORIGINAL, LINEAR = re.compile(TEXTX_STRING), re.compile(LINEAR_STRING)
QUOTED = st.text(alphabet="a\\\"'\n ", max_size=40)


def _ends(pattern: re.Pattern[str], text: str) -> list[int | None]:
    found = [pattern.match(text, i) for i in range(len(text) + 1)]
    return [None if m is None else m.end() for m in found]


@settings(max_examples=3000, deadline=None)
@given(QUOTED)
def test_the_linear_string_matches_as_textx_does(text: str) -> None:
    assert _ends(LINEAR, text) == _ends(ORIGINAL, text)


def test_an_unclosed_string_ends_at_its_last_escaped_quote_as_in_textx() -> None:
    for text in ('"abc\\"', '"a\\" b\\" c', "'x\\' y", '"\\"', '"a\\"b"c\\"'):
        assert _ends(LINEAR, text) == _ends(ORIGINAL, text), text
    assert LINEAR.match('"a\\" b\\" c').group() == '"a\\" b\\"'


def test_the_textx_string_rule_is_the_one_replaced() -> None:
    import textx.lang

    assert textx.lang.STRING.to_match_regex in (TEXTX_STRING, LINEAR_STRING)


def _table(text: str) -> list[int]:
    return [0] + [i + 1 for i, c in enumerate(text) if c == "\n"]


@settings(max_examples=300, deadline=None)
@given(st.lists(st.integers(0, 9000), max_size=12), st.integers(0, 20))
def test_lines_and_columns_as_a_table_of_every_line_gives_them(widths, empties) -> None:
    text = "\n".join("x" * w for w in widths) + "\n" * empties
    table, found = _table(text), Lines(text)
    for offset in sorted({0, len(text), *range(0, len(text) + 1, 997), *table}):
        line = bisect.bisect_right(table, offset)
        assert found.line_column(offset) == (line, offset - table[line - 1] + 1), offset
    pieces = text.split("\n")
    assert found.count == len(table) == len(pieces)
    for line, start in enumerate(table, 1):
        assert found.start(line) == start
        assert found.text_of(line) == pieces[line - 1]


def test_checkpoints_grow_with_the_text_not_with_its_lines() -> None:
    text = "\n" * 1_000_000
    found = Lines(text)
    assert len(found._lines) == len(text) // lines.STEP + 1
    assert found.line_column(len(text)) == (1_000_001, 1)
    assert found.start(500_000) == 499_999
