"""Values given on the command line (``--param``, ``--perception-noise``), read with the
language's own literal syntax so that units and signs mean what they mean in a model."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

from lightrocks.app.errors import RunError
from lightrocks.languages.lightrocks.syntax import parse_literal
from lightrocks.metamodel import ast
from lightrocks.metamodel.grammar import SyntaxProblem
from lightrocks.metamodel.units import ANGLE, LENGTH, Dimension, UnitError, lookup

Noise = tuple[float, float]
"""Perception noise: position sigma [m], rotation sigma [rad]."""


def _literal(text: str) -> Any:
    """``text`` read by the language's literal entry point, so units and signs work as in a
    model and nothing but one expression can be written."""
    try:
        return parse_literal(text, "<value>")
    except (SyntaxProblem, RecursionError):
        raise RunError(f"'{text}' is not a literal value") from None


def _dimension(quantity: ast.Quantity) -> Dimension:
    """The parser keeps an unknown unit's number as it is, so a typo must fail here."""
    try:
        return lookup(quantity.unit).dimension
    except UnitError as error:
        hint = f" (did you mean {' or '.join(error.suggestions)}?)" if error.suggestions else ""
        raise RunError(f"'{quantity.text}': {error}{hint}") from None


def parse_value(text: str) -> Any:
    """A ``--param`` value as a LightRocks literal: ``12mm``, ``0.32 Nm``, ``true``, ``"a"``."""
    value = _literal(text)
    negative = isinstance(value, ast.Unary) and value.operator == "-"
    literal = value.operand if negative else value
    if isinstance(literal, ast.Quantity):
        _dimension(literal)
        number = -literal.value if negative else literal.value
        return int(number) if _integral(literal) else float(number)
    if isinstance(literal, ast.BooleanLiteral | ast.StringLiteral) and not negative:
        return literal.value
    if isinstance(literal, ast.VectorLiteral) and not negative:
        for element in literal.elements:
            if isinstance(element, ast.Quantity):
                _dimension(element)
        return tuple(e.value for e in literal.elements if isinstance(e, ast.Quantity))
    raise RunError(f"'{text}' is not a literal value")


def _integral(literal: ast.Quantity) -> bool:
    plain = not literal.unit and not any(c in literal.text for c in ".eE")
    return plain and float(literal.value).is_integer()


def _expected(declared: tuple) -> str:
    kind, name, dimensions = declared
    if kind in ("quantity", "integer") and any(dimensions[0]):
        return f"{name} [{Dimension(dimensions[0])}]"
    if kind == "vector":
        return f"{name}, {len(dimensions)} values"
    return name


def typed_value(name: str, text: str, declared: tuple) -> Any:
    """``text`` read as a value of the declared parameter type, or a ``RunError`` naming the
    parameter, what it expects and what was given: a quantity needs its unit, numbers must
    be finite, an ``Integer`` whole, a vector complete."""
    kind, _, dimensions = declared
    if kind == "other":
        raise RunError(f"--param {name}: a {declared[1]} cannot be given on the command line")
    try:
        value = _literal(text)
    except RunError as error:
        raise RunError(f"--param {name}: {name} expects {_expected(declared)}; {error}") from None
    wrong = RunError(
        f"--param {name}={text}: {name} expects {_expected(declared)}, not {_describe(text, value)}"
    )
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


def _number(value: ast.Expression, dimension: Dimension, wrong: RunError) -> float:
    """An SI number of ``dimension`` from a (possibly negated) quantity literal."""
    negative = isinstance(value, ast.Unary) and value.operator == "-"
    literal = value.operand if negative else value
    if not isinstance(literal, ast.Quantity):
        raise wrong
    if literal.unit:
        if _dimension(literal) != dimension:
            raise wrong
    elif not dimension.dimensionless:
        raise RunError(f"{wrong} (a quantity needs its unit)")
    number = -literal.value if negative else literal.value
    if not math.isfinite(number):
        raise RunError(f"{wrong}: not a finite number")
    return float(number)


def _describe(text: str, value: ast.Expression) -> str:
    """What ``text`` (parsed as ``value``) is, in the words of an error message."""
    literal = value.operand if isinstance(value, ast.Unary) else value
    if isinstance(literal, ast.Quantity):
        if not literal.unit:
            return f"the plain number {text}"
        try:
            return f"{text} [{_dimension(literal)}]"
        except RunError:
            return f"'{text}'"
    kinds = {
        ast.BooleanLiteral: "a Boolean",
        ast.StringLiteral: "a String",
        ast.VectorLiteral: f"a vector of {len(getattr(literal, 'elements', ()))} values",
    }
    return f"{text} ({kinds.get(type(literal), 'an expression')})"


def parse_delay(text: str) -> float:
    """``+500ms`` among ``--events``: how far to advance the virtual clock, in seconds."""
    value = _literal(text.removeprefix("+"))
    if not isinstance(value, ast.Quantity) or _dimension(value) != lookup("s").dimension:
        raise RunError(f"'{text}' is not a time to wait: write it like +500ms")
    if value.value < 0:
        raise RunError(f"'{text}': time cannot go back")
    return value.value


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
        if literal.value < 0:
            raise RunError(f"--perception-noise '{text}': a sigma cannot be negative")
        if not math.isfinite(literal.value):
            raise RunError(f"--perception-noise '{text}': a sigma must be a finite number")
        sigmas.append(literal.value)
    return sigmas[0], sigmas[1]


def parameters(cls: type, given: Sequence[str]) -> dict[str, Any]:
    """``name=value`` pairs to Python attributes of the component, checked by name, declared
    type and the safe range of every command argument the parameter reaches."""
    bound = {}
    for item in given:
        name, separator, text = item.partition("=")
        if not separator:
            raise RunError(f"--param '{item}' is not name=value")
        if name.strip() not in cls.PARAMETERS:
            known = ", ".join(cls.PARAMETERS) or "none"
            raise RunError(f"{cls.NAME} has no parameter '{name.strip()}'; parameters: {known}")
        name = name.strip()
        declared = getattr(cls, "PARAMETER_TYPES", {}).get(name)
        value = typed_value(name, text.strip(), declared) if declared else parse_value(text)
        for safe in getattr(cls, "PARAMETER_RANGES", {}).get(name, ()):
            breach = safe.breach(value)
            if breach is not None:
                expected = f"{_expected(declared)} " if declared else ""
                raise RunError(
                    f"--param {name}={text.strip()}: {name} expects {expected}within the "
                    f"safe range of the command it reaches; {breach}"
                )
        bound[cls.PARAMETERS[name]] = value
    return bound
