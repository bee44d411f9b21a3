"""The Franka Hand, driven from a process of its own.

libfranka's gripper commands block until the fingers stop, and pylibfranka holds the
interpreter lock meanwhile (measured: a thread running ``Gripper.move`` stopped every other
thread for its 0.65 s), so a gripper command in the control loop's process would stall the
1 kHz loop and trip the arm's communication reflex. The hand therefore lives in a child
process; the control loop posts commands to it and reads its latest state without waiting.
"""

from __future__ import annotations

import contextlib
import json
import os
import select
import signal
import subprocess
import sys
import time
from dataclasses import dataclass
from typing import Any

from lightrocks.runtime.contract import AdapterError

OPEN_SPEED = 0.1
"""Finger speed [m/s] of ``open`` (the Hand's maximum)."""
GRASP_SPEED = 0.05
"""Finger speed [m/s] of a grasp."""
EMPTY_WIDTH = 2e-3
"""A closed hand narrower than this holds nothing (as in the simulated cell)."""
START_TIMEOUT = 30.0
"""Seconds the hand's process has to connect."""


@dataclass
class HandState:
    """What the control loop knows of the hand: its latest reading and its last command."""

    width: float = 0.0
    grasped: bool = False
    done: bool = True
    """The last command has finished (its fingers rest)."""
    closing: bool = False
    """The last command was a grasp."""
    failure: str = ""


class Hand:
    """The hand's process and the state it last reported (lines of JSON both ways)."""

    def __init__(self, address: str) -> None:
        self.address = address
        self.state = HandState()
        self._buffer = b""
        self._process = subprocess.Popen(
            [sys.executable, "-m", __name__, address],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=subprocess.DEVNULL,
        )
        assert self._process.stdout is not None
        os.set_blocking(self._process.stdout.fileno(), False)
        deadline = time.monotonic() + START_TIMEOUT
        while not self._read():
            if self._process.poll() is not None or time.monotonic() > deadline:
                self.close()
                raise AdapterError(f"the gripper at {address} did not come up")
            time.sleep(0.02)
        if self.state.failure:
            failure = self.state.failure
            self.close()
            raise AdapterError(failure)

    def command(self, name: str, *args: float) -> None:
        """Start ``open`` or ``grasp``; ``state.done`` turns true when the fingers rest."""
        self.state.done = False
        self.state.closing = name == "grasp"
        self._send(name, *args)

    def poll(self) -> None:
        """Take every report the hand has sent since the last poll, without waiting."""
        self._read()
        if not self.state.failure and self._process.poll() is not None:
            self.state.failure = f"lost the gripper at {self.address}"
        if self.state.failure:
            raise AdapterError(self.state.failure)

    @property
    def holding(self) -> bool:
        state = self.state
        return state.closing and state.done and state.grasped and state.width > EMPTY_WIDTH

    def stop(self) -> None:
        """Stop the fingers where they are."""
        self._send("stop")

    def close(self) -> None:
        self._send("quit")
        try:
            self._process.wait(2.0)
        except subprocess.TimeoutExpired:
            self._process.kill()
            self._process.wait(2.0)
        for stream in (self._process.stdin, self._process.stdout):
            if stream is not None:
                stream.close()

    def _send(self, name: str, *args: float) -> None:
        stdin = self._process.stdin
        if stdin is None or stdin.closed or self._process.poll() is not None:
            return
        try:
            stdin.write(json.dumps([name, *args]).encode() + b"\n")
            stdin.flush()
        except OSError:
            pass

    def _read(self) -> bool:
        """Take the complete lines that have arrived; whether there were any."""
        stdout = self._process.stdout
        try:
            chunk = os.read(stdout.fileno(), 65536) if stdout is not None else b""
        except (BlockingIOError, OSError):
            chunk = b""
        if not chunk:
            return False
        *lines, self._buffer = (self._buffer + chunk).split(b"\n")
        for line in lines:
            self._take(json.loads(line))
        return bool(lines)

    def _take(self, report: list[Any]) -> None:
        kind, *value = report
        state = self.state
        if kind == "state":
            state.width, state.grasped = value
        elif kind == "done":
            state.done = True
        elif kind == "failure":
            state.failure = value[0]


def serve(address: str) -> None:
    """The hand's process: connect, then run each command (a line on stdin) to its end,
    reporting the fingers' width and grasp on stdout whenever they change. Ctrl-C at the
    terminal reaches it too; the control loop's process decides what happens then."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    import pylibfranka

    from lightrocks.adapters.franka.link import one_line

    def report(*fields: Any) -> None:
        sys.stdout.write(json.dumps(fields) + "\n")
        sys.stdout.flush()

    try:
        gripper = pylibfranka.Gripper(address)
        state = gripper.read_once()
    except Exception as error:
        report("failure", f"cannot connect to the gripper at {address}: {one_line(error)}")
        return
    last = (state.width, state.is_grasped)
    report("state", *last)
    max_width = state.max_width
    try:
        while True:
            if select.select([sys.stdin], [], [], 0.01)[0]:
                line = sys.stdin.readline()
                if not line:
                    return
                name, *args = json.loads(line)
                if name == "quit":
                    return
                if name == "open":
                    gripper.move(max_width, OPEN_SPEED)
                elif name == "grasp":
                    # any width counts as a grasp: whether something is held is the width's
                    # question (EMPTY_WIDTH), as on the simulated hand
                    gripper.grasp(0.0, GRASP_SPEED, args[0], 0.005, max_width)
                elif name == "stop":
                    gripper.stop()
                state = gripper.read_once()
                last = (state.width, state.is_grasped)
                report("state", *last)
                report("done")
            else:
                state = gripper.read_once()
                if (state.width, state.is_grasped) != last:
                    last = (state.width, state.is_grasped)
                    report("state", *last)
    except BrokenPipeError:
        return
    except Exception as error:
        with contextlib.suppress(OSError):
            report("failure", f"the gripper at {address} failed: {one_line(error)}")


if __name__ == "__main__":
    serve(sys.argv[1])
