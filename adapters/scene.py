"""What a scene is: an MJCF file and the behaviour plain physics does not give it, as one
object that a ``lightrocks.scenes`` entry point registers (see adapters.scene_registry).

A scene with behaviour subclasses :class:`Scene` and overrides the hooks it needs, so that
adapters ask the scene object and never switch on its name. The defaults are plain physics:
no ground truth, nothing to do per step, no analytic fixture and no goal.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Protocol

import mujoco
import numpy as np

from lightrocks.runtime.contract import AdapterError


class SceneFault(AdapterError):
    """A scene's MJCF does not load or one of its hooks raised: the scene author's mistake,
    named with the scene, so that a run reports it as the scene's and not as its own."""


def hook_fault(scene: str, hook: str, error: Exception) -> SceneFault:
    """The fault of ``scene``'s ``hook`` that raised ``error``."""
    return SceneFault(f"scene {scene!r}: {hook}() raised {type(error).__name__}: {error}")


class FixtureTwin(Protocol):
    """The analytic fixture of a scene in the Pinocchio twin, which has no contact physics
    for moving parts: stepped every tick with the TCP pose (world frame) and whether the
    gripper is closed, it returns the wrench (force, torque; world axes, at the TCP) it exerts
    on the gripper."""

    def step(
        self, dt: float, tcp_position: np.ndarray, tcp_rotation: np.ndarray, holding: bool
    ) -> np.ndarray: ...

    def graspable(self, tcp_position: np.ndarray) -> bool: ...

    def measurements(self) -> dict[str, Any]: ...


@dataclass(frozen=True)
class Scene:
    """A scene: its MJCF (which includes the robot, see adapters.scene_registry) and hooks."""

    mjcf: Path

    def measurements(self, model: mujoco.MjModel, data: mujoco.MjData) -> dict[str, Any]:
        """Ground truth (``screw_depth``, …) read by tests, reports and the adapter's user."""
        return {}

    def step(self, model: mujoco.MjModel, data: mujoco.MjData) -> None:
        """Called before every MuJoCo step (1 kHz): keep it cheap."""

    def twin(self) -> FixtureTwin | None:
        """A new analytic fixture for the Pinocchio twin; without one, the twin reads
        :meth:`measurements` from the MuJoCo data it keeps in step with the robot."""
        return None

    def goal_met(self, values: Mapping[str, Any]) -> bool:
        """Whether :meth:`measurements` show the scene's case study done."""
        return False
