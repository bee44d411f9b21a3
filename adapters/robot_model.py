"""Where the robot and scene models live, and the facts about the robot every module shares.

Both adapters load the same MJCF: MuJoCo a scene file that includes ``lwr.xml``, Pinocchio
``lwr.xml`` itself (its MJCF parser ignores ``<include>``). The Pinocchio model keeps the two
finger slide joints, so its joint order equals MuJoCo's robot joints: j1..j7, finger_left,
finger_right (``NV`` = 9); the controllers act on the first ``ARM_DOF`` joints.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pinocchio as pin

MODELS_DIR = Path(__file__).parent / "models"
ROBOT_FILE = MODELS_DIR / "lwr.xml"

ARM_DOF = 7
NV = 9
ARM_JOINTS = tuple(f"j{i}" for i in range(1, ARM_DOF + 1))
FINGER_JOINTS = ("finger_left", "finger_right")
FINGER_TRAVEL = 0.04
"""Opening of one finger [m]; the gripper width is the sum of both finger joints."""

TCP_SITE = "tcp"
FT_SITE = "ft"
HAND_BODY = "hand"

READY_Q = np.array([0.0, 0.35, 0.0, 1.75, 0.0, np.pi - 2.1, 0.0])
"""Ready pose: elbow up, TCP pointing straight down at about (0.49, 0, 0.32) m, above the table.

j2 + j4 + j6 = pi makes the tool axis vertical; the TCP x axis points to -x of the world.
"""

ROBOT_ROOT = "base"
"""The robot's root body: every body below it belongs to the robot, not to the scene."""


def load_robot() -> pin.Model:
    """The Pinocchio model of the robot, arm joints first, then the two finger joints.

    Pinocchio 4.1 converts slide-joint ranges as if they were angles (degrees), so the finger
    limits are set here from ``FINGER_TRAVEL``.
    """
    model = pin.buildModelFromMJCF(str(ROBOT_FILE))
    model.lowerPositionLimit[ARM_DOF:] = 0.0
    model.upperPositionLimit[ARM_DOF:] = FINGER_TRAVEL
    return model


FINGER_DAMPING = 200.0
"""Joint damping [N s/m] of each finger in lwr.xml: a grip force F moves a finger at F/200 m/s."""
GRIPPER_BAND = 0.002
"""Within this distance [m] of the end of travel the finger force fades out linearly, so an
empty gripper does not press its fingers into their (soft) joint limits."""
