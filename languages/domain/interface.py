"""What a device type offers the models that use it: its commands (each parameter's name,
type and whether a call may leave it out, in order, and the returned type) and its sensors
(name and type). Two device types with equal interfaces can stand in for each other in a
cell's slot: every call and every sensor read that checks against one checks against the
other. Safe ranges, defaults and comments are no part of it: they are each device's own."""

from __future__ import annotations

from dataclasses import dataclass, field

from lightrocks.languages.domain.types import Type, Types
from lightrocks.metamodel import ast
from lightrocks.workbench.workspace import Loaded


@dataclass(frozen=True)
class Typed:
    """A type as written, compared by what it resolves to (its dimension, its elements)."""

    name: str
    resolved: Type | None = field(repr=False)

    def __str__(self) -> str:
        return self.name


@dataclass(frozen=True)
class Parameter:
    name: str
    type: Typed
    optional: bool

    def __str__(self) -> str:
        return f"{self.type} {self.name}" + (" = …" if self.optional else "")


@dataclass(frozen=True)
class Signature:
    parameters: tuple[Parameter, ...]
    returns: Typed | None

    def __str__(self) -> str:
        shown = f"({', '.join(map(str, self.parameters))})"
        return shown + (f" returns {self.returns}" if self.returns else "")


@dataclass(frozen=True)
class Interface:
    """Commands and sensors by name; a command's parameters in declaration order."""

    device: str
    commands: dict[str, Signature]
    sensors: dict[str, Typed]


def interface(types: Types, loaded: Loaded, device: ast.Device) -> Interface:
    """The interface of ``device``, declared in ``loaded``, with its types resolved."""

    def typed(name: str) -> Typed:
        return Typed(name.rpartition(".")[2], types.resolve(loaded, name))

    commands = {
        command.name: Signature(
            tuple(
                Parameter(p.name, typed(p.type), p.default is not None) for p in command.parameters
            ),
            typed(command.returns) if command.returns else None,
        )
        for command in device.commands
    }
    sensors = {sensor.name: typed(sensor.type) for sensor in device.sensors}
    return Interface(device.name, commands, sensors)


def differences(declared: Interface, offered: Interface) -> list[str]:
    """What ``offered`` lacks, adds or has otherwise than ``declared``; empty when the two
    are the same interface."""
    found = []
    for kind, mine, theirs in (
        ("command", declared.commands, offered.commands),
        ("sensor", declared.sensors, offered.sensors),
    ):
        for name, value in mine.items():
            if name not in theirs:
                found.append(f"{offered.device} has no {kind} '{name}'")
            elif theirs[name] != value:
                found.append(
                    f"{kind} '{name}' is {_shown(name, value)} in {declared.device}, "
                    f"{_shown(name, theirs[name])} in {offered.device}"
                )
        found += [
            f"{offered.device} has a {kind} '{name}' that {declared.device} does not have"
            for name in theirs
            if name not in mine
        ]
    return found


def _shown(name: str, value: Signature | Typed) -> str:
    return f"{name}{value}" if isinstance(value, Signature) else f"{value} {name}"
