"""Optional scene-specific behaviour, looked up lazily in ``adapters.scenes`` (owned by the
scene files' author). Every hook is optional: without the module, or without a hook in it,
scenes are plain physics and report no measurements.

Hooks used, all keyed by scene name:
- ``measurements(scene, model, data) -> dict``: ground truth (e.g. ``screw_depth``);
- ``scene_step(scene, model, data)``: called before every MuJoCo step;
- ``make_twin(scene)``: an analytic stand-in of the scene's fixture for the Pinocchio twin, with
  ``step(dt, tcp_position, tcp_rotation, holding) -> wrench at the TCP (world axes)``,
  ``graspable(tcp_position) -> bool`` and ``measurements() -> dict``.
"""

from __future__ import annotations

import functools
import importlib
from collections.abc import Callable
from types import ModuleType
from typing import Any, Protocol

import mujoco
import numpy as np


class FixtureTwin(Protocol):
    """The analytic fixture of a scene in the Pinocchio twin."""

    def step(
        self, dt: float, tcp_position: np.ndarray, tcp_rotation: np.ndarray, holding: bool
    ) -> np.ndarray: ...

    def graspable(self, tcp_position: np.ndarray) -> bool: ...

    def measurements(self) -> dict[str, Any]: ...


def _scenes() -> ModuleType | None:
    try:
        return importlib.import_module("lightrocks.adapters.scenes")
    except ModuleNotFoundError:
        return None


def _hook(name: str) -> Callable[..., Any] | None:
    module = _scenes()
    return None if module is None else getattr(module, name, None)


def measurements(scene: str, model: mujoco.MjModel, data: mujoco.MjData) -> dict[str, Any]:
    hook = _hook("measurements")
    return {} if hook is None else dict(hook(scene, model, data))


def step_hook(scene: str) -> Callable[[mujoco.MjModel, mujoco.MjData], None] | None:
    """The per-step hook bound to the scene, or None."""
    hook = _hook("scene_step")
    if hook is None:
        return None
    return functools.partial(hook, scene)


def fixture_twin(scene: str) -> FixtureTwin | None:
    hook = _hook("make_twin")
    return None if hook is None else hook(scene)
