"""The connection to a Franka arm through libfranka (pylibfranka), and what can go wrong.

Every way the robot or the network can fail becomes one line that says what happened and
what to do about it: an ``AdapterError``, which the runtime turns into the outcome ``error``.
libfranka waits a minute for an address that does not answer; a plain TCP probe of the FCI
port first turns that into a few seconds, and retries a refusal for a moment, since a robot
(or a simulator) that has just come up may refuse the first connection.
"""

from __future__ import annotations

import ipaddress
import socket
import time
from typing import Any

from lightrocks.adapters.franka.limits import JointRanges, joints_in_range
from lightrocks.runtime.contract import AdapterError

FCI_PORT = 1337
PROBE_TIMEOUT = 3.0
"""Seconds an address has to answer on the FCI port."""
REFUSED_RETRY = 3.0
"""Seconds a refused connection is tried again."""
INSTALL = "pip install 'lightrocks[franka]'"


def client() -> Any:
    """The pylibfranka module; a clear error when the extra is not installed."""
    try:
        import pylibfranka
    except ImportError:
        raise ValueError(f"adapter 'franka' needs pylibfranka: {INSTALL}") from None
    return pylibfranka


def probe(address: str) -> None:
    """Answer the FCI port at ``address`` within PROBE_TIMEOUT, or say why not."""
    deadline = time.monotonic() + REFUSED_RETRY
    while True:
        try:
            with socket.create_connection((address, FCI_PORT), timeout=PROBE_TIMEOUT):
                return
        except socket.gaierror:
            raise AdapterError(f"unknown robot address {address!r}: no such host") from None
        except ConnectionRefusedError:
            if time.monotonic() < deadline:
                time.sleep(0.2)
                continue
            raise AdapterError(
                f"the robot at {address} refused the connection: is it on, its brakes open "
                "and FCI enabled in Desk (or the simulator started)?"
            ) from None
        except TimeoutError:
            raise AdapterError(
                f"the robot at {address} did not answer within {PROBE_TIMEOUT:.0f} s: check "
                "the address and the network (docs/adapters.md, 'A real Franka arm')"
            ) from None
        except OSError as error:
            raise AdapterError(f"cannot reach the robot at {address}: {error.strerror}") from None


def connect(address: str) -> Any:
    """The robot at ``address``. libfranka's real-time scheduling is required for a real arm,
    as libfranka does by default, and left out for a simulator on this machine (a loopback
    address), which runs on any kernel."""
    franka = client()
    probe(address)
    simulated = on_this_machine(address)
    config = franka.RealtimeConfig.kIgnore if simulated else franka.RealtimeConfig.kEnforce
    try:
        return franka.Robot(address, config)
    except Exception as error:
        if type(error).__name__ == "RealtimeException":
            raise AdapterError(
                f"cannot run the control loop for the robot at {address} in real time: "
                f"{one_line(error)} (a real-time kernel and rtprio for this user are needed: "
                "docs/adapters.md, 'Set-up on hardware')"
            ) from None
        raise AdapterError(f"cannot connect to the robot at {address}: {one_line(error)}") from None


def on_this_machine(address: str) -> bool:
    """Whether ``address`` is a loopback one: a simulator, not an arm."""
    try:
        return ipaddress.ip_address(socket.gethostbyname(address)).is_loopback
    except (OSError, ValueError):
        return False


def check_start(state: Any, address: str, ranges: JointRanges) -> None:
    """The arm's state allows a task: idle, no errors, every joint inside its range."""
    mode = state.robot_mode.name
    if mode != "Idle":
        hint = {
            "Reflex": "a reflex stopped it: clear the error in Desk, then run again",
            "UserStopped": "the user stop (emergency stop) is pressed: release it in Desk",
            "Guiding": "it is being guided by hand: let go of the pilot buttons",
            "Move": "another program is moving it",
            "AutomaticErrorRecovery": "it is recovering from an error: wait and run again",
        }.get(mode, "open its brakes and activate FCI in Desk")
        raise AdapterError(f"the robot at {address} is in mode {mode}, not Idle: {hint}")
    if state.current_errors:
        raise AdapterError(f"the robot at {address} reports errors: {state.current_errors}")
    joints_in_range(
        list(state.q), f"the robot at {address} starts outside its joint ranges", ranges
    )


def fault(error: BaseException, address: str) -> AdapterError:
    """One line for what libfranka raised inside the control loop."""
    name = type(error).__name__
    text = one_line(error)
    if "User Stop pressed" in text:
        return AdapterError(f"the robot at {address} was stopped by its user stop: {text}")
    if name in ("ControlException", "CommandException") and "reflex" in text:
        return AdapterError(f"the robot at {address} stopped with a reflex: {text}")
    if name == "ControlException":
        if "communication_constraints_violation" in text:
            return AdapterError(
                f"the robot at {address} stopped: communication constraints violated (the "
                f"control loop missed its 1 ms deadline; use a real-time kernel): {text}"
            )
        return AdapterError(f"the robot at {address} stopped with a reflex: {text}")
    if name == "NetworkException":
        return AdapterError(f"lost the connection to the robot at {address}: {text}")
    return AdapterError(f"the robot at {address} failed: {name}: {text}")


def one_line(error: BaseException) -> str:
    """libfranka's message on one line, without its ``libfranka:`` prefix."""
    text = " ".join(str(error).split()) or type(error).__name__
    return text.removeprefix("libfranka: ")
