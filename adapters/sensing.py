"""The wrist force/torque signal as skills read it: tared, filtered, at the TCP, world axes.

A plant reports the raw wrist reading: the wrench the arm (link7) exerts on the hand subtree
(hand and fingers), at the ``ft`` site origin, in world axes. What a skill wants is the wrench
the environment exerts on the tool. In static balance
``raw + F_env + m g = 0``, so ``F_env = −raw − m g`` (and likewise for the torque of the load's
weight about the sensor). The load model (mass and centre of mass of the hand subtree, known
from the robot model) is removed on every tick, for every orientation of the hand; what is left
(the fingers' small shift of the centre of mass, inertial forces at standstill = 0) is removed
by an explicit ``tare()``, which the adapters call once after settling in the ready pose and
which callers may repeat when they know the tool is free. The result is then shifted to the TCP
and low-pass filtered (first order, ``CUTOFF_HZ``) against impact spikes of stiff contacts.

The per-tick arithmetic is adapters.kernels.sense, run by the arm state right after it takes
the plant's state (``ArmState.sense``); this class owns the parameters and the results in the
arm state's sensing buffer.
"""

from __future__ import annotations

import numpy as np

from lightrocks.adapters import kernels as k
from lightrocks.adapters.kernels import DT
from lightrocks.adapters.vec import cross

CUTOFF_HZ = 40.0
GRAVITY = np.array([0.0, 0.0, -9.81])


class WristSensor:
    """Turns raw wrist readings into the filtered environment wrench at the TCP."""

    def __init__(self, buffer: np.ndarray, load_mass: float, load_com: np.ndarray) -> None:
        """``buffer`` is the sensing buffer (layout in adapters.kernels); ``load_com`` is the
        centre of mass of the hand subtree in the ft site frame."""
        self.buffer = buffer
        self.load_weight = load_mass * GRAVITY
        self.load_com = np.asarray(load_com, dtype=float)
        buffer[k.S_WEIGHT : k.S_WEIGHT + 3] = self.load_weight
        buffer[k.S_LOAD_COM : k.S_LOAD_COM + 3] = self.load_com
        self.offset = buffer[k.S_OFFSET : k.S_OFFSET + 6]
        self.wrench = buffer[k.S_VALUES : k.S_VALUES + 6]
        """Filtered wrench at the TCP in world axes: force [N] then torque [Nm]."""
        tau = 1.0 / (2.0 * np.pi * CUTOFF_HZ)
        buffer[k.S_ALPHA] = DT / (tau + DT)

    def tare(self, raw: np.ndarray, ft_rotation: np.ndarray) -> None:
        """Declare the tool free: the current residual becomes the zero of the sensor."""
        lever = ft_rotation @ self.load_com
        residual = -raw
        residual[:3] -= self.load_weight
        residual[3:] -= cross(lever, self.load_weight)
        self.offset[:] = residual
        self.wrench[:] = 0.0
