"""The Franka Emika Panda with the Franka Hand, from the URDF that the PyPI package
``example-robot-data`` ships (franka_description, Apache-2.0; ``pip install
'lightrocks[panda]'``), with the Panda's own limits and gains.

Numbers and where they come from:
- effort limits from the URDF: 87 Nm (joints 1–4), 12 Nm (joints 5–7), 100 N per finger;
- joint stiffness of libfranka's impedance examples (600, 600, 600, 600, 250, 150, 50 Nm/rad),
  Cartesian stiffness of libfranka's default Cartesian impedance (3000 N/m, 300 Nm/rad);
- armature and damping: the URDF has only 0.003 Nm s/rad of damping and no rotor inertia;
  the arm's values are the LWR's (larger motors on joints 1–4); the 15 g fingers get 0.045 kg
  of armature, the LWR's 0.06 kg in all, without which they chattered on a part gripped with
  80 N;
- the TCP 15 mm above the fingertips, as on the LWR, so that the skills' grasp heights hold:
  the rubber pads end 0.0584 + 0.0545 = 0.1129 m below the hand's origin (the flange); it is
  turned 180° about the hand's z axis, so that the screwing task's grasp (``yaw = 90°``) and
  its turns of +179.5° keep joint 7 (±166°) between -45° and 134.5°;
- the ready pose turned 10° further about the world z axis than the LWR's, so that the turn
  to the rail's grasp orientation (180° from the LWR's ready one) is 170° the way joint 7 has
  room for;
- the hand's box is the bounding box of its collision mesh (hand.stl).
"""

from __future__ import annotations

import math
from importlib.metadata import PackageNotFoundError, distribution
from pathlib import Path

from lightrocks.adapters.robots.robot import RobotDataMissing
from lightrocks.adapters.robots.urdf import UrdfRobot

PACKAGE = "example-robot-data"
URDF = "share/example-robot-data/robots/panda_description/urdf/panda.urdf"
INSTALL = "pip install 'lightrocks[panda]'"


def urdf() -> Path:
    """The Panda's URDF among the installed files of example-robot-data."""
    try:
        files = distribution(PACKAGE).files or []
    except PackageNotFoundError:
        raise RobotDataMissing(f"robot 'panda' needs the package {PACKAGE}: {INSTALL}") from None
    for file in files:
        if file.as_posix().endswith(URDF):
            return Path(str(file.locate()))
    raise RobotDataMissing(f"{PACKAGE} is installed without {URDF}: {INSTALL}")


ROBOT = UrdfRobot(
    device_type="Panda",
    description="Franka Emika Panda with the Franka Hand (URDF of example-robot-data)",
    arm_joints=tuple(f"panda_joint{i}" for i in range(1, 8)),
    finger_joints=("panda_finger_joint1", "panda_finger_joint2"),
    root="panda_link0",
    hand="panda_hand",
    fingers=("panda_leftfinger", "panda_rightfinger"),
    # Elbow up, joints 1, 3, 5 at zero: the TCP where the LWR's is, (0.4893, 0, 0.3166) m,
    # pointing down, turned 10° further about the world z axis than the LWR's (joint 7 at 35°).
    ready=(0.0, -0.154182345697, 0.0, -2.291341107772, 0.0, 2.137158762074, math.radians(35)),
    joint_stiffness=(600.0, 600.0, 600.0, 600.0, 250.0, 150.0, 50.0),
    cartesian_stiffness=(3000.0, 3000.0, 3000.0, 300.0, 300.0, 300.0),
    finger_damping=200.0,
    locate=urdf,
    base=(0.0, 0.0, 0.0),
    tcp=((0.0, 0.0, 0.0979), (0.0, 0.0, 0.0, 1.0)),
    hand_box=((0.0, -0.0018, 0.02), (0.0317, 0.1022, 0.046)),
    armature=(0.1, 0.1, 0.1, 0.1, 0.05, 0.05, 0.05, 0.045, 0.045),
    damping=(0.5, 0.5, 0.5, 0.5, 0.2, 0.2, 0.2),
)
