"""A cell's ``robot`` slot re-bound to another device type (a run with ``--robot``), for
checking and generating.

The chosen type takes the slot only when it offers the interface of the slot's declared type
(:mod:`languages.domain.interface`); then the cell's parsed unit is copied with the slot's
type replaced, for a check that takes it in place of the cell's file
(``check(…, substituted=rebinding.substituted)``). So every value the model sends the robot
is checked against the chosen type's safe ranges, at its own file:line:col, and the
chosen type's defaults stand where the model leaves a parameter out; the parse and check
caches only ever hold what the files say (the copy is never parsed, and a check given it is
not remembered), and the generated code's cache key names the re-binding.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace
from pathlib import Path

from lightrocks.languages.domain.interface import differences, interface
from lightrocks.languages.domain.types import Types
from lightrocks.languages.lightrocks.model import running_cell
from lightrocks.metamodel import ast
from lightrocks.workbench.check import load
from lightrocks.workbench.workspace import Loaded, Symbol, Workspace

ROBOT_SLOT = "robot"
"""The cell's device that the adapters' robot is: the name they offer it under."""
LIBRARY_PACKAGE = "lightrocks.robots"
"""Where a robot's device type is looked up when the cell does not see it."""


class RebindingError(Exception):
    """The chosen robot cannot take the cell's slot; the message says why."""


class InterfaceDiffers(RebindingError):
    """The robot's device type lacks (or changes) part of the slot's interface."""


class NoDeviceType(RebindingError):
    """No device type of the robot's name is on the model path or in the device library."""


@dataclass(frozen=True)
class Rebinding:
    """The cell's file with its robot slot re-bound, and what that is in words."""

    path: Path
    unit: ast.DomainUnit
    description: str

    @property
    def substituted(self) -> dict[Path, ast.DomainUnit]:
        """The re-bound unit in place of the cell's file, for ``check(substituted=…)``."""
        return {self.path: self.unit}


def rebinding(
    model: Path, search_path: Sequence[Path], robot: str, device_type: str
) -> Rebinding | None:
    """The re-binding a run of ``model`` on the robot called ``robot``, a ``device_type``,
    needs; ``None`` when the model has no cell with a robot slot, or the slot already has
    that type.

    The models are loaded into a workspace of this look-up's own: finding the robot's type
    may load packages, which must not reach the remembered workspace of an earlier check."""
    workspace = load([model], list(search_path)).workspace
    loaded = workspace.files.get(model.resolve())
    cell = running_cell(workspace, loaded) if loaded is not None else None
    slot = next((d for d in cell.node.devices if d.name == ROBOT_SLOT), None) if cell else None
    declared = workspace.resolve(cell.loaded, slot.type) if slot is not None else None
    if declared is None or not isinstance(declared.node, ast.Device):
        return None
    offered = _device_type(workspace, cell.loaded, robot, device_type)
    if offered.qualified_name == declared.qualified_name:
        return None
    where = f"the slot '{slot.name} : {slot.type}' of cell {cell.qualified_name}"
    types = Types(workspace)
    found = differences(
        interface(types, declared.loaded, declared.node),
        interface(types, offered.loaded, offered.node),
    )
    if found:
        raise InterfaceDiffers(
            f"error: robot '{robot}' ({offered.qualified_name}) cannot take {where}: "
            f"its interface differs from {declared.name}'s:\n  " + "\n  ".join(found)
        )
    rebound = replace(slot, type=offered.qualified_name)
    node = replace(cell.node, members=_swapped(cell.node.members, slot, rebound))
    unit = replace(
        cell.loaded.unit, declarations=_swapped(cell.loaded.unit.declarations, cell.node, node)
    )
    description = f"robot '{robot}': {offered.qualified_name} in {where}"
    return Rebinding(cell.loaded.path, unit, description)


def _device_type(workspace: Workspace, cell: Loaded, robot: str, device_type: str) -> Symbol:
    """The robot's device type as the cell sees it, else from the device library."""
    found = workspace.scope(cell).get(device_type)
    if found is None or not isinstance(found.node, ast.Device):
        found = workspace.lookup(f"{LIBRARY_PACKAGE}.{device_type}")
    if found is None or not isinstance(found.node, ast.Device):
        raise NoDeviceType(
            f"robot '{robot}' is a {device_type}, but no device type {device_type} is on the "
            f"model path (nor {LIBRARY_PACKAGE}.{device_type} in the device library)"
        )
    return found


def _swapped(items: tuple, old: object, new: object) -> tuple:
    return tuple(new if item is old else item for item in items)
