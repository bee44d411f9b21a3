"""Expressions print with minimal parentheses and parse back to an equal AST."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from lightrocks.languages.lightrocks.syntax import parse_statechart
from lightrocks.metamodel import ast
from lightrocks.metamodel.convert import PRECEDENCE
from lightrocks.metamodel.printer import expression, string
from lightrocks.metamodel.units import lookup


def parse_expression(text: str) -> ast.Expression:
    unit = parse_statechart(f"statechart S {{ do / result = {text}; }}", "test.lr")
    return unit.statechart.elements[0].statements[0].value


@pytest.mark.parametrize(
    ("source", "printed"),
    [
        ("a - (b - c)", "a - (b - c)"),
        ("(a - b) - c", "a - b - c"),
        ("a * (b + c)", "a * (b + c)"),
        ("(a * b) + c", "a * b + c"),
        ("a || b && c", "a || b && c"),
        ("(a || b) && c", "(a || b) && c"),
        ("a / (b * c)", "a / (b * c)"),
        ("(a == b) == c", "a == b == c"),
        ("a < (b < c)", "a < (b < c)"),
        ("!(a && b)", "!(a && b)"),
        ("-(a.b)", "-a.b"),
        ("-(-a)", "-(-a)"),
        ("+(-3 mm)", "+(-3 mm)"),
        ("x * -3 mm", "x * -3 mm"),
        ("a - -b", "a - -b"),
        ("(3 mm).x", "(3 mm).x"),
        ("(a + b).c(1, d = 2)[0]", "(a + b).c(1, d = 2)[0]"),
        ("f(a == b, c = d == e)", "f(a == b, c = d == e)"),
        ("[1, 2 mm, -180 deg, [true, false], []]", "[1, 2 mm, -180 deg, [true, false], []]"),
        ("12.50 mm", "12.50 mm"),
        ("2000 N/m * 1e-3", "2000 N/m * 1e-3"),
        ('"a // b /* c */"', '"a // b /* c */"'),
        ('"say \\"hi\\""', '"say \\"hi\\""'),
        ("'single'", '"single"'),
        ("robot.wrench.torque.z % 2 != 0", "robot.wrench.torque.z % 2 != 0"),
    ],
)
def test_print_examples(source: str, printed: str) -> None:
    node = parse_expression(source)
    assert expression(node) == printed
    assert parse_expression(expression(node)) == node


@pytest.mark.parametrize(
    ("value", "unit", "printed"),
    [
        (0.012, "mm", "12 mm"),
        (3.141592653589793, "deg", "180 deg"),
        (-3.141592653589793, "deg", "-180 deg"),
        (0.32, "Nm", "0.32 Nm"),
        (2000.0, "N/m", "2000 N/m"),
        (0.5, "", "0.5"),
        (1e-05, "", "1e-05"),
    ],
)
def test_quantities_without_text_print_their_value_in_their_unit(
    value: float, unit: str, printed: str
) -> None:
    node = ast.Quantity(value, unit)
    assert expression(node) == printed
    assert parse_expression(printed) == node


# --- property: print -> parse gives an equal AST ----------------------------------------

UNITS = ["", "mm", "m", "deg", "rad", "N", "Nm", "N/m", "Nm/rad", "ms", "percent", "kN", "m/s"]

names = st.from_regex(r"[a-z][a-zA-Z0-9_]{0,4}", fullmatch=True).filter(
    lambda name: name not in {"true", "false"}
)


@st.composite
def quantities(draw: st.DrawFn) -> ast.Quantity:
    number = draw(st.floats(min_value=0, max_value=1e12, allow_subnormal=False))
    unit = draw(st.sampled_from(UNITS))
    sign = draw(st.sampled_from([1.0, -1.0]))
    return ast.Quantity(sign * number * lookup(unit).factor, unit)


strings = st.text(alphabet="ab \"'\\/*\n{}").filter(lambda s: not s.endswith("\\"))
leaves = st.one_of(
    names.map(ast.Name),
    quantities(),
    st.booleans().map(ast.BooleanLiteral),
    strings.map(ast.StringLiteral),
)


def _unary(operator: str, operand: ast.Expression) -> ast.Expression:
    # the converter folds a minus into a quantity literal: `-(3 mm)` is the quantity -3 mm
    if operator == "-" and isinstance(operand, ast.Quantity):
        return ast.Quantity(-operand.value, operand.unit)
    return ast.Unary(operator, operand)


def _compound(children: st.SearchStrategy[ast.Expression]) -> st.SearchStrategy:
    arguments = st.builds(ast.Argument, children, st.one_of(st.just(""), names))
    return st.one_of(
        st.builds(ast.Binary, st.sampled_from(sorted(PRECEDENCE)), children, children),
        st.builds(_unary, st.sampled_from(["!", "-", "+"]), children),
        st.builds(ast.Member, children, names),
        st.builds(ast.Call, children, st.lists(arguments, max_size=3).map(tuple)),
        st.builds(ast.Index, children, children),
        st.lists(children, max_size=3).map(lambda items: ast.VectorLiteral(tuple(items))),
    )


expressions = st.recursive(leaves, _compound, max_leaves=12)


@settings(max_examples=300, deadline=None)
@given(expressions)
def test_printed_expressions_parse_back_equal(node: ast.Expression) -> None:
    assert parse_expression(expression(node)) == node


@settings(max_examples=300, deadline=None)
@given(strings)
def test_printed_strings_parse_back_equal(value: str) -> None:
    assert parse_expression(string(value)) == ast.StringLiteral(value)
