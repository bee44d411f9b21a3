"""The contract between generated code and robot adapters.

Generated code never talks to a simulator or a robot directly: an action state hands its
device command and stop conditions to an :class:`Adapter` (the actions of orthogonal regions
hand theirs together), which runs its control loop, evaluates the stop conditions on every
control tick, reports which one fired, and tells the run of its ticks, so that the run's
listeners can sample sensors or pause without wrapping the adapter. All values crossing this
boundary are in SI units; frames are ``pinocchio.SE3`` in the world frame.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any, Protocol, runtime_checkable

import numpy as np


@dataclass(frozen=True)
class Vector3:
    """A 3-vector whose components the model language reads as ``.x``, ``.y``, ``.z``."""

    x: float = 0.0
    y: float = 0.0
    z: float = 0.0

    @classmethod
    def of(cls, values: Sequence[float] | np.ndarray) -> Vector3:
        return cls(float(values[0]), float(values[1]), float(values[2]))

    @classmethod
    def of_floats(cls, x: float, y: float, z: float) -> Vector3:
        """``Vector3(x, y, z)`` for floats, in half the time: the frozen dataclass's
        ``__init__`` sets each field with ``object.__setattr__``, and adapters build these
        on every control tick."""
        vector = object.__new__(cls)
        fields = vector.__dict__
        fields["x"], fields["y"], fields["z"] = x, y, z
        return vector

    def array(self) -> np.ndarray:
        return np.array([self.x, self.y, self.z])

    def norm(self) -> float:
        return math.hypot(self.x, self.y, self.z)  # no array: stop predicates run every tick


@dataclass(frozen=True)
class Wrench:
    """Force [N] and torque [Nm] measured at the TCP, axes of the world frame."""

    force: Vector3 = field(default_factory=Vector3)
    torque: Vector3 = field(default_factory=Vector3)

    @classmethod
    def of(cls, values: Sequence[float] | np.ndarray) -> Wrench:
        return cls(Vector3.of(values[:3]), Vector3.of(values[3:6]))

    @classmethod
    def of_floats(cls, fx: float, fy: float, fz: float, tx: float, ty: float, tz: float) -> Wrench:
        """``Wrench`` of six floats without the frozen dataclasses' ``__init__`` (see
        ``Vector3.of_floats``), its vectors built inline: calling ``Vector3.of_floats`` twice
        costs ~0.15 µs more on every control tick."""
        new = object.__new__
        wrench, force, torque = new(cls), new(Vector3), new(Vector3)
        fields = force.__dict__
        fields["x"], fields["y"], fields["z"] = fx, fy, fz
        fields = torque.__dict__
        fields["x"], fields["y"], fields["z"] = tx, ty, tz
        fields = wrench.__dict__
        fields["force"], fields["torque"] = force, torque
        return wrench


class DeviceState(Protocol):
    """The sensor values of one device at one control tick, as attributes by sensor name."""

    def __getattr__(self, sensor: str) -> Any: ...


class Snapshot(Protocol):
    """All sensor values at one control tick: ``snapshot.robot.wrench.torque.z``."""

    time: float

    def __getattr__(self, device: str) -> DeviceState: ...


StopPredicate = Callable[[Snapshot], bool]


@dataclass(frozen=True)
class StopCondition:
    """A named stop condition λ; its name becomes the outcome when it holds first."""

    name: str
    holds: StopPredicate


@dataclass(frozen=True)
class CommandResult:
    """How a device command ended: the outcome name and the command's return value μ."""

    outcome: str
    value: Any = None


@dataclass(frozen=True)
class Command:
    """One device command with its stop conditions and budget, as ``Adapter.execute`` runs it."""

    device: str
    command: str
    args: Mapping[str, Any]
    stop: Sequence[StopCondition]
    budget: float


@dataclass(frozen=True)
class AdapterOption:
    """An option an adapter's constructor takes beside ``scene``, declared by the adapter
    (``OPTIONS``) so that the front doors offer, check and list it without guessing."""

    name: str
    """The constructor's keyword."""
    kind: type | tuple[type, ...]
    """What its value is, checked before the adapter is built."""
    doc: str


TIMEOUT = "timeout"


class AdapterError(RuntimeError):
    """A fault of the device or the adapter; the runtime turns it into the outcome ``error``."""


TickListener = Callable[[Snapshot], None]
"""Told of a control tick with the live snapshot of that tick (valid during the call only)."""


@runtime_checkable
class Adapter(Protocol):
    """A robot API: the devices of one cell, a clock, and a control loop."""

    @property
    def time(self) -> float:
        """Adapter clock in seconds since the start of the run."""
        ...

    def devices(self) -> Mapping[str, str]:
        """Device instance name (as in the cell) to device type name."""
        ...

    def snapshot(self) -> Snapshot:
        """Current sensor values of every device."""
        ...

    def execute(
        self, commands: Sequence[Command], on_tick: TickListener | None = None
    ) -> Sequence[CommandResult]:
        """Run the commands together until each has ended; their results in their order.

        The commands start in the given order and are ticked in one control loop. Each ends
        with the first of its stop conditions that holds (checked in declaration order on
        every control tick; for a command without motion, such as a gripper's or a camera's,
        once it has settled), or with ``TIMEOUT`` when its ``budget`` of adapter time is
        spent; its device then holds still and compliant, whatever way it ended. Two
        commands for one device are refused with ``AdapterError`` unless the device type is
        ``<<concurrent>>`` for this adapter; an adapter that runs one command at a time
        refuses several the same way.

        ``on_tick(snapshot)`` is called once per control tick at which the stop conditions
        of a command were checked and none of them held. It may block (the adapter's time
        stands still meanwhile) or raise: the commands then stop, the devices hold, and the
        exception propagates.
        """
        ...

    def hold(self) -> None:
        """Stop every command; keep the robot still and compliant where it is."""
        ...

    def close(self) -> None:
        """Release simulator or hardware resources."""
        ...
