"""franky-sim's MuJoCo world with the objects of a LightRocks scene placed in it.

A LightRocks scene is an MJCF file that includes the robot of the run
(``<include file="robot.xml"/>``) and puts its table, parts and fixtures beside it, the
robot's base at the world origin. franky-sim builds its own MJCF tree (the FR3 with its hand
as ``robot0_…``, a ground plane and lights) and lets callers add to it before the world is
compiled (``MujocoSimulator.scene`` and ``.worldbody``). :func:`add_scene` copies the scene's
own sections into that tree: its default classes (renamed ``scene_…``, since the robot
has classes of the same names), assets, bodies, equalities, contact pairs
and exclusions, tendons, actuators and sensors, and its solver options but the time step
(franky-sim's 1 ms is the libfranka cycle). What the tree already has stays: the scene's
ground plane is left out, since franky-sim's ground lies in the same place. The scene's
per-step hook (``Scene.step``: the screw's thread) runs before every physics step.
"""

from __future__ import annotations

import copy
import xml.etree.ElementTree as ET
from pathlib import Path

from franky_sim.mujoco_simulator import MujocoSimulator

from lightrocks.adapters.scene import Scene, SceneFault, hook_fault

ROBOT_INCLUDE = "robot.xml"
"""The file a LightRocks scene includes for the robot of the run (adapters.scene_registry)."""
MERGED = ("equality", "contact", "tendon", "actuator", "sensor")
"""Top-level MJCF sections whose entries are appended to the simulator's own."""
IGNORED = ("include", "compiler", "visual", "statistic", "size")
"""Top-level sections that belong to the simulator's world, not to the scene's objects."""
FILE_ATTRIBUTE = "file"
CLASS_PREFIX = "scene_"
"""Put before the scene's default class names, which may repeat the robot's (``visual``)."""
CLASS_ATTRIBUTES = ("class", "childclass")


def add_scene(sim: MujocoSimulator, name: str, scene: Scene) -> None:
    """Place the objects of ``scene`` (registered as ``name``) in ``sim``'s world before it is
    started; a scene the simulator's world cannot take is a :class:`SceneFault`."""
    path = Path(scene.mjcf)
    try:
        root = ET.parse(path).getroot()
    except (OSError, ET.ParseError) as error:
        raise SceneFault(f"scene {name!r}: {path} does not load: {error}") from None
    _rename_classes(root)
    target = sim.scene
    for section in root:
        tag = section.tag
        if tag in IGNORED:
            if tag == "include" and section.get("file") != ROBOT_INCLUDE:
                raise SceneFault(f"scene {name!r}: franka-sim cannot include {section.get('file')}")
            continue
        if tag == "option":
            _merge_option(target, section)
        elif tag == "default":
            _merge_defaults(target, section, name)
        elif tag == "asset":
            _section(target, "asset").extend(_with_absolute_files(section, path.parent))
        elif tag == "worldbody":
            sim.worldbody.extend(copy.deepcopy(e) for e in section if not _ground(e))
        elif tag in MERGED:
            _section(target, tag).extend(copy.deepcopy(e) for e in section)
        else:
            raise SceneFault(f"scene {name!r}: franka-sim cannot take its <{tag}> section")
    sim.register_pre_step_callback(_scene_step(name, scene))


def _scene_step(name: str, scene: Scene):
    """The scene's per-step hook on the simulator's model and data."""

    def step(sim: MujocoSimulator) -> None:
        try:
            scene.step(sim.model, sim.data)
        except Exception as error:
            raise hook_fault(name, "step", error) from error

    return step


def _rename_classes(root: ET.Element) -> None:
    """Prefix every default class of the scene, where it is defined and where it is used."""
    for node in root.iter():
        for attribute in CLASS_ATTRIBUTES:
            value = node.get(attribute)
            if value is not None:
                node.set(attribute, CLASS_PREFIX + value)


def _merge_option(target: ET.Element, option: ET.Element) -> None:
    """The scene's solver options (friction cone, impedance ratio, …) over the simulator's."""
    own = target.find("option")
    if own is None:
        own = ET.SubElement(target, "option")
    for key, value in option.attrib.items():
        if key != "timestep":
            own.set(key, value)
    own.extend(copy.deepcopy(e) for e in option)


def _merge_defaults(target: ET.Element, default: ET.Element, name: str) -> None:
    """The scene's default classes beside the robot's; a scene's global defaults would change
    the robot's geoms and joints, so they are refused."""
    unnamed = [e.tag for e in default if e.tag != "default"]
    if unnamed:
        raise SceneFault(
            f"scene {name!r}: franka-sim takes only named default classes, not a global "
            f"<{unnamed[0]}> default"
        )
    _section(target, "default").extend(copy.deepcopy(e) for e in default)


def _section(target: ET.Element, tag: str) -> ET.Element:
    found = target.find(tag)
    return found if found is not None else ET.SubElement(target, tag)


def _with_absolute_files(section: ET.Element, folder: Path) -> list[ET.Element]:
    """Copies of the scene's assets whose files are named from the scene's folder, since the
    simulator's mesh folder is its own."""
    copies = [copy.deepcopy(e) for e in section]
    for element in copies:
        for node in element.iter():
            file = node.get(FILE_ATTRIBUTE)
            if file is not None and not Path(file).is_absolute():
                node.set(FILE_ATTRIBUTE, str(folder / file))
    return copies


def _ground(element: ET.Element) -> bool:
    """A ground plane of the scene's worldbody (the simulator has its own)."""
    return element.tag == "geom" and element.get("type") == "plane"
