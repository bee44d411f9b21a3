"""Scenes and robot models by name, from the ``lightrocks.scenes`` and ``lightrocks.robots``
entry points, so that a separate package adds a scene without touching this one.

A scene is an ``adapters.scene.Scene`` object. Its MJCF includes the robot by file name
(``<include file="lwr.xml"/>``): every registered robot model is offered under its entry-point
name, so the scene file may live in any package.
"""

from __future__ import annotations

from functools import cache
from importlib.metadata import entry_points
from pathlib import Path

import mujoco

from lightrocks.adapters.scene import Scene


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
