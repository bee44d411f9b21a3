"""Values written outside a model (a run's parameters, say) read with the language's literal
syntax and checked against a parameter's declared value type, so that units and signs mean
what they mean in a model.

A declared value type is what a run parameter accepts, as plain data: ``(kind, type name,
dimension exponents)``, one exponent tuple for a quantity, one per element for a vector
(the python target writes it as ``PARAMETER_TYPES``). Each refusal is a
:class:`LiteralError` whose message says what is wrong with the text.
"""

from __future__ import annotations

import math
from typing import Any

from lightrocks.languages.lightrocks.syntax import parse_literal
from lightrocks.metamodel import ast
from lightrocks.metamodel.grammar import SyntaxProblem
from lightrocks.metamodel.units import Dimension, UnitError, lookup


class LiteralError(ValueError):
    """A text that is not a value the language reads, or not one of the declared type."""


class NotALiteral(LiteralError):
    """Not one literal expression."""


class UnknownUnit(LiteralError):
    """A quantity with a unit the language does not know."""


class NotGivable(LiteralError):
    """A parameter type no literal written outside a model can be of."""


class WrongValue(LiteralError):
    """A literal, but not one of the declared type: ``found`` says what it is and
    ``detail`` (empty, or starting with its separator) what else is wrong."""

    def __init__(self, found: str, detail: str = "") -> None:
        super().__init__(f"{found}{detail}")
        self.found = found
        self.detail = detail


def read(text: str) -> ast.Expression:
    """``text`` read by the language's literal entry point: nothing but one expression."""
    try:
        return parse_literal(text, "<value>")
    except (SyntaxProblem, RecursionError):
        raise NotALiteral(f"'{text}' is not a literal value") from None


def dimension(quantity: ast.Quantity) -> Dimension:
    """The parser keeps an unknown unit's number as it is, so a typo must fail here."""
    try:
        return lookup(quantity.unit).dimension
    except UnitError as error:
        hint = f" (did you mean {' or '.join(error.suggestions)}?)" if error.suggestions else ""
        raise UnknownUnit(f"'{quantity.text}': {error}{hint}") from None


def plain_value(text: str) -> Any:
    """A literal without a declared type: ``12mm``, ``0.32 Nm``, ``true``, ``"a"``, a
    vector of numbers; numbers in SI."""
    value = read(text)
    negative = isinstance(value, ast.Unary) and value.operator == "-"
    literal = value.operand if negative else value
    if isinstance(literal, ast.Quantity):
        dimension(literal)
        number = -literal.value if negative else literal.value
        return int(number) if _integral(literal) else float(number)
    if isinstance(literal, ast.BooleanLiteral | ast.StringLiteral) and not negative:
        return literal.value
    if isinstance(literal, ast.VectorLiteral) and not negative:
        for element in literal.elements:
            if isinstance(element, ast.Quantity):
                dimension(element)
        return tuple(e.value for e in literal.elements if isinstance(e, ast.Quantity))
    raise NotALiteral(f"'{text}' is not a literal value")


def expected(declared: tuple) -> str:
    """What a parameter of the declared value type expects, in words."""
    kind, name, dimensions = declared
    if kind in ("quantity", "integer") and any(dimensions[0]):
        return f"{name} [{Dimension(dimensions[0])}]"
    if kind == "vector":
        return f"{name}, {len(dimensions)} values"
    return name


def typed_value(text: str, declared: tuple) -> Any:
    """``text`` read as a value of the declared type: a quantity needs its unit, numbers
    must be finite, an ``Integer`` whole, a vector complete."""
    kind, name, dimensions = declared
    if kind == "other":
        raise NotGivable(f"a {name} cannot be given outside a model")
    value = read(text)
    wrong = WrongValue(_describe(text, value))
    if kind == "boolean":
        if not isinstance(value, ast.BooleanLiteral):
            raise wrong
        return value.value
    if kind == "string":
        if not isinstance(value, ast.StringLiteral):
            raise wrong
        return value.value
    if kind == "vector":
        if not isinstance(value, ast.VectorLiteral) or len(value.elements) != len(dimensions):
            raise wrong
        return tuple(
            _number(element, Dimension(d), wrong)
            for element, d in zip(value.elements, dimensions, strict=True)
        )
    number = _number(value, Dimension(dimensions[0]), wrong)
    if kind == "integer":
        literal = value.operand if isinstance(value, ast.Unary) else value
        if not _integral(literal):
            raise wrong
        return int(number)
    return number


def _integral(literal: ast.Quantity) -> bool:
    plain = not literal.unit and not any(c in literal.text for c in ".eE")
    return plain and float(literal.value).is_integer()


def _number(value: ast.Expression, wanted: Dimension, wrong: WrongValue) -> float:
    """An SI number of ``wanted`` dimension from a (possibly negated) quantity literal."""
    negative = isinstance(value, ast.Unary) and value.operator == "-"
    literal = value.operand if negative else value
    if not isinstance(literal, ast.Quantity):
        raise wrong
    if literal.unit:
        if dimension(literal) != wanted:
            raise wrong
    elif not wanted.dimensionless:
        raise WrongValue(wrong.found, " (a quantity needs its unit)")
    number = -literal.value if negative else literal.value
    if not math.isfinite(number):
        raise WrongValue(wrong.found, ": not a finite number")
    return float(number)


def _describe(text: str, value: ast.Expression) -> str:
    """What ``text`` (parsed as ``value``) is, in the words of an error message."""
    literal = value.operand if isinstance(value, ast.Unary) else value
    if isinstance(literal, ast.Quantity):
        if not literal.unit:
            return f"the plain number {text}"
        try:
            return f"{text} [{dimension(literal)}]"
        except UnknownUnit:
            return f"'{text}'"
    kinds = {
        ast.BooleanLiteral: "a Boolean",
        ast.StringLiteral: "a String",
        ast.VectorLiteral: f"a vector of {len(getattr(literal, 'elements', ()))} values",
    }
    return f"{text} ({kinds.get(type(literal), 'an expression')})"
