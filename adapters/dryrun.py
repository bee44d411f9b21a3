"""A dry-run adapter: every device of any cell, no physics, simulated time.

Each command "runs" for ``duration`` seconds of simulated time in ticks of ``step``; then it
ends with the first stop condition that holds on the scripted snapshot, or with the next
outcome scripted for that command. Useful to walk a task's logic before a simulation, and to
pin the executor's semantics in tests. Motion is idealised: ``moveCartesian`` puts the TCP at
its goal (``travel`` and ``turned`` tell how far it went), ``close`` makes the gripper hold,
``open`` lets go, ``localize`` answers the pose the environment already believes (identity).
The per-command sensors start from zero with every command, as on the real devices.
"""

from __future__ import annotations

import inspect
import math
import typing
from collections.abc import Callable, Mapping, Sequence
from types import SimpleNamespace
from typing import Any

import pinocchio as pin

from lightrocks.runtime.contract import (
    TIMEOUT,
    AdapterError,
    AdapterOption,
    Command,
    StopCondition,
    Vector3,
    Wrench,
)
from lightrocks.runtime.control_loop import Started, TickingAdapter

SensorScript = Mapping[str, Any | Callable[[float], Any]]

PER_COMMAND = ("goalReached", "done", "travel", "turned", "peakForce")
"""Sensors that describe the running command: neutral again when the next one starts."""


class DryRunAdapter(TickingAdapter):
    """Implements :class:`runtime.contract.Adapter` for whatever devices a cell declares.

    ``outcomes`` scripts outcomes per command, ``{"gripper.close": ["empty", "holding"]}``:
    the next one belongs to the next call of that command and ends it once it has run
    (``"error"`` raises an adapter fault, ``"timeout"`` spends the budget); a call that
    another stop condition ends first (a preemption, an event, a time event) has used it
    all the same; one that is no outcome of the call is an adapter fault naming the
    outcomes the call can end in; ``None`` lets one call end as it comes. ``sensors``
    overrides sensor values, ``{"robot.wrench": Wrench(...)}`` or a function of the time.
    ``calls`` and ``holds`` record what the runtime asked for.
    """

    OPTIONS = (
        AdapterOption("duration", float, "seconds each command runs before it settles"),
        AdapterOption("step", float, "seconds of one tick"),
        AdapterOption("outcomes", dict, "the outcomes scripted per command"),
        AdapterOption("sensors", dict, "sensor values scripted by device.sensor"),
    )

    def __init__(
        self,
        scene: str | None = None,
        *,
        duration: float = 0.1,
        step: float = 0.01,
        outcomes: Mapping[str, Sequence[str | None]] | None = None,
        sensors: SensorScript | None = None,
    ) -> None:
        self.scene = scene
        self.duration = duration
        self.step = step
        self.PERIOD = step
        self._outcomes = {k: list(v) for k, v in (outcomes or {}).items()}
        self._script = dict(sensors or {})
        self._time = 0.0
        self._types: dict[str, str] = {}
        self._commands: dict[str, list[str]] = {}
        self._state: dict[str, dict[str, Any]] = {}
        self._neutral: dict[str, dict[str, Any]] = {}
        self.calls: list[tuple[str, str, dict[str, Any]]] = []
        self.holds = 0

    # -- what the runtime binds -----------------------------------------------------------

    def emulate(self, devices: Mapping[str, type]) -> None:
        """Offer the devices of a cell, with sensor values typed by the device protocols."""
        for instance, protocol in devices.items():
            self._types[instance] = getattr(protocol, "DEVICE_TYPE", protocol.__name__)
            hints = typing.get_type_hints(protocol)
            sensors, commands = {}, []
            for name, member in vars(protocol).items():
                if isinstance(member, property):
                    returns = typing.get_type_hints(member.fget).get("return", hints.get(name))
                    sensors[name] = _initial(returns)
                elif inspect.isfunction(member) and not name.startswith("_"):
                    commands.append(name)
            self._state[instance] = sensors
            self._neutral[instance] = dict(sensors)
            self._commands[instance] = commands

    def devices(self) -> Mapping[str, str]:
        return dict(self._types)

    def commands(self) -> Mapping[str, Sequence[str]]:
        return {k: tuple(v) for k, v in self._commands.items()}

    @property
    def time(self) -> float:
        return self._time

    def snapshot(self) -> SimpleNamespace:
        devices = {}
        for instance, sensors in self._state.items():
            values = dict(sensors)
            for key, value in self._script.items():
                device, _, sensor = key.partition(".")
                if device == instance:
                    values[sensor] = value(self._time) if callable(value) else value
            devices[instance] = SimpleNamespace(**values)
        return SimpleNamespace(time=self._time, **devices)

    # -- commands -------------------------------------------------------------------------

    # -- the control loop (runtime.control_loop) -------------------------------------------

    def start(self, commands: Sequence[Command]) -> list[Started]:
        """Start the commands; each settles after ``duration`` and then ends with its
        scripted outcome, if it has one."""
        for c in commands:
            if c.command not in self._commands.get(c.device, ()):
                raise AdapterError(f"unknown command {c.device}.{c.command}")
        return [self._started(c) for c in commands]

    def tick(self) -> None:
        self._time = round(self._time + self.step, 9)

    def live(self) -> SimpleNamespace:
        return self.snapshot()

    def _started(self, c: Command) -> Started:
        """One command, its scripted outcome taken: the next scripted outcome is this
        call's however it ends; ``timeout`` keeps its stop conditions from being checked."""
        self.calls.append((c.device, c.command, dict(c.args)))
        scripted = self._outcomes.get(f"{c.device}.{c.command}") or []
        planned = scripted.pop(0) if scripted else None
        if planned == "error":
            raise AdapterError(f"scripted fault of {c.device}.{c.command}")
        if planned not in (None, TIMEOUT) and planned not in {s.name for s in c.stop}:
            ends = ", ".join([s.name for s in c.stop if _plain(s.name)] + [TIMEOUT, "error"])
            raise AdapterError(
                f"the script's next outcome of {c.device}.{c.command}, '{planned}', cannot end"
                f" this call: it ends in {ends}"
            )
        state = self._state[c.device]
        for sensor in PER_COMMAND:
            if sensor in state:
                state[sensor] = self._neutral[c.device][sensor]
        start = self._time
        settled: list[Any] = []  # the command's value, once it has run its duration

        def checked() -> bool:
            if not settled and self._time - start >= self.duration - 1e-9:
                settled.append(self._settle(c.device, c.command, c.args))
            return planned != TIMEOUT

        def value() -> Any:
            return settled[0] if settled else None

        stop = list(c.stop)
        if planned is not None and planned != TIMEOUT:
            stop.insert(0, StopCondition(planned, lambda _: bool(settled)))
        return Started(checked, value, stop)

    def _settle(self, device: str, command: str, args: Mapping[str, Any]) -> Any:
        """The idealised end state of a command; returns the command's value."""
        state = self._state[device]
        for flag in ("goalReached", "done"):
            if flag in state:
                state[flag] = True
        if command == "moveCartesian" and isinstance(args.get("goal"), pin.SE3):
            goal, tcp = args["goal"], state.get("tcp")
            if isinstance(tcp, pin.SE3):
                if "travel" in state:
                    state["travel"] = Vector3.of(goal.translation - tcp.translation)
                if "turned" in state:
                    relative = tcp.rotation.T @ goal.rotation  # about the tool's own z
                    state["turned"] = float(math.atan2(relative[1, 0], relative[0, 0]))
            state["tcp"] = goal
        elif command == "close" and "holding" in state:
            state["holding"] = True
        elif command == "open" and "holding" in state:
            state["holding"] = False
        if command == "localize":
            return pin.SE3.Identity()
        return None

    def hold(self) -> None:
        self.holds += 1

    def close(self) -> None:
        """Nothing to release."""


def _plain(name: str) -> bool:
    """An end condition of the command's own action (not an enclosing state's, not the
    executor's probe for events and time events)."""
    return "#" not in name and not name.startswith("@")


def _initial(annotation: Any) -> Any:
    """A neutral value of a sensor type: false, zero, identity."""
    if annotation is bool:
        return False
    if annotation is pin.SE3:
        return pin.SE3.Identity()
    if annotation is Wrench:
        return Wrench()
    if annotation is Vector3:
        return Vector3()
    if annotation in (int, float):
        return annotation(0)
    if typing.get_origin(annotation) is tuple:
        return tuple(0.0 for _ in typing.get_args(annotation) if _ is not Ellipsis)
    return None
