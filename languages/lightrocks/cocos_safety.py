"""Context conditions that keep a model from meaning something its author did not write:
typed stereotype values, actions that can end, guards in their place, and safe ranges on
every path a constant takes to a device command (defaults, bindings, expressions)."""

from __future__ import annotations

import re
from collections.abc import Iterator
from dataclasses import dataclass

from lightrocks.languages.domain.types import DeviceT
from lightrocks.languages.lightrocks.analysis import Analysis, analysis
from lightrocks.languages.lightrocks.model import Component, Region
from lightrocks.metamodel import ast
from lightrocks.metamodel.units import TIME, UnitError, lookup
from lightrocks.workbench.cocos import coco
from lightrocks.workbench.diagnostics import Severity

Finding = tuple[ast.Position, str, str]

DURATION = re.compile(r"\s*(\d+(?:\.\d+)?(?:[eE][-+]?\d+)?)\s*([A-Za-z]+)\s*")
SCENE_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")


def _stereotypes(a: Analysis) -> Iterator[ast.Stereotype]:
    """Every stereotype of every loaded unit: statecharts, their states, devices and cells."""
    for loaded in a.workspace.loaded_units():
        unit = loaded.unit
        if isinstance(unit, ast.StatechartUnit):
            yield from unit.statechart.stereotypes
            yield from _state_stereotypes(unit.statechart.elements)
        else:
            for declaration in unit.declarations:
                yield from getattr(declaration, "stereotypes", ())


def _state_stereotypes(elements: tuple) -> Iterator[ast.Stereotype]:
    for element in elements:
        if isinstance(element, ast.State):
            yield from element.stereotypes
            yield from _state_stereotypes(element.body or ())


@coco("LR0501", Severity.ERROR, "a timeout is a duration with a time unit, such as 5 s")
def timeout_is_duration(context: object) -> Iterator[Finding]:
    for stereotype in _stereotypes(analysis(context)):
        if stereotype.name != "timeout":
            continue
        match = DURATION.fullmatch(stereotype.value or "")
        try:
            timed = match is not None and lookup(match.group(2)).dimension == TIME
        except UnitError:
            timed = False
        if not timed:
            yield (
                stereotype.position,
                f"timeout '{stereotype.value}' is not a duration",
                'write a number with a time unit, e.g. <<timeout="8 s">>',
            )


@coco("LR0502", Severity.ERROR, "a scene is named, not given as a path")
def scene_is_name(context: object) -> Iterator[Finding]:
    for stereotype in _stereotypes(analysis(context)):
        if stereotype.name == "scene" and not SCENE_NAME.fullmatch(stereotype.value or ""):
            yield (
                stereotype.position,
                f"scene '{stereotype.value}' is not a scene name",
                'name a scene the adapters know, e.g. <<scene="screwing">>',
            )


@coco("LR0503", Severity.ERROR, "an elemental action declares an end condition")
def action_can_end(context: object) -> Iterator[Finding]:
    for component in analysis(context).models.components:
        if component.layer == "action" and not component.region.end_conditions:
            yield (
                component.statechart.position,
                f"action '{component.name}' has no end condition: its command never ends it",
                "declare one, e.g. 'end condition done: <sensor condition>;'",
            )


@coco("LR0504", Severity.ERROR, "a condition after the stimulus follows an action")
def guard_in_place(context: object) -> Iterator[Finding]:
    for _, region in _own_regions(analysis(context)):
        for transition in region.transitions:
            if transition.postcondition is not None and transition.action is None:
                yield (
                    transition.postcondition.position,
                    "a [condition] after the stimulus is a postcondition, not a guard",
                    f"write the guard before the stimulus: "
                    f"{transition.source} -> {transition.target} [...] {transition.stimulus};",
                )


# -- safe ranges through parameters ------------------------------------------------------


@dataclass(frozen=True)
class Limit:
    """A parameter's value ends up as ``element`` of ``device.command``."""

    device: str
    command: str
    element: str
    low: list[float] | None
    high: list[float] | None

    def violated_by(self, values: list[float]) -> bool:
        for index, number in enumerate(values):
            low, high = _pick(self.low, index), _pick(self.high, index)
            if (low is not None and number < low) or (high is not None and number > high):
                return True
        return False

    def describe(self) -> str:
        low, high = _show(self.low, "-inf"), _show(self.high, "inf")
        return f"{self.device}.{self.command}({self.element}), safe range [{low}, {high}]"


@coco(
    "LR0505",
    Severity.ERROR,
    "constants reaching a command through expressions, defaults and bindings are in range",
)
def safe_through_parameters(context: object) -> Iterator[Finding]:
    a = analysis(context)
    limits = _Limits(a)
    for component, region in _own_regions(a):
        for parameter in region.parameters.values():
            if parameter.default is not None and parameter.position.file == _file(region):
                for limit in limits.of(component).get(parameter.name, ()):
                    yield from _check(parameter.default, limit, f"default of '{parameter.name}'")
        for info in region.states.values():
            called = limits.called(region, info.state)
            if called is None:
                continue
            names = list(called.region.parameters)
            for index, argument in enumerate(info.state.arguments):
                name = argument.name or (names[index] if index < len(names) else "")
                for limit in limits.of(called).get(name, ()):
                    yield from _check(argument.value, limit, f"argument '{name}'")
        for device, command, element, value in limits.command_arguments(region):
            if not isinstance(value, ast.Quantity | ast.VectorLiteral):  # LR0305 has literals
                yield from _check(value, Limit(device, command.name, *element), "value")


class _Limits:
    """Which command element each component parameter flows into, unchanged."""

    def __init__(self, a: Analysis) -> None:
        self.a = a
        self._known: dict[str, dict[str, list[Limit]]] = {}

    def of(self, component: Component) -> dict[str, list[Limit]]:
        if component.qualified_name in self._known:
            return self._known[component.qualified_name]
        found: dict[str, list[Limit]] = {}
        self._known[component.qualified_name] = found  # a cycle stops here
        for region in component.region.regions():
            own = region.parameters
            for device, command, element, value in self.command_arguments(region):
                if isinstance(value, ast.Name) and value.name in own:
                    found.setdefault(value.name, []).append(Limit(device, command.name, *element))
            for info in region.states.values():
                called = self.called(region, info.state)
                if called is None:
                    continue
                names = list(called.region.parameters)
                for index, argument in enumerate(info.state.arguments):
                    name = argument.name or (names[index] if index < len(names) else "")
                    value = argument.value
                    if isinstance(value, ast.Name) and value.name in own:
                        found.setdefault(value.name, []).extend(self.of(called).get(name, ()))
        return found

    def called(self, region: Region, state: ast.State) -> Component | None:
        reference = ast.stereotype(state.stereotypes, "import")
        if reference is None or not reference.value:
            return None
        return self.a.models.resolve_statechart(region.loaded, reference.value)

    def command_arguments(
        self, region: Region
    ) -> Iterator[tuple[str, ast.Command, tuple, ast.Expression]]:
        """(device, command, (element, low, high), value) for every argument of a do call."""
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
                env = env if env is not None else self.a.typing.environment(region)
                device = env.get(owner.name)
                if not isinstance(device, DeviceT) or device.device is None:
                    continue
                command = next(
                    (c for c in device.device.commands if c.name == call.function.name), None
                )
                if command is None:
                    continue
                parameters = {p.name: p for p in command.parameters}
                order = list(parameters)
                for index, argument in enumerate(call.arguments):
                    name = argument.name or (order[index] if index < len(order) else "")
                    declared = parameters.get(name)
                    if declared is None or (declared.low is None and declared.high is None):
                        continue
                    element = (name, constant_values(declared.low), constant_values(declared.high))
                    yield owner.name, command, element, argument.value


def _check(value: ast.Expression, limit: Limit, what: str) -> Iterator[Finding]:
    numbers = constant_values(value)
    if numbers is not None and limit.violated_by(numbers):
        yield (
            value.position,
            f"{what} is outside the safe range of {limit.describe()}",
            "",
        )


def constant_values(expression: ast.Expression | None) -> list[float] | None:
    """The numbers of a constant expression (literals, signs, + - * /, vectors); None else."""
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
            return [_apply(operator, left[0], right[0])]
    return None


def _apply(operator: str, left: float, right: float) -> float:
    if operator == "+":
        return left + right
    if operator == "-":
        return left - right
    return left * right if operator == "*" else left / right


def _pick(values: list[float] | None, index: int) -> float | None:
    if not values:
        return None
    return values[index] if len(values) > 1 and index < len(values) else values[0]


def _show(values: list[float] | None, unbounded: str) -> str:
    """SI numbers, one per element when the bound differs per element."""
    if not values:
        return unbounded
    shown = [f"{v:g}" for v in values]
    return shown[0] if len(shown) == 1 else "(" + ", ".join(shown) + ")"


def _own_regions(a: Analysis) -> Iterator[tuple[Component, Region]]:
    for component in a.models.components:
        for region in component.region.regions():
            if region.loaded is component.loaded:
                yield component, region


def _file(region: Region) -> str:
    return region.loaded.unit.package_position.file


SAFETY_COCOS = (
    timeout_is_duration,
    scene_is_name,
    action_can_end,
    guard_in_place,
    safe_through_parameters,
)
