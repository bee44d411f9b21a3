"""Operators and boolean values are read as single tokens: what they accept, and the
messages a misplaced one gives."""

from __future__ import annotations

import pytest

from lightrocks.languages.lightrocks.syntax import parse_statechart
from lightrocks.metamodel import ast
from lightrocks.metamodel.grammar import SyntaxProblem


def guard(expression: str) -> ast.Expression:
    unit = parse_statechart(f"statechart A {{ S -> T [{expression}] e; }}", "A.lr")
    transition = next(e for e in unit.statechart.elements if isinstance(e, ast.Transition))
    return transition.guard


@pytest.mark.parametrize(
    "operator", ["||", "&&", "==", "!=", "<=", ">=", "<", ">", "+", "-", "*", "/", "%"]
)
def test_every_binary_operator_is_read_whole(operator: str) -> None:
    read = guard(f"a {operator} b")
    assert isinstance(read, ast.Binary)
    assert read.operator == operator


def test_longer_operators_win_over_their_prefixes() -> None:
    read = guard("a <= b || c")
    assert read.operator == "||"
    assert read.left.operator == "<="


@pytest.mark.parametrize("operator", ["!", "-", "+"])
def test_unary_operators(operator: str) -> None:
    read = guard(f"{operator}a")
    assert isinstance(read, ast.Unary)
    assert read.operator == operator


def test_boolean_values_end_at_a_word_boundary() -> None:
    assert guard("true") == ast.BooleanLiteral(True, guard("true").position)
    assert isinstance(guard("trueish"), ast.Name)
    assert isinstance(guard("falsey"), ast.Name)


def test_two_operands_in_a_row_ask_for_an_operator() -> None:
    with pytest.raises(SyntaxProblem) as raised:
        guard("x y")
    assert "an operator" in raised.value.message
    assert (raised.value.line, raised.value.column) == (1, 26)


def test_a_missing_operand_names_what_may_start_one() -> None:
    with pytest.raises(SyntaxProblem) as raised:
        guard("x < ")
    assert "a number" in raised.value.message
    assert "a name" in raised.value.message
    assert "RegExMatch" not in raised.value.message


@pytest.mark.parametrize("operand", ["x", "x.y", "f(1)", "v[0]"])
def test_after_an_operand_each_suffix_is_asked_for_by_its_character(operand: str) -> None:
    with pytest.raises(SyntaxProblem) as raised:
        guard(f"{operand} y")
    message = raised.value.message
    assert "expected '(', '.', '[', ']', an operator but found 'y]'" in message
    assert "SuffixStart" not in message


@pytest.mark.parametrize("call", ["a.b.c", "f(1)(2)", "v[0][1]", "p.f(x)[2].q"])
def test_suffixes_chain(call: str) -> None:
    read = guard(call)
    assert isinstance(read, ast.Member | ast.Call | ast.Index)
