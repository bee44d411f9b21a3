"""The device layer the simulated adapters share: robot, gripper and camera on a ``Plant``.

A plant is the physics (MuJoCo, or the Pinocchio twin with penalty contacts); everything a
skill sees — commands, argument checks, sensors, what one 1 kHz tick does — lives here, so
the MuJoCo and Pinocchio adapters behave alike by construction; the loop that runs commands
is the runtime's (``runtime.control_loop``). See docs/adapters.md for the contract.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from types import SimpleNamespace
from typing import Any, Protocol

import mujoco
import numpy as np
import pinocchio as pin

from lightrocks.adapters import kernels
from lightrocks.adapters.arm import ArmState
from lightrocks.adapters.arm_commands import ArmCommands
from lightrocks.adapters.control import CartesianImpedance, JointImpedance
from lightrocks.adapters.kernels import DT
from lightrocks.adapters.robots.common import ARM_DOF, FT_SITE
from lightrocks.adapters.robots.robot import Robot
from lightrocks.adapters.scene_registry import objects
from lightrocks.adapters.scene_registry import robot as registered_robot
from lightrocks.adapters.sensing import WristSensor
from lightrocks.adapters.video import VideoRecorder
from lightrocks.runtime.contract import AdapterError, AdapterOption, Command, Vector3, Wrench
from lightrocks.runtime.control_loop import Started, TickingAdapter, always, nothing

DEFAULT_DAMPING = (0.7,) * 6
DEFAULT_JOINT_DAMPING = (0.7,) * ARM_DOF
SETTLE_TIME = 0.3
"""Seconds the robot holds the ready pose at start-up before the wrist sensor is tared."""
GRIPPER_SETTLE = 0.02
OPEN_FORCE = 20.0
GRIPPER_REST_SPEED = 1e-3
GRIPPER_EMPTY_WIDTH = 2e-3
"""A closed gripper narrower than this holds nothing."""


class Plant(Protocol):
    """The physics under the device layer, stepped at 1 kHz.

    ``q``/``v`` are the NV robot joint positions and velocities (arm, then fingers); ``arm``
    is the robot's kinematics and dynamics, which the cell updates after every step.
    ``model``/``data`` are the MuJoCo scene, used for ground truth and rendering; a plant that
    does not simulate with MuJoCo keeps ``data`` in sync on ``sync()``.
    """

    q: np.ndarray
    v: np.ndarray
    arm: ArmState
    model: mujoco.MjModel
    data: mujoco.MjData

    def step(self, tau: np.ndarray, grip: float) -> None:
        """Advance DT with arm torques ``tau`` and gripper force ``grip`` (> 0 closes)."""
        ...

    def wrist(self) -> np.ndarray:
        """Raw wrist wrench: link7 on the hand subtree, at the ft site, world axes."""
        ...

    def sync(self) -> None:
        """Make ``data`` reflect the current state (poses of bodies and sites)."""
        ...

    def measurements(self) -> dict[str, Any]:
        """Scene ground truth (see adapters.scene)."""
        ...


def _vector(name: str, size: int, *, positive: bool = False) -> Callable[[Any], np.ndarray]:
    def convert(value: Any) -> np.ndarray:
        try:
            array = np.asarray(value, dtype=float)
        except (TypeError, ValueError):
            raise AdapterError(f"{name} must be {size} numbers, got {value!r}") from None
        if array.shape != (size,) or not np.all(np.isfinite(array)):
            raise AdapterError(f"{name} must be {size} finite numbers, got {value!r}")
        if positive and np.any(array < 0):
            raise AdapterError(f"{name} must not be negative, got {value!r}")
        return array

    return convert


def _positive(name: str) -> Callable[[Any], float]:
    def convert(value: Any) -> float:
        try:
            number = float(value)
        except (TypeError, ValueError):
            raise AdapterError(f"{name} must be a number, got {value!r}") from None
        if not math.isfinite(number) or number <= 0:
            raise AdapterError(f"{name} must be a positive number, got {value!r}")
        return number

    return convert


def _frame(name: str) -> Callable[[Any], pin.SE3]:
    def convert(value: Any) -> pin.SE3:
        if not isinstance(value, pin.SE3):
            raise AdapterError(f"{name} must be a pinocchio.SE3, got {type(value).__name__}")
        return value

    return convert


def _optional_name(name: str) -> Callable[[Any], str | None]:
    def convert(value: Any) -> str | None:
        if value is not None and not isinstance(value, str):
            raise AdapterError(f"{name} must be a scene object name, got {value!r}")
        return value

    return convert


_REQUIRED = object()

Signatures = dict[tuple[str, str], dict[str, tuple[Any, Callable[[Any], Any]]]]


def signatures(robot: Robot) -> Signatures:
    """The commands' parameters with their defaults (the stiffnesses are the robot's) and
    converters."""
    return {
        ("robot", "moveCartesian"): {
            "goal": (_REQUIRED, _frame("goal")),
            "task": (None, _frame("task")),
            "stiffness": (robot.cartesian_stiffness, _vector("stiffness", 6, positive=True)),
            "damping": (DEFAULT_DAMPING, _vector("damping", 6, positive=True)),
            "speed": (0.1, _positive("speed")),
            "angular_speed": (1.0, _positive("angular_speed")),
            "ref": (None, _optional_name("ref")),
        },
        ("robot", "moveJoint"): {
            "q": (_REQUIRED, _vector("q", ARM_DOF)),
            "stiffness": (robot.joint_stiffness, _vector("stiffness", ARM_DOF, positive=True)),
            "damping": (DEFAULT_JOINT_DAMPING, _vector("damping", ARM_DOF, positive=True)),
        },
        ("gripper", "open"): {},
        ("gripper", "close"): {"force": (20.0, _positive("force"))},
        ("camera", "localize"): {"target": (_REQUIRED, _optional_name("target"))},
    }


def bind(table: Signatures, device: str, command: str, args: Mapping[str, Any]) -> dict[str, Any]:
    """Check and convert command arguments against the signature; defaults fill the rest."""
    signature = table.get((device, command))
    if signature is None:
        commands = sorted(c for d, c in table if d == device)
        if not commands:
            raise AdapterError(f"unknown device {device!r}; devices: robot, gripper, camera")
        raise AdapterError(f"device {device!r} has no command {command!r}; commands: {commands}")
    if not isinstance(args, Mapping):
        raise AdapterError(f"arguments of {device}.{command} must be a mapping by name")
    unknown = sorted(set(args) - set(signature))
    if unknown:
        raise AdapterError(
            f"{device}.{command} has no parameter(s) {unknown}; parameters: {list(signature)}"
        )
    bound = {}
    for name, (default, convert) in signature.items():
        if name in args:
            value = args[name]
        elif default is _REQUIRED:
            raise AdapterError(f"{device}.{command} needs the argument {name!r}")
        else:
            value = default
        bound[name] = value if value is None else convert(value)
    return bound


class RobotView:
    """Sensor values of the robot at the current tick (read lazily from the cell)."""

    def __init__(self, cell: SimulatedCell) -> None:
        self._cell = cell

    @property
    def tcp(self) -> pin.SE3:
        return self._cell.arm.tcp

    @property
    def wrench(self) -> Wrench:
        """Built at most once per tick: several predicates usually read it."""
        cell = self._cell
        if cell.wrench_value is None:
            cell.wrench_value = Wrench.of_floats(*cell.wrist.wrench.tolist())
        return cell.wrench_value

    @property
    def q(self) -> np.ndarray:
        return self._cell.arm.q[:ARM_DOF].copy()

    @property
    def goalReached(self) -> bool:
        return bool(self._cell.controller.reached(self._cell.arm))

    @property
    def travel(self) -> Vector3:
        (x, y, z), (x0, y0, z0) = self._cell.arm.position.tolist(), self._cell.travel_origin
        return Vector3.of_floats(x - x0, y - y0, z - z0)

    @property
    def turned(self) -> float:
        return self._cell.turned

    @property
    def peakForce(self) -> float:
        return self._cell.peak_force


class GripperView:
    """Sensor values of the gripper at the current tick."""

    def __init__(self, cell: SimulatedCell) -> None:
        self._cell = cell

    @property
    def width(self) -> float:
        return float(self._cell.plant.q[ARM_DOF] + self._cell.plant.q[ARM_DOF + 1])

    @property
    def done(self) -> bool:
        """Latched once the fingers came to rest after the last command, as a real gripper's
        status bit: arm motion that jiggles a held part does not clear it."""
        cell = self._cell
        if not cell.grip_settled:
            settled = cell.time - cell.grip_start >= GRIPPER_SETTLE
            rest = float(np.max(np.abs(cell.plant.v[ARM_DOF:]))) < GRIPPER_REST_SPEED
            cell.grip_settled = settled and rest
        return cell.grip_settled

    @property
    def holding(self) -> bool:
        return self._cell.grip > 0 and self.done and self.width > GRIPPER_EMPTY_WIDTH


class CameraView:
    """Sensor values of the camera: ``done`` once a localisation result is available."""

    def __init__(self, cell: SimulatedCell) -> None:
        self._cell = cell

    @property
    def done(self) -> bool:
        return self._cell.camera_done


class LiveSnapshot:
    """The snapshot stop predicates see inside the loop: reads the current tick's values."""

    def __init__(self, cell: SimulatedCell) -> None:
        self._cell = cell
        self.robot = RobotView(cell)
        self.gripper = GripperView(cell)
        self.camera = CameraView(cell)

    @property
    def time(self) -> float:
        return self._cell.time


_SENSORS = {
    "robot": ("tcp", "wrench", "q", "goalReached", "travel", "turned", "peakForce"),
    "gripper": ("holding", "width", "done"),
    "camera": ("done",),
}


def frozen(live: Any, time: float) -> SimpleNamespace:
    """A frozen copy of every sensor value of a cell's live views (robot, gripper, camera),
    as ``snapshot()`` answers it on every adapter of such a cell."""
    devices = {
        name: SimpleNamespace(**{s: getattr(getattr(live, name), s) for s in sensors})
        for name, sensors in _SENSORS.items()
    }
    return SimpleNamespace(time=time, **devices)


class SimulatedCell(ArmCommands, TickingAdapter):
    """``runtime.contract.Adapter`` for one cell (a robot arm, parallel gripper, camera) on a
    plant; the scene and the robot are registered names (adapters.scene_registry)."""

    PLANT: Callable[[str, str], Plant]
    """Builds the physics of a scene with a robot; each adapter names its own."""
    PERIOD = DT
    OPTIONS = (
        AdapterOption("robot", str, "the registered robot in the cell's robot slot"),
        AdapterOption("seed", int, "seed of the perception noise"),
        AdapterOption(
            "perception_noise", tuple, "σ of the camera's position [m] and rotation [rad]"
        ),
        AdapterOption("video", str, "an MP4 file the run is rendered to"),
    )

    def __init__(
        self,
        scene: str = "empty",
        *,
        robot: str = "lwr",
        seed: int = 0,
        perception_noise: tuple[float, float] = (0.0, 0.0),
        video: str | None = None,
    ) -> None:
        kernels.warm_up()
        self.robot = registered_robot(robot)
        self._signatures = signatures(self.robot)
        self.plant = type(self).PLANT(scene, robot)
        self.scene = scene
        self.noise = (float(perception_noise[0]), float(perception_noise[1]))
        self.rng = np.random.default_rng(seed)
        self.recorder = None if video is None else VideoRecorder(video, self.plant.model)
        self.video_written = ""
        """Where the video's frames went, once the cell is closed."""
        self.arm = self.plant.arm
        self.wrist = self._make_wrist_sensor()
        self.time = 0.0
        self.grip = -OPEN_FORCE
        self.grip_start = 0.0
        self.grip_settled = False
        self.camera_done = False
        self.travel_origin = (0.0, 0.0, 0.0)
        self.wrench_value: Wrench | None = None
        """The current tick's ``robot.wrench`` once a predicate has read it."""
        self._live = LiveSnapshot(self)
        self._sense()
        self.controller: CartesianImpedance | JointImpedance = JointImpedance(
            self.arm,
            np.array(self.robot.ready),
            np.array(self.robot.joint_stiffness),
            np.array(DEFAULT_JOINT_DAMPING),
        )
        self._start_command()
        for _ in range(round(SETTLE_TIME / DT)):
            self.tick()
        self.tare()
        self.hold()

    # -- the Adapter protocol ---------------------------------------------------------------

    def devices(self) -> Mapping[str, str]:
        return {"robot": self.robot.device_type, "gripper": "ParallelGripper", "camera": "Camera"}

    def snapshot(self) -> SimpleNamespace:
        """A frozen copy of every sensor value now."""
        return frozen(self._live, self.time)

    # -- the control loop (runtime.control_loop) -------------------------------------------

    def start(self, commands: Sequence[Command]) -> list[Started]:
        """Check every command's arguments against the device signatures, then start them."""
        bound = [bind(self._signatures, c.device, c.command, c.args) for c in commands]
        return [
            getattr(self, f"_{c.device}_{c.command}")(c, **b)
            for c, b in zip(commands, bound, strict=True)
        ]

    def tick(self) -> None:
        """Control, step, sense (``_sense`` inlined: a Python call costs ~0.1 µs per tick)."""
        self.plant.step(self.controller.torque(self.arm), self.grip)
        self.time += DT
        self.arm.sense()
        self.wrench_value = None
        if self.recorder is not None:
            self.recorder.tick(self.time, self.plant)

    def live(self) -> LiveSnapshot:
        return self._live

    def stopped(self) -> None:
        self.hold()

    def close(self) -> None:
        if self.recorder is not None:
            self.recorder.close()
            self.video_written = self.recorder.written()
            self.recorder = None

    # -- ground truth -------------------------------------------------------------------------

    def scene_pose(self, name: str) -> pin.SE3:
        """True world pose of a scene body."""
        model = self.plant.model
        body = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, name)
        if body < 0:
            raise AdapterError(f"scene {self.scene!r} has no object {name!r}")
        self.plant.sync()
        data = self.plant.data
        return pin.SE3(data.xmat[body].reshape(3, 3).copy(), data.xpos[body].copy())

    def objects(self) -> list[str]:
        """The scene's bodies a cell may name as objects (binding checks them)."""
        return objects(self.plant.model, self.robot.root)

    def measurements(self) -> dict[str, Any]:
        """Scene ground truth (e.g. screw depth) from the scene's hook, if it has one."""
        return self.plant.measurements()

    def tare(self) -> None:
        """Zero the wrist sensor: call only when the tool touches nothing."""
        self.wrist.tare(self.plant.wrist(), self.arm.ft_rotation)

    # -- commands: each starts its command and returns (settled?, value) ------------------------

    def _goal(self, goal: pin.SE3, ref: str | None) -> pin.SE3:
        return goal if ref is None else self.scene_pose(ref) * goal

    def _gripper_open(self, c: Command) -> Started:
        return self._grip(c, -OPEN_FORCE)

    def _gripper_close(self, c: Command, force: float) -> Started:
        return self._grip(c, force)

    def _grip(self, c: Command, force: float) -> Started:
        self.grip = force
        self.grip_start = self.time
        self.grip_settled = False
        view = self._live.gripper
        return Started(lambda: view.done, nothing, c.stop)

    def _camera_localize(self, c: Command, target: str) -> Started:
        true = self.scene_pose(target)
        sigma_p, sigma_r = self.noise
        offset = self.rng.normal(0.0, sigma_p, 3)
        axis = self.rng.normal(size=3)
        angle = self.rng.normal(0.0, sigma_r)
        axis /= np.linalg.norm(axis)
        rotation = pin.exp3(angle * axis) @ true.rotation
        self.camera_done = True
        pose = pin.SE3(rotation, true.translation + offset)
        return Started(always, lambda: pose, c.stop)

    # -- the 1 kHz loop ------------------------------------------------------------------------

    def _make_wrist_sensor(self) -> WristSensor:
        """Load model of the hand subtree (mass, centre of mass in the ft frame) from MuJoCo."""
        model, data = self.plant.model, self.plant.data
        self.plant.sync()
        hand = model.body(self.robot.hand).id
        site = model.site(FT_SITE).id
        rotation = data.site_xmat[site].reshape(3, 3)
        com = rotation.T @ (data.subtree_com[hand] - data.site_xpos[site])
        return WristSensor(self.arm.sensing, float(model.body_subtreemass[hand]), com)

    def _sense(self) -> None:
        """Update kinematics and sensors (wrist, ``peakForce``, ``turned``) from the plant
        state: one native call of the arm state."""
        self.arm.sense()
        self.wrench_value = None
