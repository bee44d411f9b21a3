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
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from lightrocks.adapters.control import DT
from lightrocks.adapters.vec import cross

CUTOFF_HZ = 40.0
GRAVITY = np.array([0.0, 0.0, -9.81])


class WristSensor:
    """Turns raw wrist readings into the filtered environment wrench at the TCP."""

    def __init__(self, load_mass: float, load_com: np.ndarray) -> None:
        """``load_com`` is the centre of mass of the hand subtree in the ft site frame."""
        self.load_weight = load_mass * GRAVITY
        self.load_com = np.asarray(load_com, dtype=float)
        self.offset = np.zeros(6)
        self._offset = (0.0,) * 6
        self.wrench = np.zeros(6)
        """Filtered wrench at the TCP in world axes: force [N] then torque [Nm]."""
        self.values = (0.0,) * 6
        """``wrench`` as floats, for readers on the hot path."""
        tau = 1.0 / (2.0 * np.pi * CUTOFF_HZ)
        self._alpha = DT / (tau + DT)
        self._weight = tuple(self.load_weight.tolist())

    def update(
        self,
        raw: np.ndarray,
        ft_rotation: np.ndarray,
        ft_position: np.ndarray,
        tcp_position: Sequence[float],
    ) -> None:
        """Feed one raw reading (see module docstring) with the ft site pose and TCP position.

        Plain float arithmetic, the same operations in the same order as their NumPy form:
        on 3- and 6-vectors it is several times faster than NumPy calls.
        """
        rx, ry, rz, sx, sy, sz = raw.tolist()
        ox, oy, oz, px, py, pz = self._offset
        lx, ly, lz = (ft_rotation @ self.load_com).tolist()
        wx, wy, wz = self._weight
        fx, fy, fz = -rx - ox - wx, -ry - oy - wy, -rz - oz - wz
        tx = -sx - px - (ly * wz - lz * wy)
        ty = -sy - py - (lz * wx - lx * wz)
        tz = -sz - pz - (lx * wy - ly * wx)
        (ax, ay, az), (bx, by, bz) = ft_position.tolist(), tcp_position
        dx, dy, dz = ax - bx, ay - by, az - bz
        tx += dy * fz - dz * fy
        ty += dz * fx - dx * fz
        tz += dx * fy - dy * fx
        a = self._alpha
        vx, vy, vz, ux, uy, uz = self.values
        self.values = values = (
            vx + (fx - vx) * a,
            vy + (fy - vy) * a,
            vz + (fz - vz) * a,
            ux + (tx - ux) * a,
            uy + (ty - uy) * a,
            uz + (tz - uz) * a,
        )
        self.wrench[:] = values

    def tare(self, raw: np.ndarray, ft_rotation: np.ndarray) -> None:
        """Declare the tool free: the current residual becomes the zero of the sensor."""
        lever = ft_rotation @ self.load_com
        residual = -raw
        residual[:3] -= self.load_weight
        residual[3:] -= cross(lever, self.load_weight)
        self.offset = residual
        self._offset = tuple(residual.tolist())
        self.wrench[:] = 0.0
        self.values = (0.0,) * 6
