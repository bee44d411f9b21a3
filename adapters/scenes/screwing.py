"""The screwing cell (adapters/models/screwing.xml): a wooden screw driven into a cube.

The thread catches the screw only in this scene's per-step hook, its friction grows with the
depth, and the Pinocchio twin turns a kinematic screw instead (see docs/scenes.md). This
module is the only code that knows the cell's joint and body names.

Conventions: SI units, world frame, z up; the arm base is at the world origin.
"""

from __future__ import annotations

import math
import weakref
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import mujoco
import numpy as np

from lightrocks.adapters.robots.common import MODELS_DIR
from lightrocks.adapters.scene import Scene

SCREW_PITCH = 0.003
"""Thread pitch [m per turn]: 1.5 mm of depth per 180 deg turn."""
SCREW_TARGET_DEPTH = 0.012
"""Depth [m] at which the head seats on the cube (bottom-out, 8 turns of 180 deg)."""
THREAD_TORQUE_START = 0.05
"""Thread friction torque [Nm] at depth 0."""
THREAD_TORQUE_END = 0.20
"""Thread friction torque [Nm] at the target depth (it grows linearly in between)."""
SCREW_AXIS_XY = (0.55, 0.0)
"""The hole's axis on the cube [m]."""
CUBE_TOP_Z = 0.15
"""Height [m] of the cube's top face, the hole's mouth."""
CATCH_DEPTH = 0.0008
"""The thread catches once the tip is this far [m] below the cube top (depth 0 there)."""
CATCH_WINDOW = 0.0025
"""... and no deeper than this [m] below the top: further down, the first turn is missed."""
CATCH_RADIUS = 0.001
"""... with the tip this close [m] to the hole axis ..."""
CATCH_TILT = math.radians(3.0)
"""... and the screw's axis within this angle of the hole axis."""
SCREW_LENGTH = 0.035
"""From the tip (the screw's frame origin) to the top of the head [m]."""
SCREW_HEAD_TOP_Z = CUBE_TOP_Z - CATCH_DEPTH + SCREW_LENGTH
"""Height [m] of the screw head's top face at depth 0 (head is 22 mm high, 20 mm across)."""
SCREW_START = (0.50, 0.15, 0.118)
"""Where the tip stands at the start [m]: in the holder's bore, the screw upright."""


def thread_torque(depth: float) -> float:
    """Friction torque [Nm] of the screw thread at ``depth`` [m] (linear, clipped)."""
    s = min(max(depth / SCREW_TARGET_DEPTH, 0.0), 1.0)
    return THREAD_TORQUE_START + (THREAD_TORQUE_END - THREAD_TORQUE_START) * s


@dataclass(frozen=True)
class _Thread:
    """Addresses of the screw's thread in one model (cached: the step hook runs at 1 kHz)."""

    slide: int  # qpos of screw_slide
    hinge: int  # qpos of screw_hinge
    hinge_dof: int
    dofs: tuple[int, int]  # dofs of slide and hinge
    catch: int  # the weld equality thread -> screw
    screw: int  # body

    @classmethod
    def of(cls, model: mujoco.MjModel) -> _Thread:
        slide, hinge = model.joint("screw_slide"), model.joint("screw_hinge")
        return cls(
            int(slide.qposadr[0]),
            int(hinge.qposadr[0]),
            int(hinge.dofadr[0]),
            (int(slide.dofadr[0]), int(hinge.dofadr[0])),
            int(model.equality("thread_catch").id),
            int(model.body("screw").id),
        )


_THREADS: weakref.WeakKeyDictionary[mujoco.MjModel, _Thread] = weakref.WeakKeyDictionary()


def _thread(model: mujoco.MjModel) -> _Thread:
    found = _THREADS.get(model)
    if found is None:
        found = _THREADS[model] = _Thread.of(model)
    return found


def catch_depth(tip: np.ndarray, axis_z: float) -> float | None:
    """The depth [m] at which the thread catches a screw whose tip is at ``tip`` (world) and
    whose axis has the world-z component ``axis_z``, or None when it does not catch: the tip is
    off the hole, above the catch or past it, or the screw is tilted more than CATCH_TILT."""
    below = CUBE_TOP_Z - float(tip[2])
    if not CATCH_DEPTH <= below <= CATCH_WINDOW or axis_z < math.cos(CATCH_TILT):
        return None
    off = math.hypot(float(tip[0]) - SCREW_AXIS_XY[0], float(tip[1]) - SCREW_AXIS_XY[1])
    return below - CATCH_DEPTH if off <= CATCH_RADIUS else None


def _catch(model: mujoco.MjModel, data: mujoco.MjData, thread: _Thread) -> None:
    """Engage the thread if the screw's tip has entered the hole straight enough."""
    rotation = data.xmat[thread.screw]
    depth = catch_depth(data.xpos[thread.screw], float(rotation[8]))
    if depth is None:
        return
    turn = depth * 2.0 * math.pi / SCREW_PITCH
    data.qpos[thread.slide] = depth
    data.qpos[thread.hinge] = turn
    data.qvel[list(thread.dofs)] = 0.0
    # the screw keeps its own turn about the axis: thread frame (turned by -turn about z)
    # to screw = a rotation by yaw + turn about z; it sits at the thread frame's origin
    yaw = math.atan2(float(rotation[3]), float(rotation[0]))
    half = 0.5 * (yaw + turn)
    model.eq_data[thread.catch, 3:10] = (0.0, 0.0, 0.0, math.cos(half), 0.0, 0.0, math.sin(half))
    data.eq_active[thread.catch] = 1


def place_screw(
    model: mujoco.MjModel, data: mujoco.MjData, tip: np.ndarray, tilt: float = 0.0
) -> None:
    """Put the free screw with its tip at ``tip`` (world), leaning by ``tilt`` [rad] about the
    world x axis, at rest; for fixture tests and for starting with a hand-started screw."""
    free = model.joint("screw_free")
    qpos, dof = int(free.qposadr[0]), int(free.dofadr[0])
    data.qpos[qpos : qpos + 3] = tip
    data.qpos[qpos + 3 : qpos + 7] = (math.cos(tilt / 2), math.sin(tilt / 2), 0.0, 0.0)
    data.qvel[dof : dof + 6] = 0.0
    mujoco.mj_forward(model, data)


# --- the analytic twin for the Pinocchio adapter ---------------------------------------------


def _wrap(angle: float) -> float:
    return (angle + math.pi) % (2.0 * math.pi) - math.pi


def _tightening_yaw(rotation: np.ndarray) -> float:
    """Rotation of a frame about the world -z axis (the screw axis), from its x axis."""
    return -math.atan2(float(rotation[1, 0]), float(rotation[0, 0]))


HOLE_RADIUS = 0.0025
"""Half the width of the cube's pilot hole [m] (the twin takes it round)."""
TIP_RADIUS = 0.002
"""Radius of the screw's rounded tip and shank [m]."""
CUBE_HALF = 0.025


@dataclass
class ScrewTwin:
    """Kinematic screw for dry runs: carried by the gripper, caught by the thread, turned in.

    A ``scene.FixtureTwin``, with ``reset()`` and ``hand_start()`` besides; ``tcp_position``
    (3,) and ``tcp_rotation`` (3, 3) in the world frame, ``holding`` whether the gripper is
    closed on something; ``step`` returns the wrench (force, torque; world axes, at the TCP)
    that the fixture exerts on the gripper.

    The screw counts as gripped when the gripper holds with the TCP within 1 cm of its axis and
    inside the head's height. Until the thread has caught, a gripped screw moves rigidly with
    the hand, and its round tip meets the cube's top and the edge of its (round) hole with a
    spring of ``contact_stiffness`` (frictionless); the thread catches under the same rule as
    in MuJoCo (:func:`catch_depth`). Once caught, the screw's angle follows the TCP's rotation
    about the hole axis, the depth is ``pitch * angle / 2 pi``, the thread holds the hand at
    the height of that depth with ``axial_stiffness`` and resists the turn with the thread
    torque (opposing it; smoothed around zero speed); past bottom-out the screw stops and the
    reaction grows with ``stop_stiffness`` [Nm/rad] times the extra turn. A screw let go of
    stays where it is (no gravity in the twin).
    """

    pitch: float = SCREW_PITCH
    target_depth: float = SCREW_TARGET_DEPTH
    axis_xy: tuple[float, float] = SCREW_AXIS_XY
    stop_stiffness: float = 50.0
    contact_stiffness: float = 2.0e4
    axial_stiffness: float = 2.0e4
    angle: float = 0.0
    caught: bool = False
    tip: np.ndarray = field(default_factory=lambda: np.array(SCREW_START))
    axis: np.ndarray = field(default_factory=lambda: np.array([0.0, 0.0, 1.0]))
    _gripped: bool = field(default=False, repr=False)
    _in_hand: tuple[np.ndarray, np.ndarray] = field(
        default_factory=lambda: (np.zeros(3), np.zeros(3)), repr=False
    )
    """Tip and axis in the TCP frame while carried."""
    _yaw: float = field(default=0.0, repr=False)
    _turn: float = field(default=0.0, repr=False)
    _top: float = field(default=0.0, repr=False)
    """TCP height at depth 0 of the screw in the hand, once caught."""

    @property
    def max_angle(self) -> float:
        return 2.0 * math.pi * self.target_depth / self.pitch

    @property
    def depth(self) -> float:
        return self.pitch * self.angle / (2.0 * math.pi)

    def reset(self) -> None:
        self.angle, self.caught, self._gripped, self._turn = 0.0, False, False, 0.0
        self.tip, self.axis = np.array(SCREW_START), np.array([0.0, 0.0, 1.0])

    def hand_start(self) -> None:
        """Put the screw into the hole with its thread caught at depth 0 (as a worker would)."""
        self.reset()
        self.caught = True
        self.tip = np.array([*self.axis_xy, CUBE_TOP_Z - CATCH_DEPTH])

    def graspable(self, tcp_position: np.ndarray) -> bool:
        """Whether a gripper closing at ``tcp_position`` would hold the screw head."""
        head_top = self.tip + SCREW_LENGTH * self.axis
        dx = float(tcp_position[0]) - float(head_top[0])
        dy = float(tcp_position[1]) - float(head_top[1])
        top = float(head_top[2])
        return math.hypot(dx, dy) < 0.01 and top - 0.022 <= float(tcp_position[2]) <= top + 0.005

    def step(
        self, dt: float, tcp_position: np.ndarray, tcp_rotation: np.ndarray, holding: bool
    ) -> np.ndarray:
        tcp, rotation = np.asarray(tcp_position), np.asarray(tcp_rotation)
        yaw = _tightening_yaw(rotation)
        if not holding:
            self._gripped = False
            return np.zeros(6)
        if not self._gripped:
            if not self.graspable(tcp):
                return np.zeros(6)
            self._gripped = True
            self._yaw, self._turn = yaw, self.angle
            self._top = float(tcp[2]) + self.depth
            self._in_hand = (rotation.T @ (self.tip - tcp), rotation.T @ self.axis)
        if self.caught:
            return self._turned(dt, tcp, yaw)
        self.tip = rotation @ self._in_hand[0] + tcp
        self.axis = rotation @ self._in_hand[1]
        depth = catch_depth(self.tip, float(self.axis[2]))
        if depth is not None:
            self.caught, self.angle = True, depth * 2.0 * math.pi / self.pitch
            self._yaw, self._turn, self._top = yaw, self.angle, float(tcp[2]) + depth
            return np.zeros(6)
        return self._contact(tcp)

    def _contact(self, tcp: np.ndarray) -> np.ndarray:
        """The cube's push on the round tip of a carried screw, as a wrench at the TCP."""
        wrench = np.zeros(6)
        centre = self.tip + TIP_RADIUS * self.axis
        dx, dy = float(centre[0]) - self.axis_xy[0], float(centre[1]) - self.axis_xy[1]
        if max(abs(dx), abs(dy)) > CUBE_HALF or float(centre[2]) > CUBE_TOP_Z + TIP_RADIUS:
            return wrench
        off = math.hypot(dx, dy)
        if off >= HOLE_RADIUS:  # over the top face
            normal = np.array([0.0, 0.0, 1.0])
            depth = CUBE_TOP_Z + TIP_RADIUS - float(centre[2])
        elif off > HOLE_RADIUS - TIP_RADIUS and off > 0:  # on the hole's edge
            x, y = self.axis_xy
            scale = HOLE_RADIUS / off
            edge = np.array([x + dx * scale, y + dy * scale, CUBE_TOP_Z])
            gap = centre - edge
            distance = float(np.linalg.norm(gap))
            normal, depth = gap / distance, TIP_RADIUS - distance
        else:  # in the hole
            return wrench
        if depth <= 0 or float(centre[2]) < CUBE_TOP_Z - TIP_RADIUS:
            return wrench
        force = self.contact_stiffness * depth * normal
        wrench[:3] = force
        wrench[3:] = np.cross(centre - TIP_RADIUS * normal - tcp, force)
        return wrench

    def _turned(self, dt: float, tcp: np.ndarray, yaw: float) -> np.ndarray:
        """The caught screw follows the hand's turn; the thread holds the hand's height."""
        wrench = np.zeros(6)
        self._turn += _wrap(yaw - self._yaw)
        self._yaw = yaw
        old = self.angle
        self.angle = min(max(self._turn, -math.pi), self.max_angle)
        self.tip = np.array([*self.axis_xy, CUBE_TOP_Z - CATCH_DEPTH - self.depth])
        self.axis = np.array([0.0, 0.0, 1.0])
        speed = (self.angle - old) / dt if dt > 0 else 0.0
        resist = thread_torque(self.depth) * math.tanh(speed / 0.05)
        resist += self.stop_stiffness * max(self._turn - self.max_angle, 0.0)
        # a tightening turn is about world -z; the screw pushes back about +z
        wrench[5] = resist
        wrench[2] = -self.axial_stiffness * (float(tcp[2]) - (self._top - self.depth))
        return wrench

    def measurements(self) -> dict[str, float | bool]:
        return {
            "screw_depth": self.depth,
            "screw_angle": self.angle,
            "screw_bottomed": self.depth >= self.target_depth - 1e-4,
            "thread_torque": thread_torque(self.depth),
            "thread_caught": self.caught,
            "screw_x": float(self.tip[0]),
            "screw_y": float(self.tip[1]),
            "screw_z": float(self.tip[2]),
            "screw_tilt": math.acos(min(max(float(self.axis[2]), -1.0), 1.0)),
        }


class Screwing(Scene):
    """The screwing cell: the thread's catch and friction, the screw's ground truth, the
    kinematic screw of the twin, and the goal of a screw seated at its target depth."""

    def step(self, model: mujoco.MjModel, data: mujoco.MjData) -> None:
        """Until the thread has caught, checks whether it catches now (see
        :func:`catch_depth`) and then engages it; once caught, sets the screw hinge's
        ``dof_frictionloss`` to :func:`thread_torque` of the current depth, so the torque
        needed to turn the screw grows as it goes in. Without this hook the screw never
        catches."""
        thread = _thread(model)
        if not data.eq_active[thread.catch]:
            _catch(model, data, thread)
            return
        model.dof_frictionloss[thread.hinge_dof] = thread_torque(float(data.qpos[thread.slide]))

    def measurements(self, model: mujoco.MjModel, data: mujoco.MjData) -> dict[str, float | bool]:
        """``screw_depth`` [m] advance into the cube since the thread caught, ``screw_angle``
        [rad] the thread's turn (positive = tightening), ``screw_bottomed`` (head seated),
        ``thread_torque`` [Nm] the current thread friction, ``thread_caught``, the tip's
        position ``screw_x``, ``screw_y``, ``screw_z`` [m] and ``screw_tilt`` [rad] of its
        axis."""
        thread = _thread(model)
        depth = float(data.qpos[thread.slide])
        tip = data.xpos[thread.screw]
        return {
            "screw_depth": depth,
            "screw_angle": float(data.qpos[thread.hinge]),
            "screw_bottomed": depth >= SCREW_TARGET_DEPTH - 1e-4,
            "thread_torque": thread_torque(depth),
            "thread_caught": bool(data.eq_active[thread.catch]),
            "screw_x": float(tip[0]),
            "screw_y": float(tip[1]),
            "screw_z": float(tip[2]),
            "screw_tilt": math.acos(min(max(float(data.xmat[thread.screw][8]), -1.0), 1.0)),
        }

    def twin(self) -> ScrewTwin:
        return ScrewTwin()

    def goal_met(self, values: Mapping[str, Any]) -> bool:
        """The screw is seated at its target depth."""
        return bool(values.get("screw_bottomed"))


SCENE = Screwing(MODELS_DIR / "screwing.xml")
