"""franky-sim's robot and hand servers, stepped in lock-step with the client.

As shipped, franky-sim steps its physics once per wall-clock millisecond whatever the client
does, so two runs of one task differ in the last bits, and a loaded machine changes the
outcome. Here the physics advances only when something moves:

- while a motion runs (libfranka's Move command until its success), one 1 ms step per control
  message of the client, each answering the state sent last: the client's controller sees the
  world exactly once per step, however long it takes to answer;
- while the hand moves and the arm does not, one step per loop turn, as fast as the machine
  goes (the arm holds its pose as it does between motions);
- otherwise the world stands still, and the state is sent again every millisecond (a fresh
  message each time, which libfranka needs to read one), with unchanged values.

The hand's settle check, which franky-sim runs once per loop turn, runs once per physics step
here. When a motion starts, libfranka waits for a state with the new mode, then for a fresh
one for its first control call (with a period of 0): these two go out ``HANDSHAKE_S`` apart,
and then nothing until the client answers, since any further state would reach a slow client
as a cycle of 2 ms. (A client that takes both at once gets a third after ``STALL_S``.) Every
state carries the external wrench estimated from the
hand's contacts (:mod:`app.franka_sim.wrench`).

Only franky-sim's documented hooks are overridden; :data:`WRAPPED` names each attribute this
module relies on, so that a test can say which one an upgrade removed.
"""

from __future__ import annotations

import time
from collections.abc import Iterable

import numpy as np
from franky_sim.franka_gripper_server import FrankaGripperServer
from franky_sim.franka_robot_protocol import UDPCommand
from franky_sim.franka_robot_server import FrankaRobotServer
from franky_sim.franka_robot_state import FrankaRobotState
from franky_sim.mujoco_simulator import FrankaMujocoRobot

from lightrocks.app.franka_sim.wrench import HandContacts, franka_wrenches

HAND_BODY = "robot0_hand"
"""franky-sim's name of the first robot's hand body (its bodies are prefixed ``robot0_``)."""
HEARTBEAT_S = 0.001
"""Wall-clock period [s] of the state while nothing moves (libfranka's 1 kHz)."""
HANDSHAKE_S = 0.002
"""Wall-clock delay [s] between the two states that start a motion (see the docstring)."""
STALL_S = 0.5
"""A running motion whose client has not answered for this long [s] gets its state again:
a lost datagram, or a client starved that long, which libfranka (it waits 1 s for a state)
would not survive otherwise. The client then sees a 2 ms cycle once, and the run is no
longer bitwise the same as an unhurried one."""

WRAPPED: tuple[tuple[str, str, str], ...] = (
    ("franky_sim.franka_robot_server", "FrankaRobotServer", "_setup_udp_connection"),
    ("franky_sim.franka_robot_server", "FrankaRobotServer", "_reset_state"),
    ("franky_sim.franka_robot_server", "FrankaRobotServer", "_handle_udp_command"),
    ("franky_sim.franka_robot_server", "FrankaRobotServer", "_bind_children"),
    ("franky_sim.franka_robot_server", "FrankaRobotServer", "send_state"),
    ("franky_sim.franka_robot_server", "FrankaRobotServer", "process_commands"),
    ("franky_sim.franka_robot_server", "FrankaRobotServer", "robot_state"),
    ("franky_sim.franka_robot_server", "FrankaRobotServer", "current_motion_id"),
    ("franky_sim.franka_robot_server", "FrankaRobotServer", "gripper_server"),
    ("franky_sim.franka_robot_server", "FrankaRobotServer", "udp_connected"),
    ("franky_sim.franka_gripper_server", "FrankaGripperServer", "_post_process_commands"),
    ("franky_sim.franka_robot_protocol", "UDPCommand", "from_bytes"),
    ("franky_sim.franka_robot_state", "FrankaRobotState", "replace"),
    ("franky_sim.franka_robot_state", "FrankaRobotState", "O_F_ext_hat_K"),
    ("franky_sim.franka_robot_state", "FrankaRobotState", "K_F_ext_hat_K"),
    ("franky_sim.franka_robot_state", "FrankaRobotState", "tau_ext_hat_filtered"),
    ("franky_sim.mujoco_simulator", "MujocoSimulator", "scene"),
    ("franky_sim.mujoco_simulator", "MujocoSimulator", "worldbody"),
    ("franky_sim.mujoco_simulator", "MujocoSimulator", "register_pre_step_callback"),
    ("franky_sim.mujoco_simulator", "MujocoSimulator", "add_robot"),
    ("franky_sim.mujoco_simulator", "MujocoSimulator", "step"),
    ("franky_sim.mujoco_simulator", "FrankaMujocoRobot", "model"),
    ("franky_sim.mujoco_simulator", "FrankaMujocoRobot", "data"),
    ("franky_sim.mujoco_simulator", "FrankaMujocoRobot", "_dof_addrs"),
)
"""(module, class, attribute) of franky-sim that this package subclasses, calls or reads
(``_dof_addrs`` is set in ``__init__``; the test checks it on an instance)."""


class SteppedGripper(FrankaGripperServer):
    """The hand's server whose settle check runs once per physics step, not per loop turn
    (installed on the instance the robot server creates, see ``_bind_children``)."""

    check_due: bool = False

    def _post_process_commands(self) -> None:
        if self.check_due:
            self.check_due = False
            super()._post_process_commands()

    @property
    def busy(self) -> bool:
        """Whether a move, grasp or homing of the hand awaits its end."""
        return self._pending_command_id is not None


class LockstepRobotServer(FrankaRobotServer):
    """The robot's server that knows whether the client has answered the last state, and
    fills the external wrench into every state it sends."""

    def __init__(self, robot: FrankaMujocoRobot, hostnames: Iterable[str]) -> None:
        self._sent = -1
        self._answered = False
        self._handshake = 0
        self._motion = 0
        self._last_send = 0.0
        self._contacts: HandContacts | None = None
        self.stalls = 0
        """How often a running motion's state went out again unanswered (``STALL_S``)."""
        super().__init__(robot, hostnames)

    # -- franky-sim's hooks -------------------------------------------------------------------

    def _bind_children(self, hostname: str) -> None:
        super()._bind_children(hostname)
        if self.gripper_server is not None:
            self.gripper_server.__class__ = SteppedGripper

    def _setup_udp_connection(self, network_udp_port: int) -> None:
        super()._setup_udp_connection(network_udp_port)
        self._sent = -1  # franky-sim numbers the states of a connection from 0

    def _reset_state(self) -> None:
        super()._reset_state()
        self._sent, self._answered, self._motion = -1, False, 0
        self._handshake = 0

    def _handle_udp_command(self, command_data: bytes) -> None:
        if UDPCommand.from_bytes(command_data).message_id == self._sent:
            self._answered = True
        super()._handle_udp_command(command_data)

    def send_state(self) -> None:
        if self.udp_connected:
            self._sent += 1
        self._last_send = time.monotonic()
        super().send_state()

    @property
    def robot_state(self) -> FrankaRobotState:
        state = super().robot_state
        robot = self.robot
        if robot.model is None:
            return state
        if self._contacts is None:
            self._contacts = HandContacts.of(robot.model, HAND_BODY, tuple(robot._dof_addrs))
        o_t_k = _matrix(state.O_T_EE) @ _matrix(state.EE_T_K)
        o_f, k_f, tau = franka_wrenches(self._contacts, robot.model, robot.data, o_t_k)
        return state.replace(O_F_ext_hat_K=o_f, K_F_ext_hat_K=k_f, tau_ext_hat_filtered=tau)

    # -- the lock-step ------------------------------------------------------------------------

    @property
    def gripper(self) -> SteppedGripper | None:
        found = self.gripper_server
        return found if isinstance(found, SteppedGripper) else None

    def poll(self) -> None:
        """Take what the client sent (commands, control messages) without stepping."""
        self.process_commands()
        motion = self.current_motion_id
        if motion != self._motion:
            self._motion = motion
            self._handshake = 2 if motion != 0 else 0

    def step_due(self) -> bool:
        """Whether the world advances one step now: the client answered the last state, or
        the hand moves while the arm stands."""
        if self._answered:
            self._answered = False
            return True
        gripper = self.gripper
        return self.current_motion_id == 0 and gripper is not None and gripper.busy

    def resend_due(self, now: float) -> bool:
        """Whether the unchanged state goes out again now (see the module's docstring)."""
        waited = now - self._last_send
        if self.current_motion_id == 0:
            return waited >= HEARTBEAT_S
        if self._handshake == 2 or (self._handshake == 1 and waited >= HANDSHAKE_S):
            self._handshake -= 1
            return True
        if self._handshake or waited < STALL_S:
            return False
        self.stalls += 1
        return True

    def stepped(self) -> None:
        """After a physics step: the hand checks whether it has settled."""
        gripper = self.gripper
        if gripper is not None:
            gripper.check_due = True


def _matrix(column_major: tuple[float, ...]) -> np.ndarray:
    return np.array(column_major, dtype=float).reshape((4, 4), order="F")
