"""The values a condition reads, as solver variables with their declared ranges and units.

A name in a guard or end condition is a parameter, a sensor of a device of the cell, an
attribute of a scene object, or a field of one of these. Each becomes one variable per
path (``robot.wrench.force.z``) so that two mentions of it agree. Quantities are reals in
SI; the unit kept with a variable is the one its declaration is written in, so that a
witness reads as the model does.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cache

from lightrocks.languages.domain.types import (
    BOOLEAN,
    FRAME,
    FRAME_MEMBERS,
    INTEGER,
    DeviceT,
    QuantityT,
    StructT,
    Type,
)
from lightrocks.metamodel import ast
from lightrocks.metamodel.constants import fold
from lightrocks.metamodel.units import UnitError, known_units, lookup

Bound = tuple[float | None, float | None]


@dataclass(frozen=True)
class Variable:
    """One value a condition reads: its path, sort, range and display unit."""

    path: str
    sort: str  # "Real" | "Int" | "Bool"
    unit: str = ""
    low: float | None = None
    high: float | None = None
    start: float | bool | None = None  # the value when a command of its device starts
    measured: bool = False  # a sensor reading: noisy, never exactly equal to a number
    kind: str = "parameter"  # "parameter" | "sensor" | "attribute"


@dataclass
class Leaf:
    """A scalar leaf of a (possibly structured) type, with its field path."""

    suffix: tuple[str, ...]
    type: Type


def leaves(kind: Type, suffix: tuple[str, ...] = ()) -> list[Leaf]:
    """The scalar leaves of a type in declaration order: fields of structures, the
    translation of a frame, the type itself for a quantity or a Boolean."""
    if isinstance(kind, StructT):
        found: list[Leaf] = []
        for name, inner in kind.fields:
            found += leaves(inner, (*suffix, name))
        return found
    if kind == FRAME:
        return [Leaf((*suffix, n), t) for n, t in FRAME_MEMBERS.items()]
    if isinstance(kind, QuantityT) or kind == BOOLEAN:
        return [Leaf(suffix, kind)]
    return []


def sort_of(kind: Type) -> str | None:
    if kind == BOOLEAN:
        return "Bool"
    if kind == INTEGER:
        return "Int"
    if isinstance(kind, QuantityT):
        return "Real"
    return None


def unit_of(expression: ast.Expression | None) -> str:
    """The unit a literal (or a vector's first element, or a negated literal) is written in."""
    if isinstance(expression, ast.VectorLiteral) and expression.elements:
        return unit_of(expression.elements[0])
    if isinstance(expression, ast.Unary):
        return unit_of(expression.operand)
    if isinstance(expression, ast.Quantity) and expression.unit:
        try:
            lookup(expression.unit)
        except UnitError:
            return ""
        return expression.unit
    return ""


def element_bound(expression: ast.Expression | None, index: int) -> float | None:
    """Element ``index`` of a bound: a vector literal has one per numeric leaf; a scalar is
    the bound of every leaf of its dimension."""
    if expression is None:
        return None
    if isinstance(expression, ast.VectorLiteral):
        if index >= len(expression.elements):
            return None
        expression = expression.elements[index]
    value = fold(expression)
    if isinstance(value, bool) or not isinstance(value, int | float):
        return None
    return float(value)


@dataclass
class Hull:
    """The smallest interval holding every safe range of one dimension of a device."""

    bounds: dict[object, Bound] = field(default_factory=dict)

    def add(self, dimension: object, low: float | None, high: float | None) -> None:
        old_low, old_high = self.bounds.get(dimension, (low, high))
        lows = [v for v in (old_low, low) if v is not None]
        highs = [v for v in (old_high, high) if v is not None]
        self.bounds[dimension] = (min(lows) if lows else None, max(highs) if highs else None)


def device_hull(device: ast.Device) -> Hull:
    """The safe ranges a device declares for its command parameters, by dimension, made
    symmetric about zero (a sensor reads a direction as a sign): the default range of a
    sensor that declares none."""
    hull = Hull()
    for command in device.commands:
        for parameter in command.parameters:
            if parameter.low is None or parameter.high is None:
                continue
            lows = _elements(parameter.low)
            highs = _elements(parameter.high)
            for low, high in zip(lows, highs, strict=False):
                if low[1] is None or high[1] is None or low[1] != high[1]:
                    continue
                largest = max(abs(low[0]), abs(high[0]))
                hull.add(low[1], -largest, largest)
    return hull


def _elements(expression: ast.Expression) -> list[tuple[float, object]]:
    parts = expression.elements if isinstance(expression, ast.VectorLiteral) else (expression,)
    found = []
    for part in parts:
        value = fold(part)
        unit = unit_of(part)
        if isinstance(value, int | float) and not isinstance(value, bool) and unit:
            dimension = lookup(unit).dimension
            found.append((float(value), None if dimension.dimensionless else dimension))
        else:
            found.append((0.0, None))
    return found


def sensor_variables(instance: str, device: DeviceT, sensor: ast.Sensor, kind: Type) -> list:
    """One variable per scalar leaf of ``instance.sensor``."""
    hull = device_hull(device.device) if device.device is not None else Hull()
    found = []
    numeric = 0
    for leaf in leaves(kind):
        sort = sort_of(leaf.type)
        path = ".".join((instance, sensor.name, *leaf.suffix))
        if sort == "Bool":
            start = fold(sensor.start) if sensor.start is not None else None
            found.append(
                Variable(
                    path, sort, start=start if isinstance(start, bool) else None, kind="sensor"
                )
            )
            continue
        low = element_bound(sensor.low, numeric)
        high = element_bound(sensor.high, numeric)
        start = element_bound(sensor.start, numeric)
        dimension = leaf.type.dimension if isinstance(leaf.type, QuantityT) else None
        if sensor.low is None and dimension is not None and not dimension.dimensionless:
            low, high = hull.bounds.get(dimension, (None, None))
        numeric += 1
        unit = unit_of(sensor.low) or unit_of(sensor.start) or si_unit(dimension)
        found.append(
            Variable(path, sort, unit, low, high, start, measured=sort == "Real", kind="sensor")
        )
    return found


@cache
def si_unit(dimension: object) -> str:
    """The symbol of the SI unit of a dimension (``N`` for forces), or ''."""
    for unit in known_units():
        info = lookup(unit)
        if info.factor == 1 and info.dimension == dimension and not info.dimension.dimensionless:
            return unit
    return ""


def attribute_variable(obj: str, attribute: ast.Parameter, kind: Type) -> Variable | None:
    sort = sort_of(kind)
    if sort is None:
        return None
    low = element_bound(attribute.low, 0)
    high = element_bound(attribute.high, 0)
    unit = unit_of(attribute.low) or unit_of(attribute.default)
    return Variable(f"{obj}.{attribute.name}", sort, unit, low, high, kind="attribute")


def parameter_variable(parameter: ast.Parameter, kind: Type) -> Variable | None:
    sort = sort_of(kind)
    if sort is None:
        return None
    return Variable(parameter.name, sort, unit_of(parameter.default))
