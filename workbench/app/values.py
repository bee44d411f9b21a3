"""Values given on the command line (``--param``, ``--perception-noise``), read with the
language's own literal syntax so that units and signs mean what they mean in a model."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any

from lightrocks.languages.domain.types import (
    BOOLEAN,
    STRING,
    QuantityT,
    Type,
    VectorT,
    compatible,
    describe,
    quantity_of,
)
from lightrocks.languages.lightrocks.syntax import parse_statechart
from lightrocks.metamodel import ast
from lightrocks.metamodel.grammar import SyntaxProblem
from lightrocks.metamodel.units import ANGLE, LENGTH, Dimension, UnitError, lookup
from lightrocks.workbench.app.errors import RunError

Noise = tuple[float, float]
"""Perception noise: position sigma [m], rotation sigma [rad]."""


def _literal(text: str) -> Any:
    """The expression of ``text`` parsed as a parameter default, so units and signs work."""
    wrapper = f"statechart P {{ parameters {{ Real p = {text}; }} }}"
    try:
        unit = parse_statechart(wrapper, "<param>")
    except SyntaxProblem:
        raise RunError(f"'{text}' is not a literal value") from None
    (block,) = unit.statechart.elements
    return block.parameters[0].default if len(block.parameters) == 1 else None


def _dimension(quantity: ast.Quantity) -> Dimension:
    """The parser keeps an unknown unit's number as it is, so a typo must fail here."""
    try:
        return lookup(quantity.unit).dimension
    except UnitError as error:
        hint = f" (did you mean {' or '.join(error.suggestions)}?)" if error.suggestions else ""
        raise RunError(f"'{quantity.text}': {error}{hint}") from None


def _finite(text: str, number: float) -> float:
    if not math.isfinite(number):
        raise RunError(f"'{text}' is not a finite number")
    return number


def parse_value(text: str, expected: Type | None = None) -> Any:
    """A ``--param`` value as a LightRocks literal: ``12mm``, ``0.32 Nm``, ``true``, ``"a"``;
    checked against the declared type when it is known, so ``depth=20`` is not 20 m."""
    value = _literal(text)
    if expected is not None:
        _check_type(text, value, expected)
    negative = isinstance(value, ast.Unary) and value.operator == "-"
    literal = value.operand if negative else value
    if isinstance(literal, ast.Quantity):
        _dimension(literal)
        number = _finite(text, -literal.value if negative else literal.value)
        plain = not literal.unit and not any(c in literal.text for c in ".eE")
        return int(number) if plain and float(number).is_integer() else float(number)
    if isinstance(literal, ast.BooleanLiteral | ast.StringLiteral) and not negative:
        return literal.value
    if isinstance(literal, ast.VectorLiteral) and not negative:
        for element in literal.elements:
            if isinstance(element, ast.Quantity):
                _dimension(element)
        numbers = [_element(text, e) for e in literal.elements]
        return tuple(_finite(text, n) for n in numbers)
    raise RunError(f"'{text}' is not a literal value")


def _element(text: str, element: Any) -> float:
    """Vector elements are numbers (optionally negated): a run value has no nesting."""
    negative = isinstance(element, ast.Unary) and element.operator == "-"
    literal = element.operand if negative else element
    if not isinstance(literal, ast.Quantity):
        raise RunError(f"'{text}': vector elements must be numbers")
    return -literal.value if negative else literal.value


def _type_of(value: Any) -> Type | None:
    """The type of a literal as the checker sees it; None for anything but a literal."""
    if isinstance(value, ast.Unary) and value.operator == "-":
        value = value.operand
    if isinstance(value, ast.Quantity):
        return quantity_of(value)
    if isinstance(value, ast.BooleanLiteral):
        return BOOLEAN
    if isinstance(value, ast.StringLiteral):
        return STRING
    if isinstance(value, ast.VectorLiteral):
        elements = tuple(_type_of(e) for e in value.elements)
        return None if None in elements else VectorT("vector", elements)
    return None


def _check_type(text: str, value: Any, expected: Type) -> None:
    actual = _type_of(value)
    wanted = describe(expected)
    if isinstance(expected, QuantityT) and not expected.dimension.dimensionless:
        wanted += " with its unit"
    if actual is None or not compatible(expected, actual):
        given = "an expression" if actual is None else describe(actual)
        raise RunError(f"expects {wanted}; given '{text}' ({given})")
    if expected.name == "Integer" and not float(_literal_number(value)).is_integer():
        raise RunError(f"expects Integer; given '{text}'")


def _literal_number(value: Any) -> float:
    negative = isinstance(value, ast.Unary)
    number = (value.operand if negative else value).value
    return -number if negative else number


def parse_noise(text: str) -> Noise:
    """``--perception-noise 2mm,2deg``: the camera's position and rotation sigmas in SI."""
    usage = f"--perception-noise '{text}' is not LENGTH,ANGLE such as 2mm,2deg"
    parts = text.split(",")
    if len(parts) != 2:
        raise RunError(usage)
    sigmas = []
    for part, dimension in zip(parts, (LENGTH, ANGLE), strict=True):
        literal = _literal(part.strip())
        if not isinstance(literal, ast.Quantity) or _dimension(literal) != dimension:
            raise RunError(usage)
        if not math.isfinite(literal.value):
            raise RunError(f"--perception-noise '{text}': a sigma must be a finite number")
        if literal.value < 0:
            raise RunError(f"--perception-noise '{text}': a sigma cannot be negative")
        sigmas.append(literal.value)
    return sigmas[0], sigmas[1]


DECLARED_TYPES = "DECLARED_TYPES"
"""Class attribute set by loading: model parameter name -> its declared :class:`Type`."""

SAFE_RANGES = "SAFE_RANGES"
"""Class attribute set by loading: the devices' declared safe ranges, enforced at run time."""


def parameters(cls: type, given: Sequence[str]) -> dict[str, Any]:
    """``name=value`` pairs to Python attributes of the component, checked by name and,
    when the class was loaded from its model, by declared type, dimension and finiteness."""
    declared: Mapping[str, Type] = getattr(cls, DECLARED_TYPES, {})
    bound = {}
    for item in given:
        name, separator, text = item.partition("=")
        if not separator:
            raise RunError(f"--param '{item}' is not name=value")
        if name.strip() not in cls.PARAMETERS:
            known = ", ".join(cls.PARAMETERS) or "none"
            raise RunError(f"{cls.NAME} has no parameter '{name.strip()}'; parameters: {known}")
        key = name.strip()
        try:
            bound[cls.PARAMETERS[key]] = parse_value(text.strip(), declared.get(key))
        except RunError as error:
            raise RunError(f"parameter '{key}': {error}") from None
    return bound
