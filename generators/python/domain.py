"""The domain module ``_domain.py``: device types as ``typing.Protocol`` classes and cells
as ``runtime.Cell`` classes.

The device library (``lightrocks.robots``, on every model path) is a catalogue: of its device
types only those a cell uses are emitted, so that a type added to it changes no generated
module of a model that does not use it. A model's own device types are always emitted."""

from __future__ import annotations

import keyword

from lightrocks.generators.python.builder import Builder
from lightrocks.generators.python.expressions import Scope
from lightrocks.generators.python.names import identifier
from lightrocks.generators.python.values import python_type, stereotype_value, zero_value
from lightrocks.generators.python.views import docstring_text
from lightrocks.metamodel import ast
from lightrocks.workbench.modelpath import in_library
from lightrocks.workbench.workspace import Symbol


def domain_module(builder: Builder, environment) -> str | None:
    workspace = builder.workspace
    symbols = sorted(workspace.symbols.values(), key=lambda s: s.qualified_name)
    used = _used_devices(builder, [s for s in symbols if isinstance(s.node, ast.Cell)])
    devices, cells = [], []
    for symbol in symbols:
        if isinstance(symbol.node, ast.Device):
            if symbol.qualified_name in used or not in_library(symbol.loaded.path):
                devices.append(_device_view(builder, symbol))
        elif isinstance(symbol.node, ast.Cell):
            cells.append(_cell_view(builder, symbol))
    if not devices and not cells:
        return None
    return environment.get_template("domain.py.jinja").render(devices=devices, cells=cells)


def _used_devices(builder: Builder, cells: list[Symbol]) -> set[str]:
    """The qualified names of the device types the cells' devices have."""
    found = set()
    for cell in cells:
        for device in cell.node.devices:
            symbol = builder.workspace.resolve(cell.loaded, device.type)
            if symbol is not None:
                found.add(symbol.qualified_name)
    return found


def _device_view(builder: Builder, symbol) -> dict:
    device: ast.Device = symbol.node
    types = builder.typing.types
    commands = []
    for command in device.commands:
        parameters = "".join(
            f", {_member_name(p.name)}: {python_type(types.resolve(symbol.loaded, p.type))}"
            + (" = ..." if p.default is not None else "")
            for p in command.parameters
        )
        returns = (
            python_type(types.resolve(symbol.loaded, command.returns))
            if command.returns
            else "None"
        )
        commands.append({"name": _member_name(command.name), "parameters": parameters,
                         "returns": returns})  # fmt: skip
    sensors = [
        {"name": _member_name(s.name), "type": python_type(types.resolve(symbol.loaded, s.type))}
        for s in device.sensors
    ]
    return {
        "name": identifier(device.name),
        "qualified": docstring_text(symbol.qualified_name),
        "type_name": repr(device.name),
        "commands": commands,
        "sensors": sensors,
    }


def _cell_view(builder: Builder, symbol) -> dict:
    cell: ast.Cell = symbol.node
    scope = Scope(None, None)
    devices = ", ".join(
        f"{d.name!r}: {identifier(d.type.rpartition('.')[2])}" for d in cell.devices
    )
    objects = []
    for obj in cell.objects:
        values = []
        for a in obj.attributes:
            if a.default is not None:
                value = builder.compile(a.default, scope)
            else:
                value = zero_value(builder.typing.types.resolve(symbol.loaded, a.type))
            if value is not None:
                values.append(f"{identifier(a.name)!r}: {value}")
        objects.append(f"{identifier(obj.name)!r}: {{{', '.join(values)}}}")
    return {
        "name": identifier(cell.name),
        "qualified": docstring_text(symbol.qualified_name),
        "scene": repr(stereotype_value(cell.stereotypes, "scene")),
        "devices": "{" + devices + "}",
        "objects": "{" + ", ".join(objects) + "}",
    }


def _member_name(name: str) -> str:
    """A command, parameter or sensor name as the adapter knows it (only keywords change)."""
    return f"{name}_" if keyword.iskeyword(name) else name
