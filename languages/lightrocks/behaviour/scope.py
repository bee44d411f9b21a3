"""What a name in a condition of one region stands for: a parameter, a sensor leaf, an
attribute of a scene object, or something the solver cannot know (then ``None``)."""

from __future__ import annotations

from functools import cached_property

from lightrocks.languages.domain.types import (
    FRAME,
    FRAME_MEMBERS,
    DeviceT,
    ObjectT,
    StructT,
    Type,
)
from lightrocks.languages.lightrocks.access import names_of
from lightrocks.languages.lightrocks.behaviour.variables import (
    Variable,
    attribute_variable,
    parameter_variable,
    sensor_variables,
    sort_of,
)
from lightrocks.languages.lightrocks.model import Region, visible_cells
from lightrocks.languages.lightrocks.typing import Typing
from lightrocks.metamodel import ast


class Scope:
    """Names of one region resolved to solver variables, built lazily and kept per path."""

    def __init__(self, typing: Typing, region: Region) -> None:
        self.typing = typing
        self.region = region
        self._variables: dict[str, Variable | None] = {}

    @cached_property
    def env(self) -> dict[str, Type]:
        return self.typing.environment(self.region)

    @cached_property
    def parameters(self) -> dict[str, ast.Parameter]:
        found: dict[str, ast.Parameter] = {}
        current: Region | None = self.region
        while current is not None:
            for name, parameter in current.parameters.items():
                found.setdefault(name, parameter)
            current = current.parent
        return found

    @cached_property
    def objects(self) -> dict[str, ast.SceneObject]:
        workspace = self.typing.models.workspace
        found: dict[str, ast.SceneObject] = {}
        for symbol in visible_cells(workspace, self.region.loaded):
            found.update((o.name, o) for o in symbol.node.objects)
        return found

    def variable(self, expression: ast.Expression) -> Variable | None:
        """The variable a name or member chain reads, or None when it is no scalar value."""
        chain = names_of(expression)
        if chain is None:
            return None
        path = ".".join(chain)
        if path not in self._variables:
            self._variables[path] = self._resolve(chain)
        return self._variables[path]

    def _resolve(self, chain: list[str]) -> Variable | None:
        head, rest = chain[0], chain[1:]
        kind = self.env.get(head)
        if kind is None:
            return None
        if head in self.parameters and not isinstance(kind, ObjectT):
            if not rest:
                return parameter_variable(self.parameters[head], kind)
            return _free(chain, _walk(kind, rest), "parameter")
        if isinstance(kind, DeviceT) and kind.device is not None and rest:
            return self._sensor(head, kind, rest)
        if isinstance(kind, ObjectT) and rest:
            return self._attribute(head, kind, rest)
        return None

    def _sensor(self, instance: str, device: DeviceT, rest: list[str]) -> Variable | None:
        sensor = next((s for s in device.device.sensors if s.name == rest[0]), None)
        if sensor is None:
            return None
        kind = self.typing.types.resolve(self._declaring(device.device), sensor.type)
        if kind is None:
            return None
        path = ".".join((instance, *rest))
        for variable in sensor_variables(instance, device, sensor, kind):
            if variable.path == path:
                return variable
        return None

    def _attribute(self, name: str, kind: ObjectT, rest: list[str]) -> Variable | None:
        declared = self.objects.get(name) if kind.attributes is not None else None
        attributes = dict(kind.attributes or ())
        if rest[0] == "pose":
            return _free([name, *rest], _walk(FRAME, rest[1:]), "attribute")
        if declared is None:  # an Object parameter: which object is known only at run time
            return self._any_object(name, rest)
        attribute = next((a for a in declared.attributes if a.name == rest[0]), None)
        if attribute is None or rest[0] not in attributes:
            return None
        if len(rest) > 1:
            return _free([name, *rest], _walk(attributes[rest[0]], rest[1:]), "attribute")
        return attribute_variable(name, attribute, attributes[rest[0]])

    def _any_object(self, name: str, rest: list[str]) -> Variable | None:
        """An attribute of an ``Object`` parameter: typed and ranged as the attributes of
        that name of every object of the cell, when they all agree."""
        found = set()
        for obj, kind in self.env.items():
            if not isinstance(kind, ObjectT) or kind.attributes is None or obj not in self.objects:
                continue
            attribute = next((a for a in self.objects[obj].attributes if a.name == rest[0]), None)
            if attribute is not None:
                variable = attribute_variable(name, attribute, dict(kind.attributes)[rest[0]])
                found.add(variable)
        if len(found) != 1 or len(rest) > 1:
            return None
        return found.pop()

    def _declaring(self, device: ast.Device):
        for loaded in self.typing.models.workspace.loaded_units():
            if loaded.unit.package_position.file == device.position.file:
                return loaded
        return self.region.loaded


def _walk(kind: Type | None, names: list[str]) -> Type | None:
    for name in names:
        if isinstance(kind, StructT):
            kind = kind.field(name)
        elif kind == FRAME:
            kind = FRAME_MEMBERS.get(name)
        else:
            return None
    return kind


def _free(chain: list[str], kind: Type | None, origin: str) -> Variable | None:
    sort = sort_of(kind) if kind is not None else None
    return Variable(".".join(chain), sort, kind=origin) if sort is not None else None
