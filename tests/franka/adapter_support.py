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
def simulator(scene: str, where: str) -> Iterator[subprocess.Popen[str]]:
    """The protocol simulator with ``scene`` on ``where`` until the block ends."""
    need_franka()
    process = subprocess.Popen(
        [sys.executable, "-c", SERVE, scene, where],
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
