"""Safe ranges of device command arguments as a domain interface declares them: the constant
value of an expression, the bounds of each element in the unit they were written in, and the
message that names device, command, element and range."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TypeVar

from lightrocks.metamodel import ast
from lightrocks.metamodel.units import UnitError, lookup

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

    def breach(self, value: ast.Expression) -> str | None:
        """Why a constant ``value`` is unsafe here; ``None`` when it is safe or not constant."""
        numbers = constant_values(value)
        if numbers is None:
            return None
        elements = self.elements()
        vector = len(numbers) > 1 or len(elements) > 1
        for index, number in enumerate(numbers):
            low, high, unit, factor = _at(elements, index) or (None, None, "", 1.0)
            if (low is not None and number < low) or (high is not None and number > high):
                element = f"{self.argument}[{index}]" if vector else self.argument
                shown = [_show(n, unit, factor, u) for n, u in ((low, "-inf"), (high, "inf"))]
                return (
                    f"{self.device}.{self.command}({element}) = {_show(number, unit, factor)}"
                    f" is outside its safe range {shown[0]} .. {shown[1]}"
                )
        return None


def constant_values(expression: ast.Expression | None) -> list[float] | None:
    """The SI numbers of a constant expression (literals, signs, + - * /, vectors); None else."""
    match expression:
        case ast.Quantity():
            return [expression.value]
        case ast.Unary(operator="-"):
            inner = constant_values(expression.operand)
            return None if inner is None else [-n for n in inner]
        case ast.VectorLiteral():
            parts = [constant_values(e) for e in expression.elements]
            if any(p is None or len(p) != 1 for p in parts):
                return None
            return [p[0] for p in parts]
        case ast.Binary(operator=operator) if operator in "+-*/":
            left, right = constant_values(expression.left), constant_values(expression.right)
            if left is None or right is None or len(left) != 1 or len(right) != 1:
                return None
            if operator == "/" and right[0] == 0:
                return None
            result = _apply(operator, left[0], right[0])
            return [result] if math.isfinite(result) else None
    return None


def _apply(operator: str, left: float, right: float) -> float:
    if operator == "+":
        return left + right
    if operator == "-":
        return left - right
    return left * right if operator == "*" else left / right


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


def _show(number: float | None, unit: str, factor: float, unbounded: str = "") -> str:
    if number is None:
        return unbounded
    return f"{number / factor:g} {unit}".rstrip()


def command_ranges(device: str, command: ast.Command) -> dict[str, Range]:
    """The declared safe range of every ranged parameter of ``device.command``."""
    return {
        p.name: Range(device, command.name, p.name, p.low, p.high)
        for p in command.parameters
        if p.low is not None or p.high is not None
    }
