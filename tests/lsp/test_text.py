"""Model positions to LSP ranges: names are found after their node's start, never inside a
stereotype value or a qualified name when they are declared."""

from __future__ import annotations

from lsprotocol import types as lsp
from pygls.workspace import PositionCodec

from lightrocks.app.lsp.text import Text
from lightrocks.metamodel import ast


def shown(text: Text, found: lsp.Range) -> str:
    return text.lines[found.start.line][found.start.character : found.end.character]


def test_a_declared_name_skips_a_stereotype_value_of_the_same_name() -> None:
    text = Text('  <<import="Lift">> state Lift;')
    found = text.name_range(1, 3, "Lift", declared=True)
    assert found.start.character == text.source.rindex("Lift")


def test_a_reference_may_be_the_last_part_of_a_qualified_name() -> None:
    text = Text("import screwing.actions.Lift;")
    found = text.name_range(1, 1, "screwing.actions.Lift")
    assert shown(text, found) == "Lift" and found.start.character == text.source.index("Lift")


def test_a_name_on_a_later_line_and_a_missing_name() -> None:
    text = Text("<<skill>>\nstatechart Retreat {\n}")
    assert text.name_range(1, 1, "Retreat", declared=True).start == lsp.Position(1, 11)
    missing = text.name_range(2, 1, "Nowhere")
    assert shown(text, missing) == "statechart"  # the word at the position


def test_positions_outside_the_text_are_clamped() -> None:
    text = Text("ab\ncd")
    assert text.offset(7, 3) == len(text.source)
    assert text.position(text.offset(1, 9)) == lsp.Position(1, 2)
    assert text.word_at(lsp.Position(5, 0)) == "" and text.prefix(lsp.Position(1, 1)) == "c"


def test_characters_outside_the_bmp_count_as_the_encoding_says() -> None:
    source = 'x = "🤖"; y'
    offset = source.index("y")
    for encoding, character in (("utf-16", 10), ("utf-8", 12), ("utf-32", 9)):
        text = Text(source, PositionCodec(encoding))
        assert text.position(offset) == lsp.Position(0, character)
        assert text.offset(0, character) == offset
        assert text.word_at(lsp.Position(0, character)) == "y"
    inside = Text(source).offset(0, 6)  # between the emoji's two UTF-16 units
    assert inside == source.index("🤖") + 1


def test_a_model_span_becomes_a_range_and_a_name_is_found_inside_it() -> None:
    text = Text('/* 🤖 */ <<import="Up">> state Up;')
    where = ast.Position("A.lr", 1, 9, 1, 34)
    assert text.span(where) == lsp.Range(lsp.Position(0, 9), lsp.Position(0, 34))
    found = text.name_in(where, "Up", declared=True)
    assert found.start.character == text.source.rindex("Up") + 1
    assert text.span(ast.Position("A.lr", 1, 1)) is None  # no end known
