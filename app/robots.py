"""The robots a run can put in its cell's robot slot (``--robot``): those that the
``lightrocks.robots`` entry point registers (``adapters.scene_registry``)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from lightrocks.app.errors import RunError


@dataclass(frozen=True)
class RobotChoice:
    """A registered robot as a run needs it: its name for the adapter, its device type for
    the cell. Plain data, so that a spec carrying it crosses to worker processes."""

    name: str
    device_type: str


def registered() -> dict[str, Any]:
    """Every registered robot by name (imported here only: the registry loads MuJoCo)."""
    from lightrocks.adapters import scene_registry

    return scene_registry.robots()


def choose(name: str) -> RobotChoice:
    """The registered robot ``name``; an unknown one is a ``RunError`` naming the known."""
    from lightrocks.adapters import scene_registry

    try:
        robot = scene_registry.robot(name)
    except scene_registry.UnknownRobot as error:
        raise RunError(str(error)) from None
    return RobotChoice(name, robot.device_type)
