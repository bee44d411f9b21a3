"""Safe ranges of device command arguments as a domain interface declares them: the constant
value of an expression and the bounds of each element in the unit they were written in. The
check and its message are the runtime's (``runtime.safety.SafeRange``), so that a constant
the check accepts is one the run accepts."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TypeVar

from lightrocks.metamodel import ast
from lightrocks.metamodel.constants import fold
from lightrocks.metamodel.units import UnitError, lookup
from lightrocks.runtime.safety import Bound, SafeRange

T = TypeVar("T")

Element = tuple[float | None, float | None, str, float]
"""One element's bounds in SI, the unit they were written in, and that unit's SI factor."""


@dataclass(frozen=True)
class Range:
    """The declared safe range of ``device.command(argument)``."""

    device: str
    command: str
    argument: str
    low: ast.Expression | None
    high: ast.Expression | None

    def elements(self) -> tuple[Element, ...]:
        """One bound per element of a vector range, a single one for a scalar."""
        lows, highs = _bound(self.low), _bound(self.high)
        size = max(len(lows), len(highs))
        return tuple(_merge(_at(lows, i), _at(highs, i)) for i in range(size))

    def safe_range(self) -> SafeRange | None:
        """The range as the runtime checks it; ``None`` when its bounds are not constant."""
        bounds = tuple(Bound(*element) for element in self.elements())
        return SafeRange(self.device, self.command, self.argument, bounds) if bounds else None

    def breach(self, value: ast.Expression) -> str | None:
        """Why a constant ``value`` is unsafe here; ``None`` when it is safe or not constant."""
        numbers = constant_values(value)
        safe = self.safe_range()
        if numbers is None or safe is None:
            return None
        return safe.breach(numbers)


def constant_values(expression: ast.Expression | None) -> list[float] | None:
    """The SI numbers of a constant expression (a number or a vector of numbers); None else."""
    value = fold(expression)
    if isinstance(value, tuple):
        return [float(v) for v in value]
    if isinstance(value, int | float) and not isinstance(value, bool):
        return [float(value)]
    return None


def _bound(expression: ast.Expression | None) -> list[tuple[float | None, str, float]]:
    """Each element of a bound: its SI number (None for an infinite one, which bounds
    nothing), and the unit (with factor) it was written in."""
    if expression is None:
        return []
    parts = expression.elements if isinstance(expression, ast.VectorLiteral) else (expression,)
    found = []
    for part in parts:
        numbers = constant_values(part)
        if numbers is None or len(numbers) != 1:
            return []
        found.append((numbers[0] if math.isfinite(numbers[0]) else None, *_unit(part)))
    return found


def _unit(expression: ast.Expression) -> tuple[str, float]:
    literal = expression.operand if isinstance(expression, ast.Unary) else expression
    if isinstance(literal, ast.Quantity) and literal.unit:
        try:
            return literal.unit, lookup(literal.unit).factor
        except UnitError:
            pass
    return "", 1.0


def _merge(low: tuple | None, high: tuple | None) -> Element:
    unit, factor = (low or high or (0.0, "", 1.0))[1:]
    return (low[0] if low else None, high[0] if high else None, unit, factor)


def _at(values: Sequence[T], index: int) -> T | None:
    if not values:
        return None
    return values[index] if index < len(values) else values[0]


def command_ranges(device: str, command: ast.Command) -> dict[str, Range]:
    """The declared safe range of every ranged parameter of ``device.command``."""
    return {
        p.name: Range(device, command.name, p.name, p.low, p.high)
        for p in command.parameters
        if p.low is not None or p.high is not None
    }
