"""The optional behaviour of a scene, from its registration (see adapters.scene_registry).
Every hook is optional: a scene without hooks is plain physics and reports no measurements.

- ``measurements(model, data) -> dict``: ground truth (e.g. ``screw_depth``);
- ``step(model, data)``: called before every MuJoCo step;
- ``twin()``: an analytic stand-in of the scene's fixture for the Pinocchio twin, with
  ``step(dt, tcp_position, tcp_rotation, holding) -> wrench at the TCP (world axes)``,
  ``graspable(tcp_position) -> bool`` and ``measurements() -> dict``.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, Protocol

import mujoco
import numpy as np

from lightrocks.adapters.scene_registry import scene as registered


class FixtureTwin(Protocol):
    """The analytic fixture of a scene in the Pinocchio twin."""

    def step(
        self, dt: float, tcp_position: np.ndarray, tcp_rotation: np.ndarray, holding: bool
    ) -> np.ndarray: ...

    def graspable(self, tcp_position: np.ndarray) -> bool: ...

    def measurements(self) -> dict[str, Any]: ...


def measurements(scene: str, model: mujoco.MjModel, data: mujoco.MjData) -> dict[str, Any]:
    hook = registered(scene).measurements
    return {} if hook is None else dict(hook(model, data))


def step_hook(scene: str) -> Callable[[mujoco.MjModel, mujoco.MjData], None] | None:
    """The per-step hook of the scene, or None."""
    return registered(scene).step


def fixture_twin(scene: str) -> FixtureTwin | None:
    make = registered(scene).twin
    return None if make is None else make()
