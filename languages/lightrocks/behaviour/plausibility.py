"""Physical plausibility of an elemental action, from what its domain interface declares.

Values are taken as the action writes them, its parameters at their defaults. Each finding
is a warning with its reason and a fix:

- LR0607: the time budget is shorter than the commanded motion takes at the commanded (else
  the device's highest) speed;
- LR0608: a stiffness or damping a hundred times or more off the device's typical value (its
  default): a unit mixed up, N/mm meant where N/m is written;
- LR0609: a number of degrees that is π, π/2, 2π…: radians meant;
- LR0610: a force end condition whose sign a contact cannot have while the arm moves along
  the commanded direction (a contact pushes back against the motion).
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from dataclasses import fields, is_dataclass, replace

from lightrocks.languages.domain.types import DeviceT
from lightrocks.languages.lightrocks.behaviour.conditions import Finding, start_of
from lightrocks.languages.lightrocks.behaviour.judge import Judge
from lightrocks.languages.lightrocks.behaviour.scope import Scope
from lightrocks.languages.lightrocks.behaviour.terms import Terms, exact
from lightrocks.languages.lightrocks.model import Component
from lightrocks.languages.lightrocks.typing import Typing
from lightrocks.metamodel import ast
from lightrocks.metamodel.constants import fold
from lightrocks.metamodel.units import ANGLE, FORCE, LENGTH, TIME, UnitError, lookup

TYPICAL_RATIO = 100.0
MULTIPLES_OF_PI = {"π/4": math.pi / 4, "π/2": math.pi / 2, "π": math.pi, "2π": 2 * math.pi}
AXES = ("x", "y", "z")


class Plausibility:
    """The findings on one action component written in its own file."""

    def __init__(self, typing: Typing, component: Component) -> None:
        self.typing = typing
        self.component = component
        self.region = component.region
        self.defaults = {n: p.default for n, p in self.region.parameters.items() if p.default}

    def findings(self) -> Iterator[Finding]:
        call = self._call()
        if call is None:
            return
        device, command, arguments = call
        yield from self._budget(device, command, arguments)
        yield from self._magnitudes(device, command, arguments)
        yield from self._force_signs(device, command, arguments)

    # -- the command ----------------------------------------------------------------------

    def _call(self) -> tuple[str, ast.Command, dict[str, ast.Expression]] | None:
        for action in self.region.actions:
            for statement in action.statements if action.kind == "do" else ():
                call = statement.value if isinstance(statement, ast.Assignment) else None
                call = call or getattr(statement, "expression", None)
                function = getattr(call, "function", None)
                if not isinstance(function, ast.Member) or not isinstance(
                    function.target, ast.Name
                ):
                    continue
                device = Scope(self.typing, self.region).env.get(function.target.name)
                if not isinstance(device, DeviceT) or device.device is None:
                    continue
                command = next((c for c in device.device.commands if c.name == function.name), None)
                if command is None:
                    continue
                names = [p.name for p in command.parameters]
                arguments = {}
                for index, argument in enumerate(call.arguments):
                    key = argument.name or (names[index] if index < len(names) else "")
                    arguments[key] = argument.value
                return function.target.name, command, arguments
        return None

    def _value(self, expression: ast.Expression | None) -> object:
        """A constant with the action's parameters at their defaults, else None."""
        return fold(_substitute(expression, self.defaults, 4)) if expression is not None else None

    # -- LR0607 -----------------------------------------------------------------------------

    def _budget(
        self, device: str, command: ast.Command, arguments: dict[str, ast.Expression]
    ) -> Iterator[Finding]:
        declared = Scope(self.typing, self.region).env.get(device)
        written = self.component.command_budget(declared.device)
        goal = _goal(command, arguments)
        if written.stereotype is None or goal is None:
            return  # LR0607 judges a written budget, not the default
        budget = written.seconds
        stereotype = self.component.budget
        motion = _relative_motion(goal, device)
        if motion is None:
            return
        translation, rotation = motion
        distance = _norm([self._value(part) for part in translation])
        angle = sum(abs(v) for v in (self._value(r) for r in rotation) if _number(v))
        needed = []
        speed = self._speed(command, arguments, LENGTH / TIME)
        if distance and speed:
            needed.append((distance / speed, f"{distance * 1000:g} mm at {speed * 1000:g} mm/s"))
        turn = self._speed(command, arguments, ANGLE / TIME)
        if angle and turn:
            needed.append((angle / turn, f"{math.degrees(angle):g} deg at {turn:g} rad/s"))
        for needs, how in needed:
            if needs > budget:
                where = stereotype.position if stereotype else self.component.statechart.position
                yield Finding(
                    "LR0607",
                    where,
                    f"the time budget {budget:g} s is shorter than the motion takes: {how} "
                    f"is {needs:g} s",
                    "raise the <<timeout>>, or move faster or less far",
                )

    def _speed(
        self, command: ast.Command, arguments: dict[str, ast.Expression], dimension: object
    ) -> float | None:
        """The commanded speed of a dimension, else its default, else its safe upper bound."""
        for parameter in command.parameters:
            unit = _unit(parameter.default) or _unit(parameter.high)
            if unit is None or lookup(unit).dimension != dimension:
                continue
            for value in (arguments.get(parameter.name), parameter.default, parameter.high):
                number = self._value(value)
                if _number(number) and number > 0:
                    return float(number)
        return None

    # -- LR0608 -----------------------------------------------------------------------------

    def _magnitudes(
        self, device: str, command: ast.Command, arguments: dict[str, ast.Expression]
    ) -> Iterator[Finding]:
        for parameter in command.parameters:
            if not any(word in parameter.type for word in ("Stiffness", "Damping")):
                continue
            written = arguments.get(parameter.name)
            typical = fold(parameter.default)
            value = self._value(written)
            if written is None or typical is None or value is None:
                continue
            where = self._origin(written)
            typicals = typical if isinstance(typical, tuple) else (typical,)
            values = value if isinstance(value, tuple) else (value,)
            for index, (number, usual) in enumerate(zip(values, typicals, strict=False)):
                if not (_number(number) and _number(usual)) or number == 0 or usual == 0:
                    continue
                ratio = abs(number / usual)
                if ratio >= TYPICAL_RATIO or ratio <= 1 / TYPICAL_RATIO:
                    element = f"{parameter.name}[{index}]" if len(values) > 1 else parameter.name
                    yield Finding(
                        "LR0608",
                        where,
                        f"{device}.{command.name}({element}) = {number:g} (SI) is "
                        f"{max(ratio, 1 / ratio):g} times {'above' if ratio > 1 else 'below'} "
                        f"its typical {usual:g}",
                        "check the unit: N/mm or N/m, Nm/rad or Nm/deg",
                    )
                    break

    def _origin(self, written: ast.Expression) -> ast.Position:
        """Where a value is written: the parameter's default when passed on unchanged."""
        if isinstance(written, ast.Name) and written.name in self.defaults:
            return start_of(self.defaults[written.name])
        return start_of(written)

    # -- LR0610 -----------------------------------------------------------------------------

    def _force_signs(
        self, device: str, command: ast.Command, arguments: dict[str, ast.Expression]
    ) -> Iterator[Finding]:
        goal = _goal(command, arguments)
        motion = _relative_motion(goal, device) if goal is not None else None
        if motion is None or motion[1]:
            return
        direction = [self._value(part) for part in motion[0]]
        if not all(_number(v) for v in direction) or sum(1 for v in direction if v) != 1:
            return
        axis = next(i for i, v in enumerate(direction) if v)
        moving = 1 if direction[axis] > 0 else -1
        terms = Terms(Scope(self.typing, self.region))
        judge = Judge(terms)
        for condition in self.region.end_conditions:
            if condition.expression is None or condition.position.file != _file(self.component):
                continue
            term = terms.condition(condition.expression)
            forces = [
                (path, constant)
                for path, (variable, constant) in terms.read.items()
                if variable.kind == "sensor"
                and path.startswith(f"{device}.")
                and path.endswith(f".{AXES[axis]}")
                and _dimension(variable.unit) == FORCE
            ]
            defaults = self._defaults_of(terms)
            for path, force in forces:
                pushed_back = force * (-moving) >= 0
                if judge.never(term, pushed_back, *defaults) and not judge.never(term, *defaults):
                    way = f"{'+' if moving > 0 else '-'}{AXES[axis]}"
                    yield Finding(
                        "LR0610",
                        start_of(condition.expression),
                        f"end condition '{condition.name}' needs {path} "
                        f"{'>' if moving > 0 else '<'} 0 while the arm moves {way}: a contact "
                        "pushes back against the motion, so it cannot hold on the way",
                        "mind the sign of the threshold",
                    )

    def _defaults_of(self, terms: Terms) -> list:
        """The action's parameters read so far, each at its constant default."""
        facts = []
        for path, (variable, constant) in terms.read.items():
            value = self._value(self.defaults.get(path)) if variable.kind == "parameter" else None
            if _number(value):
                facts.append(constant == exact(float(value)))
        return facts


def _goal(command: ast.Command, arguments: dict[str, ast.Expression]) -> ast.Expression | None:
    frames = [p.name for p in command.parameters if p.type == "Frame"]
    return arguments.get(frames[0]) if frames else None


def _relative_motion(
    goal: ast.Expression, device: str
) -> tuple[list[ast.Expression], list[ast.Expression]] | None:
    """The translation (world axes) and rotations of a goal written relative to where the
    device is: ``transl(x, y, z) * device.sensor`` or ``device.sensor * rotZ(a) * …``."""
    factors = _factors(goal)
    anchors = [i for i, f in enumerate(factors) if _reads_device(f, device)]
    if len(anchors) != 1:
        return None
    before, after = factors[: anchors[0]], factors[anchors[0] + 1 :]
    translation: list[ast.Expression] = []
    rotation: list[ast.Expression] = []
    for factor in before:
        if _call(factor) == "transl" and not translation:
            translation = [a.value for a in factor.arguments]
        else:
            return None
    for factor in after:
        name = _call(factor)
        if name in ("rotX", "rotY", "rotZ"):
            rotation.append(factor.arguments[0].value)
        elif name != "transl":
            return None
    if after and translation:
        return None
    return translation, rotation


def _factors(expression: ast.Expression) -> list[ast.Expression]:
    if isinstance(expression, ast.Binary) and expression.operator == "*":
        return _factors(expression.left) + _factors(expression.right)
    return [expression]


def _call(expression: ast.Expression) -> str:
    if isinstance(expression, ast.Call) and isinstance(expression.function, ast.Name):
        return expression.function.name
    return ""


def _reads_device(expression: ast.Expression, device: str) -> bool:
    return (
        isinstance(expression, ast.Member)
        and isinstance(expression.target, ast.Name)
        and expression.target.name == device
    )


def _substitute(expression: object, values: dict[str, ast.Expression], depth: int) -> object:
    """An expression with parameter names replaced by their defaults (a few levels deep)."""
    if isinstance(expression, ast.Name) and expression.name in values and depth > 0:
        return _substitute(values[expression.name], values, depth - 1)
    if isinstance(expression, tuple):
        return tuple(_substitute(e, values, depth) for e in expression)
    if is_dataclass(expression) and not isinstance(expression, ast.Position | ast.Member):
        changed = {
            f.name: _substitute(getattr(expression, f.name), values, depth)
            for f in fields(expression)
            if f.name != "position"
        }
        return replace(expression, **changed)
    return expression


def _number(value: object) -> bool:
    return isinstance(value, int | float) and not isinstance(value, bool)


def _norm(parts: list[object]) -> float | None:
    if not parts or not all(_number(p) for p in parts):
        return None
    return math.sqrt(sum(float(p) ** 2 for p in parts))


def _unit(expression: ast.Expression | None) -> str | None:
    literal = expression.operand if isinstance(expression, ast.Unary) else expression
    if isinstance(literal, ast.Quantity) and literal.unit:
        try:
            lookup(literal.unit)
        except UnitError:
            return None
        return literal.unit
    return None


def _dimension(unit: str) -> object:
    try:
        return lookup(unit).dimension if unit else None
    except UnitError:
        return None


def _file(component: Component) -> str:
    return component.loaded.unit.package_position.file


def degree_findings(expressions: list[tuple[ast.Expression, object]]) -> Iterator[Finding]:
    """LR0609: a number of degrees that is a multiple of π, among the typed expressions of a
    file (the typing pass keeps every one)."""
    factor = lookup("deg").factor
    for node, _ in expressions:
        if isinstance(node, ast.Quantity) and node.unit == "deg":
            number = abs(node.value / factor)
            for name, value in MULTIPLES_OF_PI.items():
                if number != 0 and abs(number - value) < 5e-4:
                    yield Finding(
                        "LR0609",
                        node.position,
                        f"{node.text} is {name} degrees: radians were meant",
                        f"write {math.degrees(value):g} deg, or {number:g} rad",
                    )
