"""Scenes and robot models by name, from the ``lightrocks.scenes`` and ``lightrocks.robots``
entry points, so that a separate package adds a scene without touching this one.

A scene is an MJCF file plus optional hooks (ground truth, a per-step hook, an analytic
twin of its fixture for Pinocchio). Its MJCF includes the robot by file name
(``<include file="lwr.xml"/>``): every registered robot model is offered under its entry-point
name, so the scene file may live in any package.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from functools import cache
from importlib.metadata import entry_points
from pathlib import Path
from typing import Any

import mujoco


@dataclass(frozen=True)
class Scene:
    mjcf: Path
    measurements: Callable[[mujoco.MjModel, mujoco.MjData], Mapping[str, Any]] | None = None
    """Ground truth (``screw_depth``, …) read by tests, reports and the adapter's user."""
    step: Callable[[mujoco.MjModel, mujoco.MjData], None] | None = None
    """Called before every MuJoCo step (1 kHz): keep it cheap."""
    twin: Callable[[], Any] | None = None
    """Builds the analytic fixture of the Pinocchio twin (see scene_hooks.FixtureTwin)."""


class UnknownScene(ValueError):
    """No registered scene has this name."""


@cache
def scenes() -> dict[str, Scene]:
    return {e.name: e.load() for e in entry_points(group="lightrocks.scenes")}


@cache
def robot_files() -> dict[str, Path]:
    return {e.name: e.load() for e in entry_points(group="lightrocks.robots")}


def scene(name: str) -> Scene:
    found = scenes().get(name) if isinstance(name, str) else None
    if found is None:
        raise UnknownScene(f"unknown scene {name!r}; known scenes: {', '.join(sorted(scenes()))}")
    return found


def load_model(name: str) -> mujoco.MjModel:
    """The MuJoCo model of a scene, its robot include resolved from the robot registry."""
    robots = {f"{robot}.xml": path.read_bytes() for robot, path in robot_files().items()}
    return mujoco.MjModel.from_xml_path(str(scene(name).mjcf), robots)


def objects(model: mujoco.MjModel, robot_body: str) -> list[str]:
    """Named bodies of a scene that are not part of the robot: what a cell may name."""
    robot_root = model.body_rootid[model.body(robot_body).id]
    return [
        model.body(i).name
        for i in range(1, model.nbody)
        if model.body(i).name and model.body_rootid[i] != robot_root
    ]
