"""The LightRocks LWR (adapters/models/lwr.xml): a 7-DoF KUKA LWR/iiwa-like arm with a
parallel gripper, written for this repository in primitive geoms."""

from __future__ import annotations

import math

from lightrocks.adapters.robots.common import MODELS_DIR
from lightrocks.adapters.robots.robot import MjcfRobot

ROBOT = MjcfRobot(
    device_type="LWR",
    description="7-DoF KUKA LWR/iiwa-like arm with a parallel gripper (primitive geoms)",
    arm_joints=tuple(f"j{i}" for i in range(1, 8)),
    finger_joints=("finger_left", "finger_right"),
    root="base",
    hand="hand",
    fingers=("finger_left", "finger_right"),
    # Elbow up, j2 + j4 + j6 = pi: the tool axis points straight down, the TCP at about
    # (0.49, 0, 0.32) m with its x axis along -x of the world.
    ready=(0.0, 0.35, 0.0, 1.75, 0.0, math.pi - 2.1, 0.0),
    joint_stiffness=(400.0, 400.0, 300.0, 300.0, 100.0, 100.0, 50.0),
    cartesian_stiffness=(2000.0, 2000.0, 2000.0, 200.0, 200.0, 200.0),
    finger_damping=200.0,
    path=MODELS_DIR / "lwr.xml",
)
