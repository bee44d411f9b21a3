"""Values given on the command line (``--param``, ``--perception-noise``), read and checked
by the language's literal service (:mod:`languages.lightrocks.literals`), so that units and
signs mean what they mean in a model; its refusals become run errors naming the option."""

from __future__ import annotations

import math
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from typing import Any

from lightrocks.app.errors import RunError
from lightrocks.languages.lightrocks import literals
from lightrocks.metamodel import ast
from lightrocks.metamodel.units import ANGLE, LENGTH, Dimension, lookup

Noise = tuple[float, float]
"""Perception noise: position sigma [m], rotation sigma [rad]."""


@contextmanager
def _refusals() -> Iterator[None]:
    """The literal service's refusals as run errors, in its words."""
    try:
        yield
    except literals.LiteralError as error:
        raise RunError(str(error)) from None


def _literal(text: str) -> ast.Expression:
    with _refusals():
        return literals.read(text)


def _dimension(quantity: ast.Quantity) -> Dimension:
    with _refusals():
        return literals.dimension(quantity)


def parse_value(text: str) -> Any:
    """A ``--param`` value as a LightRocks literal: ``12mm``, ``0.32 Nm``, ``true``, ``"a"``."""
    with _refusals():
        return literals.plain_value(text)


def typed_value(name: str, text: str, declared: tuple) -> Any:
    """``text`` read as a value of the declared parameter type, or a ``RunError`` naming the
    parameter, what it expects and what was given."""
    expects = f"{name} expects {literals.expected(declared)}"
    try:
        return literals.typed_value(text, declared)
    except literals.NotGivable:
        raise RunError(
            f"--param {name}: a {declared[1]} cannot be given on the command line"
        ) from None
    except literals.NotALiteral as error:
        raise RunError(f"--param {name}: {expects}; {error}") from None
    except literals.WrongValue as error:
        raise RunError(f"--param {name}={text}: {expects}, not {error}") from None
    except literals.UnknownUnit as error:
        raise RunError(str(error)) from None


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
                expected = f"{literals.expected(declared)} " if declared else ""
                raise RunError(
                    f"--param {name}={text.strip()}: {name} expects {expected}within the "
                    f"safe range of the command it reaches; {breach}"
                )
        bound[cls.PARAMETERS[name]] = value
    return bound
