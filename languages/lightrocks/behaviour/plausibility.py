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
from collections.abc import Callable, Iterator
from dataclasses import fields, is_dataclass, replace
from functools import cached_property

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

    @cached_property
    def scope(self) -> Scope:
        """The names of the action's region, resolved once for every judgement."""
        return Scope(self.typing, self.region)

    def findings(self) -> Iterator[Finding]:
        call = self.call()
        if call is None:
            return
        device, command, arguments = call
        yield from self._budget(device, command, arguments)
        yield from self._magnitudes(device, command, arguments)
        yield from self._force_signs(device, command, arguments)

    # -- the command ----------------------------------------------------------------------

    def call(self) -> tuple[str, ast.Command, dict[str, ast.Expression]] | None:
        for action in self.region.actions:
            for statement in action.statements if action.kind == "do" else ():
                call = statement.value if isinstance(statement, ast.Assignment) else None
                call = call or getattr(statement, "expression", None)
                function = getattr(call, "function", None)
                if not isinstance(function, ast.Member) or not isinstance(
                    function.target, ast.Name
                ):
                    continue
                device = self.scope.env.get(function.target.name)
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

    def value(self, expression: ast.Expression | None) -> object:
        """A constant with the action's parameters at their defaults, else None."""
        return fold(_substitute(expression, self.defaults, 4)) if expression is not None else None

    # -- LR0607 -----------------------------------------------------------------------------

    def _budget(
        self, device: str, command: ast.Command, arguments: dict[str, ast.Expression]
    ) -> Iterator[Finding]:
        declared = self.scope.env.get(device)
        written = self.component.command_budget(declared.device)
        goal = goal_argument(command, arguments)
        if written.stereotype is None or goal is None:
            return  # LR0607 judges a written budget, not the default
        budget = written.seconds
        stereotype = self.component.budget
        motion = _relative_motion(goal, device)
        if motion is None:
            return
        translation, rotation = motion
        distance = _norm([self.value(part) for part in translation])
        angle = sum(abs(v) for v in (self.value(r) for r in rotation) if is_number(v))
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
                number = self.value(value)
                if is_number(number) and number > 0:
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
            value = self.value(written)
            if written is None or typical is None or value is None:
                continue
            where = self.origin(written)
            typicals = typical if isinstance(typical, tuple) else (typical,)
            values = value if isinstance(value, tuple) else (value,)
            for index, (number, usual) in enumerate(zip(values, typicals, strict=False)):
                if not (is_number(number) and is_number(usual)) or number == 0 or usual == 0:
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

    def origin(self, written: ast.Expression) -> ast.Position:
        """Where a value is written: the parameter's default when passed on unchanged."""
        if isinstance(written, ast.Name) and written.name in self.defaults:
            return start_of(self.defaults[written.name])
        return start_of(written)

    # -- LR0610 -----------------------------------------------------------------------------

    def _force_signs(
        self, device: str, command: ast.Command, arguments: dict[str, ast.Expression]
    ) -> Iterator[Finding]:
        goal = goal_argument(command, arguments)
        motion = _relative_motion(goal, device) if goal is not None else None
        if motion is None or motion[1]:
            return
        direction = [self.value(part) for part in motion[0]]
        if not all(is_number(v) for v in direction) or sum(1 for v in direction if v) != 1:
            return
        axis = next(i for i, v in enumerate(direction) if v)
        moving = 1 if direction[axis] > 0 else -1
        for condition, path, kind in self.against(device, axis, moving, self.defaults_of):
            if kind != "force":
                continue  # a displacement against the motion is LR0631's (behaviour.physics)
            way = f"{'+' if moving > 0 else '-'}{AXES[axis]}"
            yield Finding(
                "LR0610",
                start_of(condition.expression),
                f"end condition '{condition.name}' needs {path} "
                f"{'>' if moving > 0 else '<'} 0 while the arm moves {way}: a contact "
                "pushes back against the motion, so it cannot hold on the way",
                "mind the sign of the threshold",
            )

    def against(
        self,
        device: str,
        axis: int,
        moving: int,
        given: Callable[[Terms], list],
    ) -> Iterator[tuple[ast.Condition, str, str]]:
        """The end conditions (written in the action's file) that cannot hold while the arm
        moves along world axis ``axis`` in the sign ``moving``, with the sensor path each
        needs and its kind: a ``force`` of the sign a contact cannot have (it pushes back
        against the motion), a ``travel`` (a length that is 0 when the command starts)
        against the motion. ``given`` says what is known of the parameters read."""
        terms = Terms(self.scope)
        judge = Judge(terms)
        for condition in self.region.end_conditions:
            if condition.expression is None or condition.position.file != file_of(self.component):
                continue
            term = terms.condition(condition.expression)
            readings = []
            for path, (variable, constant) in terms.read.items():
                if variable.kind != "sensor" or not path.startswith(f"{device}."):
                    continue
                if not path.endswith(f".{AXES[axis]}"):
                    continue
                dimension = dimension_of(variable.unit)
                if dimension == FORCE:
                    readings.append((path, "force", constant * (-moving) >= 0))
                elif dimension == LENGTH and variable.start == 0:
                    readings.append((path, "travel", constant * moving >= 0))
            facts = given(terms)
            for path, kind, on_the_way in readings:
                if judge.never(term, on_the_way, *facts) and not judge.never(term, *facts):
                    yield condition, path, kind

    def defaults_of(self, terms: Terms) -> list:
        """The action's parameters read so far, each at its constant default."""
        facts = []
        for path, (variable, constant) in terms.read.items():
            value = self.value(self.defaults.get(path)) if variable.kind == "parameter" else None
            if is_number(value):
                facts.append(constant == exact(float(value)))
        return facts


def goal_argument(
    command: ast.Command, arguments: dict[str, ast.Expression]
) -> ast.Expression | None:
    frames = [p.name for p in command.parameters if p.type == "Frame"]
    return arguments.get(frames[0]) if frames else None


def _relative_motion(
    goal: ast.Expression, device: str
) -> tuple[list[ast.Expression], list[ast.Expression]] | None:
    """The translation (world axes) and rotations of a goal written relative to where the
    device is: ``transl(x, y, z) * device.sensor`` or ``device.sensor * rotZ(a) * …``."""
    factors = product_factors(goal)
    anchors = [i for i, f in enumerate(factors) if reads_device(f, device)]
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


def product_factors(expression: ast.Expression) -> list[ast.Expression]:
    if isinstance(expression, ast.Binary) and expression.operator == "*":
        return product_factors(expression.left) + product_factors(expression.right)
    return [expression]


def _call(expression: ast.Expression) -> str:
    if isinstance(expression, ast.Call) and isinstance(expression.function, ast.Name):
        return expression.function.name
    return ""


def reads_device(expression: ast.Expression, device: str) -> bool:
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


def is_number(value: object) -> bool:
    return isinstance(value, int | float) and not isinstance(value, bool)


def _norm(parts: list[object]) -> float | None:
    if not parts or not all(is_number(p) for p in parts):
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


def dimension_of(unit: str) -> object:
    try:
        return lookup(unit).dimension if unit else None
    except UnitError:
        return None


def file_of(component: Component) -> str:
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
