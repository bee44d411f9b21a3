"""One simulated FR3 with its hand on a loopback address, in a LightRocks scene.

``FrankaSim(scene)`` builds franky-sim's MuJoCo world with the scene's objects
(:mod:`app.franka_sim.world`), puts the arm in the Panda's ready pose, binds libfranka's ports
(1337 for the arm, 1338 for the hand; libfranka has no other) on the given 127.x.y.z address
and lets the world settle for ``SETTLE_STEPS``; :meth:`FrankaSim.serve` then answers clients
in lock-step (:mod:`app.franka_sim.lockstep`) until its stop event is set. The physics is the
same for every run of the same client: states, the scene's ground truth and the step count
depend on the commands only, never on the wall clock (libfranka's ``RobotState.time``, which
counts the messages sent, does).
"""

from __future__ import annotations

import ipaddress
import socket
import threading
import time
from collections.abc import Sequence
from typing import Any

import mujoco
import numpy as np
from franky_sim.mujoco_simulator import MujocoSimulator

from lightrocks.adapters.robots.panda import ROBOT as PANDA
from lightrocks.adapters.scene import Scene, SceneFault
from lightrocks.adapters.scene_registry import scene as registered_scene
from lightrocks.app.franka_sim.lockstep import LockstepRobotServer
from lightrocks.app.franka_sim.world import add_scene

PORTS = (1337, 1338)
"""libfranka's command ports of the arm and of the hand."""
SETTLE_STEPS = 200
"""Steps [1 ms] the world takes at start-up, arm holding, so that loose parts come to rest."""
IDLE_SLEEP_S = 5e-5
"""Sleep [s] of a loop turn that neither steps nor sends."""
READY = PANDA.ready
"""The arm's start pose: the Panda's ready pose (the FR3 shares its kinematics), the TCP
pointing down above the table."""


class AddressError(ValueError):
    """The address is not a loopback one, or libfranka's ports are taken on it."""


def check_address(address: str) -> None:
    """Refuse anything but a free 127.x.y.z: the simulator is a rehearsal on this machine."""
    try:
        parsed = ipaddress.IPv4Address(address)
    except ValueError:
        raise AddressError(f"{address!r} is no IPv4 address (give 127.x.y.z)") from None
    if not parsed.is_loopback:
        raise AddressError(f"{address} is not a loopback address (give 127.x.y.z)")
    for port in PORTS:
        with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as probe:
            probe.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
            try:
                probe.bind((address, port))
            except OSError as error:
                raise AddressError(f"cannot listen on {address}:{port}: {error.strerror}") from None


class FrankaSim:
    """The simulator: build with a scene name (or a :class:`Scene`), :meth:`start`,
    :meth:`serve` (or :meth:`serve_in_thread`), :meth:`close`; also a context manager that
    starts and closes. ``steps`` counts the physics steps [1 ms] since start-up."""

    def __init__(
        self,
        scene: str | Scene = "empty",
        address: str = "127.0.0.1",
        initial_q: Sequence[float] = READY,
    ) -> None:
        self.scene_name = scene if isinstance(scene, str) else "custom"
        self.scene = registered_scene(scene) if isinstance(scene, str) else scene
        self.address = address
        self.initial_q = tuple(float(q) for q in initial_q)
        self.steps = 0
        self._stalls = 0
        self.sim: MujocoSimulator | None = None
        self.server: LockstepRobotServer | None = None
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None

    def start(self) -> None:
        """Build the world, bind the ports and let the world settle."""
        check_address(self.address)
        sim = MujocoSimulator()
        add_scene(sim, self.scene_name, self.scene)
        sim.init()
        robot = sim.add_robot(initial_q=self.initial_q)
        server = LockstepRobotServer(robot, [self.address])
        server.init()
        try:
            sim.start()
        except ValueError as error:  # MuJoCo's compiler: the merged world does not load
            server.cleanup()
            detail = "; ".join(line.strip() for line in str(error).splitlines() if line.strip())
            raise SceneFault(f"scene {self.scene_name!r} in franky-sim's world: {detail}") from None
        self.sim, self.server = sim, server
        for _ in range(SETTLE_STEPS):
            server.poll()
            self._step()

    def serve(self, stop: threading.Event | None = None) -> None:
        """Answer clients until ``stop`` (or :meth:`close`) is set."""
        stop = stop or self._stop
        server = self._running()
        while not (stop.is_set() or self._stop.is_set()):
            server.poll()
            if server.step_due():
                self._step()
                server.send_state()
            elif server.resend_due(time.monotonic()):
                server.send_state()
            else:
                time.sleep(IDLE_SLEEP_S)

    def serve_in_thread(self) -> None:
        """:meth:`serve` in a daemon thread, until :meth:`close`."""
        self._thread = threading.Thread(target=self.serve, name="franka-sim", daemon=True)
        self._thread.start()

    def close(self) -> None:
        """Stop serving, close the sockets and the world."""
        self._stop.set()
        if self._thread is not None:
            self._thread.join()
            self._thread = None
        if self.server is not None:
            self._stalls = self.server.stalls
            self.server.cleanup()
            self.server = None
        if self.sim is not None:
            self.sim.cleanup()
            self.sim = None

    @property
    def stalls(self) -> int:
        """How often a client left a running motion unanswered for 0.5 s (see
        ``lockstep.STALL_S``): a run with stalls is not bitwise reproducible."""
        return self.server.stalls if self.server is not None else self._stalls

    def measurements(self) -> dict[str, Any]:
        """The scene's ground truth now (``screw_depth``, …), which a real arm never knows."""
        sim = self._world()
        return self.scene.measurements(sim.model, sim.data)

    def physics(self) -> np.ndarray:
        """The world's whole physical state (time, positions, velocities, actuation) as one
        array, for comparing runs bit for bit."""
        sim = self._world()
        size = mujoco.mj_stateSize(sim.model, mujoco.mjtState.mjSTATE_INTEGRATION)
        state = np.empty(size)
        mujoco.mj_getState(sim.model, sim.data, state, mujoco.mjtState.mjSTATE_INTEGRATION)
        return state

    def __enter__(self) -> FrankaSim:
        self.start()
        return self

    def __exit__(self, *_: object) -> None:
        self.close()

    def _step(self) -> None:
        self._world().step()
        self._running().stepped()
        self.steps += 1

    def _world(self) -> MujocoSimulator:
        if self.sim is None:
            raise RuntimeError("the simulator is not started")
        return self.sim

    def _running(self) -> LockstepRobotServer:
        if self.server is None:
            raise RuntimeError("the simulator is not started")
        return self.server
