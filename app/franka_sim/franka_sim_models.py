"""The FR3 arm and the Franka Hand as franka-sim loads them offline, cut from the FR3 model
that franky-sim ships.

franka-sim (the strict judge: the FCI's communication constraints and motion limits) takes
its models from MuJoCo Menagerie, downloaded on first use, unless ``$FR3_MJCF`` names an arm
(joints ``fr3_joint1…7``, grafting the hand on ``fr3_link7`` 0.107 m up) and
``$FRANKA_HAND_MJCF`` a standalone hand (its first body the hand, turned 180° about z as
Menagerie's is). franky-sim's ``assets/fr3.xml`` holds both in one tree; :func:`write_models`
splits it into these two files, with franky-sim's mesh folder named absolutely::

    python -m lightrocks.app.franka_sim.franka_sim_models FOLDER   # prints the two paths
"""

from __future__ import annotations

import copy
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import franky_sim

ASSETS = Path(franky_sim.__file__).parent / "assets"
HAND = "hand"
HAND_QUAT = "0 0 0 1"
"""The hand body's own turn in Menagerie's ``hand.xml``, which franka-sim's graft expects."""
SHARED = ("option", "default", "asset")
HAND_SECTIONS = ("tendon", "equality")


def write_models(folder: Path) -> tuple[Path, Path]:
    """Write ``fr3.xml`` (the arm) and ``hand.xml`` into ``folder``; their paths."""
    root = ET.parse(ASSETS / "fr3.xml").getroot()
    meshes = str(ASSETS / "meshes")
    arm, hand = _split(root)
    for model in (arm, hand):
        compiler = model.find("compiler")
        if compiler is None:
            compiler = ET.SubElement(model, "compiler")
        compiler.set("meshdir", meshes)
    folder.mkdir(parents=True, exist_ok=True)
    paths = folder / "fr3.xml", folder / "hand.xml"
    for model, path in zip((arm, hand), paths, strict=True):
        path.write_text(ET.tostring(model, encoding="unicode"), encoding="utf-8")
    return paths


def _split(root: ET.Element) -> tuple[ET.Element, ET.Element]:
    arm = copy.deepcopy(root)
    parent = next(p for p in arm.iter() for c in p if c.tag == "body" and c.get("name") == HAND)
    body = next(c for c in parent if c.get("name") == HAND)
    parent.remove(body)
    fingers = {j.get("name") for j in body.iter("joint")}
    for tag in (*HAND_SECTIONS, "keyframe"):
        for section in arm.findall(tag):
            arm.remove(section)
    joints = _arm_joints(arm)
    for actuators in arm.findall("actuator"):
        for actuator in list(actuators):
            if actuator.get("joint") not in joints:
                actuators.remove(actuator)
    hand = ET.Element("mujoco", model="franka_hand")
    shared = (root.find(tag) for tag in ("compiler", *SHARED))
    hand.extend(copy.deepcopy(section) for section in shared if section is not None)
    world = ET.SubElement(hand, "worldbody")
    body.attrib.pop("pos", None)
    body.set("quat", HAND_QUAT)
    body.set("childclass", "fr3")
    world.append(body)
    for tag in HAND_SECTIONS:
        section = root.find(tag)
        if section is not None and any(_names_finger(e, fingers) for e in section.iter()):
            hand.append(copy.deepcopy(section))
    return arm, hand


def _arm_joints(model: ET.Element) -> set[str]:
    return {j.get("name") for j in model.iter("joint") if j.get("name")}


def _names_finger(element: ET.Element, fingers: set[str]) -> bool:
    return any(element.get(key) in fingers for key in ("joint", "joint1", "joint2"))


if __name__ == "__main__":
    for written in write_models(Path(sys.argv[1])):
        print(written)
