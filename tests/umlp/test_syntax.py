"""UML/P statecharts as MontiCore writes them (``.sc``): every construct of the grammar
parses, prints back to an equal syntax tree and keeps its comments; the language is found
through the ``lightrocks.languages`` entry point like one of a separate package."""

from __future__ import annotations

import dataclasses
import re
from importlib.metadata import entry_points
from pathlib import Path

import pytest

from lightrocks.languages.umlp import nodes as n
from lightrocks.languages.umlp.printer import format_sc_text, print_sc
from lightrocks.languages.umlp.syntax import parse_sc
from lightrocks.metamodel import ast
from lightrocks.metamodel.grammar import SyntaxProblem
from lightrocks.workbench.languages import language_for

MODELS = Path(__file__).with_name("models")
FILES = sorted(MODELS.rglob("*.sc"))


def _nodes(unit: object) -> list[object]:
    return list(ast.walk(unit))


def test_the_models_exist() -> None:
    assert {f.relative_to(MODELS).as_posix() for f in FILES} >= {
        "syntax/Everything.sc",
        "syntax/Unnamed.sc",
        "shared/Door.sc",
        "runnable/Counter.sc",
    }


@pytest.mark.parametrize("file", FILES, ids=lambda f: f.relative_to(MODELS).as_posix())
def test_prints_back_to_an_equal_tree(file: Path) -> None:
    text = file.read_text(encoding="utf-8")
    unit = parse_sc(text, str(file))
    printed = format_sc_text(text, str(file))
    assert parse_sc(printed, str(file)) == unit
    assert format_sc_text(printed, str(file)) == printed  # canonical: printing is stable
    assert parse_sc(print_sc(unit), str(file)) == unit  # also without the source's comments


@pytest.mark.parametrize("file", FILES, ids=lambda f: f.relative_to(MODELS).as_posix())
def test_no_comment_is_lost(file: Path) -> None:
    text = file.read_text(encoding="utf-8")
    printed = format_sc_text(text, str(file))
    comments = re.findall(r"//[^\n]*|/\*[\s\S]*?\*/", text)
    assert comments
    for comment in comments:
        assert comment.strip() in printed


NODE_TYPES = {
    value
    for value in vars(n).values()
    if isinstance(value, type) and dataclasses.is_dataclass(value)
    if value.__module__ == n.__name__
}

BINARY = "+ - * / % < > <= >= == != && || & | ^ << >> >>>"
ASSIGNING = "= += -= *= /= %= &= |= ^= <<= >>= >>>="
PREFIX = "++ -- + - ! ~"


def test_the_models_use_every_construct_of_the_grammar() -> None:
    found = [node for file in FILES for node in _nodes(parse_sc(file.read_text(), str(file)))]
    assert NODE_TYPES - {type(node) for node in found} == set()
    binary = {node.operator for node in found if isinstance(node, n.JBinary)}
    assert binary == set(BINARY.split(" "))
    assigned = {node.operator for node in found if isinstance(node, n.JAssignment)}
    assert assigned == set(ASSIGNING.split(" "))
    prefix = {node.operator for node in found if isinstance(node, n.JPrefix)}
    assert prefix == set(PREFIX.split(" "))
    assert {node.operator for node in found if isinstance(node, n.JPostfix)} == {"++", "--"}
    literals = {node.kind for node in found if isinstance(node, n.JLiteral)}
    assert literals == {"null", "boolean", "char", "string", "number"}
    assert {node.keyword for node in found if isinstance(node, n.SCStatechart)} == {
        "statechart",
        "automaton",
    }
    assert {node.kind for node in found if isinstance(node, n.SCAction)} == {
        "entry",
        "exit",
        "do",
    }
    assert {node.keyword for node in found if isinstance(node, n.JJump)} == {"break", "continue"}
    states = [node for node in found if isinstance(node, n.SCState)]
    assert any(s.initial and s.final for s in states)
    assert any(s.ante is not None and s.body for s in states)  # ante, invariant and body
    assert any(s.body == () for s in states)  # `{ }`
    events = [node for node in found if isinstance(node, n.SCEvent)]
    assert {e.arguments is None for e in events} == {True, False}  # `close` and `close()`
    assert any("." in e.name for e in events)
    assert {c.complete for c in found if isinstance(c, n.SCCompleteness)} == {True, False}


ISSUE_FRAGMENTS = {
    "a }; after a state body": "statechart A { state S { state T; }; }",
    "an ante block before an initial state": "statechart A { initial { x(); } state S; }",
    "events with parentheses and arguments": "statechart A { state S; S -> S go(1, a.b); }",
    "typed event declarations": "statechart A { event java.lang.Integer f(boolean b); }",
    "automaton": "automaton A { }",
    "completeness markers": "statechart A { (c) state S { (...) }; }",
    "postconditions after the action": "statechart A { state S; S -> S e / { x(); } [y]; }",
    "Java statements in actions": "statechart A { state S { entry / { int i = 0; i++; } }; }",
}
"""What issue 38 found LightRocks' own syntax refuse in MontiCore's models."""


@pytest.mark.parametrize("text", ISSUE_FRAGMENTS.values(), ids=ISSUE_FRAGMENTS.keys())
def test_what_lightrocks_syntax_refused_is_read(text: str) -> None:
    unit = parse_sc(text, "A.sc")
    assert parse_sc(print_sc(unit), "A.sc") == unit


@pytest.mark.parametrize(
    ("text", "line", "column"),
    [
        ("statechart A {\n  state S { state T; }\n}\n", 3, 1),  # MontiCore wants `};`
        ("statechart A {\n  S -> T [x +] e;\n}\n", 2, 14),
        ("statechart A {\n  entry / { x(); }\n}\n", 2, 9),  # entry belongs to a state
    ],
)
def test_a_syntax_error_is_located(text: str, line: int, column: int) -> None:
    with pytest.raises(SyntaxProblem) as problem:
        parse_sc(text, "A.sc")
    assert (problem.value.line, problem.value.column) == (line, column)
    assert problem.value.message.startswith("syntax error")


def test_brackets_and_literals_print_as_written() -> None:
    text = "statechart A { state S [((a)) && -(-b) > - -c == 0x1F + 1.5e3f + '\\n']; }"
    unit = parse_sc(text, "A.sc")
    printed = print_sc(unit)
    assert "[((a)) && -(-b) > - -c == 0x1F + 1.5e3f + '\\n']" in printed


def test_the_language_comes_through_the_entry_point() -> None:
    found = {e.name: e.value for e in entry_points(group="lightrocks.languages")}
    assert found["umlp"] == "lightrocks.languages.umlp:LANGUAGE"
    language = language_for(".sc")
    assert language is not None and language.name == "umlp"
    assert language_for(".aut") is language
    unit = language.parse("statechart A { }", "A.sc")
    assert language.declarations(unit) == []  # nothing in the workbench's symbol table
    assert unit.imports == () and unit.declarations == ()


def _shape(node: n.JExpression) -> str:
    """The tree of an expression with every binary operation in brackets."""
    match node:
        case n.JBinary(operator=operator, left=left, right=right):
            return f"({_shape(left)} {operator} {_shape(right)})"
        case n.JPrefix(operator=operator, operand=operand):
            return f"{operator}{_shape(operand)}"
        case n.JConditional(condition=c, then=t, otherwise=o):
            return f"({_shape(c)} ? {_shape(t)} : {_shape(o)})"
        case n.JBracket(expression=inner):
            return f"[{_shape(inner)}]"
    return node.name if isinstance(node, n.JName) else node.text


@pytest.mark.parametrize(
    ("text", "shape"),
    [
        (
            "a || b && c | d ^ e & f == g < h << i + j * k",
            ("(a || (b && (c | (d ^ (e & (f == (g < (h << (i + (j * k))))))))))"),
        ),
        (
            "a * b + c << d < e == f & g ^ h | i && j || k",
            ("((((((((((a * b) + c) << d) < e) == f) & g) ^ h) | i) && j) || k)"),
        ),
        ("a - b - c / d / e % f", "((a - b) - (((c / d) / e) % f))"),
        ("a == b != c < d >= e", "((a == b) != ((c < d) >= e))"),
        (
            "!a && -b < (c + d) * e ? f : g ? h : i",
            ("((!a && (-b < ([(c + d)] * e))) ? f : (g ? h : i))"),
        ),
    ],
)
def test_java_precedence(text: str, shape: str) -> None:
    unit = parse_sc(f"statechart A {{ state S [{text}]; }}", "A.sc")
    assert _shape(unit.statechart.elements[0].invariant) == shape


@pytest.mark.parametrize(
    "guard",
    ["(" * 150 + "a" + ")" * 150, " + ".join(["a"] * 500)],
    ids=["brackets", "a long sum"],
)
def test_nesting_too_deep_is_a_syntax_problem_not_a_crash(guard: str) -> None:
    with pytest.raises(SyntaxProblem) as problem:
        parse_sc(f"statechart D {{ state S [{guard}]; }}", "D.sc")
    assert problem.value.message.startswith("expression nested too deeply")
