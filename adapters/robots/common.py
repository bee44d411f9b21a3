"""The facts every robot shares, and where the scene models live.

Each robot is an object of its own (adapters.robots.robot, one module per robot under
adapters/robots/); what they all have in common is here. The native tick is compiled for
ARM_DOF arm joints and two finger slides of FINGER_TRAVEL each (``NV`` = 9 joints, arm first;
adapters.kernels.layout repeats these numbers). The hand carries the sites ``tcp`` and ``ft``,
and the wrist's force and torque sensors sit at ``ft``.
"""

from __future__ import annotations

from pathlib import Path

MODELS_DIR = Path(__file__).parents[1] / "models"

ARM_DOF = 7
NV = 9
FINGER_TRAVEL = 0.04
"""Opening of one finger [m]; the gripper width is the sum of both finger joints."""

TCP_SITE = "tcp"
FT_SITE = "ft"
FORCE_SENSOR = "ft_force"
TORQUE_SENSOR = "ft_torque"
"""The wrist's sensors at the ``ft`` site; the torque sensor's values follow the force's."""

GRIPPER_BAND = 0.002
"""Within this distance [m] of the end of travel the finger force fades out linearly, so an
empty gripper does not press its fingers into their (soft) joint limits."""
