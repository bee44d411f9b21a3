"""Scenes and robots by name, from the ``lightrocks.scenes`` and ``lightrocks.robots`` entry
points, so that a separate package adds a scene or a robot without touching this one.

A scene is an ``adapters.scene.Scene`` object, a robot an ``adapters.robots.robot.Robot``. A scene's
MJCF includes the robot of the run by file name, ``<include file="robot.xml"/>``; that robot
is offered under its own name too (``lwr.xml``), for scenes written before robots could be
chosen, which then run with that robot only.
"""

from __future__ import annotations

from functools import cache
from importlib.metadata import entry_points
from pathlib import Path

import mujoco

from lightrocks.adapters.robots.robot import Robot
from lightrocks.adapters.scene import Scene, SceneFault


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
    """The MuJoCo model of a scene with the named robot as its ``robot.xml``; an MJCF that
    does not load is the scene's fault (:class:`SceneFault`), named with the scene and file."""
    chosen = robot(robot_name)
    mjcf = chosen.mjcf()
    assets = {"robot.xml": mjcf, f"{robot_name}.xml": mjcf}
    path = scene(name).mjcf
    if not Path(path).is_file():
        raise SceneFault(f"scene {name!r}: its MJCF file {path} does not exist")
    try:
        model = mujoco.MjModel.from_xml_path(str(path), assets)
    except ValueError as error:
        raise SceneFault(f"scene {name!r}: {path} does not load: {_one_line(error)}") from None
    if mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, chosen.arm_joints[0]) < 0:
        raise SceneFault(
            f"scene {name!r}: {path} does not include the robot {robot_name!r}: {ROBOT_INCLUDE}"
        )
    return model


ROBOT_INCLUDE = 'a scene includes the robot of the run as <include file="robot.xml"/>'


def _one_line(error: ValueError) -> str:
    """MuJoCo's multi-line XML message on one line; a file an include could not open gets
    the rule for including the robot."""
    text = "; ".join(line.strip().rstrip(":") for line in str(error).splitlines() if line.strip())
    if "Error opening file" in text and "'include'" in text:
        text += f" ({ROBOT_INCLUDE}; other included files lie beside the scene's MJCF)"
    return text


def objects(model: mujoco.MjModel, robot_body: str) -> list[str]:
    """Named bodies of a scene that are not part of the robot: what a cell may name."""
    robot_root = model.body_rootid[model.body(robot_body).id]
    return [
        model.body(i).name
        for i in range(1, model.nbody)
        if model.body(i).name and model.body_rootid[i] != robot_root
    ]
