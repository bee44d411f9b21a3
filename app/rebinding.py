"""A run on another robot than its cell names (``--robot``): the language's re-binding of the
cell's robot slot (:mod:`languages.domain.rebinding`) for the robot chosen on the command
line, its refusals as the application's errors."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

from lightrocks.app.errors import ModelError, RunError
from lightrocks.app.robots import RobotChoice
from lightrocks.languages.domain import rebinding as language
from lightrocks.languages.domain.rebinding import Rebinding

__all__ = ["Rebinding", "rebinding"]


def rebinding(model: Path, search_path: Sequence[Path], robot: RobotChoice) -> Rebinding | None:
    """The re-binding a run of ``model`` on ``robot`` needs, or None; a device type that
    does not offer the slot's interface is a ``ModelError`` naming what differs, a missing
    one a ``RunError``."""
    try:
        return language.rebinding(model, search_path, robot.name, robot.device_type)
    except language.InterfaceDiffers as error:
        raise ModelError(str(error)) from None
    except language.NoDeviceType as error:
        raise RunError(str(error)) from None
