"""Frames of the model language: ``pinocchio.SE3`` poses in the world frame.

Generated code builds frames only through these helpers, so the SI convention (metres,
radians) and the composition order (left to right, each factor in the frame built so far)
are stated once.
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin

Frame = pin.SE3


def rotX(angle: float) -> Frame:
    """Rotation about the x axis by ``angle`` radians."""
    return Frame(pin.utils.rotate("x", angle), np.zeros(3))


def rotY(angle: float) -> Frame:
    """Rotation about the y axis by ``angle`` radians."""
    return Frame(pin.utils.rotate("y", angle), np.zeros(3))


def rotZ(angle: float) -> Frame:
    """Rotation about the z axis by ``angle`` radians."""
    return Frame(pin.utils.rotate("z", angle), np.zeros(3))


def transl(x: float, y: float, z: float) -> Frame:
    """Translation by (x, y, z) metres."""
    return Frame(np.eye(3), np.array([x, y, z], dtype=float))


def coordinate(frame: Frame, axis: int) -> float:
    """``frame.x`` / ``.y`` / ``.z`` of the model language: the translation, world axes."""
    return float(frame.translation[axis])
