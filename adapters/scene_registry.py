"""Scenes and robots by name, from the ``lightrocks.scenes`` and ``lightrocks.robots`` entry
points, so that a separate package adds a scene or a robot without touching this one.

A scene is an ``adapters.scene.Scene`` object, a robot an ``adapters.robot.Robot``. A scene's
MJCF includes the robot of the run by file name, ``<include file="robot.xml"/>``; that robot
is offered under its own name too (``lwr.xml``), for scenes written before robots could be
chosen, which then run with that robot only.
"""

from __future__ import annotations

from functools import cache
from importlib.metadata import entry_points

import mujoco

from lightrocks.adapters.robot import Robot
from lightrocks.adapters.scene import Scene


class UnknownScene(ValueError):
    """No registered scene has this name."""


class UnknownRobot(ValueError):
    """No registered robot has this name."""


@cache
def scenes() -> dict[str, Scene]:
    return {e.name: e.load() for e in entry_points(group="lightrocks.scenes")}


@cache
def robots() -> dict[str, Robot]:
    """Every registered robot; loading one reads no model files (that happens when a scene
    with it is loaded), so listing them needs no robot's data installed."""
    return {e.name: e.load() for e in entry_points(group="lightrocks.robots")}


def scene(name: str) -> Scene:
    found = scenes().get(name) if isinstance(name, str) else None
    if found is None:
        raise UnknownScene(f"unknown scene {name!r}; known scenes: {', '.join(sorted(scenes()))}")
    return found


def robot(name: str) -> Robot:
    found = robots().get(name) if isinstance(name, str) else None
    if found is None:
        raise UnknownRobot(f"unknown robot {name!r}; known robots: {', '.join(sorted(robots()))}")
    return found


def load_model(name: str, robot_name: str = "lwr") -> mujoco.MjModel:
    """The MuJoCo model of a scene with the named robot as its ``robot.xml``."""
    chosen = robot(robot_name)
    mjcf = chosen.mjcf()
    assets = {"robot.xml": mjcf, f"{robot_name}.xml": mjcf}
    model = mujoco.MjModel.from_xml_path(str(scene(name).mjcf), assets)
    if mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, chosen.arm_joints[0]) < 0:
        raise ValueError(
            f"scene {name!r} does not include the robot {robot_name!r}: "
            'its MJCF must include <include file="robot.xml"/>'
        )
    return model


def objects(model: mujoco.MjModel, robot_body: str) -> list[str]:
    """Named bodies of a scene that are not part of the robot: what a cell may name."""
    robot_root = model.body_rootid[model.body(robot_body).id]
    return [
        model.body(i).name
        for i in range(1, model.nbody)
        if model.body(i).name and model.body_rootid[i] != robot_root
    ]
