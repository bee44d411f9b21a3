"""Binding an adapter: check that it offers every device, command and sensor a cell uses,
and, when it simulates a scene (it has ``objects()``), every object the cell names.

The device types are the ``typing.Protocol`` classes the generator emits from the domain
interface: their methods are the commands, their properties the sensors. All problems are
reported in one :class:`BindingError` so a user fixes them in one go.
"""

from __future__ import annotations

import inspect
from collections.abc import Mapping
from typing import Any

from lightrocks.runtime.contract import Adapter


class BindingError(Exception):
    """The adapter does not conform to the cell's device interface."""


def members(protocol: type) -> tuple[list[str], list[str]]:
    """Commands (methods) and sensors (properties) of a device protocol, in declaration order."""
    commands, sensors = [], []
    for name, value in vars(protocol).items():
        if isinstance(value, property):
            sensors.append(name)
        elif inspect.isfunction(value) and not name.startswith("_"):
            commands.append(name)
    return commands, sensors


def problems(adapter: Adapter, devices: Mapping[str, type]) -> list[str]:
    """Everything the adapter lacks for these device instances (name -> protocol)."""
    emulate = getattr(adapter, "emulate", None)
    if emulate is not None:  # a dry run offers the devices it is asked for
        emulate(devices)
    offered = adapter.devices()
    found: list[str] = []
    snapshot: Any = adapter.snapshot() if offered else None
    offered_commands = getattr(adapter, "commands", None)
    for instance, protocol in devices.items():
        type_name = getattr(protocol, "DEVICE_TYPE", protocol.__name__)
        if instance not in offered:
            found.append(f"missing device '{instance}' ({type_name})")
            continue
        if offered[instance] != type_name:
            found.append(f"device '{instance}' is a {offered[instance]}, expected {type_name}")
        commands, sensors = members(protocol)
        state = getattr(snapshot, instance, None)
        for sensor in sensors:
            if state is None or not hasattr(state, sensor):
                found.append(f"missing sensor '{instance}.{sensor}'")
        if offered_commands is not None:
            known = set(offered_commands().get(instance, ()))
            found += [f"missing command '{instance}.{c}'" for c in commands if c not in known]
    return found


def missing_objects(adapter: Adapter, objects: Mapping[str, Any]) -> list[str]:
    """The cell's objects the adapter's scene does not have (none without a scene)."""
    offered = getattr(adapter, "objects", None)
    if offered is None:
        return []
    scene = getattr(adapter, "scene", "?")
    known = set(offered())
    return [f"scene '{scene}' has no object '{name}'" for name in objects if name not in known]


def bind(adapter: Adapter, cell: Any) -> None:
    """Raise :class:`BindingError` naming every missing device, command, sensor and object."""
    if cell is None:
        return
    found = problems(adapter, cell.DEVICES) + missing_objects(adapter, cell.OBJECTS)
    if found:
        raise BindingError(
            f"adapter {type(adapter).__name__} does not fit cell {cell.__name__}:\n  "
            + "\n  ".join(found)
        )
