"""Safe ranges of device command arguments as the model declares them: the constant value of
an expression, the bounds of each element in the unit they were written in, the message that
names device, command, element and range, and which statechart parameters flow unchanged
into a ranged argument (directly or through the bindings of imported statecharts)."""

from __future__ import annotations

import math
from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, TypeVar

from lightrocks.languages.domain.types import DeviceT
from lightrocks.languages.lightrocks.model import Component, Region
from lightrocks.metamodel import ast
from lightrocks.metamodel.units import UnitError, lookup

if TYPE_CHECKING:  # the typing uses these ranges itself
    from lightrocks.languages.lightrocks.typing import Typing

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


# -- where values go -----------------------------------------------------------------------


class Flows:
    """Which ranged command argument each parameter of a statechart reaches unchanged."""

    def __init__(self, typing: Typing) -> None:
        self.typing = typing
        self._known: dict[str, dict[str, list[Range]]] = {}

    def of(self, component: Component) -> dict[str, list[Range]]:
        if component.qualified_name in self._known:
            return self._known[component.qualified_name]
        found: dict[str, list[Range]] = {}
        self._known[component.qualified_name] = found  # a cycle stops here
        for region in component.region.regions():
            own = region.parameters
            for safe, value in self.command_arguments(region):
                if isinstance(value, ast.Name) and value.name in own:
                    found.setdefault(value.name, []).append(safe)
            for called, name, value in self.bindings(region):
                if isinstance(value, ast.Name) and value.name in own:
                    found.setdefault(value.name, []).extend(self.of(called).get(name, ()))
        return found

    def bindings(self, region: Region) -> Iterator[tuple[Component, str, ast.Expression]]:
        """(imported statechart, its parameter, the value bound) for every state argument."""
        for info in region.states.values():
            called = self.called(region, info.state)
            if called is None:
                continue
            names = list(called.region.parameters)
            for index, argument in enumerate(info.state.arguments):
                name = argument.name or (names[index] if index < len(names) else "")
                yield called, name, argument.value

    def called(self, region: Region, state: ast.State) -> Component | None:
        reference = ast.stereotype(state.stereotypes, "import")
        if reference is None or not reference.value:
            return None
        return self.typing.models.resolve_statechart(region.loaded, reference.value)

    def command_arguments(self, region: Region) -> Iterator[tuple[Range, ast.Expression]]:
        """The safe range and the value of every ranged argument of a do call."""
        env = None
        for action in region.actions:
            if action.kind != "do":
                continue
            for statement in action.statements:
                call = (
                    statement.value
                    if isinstance(statement, ast.Assignment)
                    else statement.expression
                )
                if not isinstance(call, ast.Call) or not isinstance(call.function, ast.Member):
                    continue
                owner = call.function.target
                if not isinstance(owner, ast.Name):
                    continue
                env = env if env is not None else self.typing.environment(region)
                device = env.get(owner.name)
                if isinstance(device, DeviceT) and device.device is not None:
                    yield from _ranged(owner.name, device.device, call)


def command_ranges(device: str, command: ast.Command) -> dict[str, Range]:
    """The declared safe range of every ranged parameter of ``device.command``."""
    return {
        p.name: Range(device, command.name, p.name, p.low, p.high)
        for p in command.parameters
        if p.low is not None or p.high is not None
    }


def _ranged(
    owner: str, device: ast.Device, call: ast.Call
) -> Iterator[tuple[Range, ast.Expression]]:
    command = next((c for c in device.commands if c.name == call.function.name), None)
    if command is None:
        return
    ranges = command_ranges(owner, command)
    order = [p.name for p in command.parameters]
    for index, argument in enumerate(call.arguments):
        name = argument.name or (order[index] if index < len(order) else "")
        if name in ranges:
            yield ranges[name], argument.value
