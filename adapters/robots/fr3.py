"""The Franka Research 3 with the Franka Hand, from the URDF that the PyPI package
``franky-sim`` ships (``assets/fr3.urdf``, Apache-2.0; ``pip install 'lightrocks[franka]'``).

The FR3 shares the Panda's kinematics and hand, so its TCP, hand box, ready pose, gains,
armature and damping are the Panda's (adapters.robots.panda says where they come from); what
differs comes from the URDF: the joint ranges (joint 4 [-3.077, -0.1169] rad, joint 6
[0.4398, 4.6216] rad, the others a little wider than the Panda's) and the links' masses.
Its device type is the library's ``Panda``: the same commands and sensors, and the device
type the Franka adapter drives.
"""

from __future__ import annotations

import dataclasses
from importlib.metadata import PackageNotFoundError, distribution
from pathlib import Path

from lightrocks.adapters.robots import panda
from lightrocks.adapters.robots.robot import RobotDataMissing
from lightrocks.adapters.robots.urdf import UrdfRobot

PACKAGE = "franky-sim"
URDF = "franky_sim/assets/fr3.urdf"
INSTALL = "pip install 'lightrocks[franka]'"


def urdf() -> Path:
    """The FR3's URDF among the installed files of franky-sim."""
    try:
        files = distribution(PACKAGE).files or []
    except PackageNotFoundError:
        raise RobotDataMissing(f"robot 'fr3' needs the package {PACKAGE}: {INSTALL}") from None
    for file in files:
        if file.as_posix().endswith(URDF):
            return Path(str(file.locate()))
    raise RobotDataMissing(f"{PACKAGE} is installed without {URDF}: {INSTALL}")


ROBOT: UrdfRobot = dataclasses.replace(
    panda.ROBOT,
    description="Franka Research 3 with the Franka Hand (URDF of franky-sim)",
    arm_joints=tuple(f"fr3_joint{i}" for i in range(1, 8)),
    finger_joints=("fr3_finger_joint1", "fr3_finger_joint2"),
    root="fr3_link0",
    hand="fr3_hand",
    fingers=("fr3_leftfinger", "fr3_rightfinger"),
    locate=urdf,
)
