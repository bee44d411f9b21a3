"""The physical scenes of the case studies: measurements, per-step hooks and analytic twins.

Scenes are MJCF files in ``adapters/models`` that include ``lwr.xml``. A scene is named by its
file stem (``"screwing"``, ``"din_rail"``); every function here also accepts the file name or a
path. This module is the only place that knows the scene-specific joint and body names:

- :func:`measurements` turns the MuJoCo state into scene values (``screw_depth``,
  ``terminal1_latched``, ...) that adapters publish to stop conditions and tests.
- :func:`scene_step` is the per-physics-step hook of a scene (the screw thread's depth-dependent
  friction). Adapters call it before every ``mj_step``; it costs about a microsecond.
- :class:`ScrewTwin` and :class:`RailTwin` are kinematic stand-ins of the two fixtures for the
  Pinocchio twin, which has no contact physics (see docs/scenes.md).

Conventions: SI units, world frame, z up; the arm base is at the world origin.
"""

from __future__ import annotations

import math
import os
import weakref
from collections.abc import Mapping
from dataclasses import dataclass, field

import mujoco
import numpy as np

# --- screwing cell (adapters/models/screwing.xml) -------------------------------------------

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

# --- top-hat rail cell (adapters/models/din_rail.xml) ---------------------------------------

TERMINALS = ("terminal1", "terminal2", "terminal3")
RAIL_X = 0.60
"""Rail centre line [m]; the rail runs along the world y axis."""
RAIL_LIP_TOP_Z = 0.1075
"""Height [m] of the rail lips' top face: a latched terminal's housing rests there."""
RAIL_HALF_LENGTH = 0.12
TERMINAL_Y = (-0.07, 0.0, 0.07)
"""y [m] of the terminals in the tray, and of their target slots on the rail."""
TRAY_X = 0.45
TERMINAL_TRAY_Z = 0.1101
"""Height [m] of a terminal's origin (housing underside) standing in the tray."""
TERMINAL_HEIGHT = 0.04
SNAP_FORCE = 34.0
"""Designed snap-through force [N] of a terminal (measured: see docs/scenes.md)."""
LIPS = (0.0125, 0.0175)
"""Distance [m] of the rail lips' inner and outer edges from its centre line (din_rail.xml)."""
WEDGE_REACH = 0.0235
"""Distance [m] of the latch wedges' outer ends from the terminal's centre (din_rail.xml)."""
RAMP_BOTTOM = 0.0061
"""Depth [m] of the wedges' lowest point, their outer end, below the housing underside."""
LEAD_IN = WEDGE_REACH - LIPS[1]
"""A terminal set down closer than this [m] to the rail's centre line meets a lip with a latch
ramp, which pushes it onto the centre line; up to WEDGE_REACH - LIPS[0] off, a wedge's end
stands on a lip."""
LATCH_ENGAGED = 0.00075
"""A latch deflected less than this [m] has its catch under the lip (overlap is 1.5 mm)."""


def scene_key(scene_name: str) -> str:
    """Normalise ``"screwing"``, ``"screwing.xml"`` or a path to the scene's file stem."""
    return os.path.splitext(os.path.basename(scene_name))[0]


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


def scene_step(scene_name: str, model: mujoco.MjModel, data: mujoco.MjData) -> None:
    """Per-step hook; adapters call it before every ``mj_step`` of the scene (1 kHz hot path).

    Screwing: until the thread has caught, checks whether it catches now (see
    :func:`catch_depth`) and then engages it; once caught, sets the screw hinge's
    ``dof_frictionloss`` to :func:`thread_torque` of the current depth, so the torque needed
    to turn the screw grows as it goes in. Without this hook the screw never catches.
    Other scenes: nothing to do.
    """
    if scene_name != "screwing" and scene_key(scene_name) != "screwing":
        return
    thread = _thread(model)
    if not data.eq_active[thread.catch]:
        _catch(model, data, thread)
        return
    model.dof_frictionloss[thread.hinge_dof] = thread_torque(float(data.qpos[thread.slide]))


def measurements(
    scene_name: str, model: mujoco.MjModel, data: mujoco.MjData
) -> dict[str, float | bool]:
    """Scene values for stop conditions, environment updates and tests.

    screwing: ``screw_depth`` [m] advance into the cube since the thread caught,
    ``screw_angle`` [rad] the thread's turn (positive = tightening), ``screw_bottomed`` (head
    seated), ``thread_torque`` [Nm] the current thread friction, ``thread_caught``, the tip's
    position ``screw_x``, ``screw_y``, ``screw_z`` [m] and ``screw_tilt`` [rad] of its axis.
    din_rail: ``terminalN_latched`` (on the rail, upright, housing on the lips and both catches
    under the lips), ``terminalN_height`` [m] of the housing underside above the lips' top, and
    ``terminals_latched`` (how many are latched).
    Unknown scenes: an empty dict.
    """
    key = scene_key(scene_name)
    if key == "screwing":
        return _screwing_measurements(model, data)
    if key == "din_rail":
        return _rail_measurements(model, data)
    return {}


def goal_met(scene_name: str, values: Mapping[str, float | bool]) -> bool:
    """Whether :func:`measurements` show the scene's case study done: the screw seated at its
    target depth, or all three terminals latched. False for scenes without a goal."""
    key = scene_key(scene_name)
    if key == "screwing":
        return bool(values.get("screw_bottomed"))
    if key == "din_rail":
        return values.get("terminals_latched") == len(TERMINALS)
    return False


def _screwing_measurements(model: mujoco.MjModel, data: mujoco.MjData) -> dict[str, float | bool]:
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


def terminal_latched(model: mujoco.MjModel, data: mujoco.MjData, terminal: str) -> bool:
    """Whether ``terminal`` sits latched on the rail (see :func:`measurements`)."""
    pos = data.body(terminal).xpos
    rail = data.body("rail").xpos
    upright = float(data.body(terminal).xmat[8]) > 0.995
    on_rail = abs(pos[0] - rail[0]) < 0.0015 and abs(pos[1] - rail[1]) < RAIL_HALF_LENGTH - 0.005
    seated = abs(pos[2] - (rail[2] + 0.0075)) < 0.0006
    catches = all(
        float(data.qpos[model.jnt_qposadr[model.joint(f"{terminal}_latch_{side}").id]])
        < LATCH_ENGAGED
        for side in ("l", "r")
    )
    return bool(upright and on_rail and seated and catches)


def _rail_measurements(model: mujoco.MjModel, data: mujoco.MjData) -> dict[str, float | bool]:
    values: dict[str, float | bool] = {}
    rail_top = float(data.body("rail").xpos[2]) + 0.0075
    count = 0
    for terminal in TERMINALS:
        latched = terminal_latched(model, data, terminal)
        count += latched
        values[f"{terminal}_latched"] = latched
        values[f"{terminal}_height"] = float(data.body(terminal).xpos[2]) - rail_top
    values["terminals_latched"] = float(count)
    return values


# --- analytic twins for the Pinocchio adapter -----------------------------------------------


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

    Interface (shared with :class:`RailTwin`): ``reset()``, ``graspable(tcp_position)``,
    ``step(dt, tcp_position, tcp_rotation, holding) -> wrench`` and ``measurements()``;
    ``tcp_position`` (3,) and ``tcp_rotation`` (3, 3) in the world frame,
    ``holding`` whether the gripper is closed on something; the result is the wrench (force,
    torque; world axes, at the TCP) that the fixture exerts on the gripper.

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


@dataclass
class _Terminal:
    position: np.ndarray
    latched: bool = False
    carried: bool = False
    offset: np.ndarray = field(default_factory=lambda: np.zeros(3))


@dataclass
class RailTwin:
    """Kinematic terminals and rail for dry runs (same ``step`` interface as ScrewTwin).

    A closed gripper whose TCP is within 8 mm (x, y) and 12 mm (z) of a terminal's grasp point
    (25 mm above its underside, centre) carries that terminal rigidly. A carried terminal within
    LEAD_IN of the rail's centre line whose ramps reach the lips is slid onto the centre line
    in the grip (the lead-in; MuJoCo's soft hand moves sideways instead). Farther off, up to
    WEDGE_REACH - LIPS[0], the end of one wedge stands on a lip: a stiff upward force there,
    which twists the wrist. Over the rail, pushing
    a carried terminal down meets the snap-fit: the resisting force rises linearly to
    ``snap_force`` over the 1.5 mm ramp, falls to the ``friction`` plateau for the next
    1 mm, and the terminal latches when its underside is 0.1 mm above the lips; pushing on
    a latched terminal meets the rail (``seat_stiffness`` N/m). A latched terminal stays when
    the gripper opens and cannot be pulled off; a terminal released elsewhere stays where it
    is (no gravity in the twin).
    """

    snap_force: float = SNAP_FORCE
    friction: float = 4.5
    seat_stiffness: float = 2.0e5
    terminals: dict[str, _Terminal] = field(default_factory=dict)

    def __post_init__(self) -> None:
        if not self.terminals:
            self.reset()

    def reset(self) -> None:
        self.terminals = {
            name: _Terminal(np.array([TRAY_X, y, TERMINAL_TRAY_Z]))
            for name, y in zip(TERMINALS, TERMINAL_Y, strict=True)
        }

    @staticmethod
    def _near(term: _Terminal, tcp: np.ndarray) -> bool:
        near = np.abs(tcp - (term.position + np.array([0.0, 0.0, 0.025])))
        return bool(near[0] < 0.008 and near[1] < 0.008 and near[2] < 0.012)

    def graspable(self, tcp_position: np.ndarray) -> bool:
        """Whether a gripper closing at ``tcp_position`` would hold a terminal."""
        tcp = np.asarray(tcp_position, dtype=float)
        return any(self._near(term, tcp) for term in self.terminals.values())

    def _resistance(self, height: float) -> float:
        """Upward force [N] of the rail on a terminal whose underside is ``height`` above it."""
        if height >= 0.0026:
            return 0.0
        if height >= 0.0011:
            return self.snap_force * (0.0026 - height) / 0.0015
        if height >= 0.0001:
            return self.friction
        return self.seat_stiffness * max(-height, 0.0)

    def step(
        self, dt: float, tcp_position: np.ndarray, tcp_rotation: np.ndarray, holding: bool
    ) -> np.ndarray:
        tcp = np.asarray(tcp_position, dtype=float)
        wrench = np.zeros(6)
        for term in self.terminals.values():
            if not holding:
                term.carried = False
                continue
            if not term.carried:
                if self._near(term, tcp):
                    term.carried, term.offset = True, term.position - tcp
                continue
            wanted = tcp + term.offset
            across = float(wanted[0]) - RAIL_X
            height = float(wanted[2]) - RAIL_LIP_TOP_Z
            along_rail = abs(wanted[1]) < RAIL_HALF_LENGTH
            if along_rail and LEAD_IN <= abs(across) < WEDGE_REACH - LIPS[0]:
                term.position = wanted
                if height < RAMP_BOTTOM:
                    self._stand_on_lip(term, tcp, across, height, wrench)
                continue
            if not (along_rail and abs(across) < LEAD_IN):
                term.position = wanted
                continue
            if height < RAMP_BOTTOM:  # the ramps on the lips: the lead-in
                term.offset[0] -= across
                wanted[0] = RAIL_X
            if not term.latched and height < 0.0001:
                term.latched = True
            if term.latched:  # held down by the lips, held up by the catches
                term.position = np.array([RAIL_X, wanted[1], RAIL_LIP_TOP_Z])
                wrench[2] -= self.seat_stiffness * height
            else:
                term.position = wanted
                wrench[2] += self._resistance(height)
        return wrench

    def _stand_on_lip(
        self, term: _Terminal, tcp: np.ndarray, across: float, height: float, wrench: np.ndarray
    ) -> None:
        """A wedge's end on a lip: the terminal stays on it, pushed up (``seat_stiffness``) at
        that end, which adds a torque about the TCP."""
        term.position[2] = RAIL_LIP_TOP_Z + RAMP_BOTTOM
        push = self.seat_stiffness * (RAMP_BOTTOM - height)
        end = term.position - np.array([math.copysign(WEDGE_REACH, across), 0.0, 0.0])
        wrench[2] += push
        wrench[3:] += np.cross(end - tcp, (0.0, 0.0, push))

    def measurements(self) -> dict[str, float | bool]:
        values: dict[str, float | bool] = {}
        for name, term in self.terminals.items():
            values[f"{name}_latched"] = term.latched
            values[f"{name}_height"] = float(term.position[2]) - RAIL_LIP_TOP_Z
        values["terminals_latched"] = float(sum(t.latched for t in self.terminals.values()))
        return values


def make_twin(scene_name: str) -> ScrewTwin | RailTwin | None:
    """The analytic twin of a scene's fixture, or None for scenes without one."""
    key = scene_key(scene_name)
    if key == "screwing":
        return ScrewTwin()
    if key == "din_rail":
        return RailTwin()
    return None
