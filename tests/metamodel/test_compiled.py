"""The compiled parser accepts what Arpeggio accepts and builds the very same parse tree."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest
from arpeggio import EndOfFile, NonTerminal, Terminal
from hypothesis import given, settings
from hypothesis import strategies as st
from peg_models import PEG, ROOT, model_files, peg_grammars
from textx import TextXSyntaxError, metamodel_from_str

from lightrocks.languages.domain import syntax as domain
from lightrocks.languages.lightrocks import syntax as lightrocks
from lightrocks.metamodel.compiled import compile_parser
from lightrocks.metamodel.grammar import textx_metamodel


def shape(node: Any) -> tuple:
    """Everything of a parse-tree node that a reader could look at."""
    rule = "EOF" if isinstance(node.rule, EndOfFile) else id(node.rule)
    common = (type(node).__name__, rule, node.rule_name, node.position, node.position_end)
    if isinstance(node, Terminal):
        return (*common, node.value, node.suppress, node.error)
    assert isinstance(node, NonTerminal)
    return (*common, node.error, tuple(shape(child) for child in node))


def arpeggio_shape(metamodel: Any, text: str) -> tuple | None:
    parser = metamodel._parser_blueprint.clone()
    try:
        parser.parse(text)
    except TextXSyntaxError:
        return None
    return shape(parser.parse_tree)


def compiled_shape(metamodel: Any, text: str) -> tuple | None:
    parse = compile_parser(metamodel._parser_blueprint)
    assert parse is not None, "the parser model should compile"
    tree = parse(text)
    return None if tree is None else shape(tree)


def agree(metamodel: Any, text: str) -> tuple | None:
    """Assert both parsers agree on ``text``; the tree, or None where both reject it."""
    expected = arpeggio_shape(metamodel, text)
    assert compiled_shape(metamodel, text) == expected
    return expected


def language_metamodel(file: Path, monkeypatch: pytest.MonkeyPatch) -> Any:
    language = lightrocks if file.suffix == ".lr" else domain
    extensions = lightrocks.grammar_extensions() if file.suffix == ".lr" else ()
    if file.suffix == ".lr" and file.is_relative_to(PEG):
        extensions += peg_grammars(monkeypatch)
    return textx_metamodel(language.GRAMMAR, language.FRAGMENTS, extensions)


@pytest.mark.parametrize("file", model_files(), ids=lambda f: str(f.relative_to(ROOT)))
def test_every_model_file_gives_arpeggios_tree(file: Path, monkeypatch) -> None:
    text = file.read_text(encoding="utf-8")
    assert agree(language_metamodel(file, monkeypatch), text) is not None


EDITS = st.lists(
    st.tuples(
        st.sampled_from(["delete", "insert", "repeat"]),
        st.floats(0, 1),
        st.integers(1, 12),
        st.sampled_from(
            [
                "",
                ";",
                "{",
                "}",
                "->",
                "[",
                "]",
                "(",
                ")",
                "state ",
                "x",
                "1 mm",
                "//c\n",
                "/*",
                "*/",
                "<<",
                ">>",
                ",",
                "=",
                ".",
                "\n",
            ]
        ),
    ),
    min_size=1,
    max_size=4,
)


def edited(text: str, edits: list[tuple[str, float, int, str]]) -> str:
    for kind, where, length, token in edits:
        at = int(where * len(text))
        if kind == "delete":
            text = text[:at] + text[at + length :]
        elif kind == "insert":
            text = text[:at] + token + text[at:]
        else:
            text = text[:at] + text[at : at + length] + text[at:]
    return text


SAMPLES = [f for f in model_files() if f.suffix == ".lr" and not f.is_relative_to(PEG)][:12]


@settings(max_examples=150, deadline=None)
@given(st.sampled_from(SAMPLES), EDITS)
def test_edited_models_are_accepted_and_rejected_alike(file: Path, edits) -> None:
    metamodel = textx_metamodel(lightrocks.GRAMMAR, lightrocks.FRAGMENTS, ())
    agree(metamodel, edited(file.read_text(encoding="utf-8"), edits))


QUIRKS = r"""
Model: 'model' lists*=List extras*=Extra 'end';
List: 'list' items*=ID[','] open?=',' ';' numbers+=INT[','] tags=Tags?;
Tags: '#' names*=ID;
Extra: Bracket | Plus | Named | Flag;
Bracket: '(' (inner*=ID)? ')';
Plus: &'+' '+' value=INT;
Named: !'end' !'list' name=Qualified;
Qualified: ID ('.' ID)*;
Flag: marked?='!' 'flag' kind=Kind;
Kind: 'on' | 'off';
Comment: /\/\/.*?$|\/\*(.|\n)*?\*\//;
"""


@pytest.mark.parametrize(
    "text",
    [
        "model end",
        "model list a, b, ; 1 end",  # a trailing separator stays in the tree
        "model list ; 1, 2 # list a; 3 # x y end",
        "model ( ) ( a b ) + 3 a.b.c ! flag on flag off end",
        "model /* one */ list // two\n a ; 1 // three\n end",
        "model list a ; end",  # one or more numbers: none
        "model + end",
        "model ( a end",
        "model flag maybe end",
        "model end trailing",
        "",
    ],
)
def test_every_kind_of_expression_gives_arpeggios_tree(text: str) -> None:
    agree(metamodel_from_str(QUIRKS, autokwd=True), text)


def commas(tree: tuple) -> list[int]:
    """Positions of the ',' terminals of a tree shape."""
    if tree[0] == "Terminal":
        return [tree[3]] if tree[5] == "," else []
    return [at for child in tree[-1] for at in commas(child)]


def test_a_trailing_separator_is_kept_where_the_next_rule_matches_it_again() -> None:
    metamodel = metamodel_from_str(QUIRKS, autokwd=True)
    tree = agree(metamodel, "model list a, b, ; 1 end")
    assert tree is not None
    assert commas(tree) == [12, 15, 15]
    assert agree(metamodel, "model list a ; end") is None


@pytest.mark.parametrize(
    ("grammar", "options"),
    [
        ("Model: 'a' words*=Word; Word[noskipws]: /\\w+/ ' ';", {}),
        ("Model: 'a' words*=ID;", {"memoization": True}),
        ("Model: 'a' words*=ID; Comment: '#' /.*$/;", {}),
    ],
    ids=["whitespace of a rule", "memoization", "comment rule of two parts"],
)
def test_a_parser_model_it_cannot_reproduce_is_not_compiled(grammar: str, options) -> None:
    metamodel = metamodel_from_str(grammar, **options)
    assert compile_parser(metamodel._parser_blueprint) is None
