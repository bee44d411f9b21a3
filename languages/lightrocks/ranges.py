"""Which statechart parameters flow unchanged into a ranged command argument, directly or
through the bindings of imported statecharts (the ranges themselves are the domain's)."""

from __future__ import annotations

from collections.abc import Iterator
from typing import TYPE_CHECKING

from lightrocks.languages.domain.ranges import Range, command_ranges
from lightrocks.languages.domain.types import DeviceT
from lightrocks.languages.lightrocks.model import Component, Region
from lightrocks.metamodel import ast

if TYPE_CHECKING:  # the typing uses the domain's ranges itself
    from lightrocks.languages.lightrocks.typing import Typing


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
                call = ast.evaluated(statement)
                if not isinstance(call, ast.Call) or not isinstance(call.function, ast.Member):
                    continue
                owner = call.function.target
                if not isinstance(owner, ast.Name):
                    continue
                env = env if env is not None else self.typing.environment(region)
                device = env.get(owner.name)
                if isinstance(device, DeviceT) and device.device is not None:
                    yield from _ranged(owner.name, device.device, call)


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
