"""Values given on the command line (``--param``, ``--perception-noise``), read with the
language's own literal syntax so that units and signs mean what they mean in a model."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

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


def parse_value(text: str) -> Any:
    """A ``--param`` value as a LightRocks literal: ``12mm``, ``0.32 Nm``, ``true``, ``"a"``."""
    value = _literal(text)
    negative = isinstance(value, ast.Unary) and value.operator == "-"
    literal = value.operand if negative else value
    if isinstance(literal, ast.Quantity):
        _dimension(literal)
        number = -literal.value if negative else literal.value
        plain = not literal.unit and not any(c in literal.text for c in ".eE")
        return int(number) if plain and float(number).is_integer() else float(number)
    if isinstance(literal, ast.BooleanLiteral | ast.StringLiteral) and not negative:
        return literal.value
    if isinstance(literal, ast.VectorLiteral) and not negative:
        for element in literal.elements:
            if isinstance(element, ast.Quantity):
                _dimension(element)
        return tuple(e.value for e in literal.elements if isinstance(e, ast.Quantity))
    raise RunError(f"'{text}' is not a literal value")


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
        sigmas.append(literal.value)
    return sigmas[0], sigmas[1]


def parameters(cls: type, given: Sequence[str]) -> dict[str, Any]:
    """``name=value`` pairs to Python attributes of the component, checked by name."""
    bound = {}
    for item in given:
        name, separator, text = item.partition("=")
        if not separator:
            raise RunError(f"--param '{item}' is not name=value")
        if name.strip() not in cls.PARAMETERS:
            known = ", ".join(cls.PARAMETERS) or "none"
            raise RunError(f"{cls.NAME} has no parameter '{name.strip()}'; parameters: {known}")
        bound[cls.PARAMETERS[name.strip()]] = parse_value(text.strip())
    return bound
