"""``--adapter franka``: a Franka arm and its hand through libfranka (pylibfranka).

The arm runs in libfranka's torque mode with the very impedance controllers of the simulated
cell (adapters.control) on a Pinocchio model of the robot: one control tick is one robot
state read, one torque command written, in step with the robot's 1 kHz, and the stop
conditions are checked on every one of them, as on MuJoCo. The robot compensates gravity
itself, so the model's gravity is off. The wrist wrench is libfranka's estimate of the
external wrench, turned into the cell's convention (what the environment exerts on the tool,
at the TCP, world axes) and filtered and tared as the simulated wrist sensor is.

Every command is checked against the real arm's limits (adapters.franka.limits) before
anything is sent; the robot's own reflex thresholds are set just above them. Between
commands the arm holds in the robot's own controller. Faults of the robot, the network or the
start check end the run with the outcome ``error`` and a one-line message
(adapters.franka.link); a connection that fails while the adapter is built is reported by
the first command, so that the run's trace shows where it stopped.
"""

from __future__ import annotations

import math
import sys
import time
from collections.abc import Mapping, Sequence
from types import SimpleNamespace
from typing import Any

import mujoco
import numpy as np
import pinocchio as pin

from lightrocks.adapters import kernels
from lightrocks.adapters.arm import PinocchioArm
from lightrocks.adapters.arm_commands import ArmCommands
from lightrocks.adapters.control import CartesianImpedance, JointImpedance
from lightrocks.adapters.devices import (
    DEFAULT_JOINT_DAMPING,
    CameraView,
    RobotView,
    bind,
    frozen,
    signatures,
)
from lightrocks.adapters.franka import link
from lightrocks.adapters.franka.hand import Hand
from lightrocks.adapters.franka.limits import Limits
from lightrocks.adapters.kernels import DT
from lightrocks.adapters.robots.common import ARM_DOF, NV
from lightrocks.adapters.scene_registry import load_model, objects
from lightrocks.adapters.scene_registry import robot as registered_robot
from lightrocks.adapters.sensing import WristSensor
from lightrocks.runtime.contract import AdapterError, AdapterOption, Command, Wrench
from lightrocks.runtime.control_loop import Started, TickingAdapter, always, nothing

FRANKA_ROBOTS = ("panda", "fr3")
"""The registered robots that are a Franka arm with the Franka Hand."""
EFFORT = np.array([87.0, 87.0, 87.0, 87.0, 12.0, 12.0, 12.0])
"""The arm's joint torque limits [Nm]: a command is clipped to them."""
TORQUE_RATE = 0.9
"""Largest change [Nm] of a joint's torque command from one tick to the next (Franka: 1000
Nm/s), so that switching controllers never trips the torque discontinuity reflex."""
LATE = 1.5 * DT
"""A robot state that comes later than this after the previous one: cycles were missed."""


class FrankaAdapter(ArmCommands, TickingAdapter):
    """``runtime.contract.Adapter`` for a Franka arm, its hand and the cell's scene."""

    PERIOD = DT
    OPTIONS = (
        AdapterOption("robot_ip", str, "the address of the robot (its FCI network)"),
        AdapterOption("confirm", bool, "ask once before the first motion"),
        AdapterOption("robot", str, "the registered Franka robot model (panda, fr3)"),
        AdapterOption("limits", Limits, "workspace, speed, force and stiffness limits"),
    )

    def __init__(
        self,
        scene: str | None = "empty",
        *,
        robot_ip: str | None = None,
        confirm: bool = False,
        robot: str = "panda",
        limits: Limits | None = None,
    ) -> None:
        if not robot_ip:
            raise ValueError("a real arm needs its address: --robot-ip ADDRESS")
        if robot not in FRANKA_ROBOTS:
            raise ValueError(f"robot {robot!r} is no Franka arm; choose one of {FRANKA_ROBOTS}")
        link.client()
        kernels.warm_up()
        self.address = robot_ip
        self.scene = scene or "empty"
        self.limits = limits or Limits()
        self.robot = registered_robot(robot)
        self._signatures = signatures(self.robot)
        self._poses, self._objects = _scene_poses(self.scene, robot, self.robot.root)
        model = self.robot.model()
        self.joint_ranges = (
            model.lowerPositionLimit[:ARM_DOF].copy(),
            model.upperPositionLimit[:ARM_DOF].copy(),
        )
        """The arm's joint ranges from its own model: goals and the start are checked in them."""
        model.gravity.linear[:] = 0.0  # the robot compensates gravity itself
        self.arm = PinocchioArm(model)
        self.wrist = WristSensor(self.arm.sensing, 0.0, np.zeros(3))
        self.controller: CartesianImpedance | JointImpedance
        self.travel_origin = (0.0, 0.0, 0.0)
        self.wrench_value: Wrench | None = None
        self.camera_done = False
        self.stats = LoopStats()
        self._time = 0.0
        self._tau = np.zeros(ARM_DOF)
        self._fresh = False
        """The next tick is the first of a motion."""
        self._control: Any = None
        self._robot: Any = None
        self._hand: Hand | None = None
        self._asked = not confirm
        self._torques = link.client().Torques
        self._live = SimpleNamespace(
            robot=RobotView(self), gripper=HandView(self), camera=CameraView(self), time=0.0
        )
        self.fault = ""
        """Why the adapter cannot move the arm: the first command raises it."""
        try:
            self._connect()
        except AdapterError as error:
            self.fault = str(error)
        self.controller = JointImpedance(
            self.arm,
            self.arm.q[:ARM_DOF].copy(),
            np.array(self.robot.joint_stiffness),
            np.array(DEFAULT_JOINT_DAMPING),
        )

    # -- the Adapter protocol ---------------------------------------------------------------

    @property
    def time(self) -> float:
        return self._time

    def devices(self) -> Mapping[str, str]:
        return {"robot": self.robot.device_type, "gripper": "ParallelGripper", "camera": "Camera"}

    def objects(self) -> list[str]:
        """The scene's objects a cell may name (their poses are the scene's, see localize)."""
        return list(self._objects)

    def snapshot(self) -> SimpleNamespace:
        """A frozen copy of every sensor value of the last robot state read."""
        return frozen(self.live(), self._time)

    def hold(self) -> None:
        """Stop every command: inside the control loop the arm holds where it is with the
        impedance of its last command; outside it the robot's own controller holds it."""
        if self._hand is not None and not self._hand.state.done:
            self._hand.stop()
        if self._control is not None:
            self.hold_arm()

    def close(self) -> None:
        self.stopped()
        if self._hand is not None:
            self._hand.close()
            self._hand = None
        self._robot = None

    # -- the control loop (runtime.control_loop) -------------------------------------------

    def start(self, commands: Sequence[Command]) -> list[Started]:
        """Check every command against the device signatures and the arm's limits, ask for
        confirmation before the first motion, then start them in the robot's torque mode."""
        if self.fault:
            raise AdapterError(self.fault)
        bound = [bind(self._signatures, c.device, c.command, c.args) for c in commands]
        for c, b in zip(commands, bound, strict=True):
            self._check(c, b)
        if not self._asked:
            self._ask()
        self._begin()
        return [
            getattr(self, f"_{c.device}_{c.command}")(c, **b)
            for c, b in zip(commands, bound, strict=True)
        ]

    def tick(self) -> None:
        """Wait for the next robot state, check it, write the controller's torques."""
        control = self._control
        began = 0.0
        try:
            state, period = control.readOnce()
            began = time.perf_counter()
            # the first period of a motion reaches back to the state read before it started
            self._take(state, DT if self._fresh else period.to_sec())
            self._fresh = False
            mode = state.robot_mode.name
            if mode != "Move":
                raise AdapterError(_stopped(mode, state, self.address))
            self._watch()
            tau = self.controller.torque(self.arm)
            step = np.clip(tau - self._tau, -TORQUE_RATE, TORQUE_RATE)
            self._tau = np.clip(self._tau + step, -EFFORT, EFFORT)
            control.writeOnce(self._torques(self._tau.tolist()))
        except AdapterError:
            raise  # the motion still runs: ``stopped`` ends it, and the robot holds
        except Exception as error:
            self._drop()
            raise link.fault(error, self.address) from None
        finally:
            if began:
                self.stats.step(time.perf_counter() - began)
        if self._hand is not None:
            self._hand.poll()

    def live(self) -> SimpleNamespace:
        self._live.time = self._time
        return self._live

    def stopped(self) -> None:
        """End the torque motion: the robot's own controller holds the arm where it is."""
        control, self._control = self._control, None
        if control is None:
            return
        try:
            finish = self._torques([0.0] * ARM_DOF)
            finish.motion_finished = True
            control.writeOnce(finish)
        except Exception:  # the connection is gone, or the robot stopped itself already
            pass
        self._tau[:] = 0.0

    # -- commands: each starts its command and returns Started --------------------------------

    def _gripper_open(self, c: Command) -> Started:
        return self._grip(c, "open")

    def _gripper_close(self, c: Command, force: float) -> Started:
        return self._grip(c, "grasp", force)

    def _grip(self, c: Command, name: str, *args: float) -> Started:
        hand = self._hand
        assert hand is not None
        hand.command(name, *args)
        return Started(lambda: hand.state.done, nothing, c.stop)

    def _camera_localize(self, c: Command, target: str) -> Started:
        pose = self._pose(target)
        self.camera_done = True
        return Started(always, lambda: pose, c.stop)

    # -- sensors ------------------------------------------------------------------------------

    @property
    def width(self) -> float:
        return self._hand.state.width if self._hand is not None else 0.0

    def tare(self) -> None:
        """Zero the wrench estimate: call only when the tool touches nothing."""
        self.wrist.tare(self.arm.raw.copy(), self.arm.ft_rotation)

    # -- inside ---------------------------------------------------------------------------------

    def _connect(self) -> None:
        """Connect, check the arm's state, set its reflexes from the limits, start the hand."""
        self._robot = link.connect(self.address)
        state = self._robot.read_once()
        link.check_start(state, self.address, self.joint_ranges)
        joint, wrench = self.limits.collision_thresholds()
        contact_joint, contact_wrench = [0.5 * t for t in joint], [0.5 * f for f in wrench]
        try:
            self._robot.set_collision_behavior(contact_joint, joint, contact_wrench, wrench)
        except Exception as error:
            raise link.fault(error, self.address) from None
        self._hand = Hand(self.address)
        self._take(state, 0.0)
        self.tare()

    def _begin(self) -> None:
        """Start a torque motion, from the current robot state, unless one runs."""
        if self._control is not None:
            return
        try:
            self._take(self._robot.read_once(), 0.0)
            self._control = self._robot.start_torque_control()
        except Exception as error:
            raise link.fault(error, self.address) from None
        self._fresh = True
        self.hold()

    def _take(self, state: Any, period: float) -> None:
        """The robot state of this tick into the arm state and the wrist sensing."""
        self._time += period
        self.stats.period(period)
        arm = self.arm
        arm.q[:ARM_DOF] = state.q
        arm.v[:ARM_DOF] = state.dq
        arm.q[ARM_DOF:NV] = 0.5 * self.width
        arm.v[ARM_DOF:NV] = 0.0
        arm.compute()
        arm.update()
        arm.raw[:] = _wrench_at_ft(state, arm.ft_position, self.robot.base)
        arm.sense()
        self.wrench_value = None

    def _watch(self) -> None:
        """The TCP in its box, the contact wrench below the limits."""
        self.limits.check_tcp(self.arm.position)
        w = self.wrist.wrench
        self.limits.check_wrench(math.hypot(*w[:3]), math.hypot(*w[3:]))

    def _check(self, c: Command, b: dict[str, Any]) -> None:
        """The arm's limits, before anything is sent."""
        if c.device == "robot" and c.command == "moveCartesian":
            task = pin.SE3.Identity() if b["task"] is None else b["task"]
            tcp_goal = self._goal(b["goal"], b["ref"]) * task.inverse()
            self.limits.check_cartesian(
                tcp_goal.translation, b["stiffness"], b["speed"], b["angular_speed"]
            )
        elif c.device == "robot" and c.command == "moveJoint":
            self.limits.check_joint(b["q"], b["stiffness"], self.joint_ranges)
        elif c.device == "gripper" and c.command == "close":
            self.limits.check_grip(b["force"])

    def _ask(self) -> None:
        """``--confirm``: once, before the first motion; never on a stdin that is no terminal."""
        if not sys.stdin.isatty():
            raise AdapterError("--confirm needs a terminal to ask on: stdin is not one")
        print(
            f"The arm at {self.address} is about to move. Clear the workspace, keep the "
            "emergency stop at hand. Move? [y/N] ",
            end="",
            flush=True,
        )
        if sys.stdin.readline().strip().lower() not in ("y", "yes"):
            raise AdapterError("the first motion was not confirmed")
        self._asked = True

    def _goal(self, goal: pin.SE3, ref: str | None) -> pin.SE3:
        return goal if ref is None else self._pose(ref) * goal

    def _pose(self, name: str) -> pin.SE3:
        pose = self._poses.get(name)
        if pose is None:
            raise AdapterError(f"scene {self.scene!r} has no object {name!r}")
        return pose

    def _drop(self) -> None:
        """After a fault: no more commands on this motion (the robot has stopped it)."""
        self._control = None
        self._tau[:] = 0.0


class HandView:
    """Sensor values of the Franka Hand at the current tick."""

    def __init__(self, adapter: FrankaAdapter) -> None:
        self._adapter = adapter

    @property
    def width(self) -> float:
        return self._adapter.width

    @property
    def done(self) -> bool:
        hand = self._adapter._hand
        return hand is None or hand.state.done

    @property
    def holding(self) -> bool:
        hand = self._adapter._hand
        return hand is not None and hand.holding


class LoopStats:
    """The control loop's timing: robot periods (missed cycles) and the control step (from
    the robot state's arrival to the torque command's departure)."""

    def __init__(self) -> None:
        self.ticks = 0
        self.missed = 0
        self.robot_time = 0.0
        self.steps: list[float] = []

    def period(self, seconds: float) -> None:
        if seconds <= 0.0:
            return
        self.ticks += 1
        self.robot_time += seconds
        if seconds > LATE:
            self.missed += round(seconds / DT) - 1

    def step(self, seconds: float) -> None:
        self.steps.append(seconds)


def _stopped(mode: str, state: Any, address: str) -> str:
    """Why the robot left the motion by itself: an emergency stop, a reflex, ..."""
    if mode == "UserStopped":
        return f"the robot at {address} was stopped by its user stop (emergency stop)"
    errors = state.current_errors or state.last_motion_errors
    return f"the robot at {address} left the motion (mode {mode}): {errors or 'no error given'}"


def _wrench_at_ft(state: Any, ft: np.ndarray, base: tuple[float, float, float]) -> np.ndarray:
    """libfranka's external wrench estimate as the raw reading the wrist sensing takes.

    ``O_F_ext_hat_K`` is the wrench the robot exerts on its environment (libfranka's sign),
    at the stiffness frame K, base axes; the sensing wants the reading of a wrist sensor at
    the ``ft`` site, whose negative is what the environment exerts on the tool. The robot's
    base axes are the world's; only its origin may sit elsewhere (``base``).
    """
    wrench = np.array(state.O_F_ext_hat_K, dtype=float)
    o_t_ee = np.array(state.O_T_EE).reshape(4, 4, order="F")
    ee_t_k = np.array(state.EE_T_K).reshape(4, 4, order="F")
    k = (o_t_ee @ ee_t_k)[:3, 3] + np.array(base)
    wrench[3:] += np.cross(k - ft, wrench[:3])
    return wrench


def _scene_poses(scene: str, robot: str, root: str) -> tuple[dict[str, pin.SE3], list[str]]:
    """Where the scene places its objects (world frame), and their names: a real cell has no
    ground truth, so the camera reports these poses."""
    model = load_model(scene, robot)
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    names = objects(model, root)
    poses = {}
    for name in names:
        body = model.body(name).id
        poses[name] = pin.SE3(data.xmat[body].reshape(3, 3).copy(), data.xpos[body].copy())
    return poses, names
