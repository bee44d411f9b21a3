"""What the adapter's tests share: the client library or the judge missing, and a protocol
simulator in a process of its own on a loopback address.

The simulator cannot run in the test's process: pylibfranka holds the interpreter lock while
it waits for a robot state, so a simulator thread beside it would never send one.
"""

from __future__ import annotations

import importlib.util
import os
import signal
import subprocess
import sys
import time
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

from judges import missing

ROOT = Path(__file__).resolve().parents[2]
INSTALL = "pip install 'lightrocks[franka]'"
SERVE = """
import sys
from lightrocks.app.franka_sim import FrankaSim
sim = FrankaSim(sys.argv[1], address=sys.argv[2])
sim.start()
if len(sys.argv) > 3:  # another robot mode: from the start, or from the given physics step
    # of the first motion on, that motion aborted with the matching status (user stop, reflex)
    from franky_sim.franka_robot_protocol import BaseCommand, MoveStatus, RobotCommand, RobotMode
    mode, after = getattr(RobotMode, "k" + sys.argv[3]), int(sys.argv[4])
    user_stop = sys.argv[3] == "UserStopped"
    status = MoveStatus.kEmergencyAborted if user_stop else MoveStatus.kReflexAborted
    began = []
    server = type(sim.server)
    shipped = server.robot_state
    def robot_state(self):
        if self.current_motion_id and not began:
            began.append(sim.steps)
        faked = after == 0 or (began and sim.steps >= began[0] + after)
        if faked and self.current_motion_id:
            motion = self.current_motion_id
            BaseCommand.send_response(self._tcp_socket, RobotCommand.kMove, motion, status)
            self.stop_motion(send_preemption_signal=False)
        state = shipped.fget(self)
        return state.replace(robot_mode=mode) if faked else state
    server.robot_state = property(robot_state)
print("ready", flush=True)
sim.serve()
"""
START_TIMEOUT = 120.0


def need_franka() -> None:
    """Skip (or fail in CI) without pylibfranka or franky-sim."""
    for module, what in (("pylibfranka", "pylibfranka"), ("franky_sim", "franky-sim")):
        if importlib.util.find_spec(module) is None:
            missing(what, INSTALL)


def address(slot: int) -> str:
    """A loopback address of its own for each test module and xdist worker."""
    worker = os.environ.get("PYTEST_XDIST_WORKER", "gw0").removeprefix("gw") or "0"
    return f"127.{40 + slot}.{int(worker) % 250 + 1}.{os.getpid() % 250 + 1}"


@contextmanager
def simulator(
    scene: str, where: str, mode: str | None = None, after: int = 0
) -> Iterator[subprocess.Popen[str]]:
    """The protocol simulator with ``scene`` on ``where`` until the block ends; with
    ``mode`` (``Reflex``, ``UserStopped``, …) its robot reports that mode from ``after``
    physics steps on."""
    need_franka()
    faked = [mode, str(after)] if mode is not None else []
    process = subprocess.Popen(
        [sys.executable, "-c", SERVE, scene, where, *faked],
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
        cwd=ROOT,
        start_new_session=True,
    )
    try:
        deadline = time.monotonic() + START_TIMEOUT
        assert process.stdout is not None
        line = process.stdout.readline()
        while line and "ready" not in line and time.monotonic() < deadline:
            line = process.stdout.readline()
        if "ready" not in line:
            raise RuntimeError(f"the simulator did not start: {line.strip() or 'no output'}")
        yield process
    finally:
        stop(process)


def stop(process: subprocess.Popen[str]) -> None:
    """End the simulator (its process group, which it leads)."""
    if process.poll() is None:
        os.killpg(process.pid, signal.SIGTERM)
        try:
            process.wait(10)
        except subprocess.TimeoutExpired:
            os.killpg(process.pid, signal.SIGKILL)
            process.wait(10)
    if process.stdout is not None:
        process.stdout.close()
