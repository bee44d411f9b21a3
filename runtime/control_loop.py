"""The one ``execute`` loop of the adapter contract.

Every adapter — the MuJoCo and Pinocchio cells, the dry run, a real arm — runs device commands
the same way: start them, tick, check each command's stop conditions in declaration order once
it has settled, end it with ``TIMEOUT`` when its budget is spent, tell the run's listener of
every tick on which a command went on, and hold whatever way the loop ends. The loop lives
here, once; an adapter supplies only what differs: how a command starts, what one control
tick does, and the snapshot of that tick (:class:`TickingAdapter`).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

from lightrocks.runtime.contract import (
    TIMEOUT,
    AdapterError,
    Command,
    CommandResult,
    Snapshot,
    StopCondition,
    TickListener,
)


@dataclass(frozen=True)
class Started:
    """A command an adapter has started.

    ``settled()`` tells whether its stop conditions are checked from this tick on (a motion
    at once, a gripper once its fingers rest); ``value()`` is its return value μ when it ends;
    ``stop`` are the conditions checked, normally the command's own.
    """

    settled: Callable[[], bool]
    value: Callable[[], Any]
    stop: Sequence[StopCondition]


def always() -> bool:
    """``Started.settled`` of a command whose stop conditions hold from its first tick."""
    return True


def nothing() -> None:
    """``Started.value`` of a command that returns nothing."""
    return None


class TickingAdapter:
    """The ``execute`` of ``runtime.contract.Adapter``, for an adapter that can start
    commands, advance one control tick and show the snapshot of that tick.

    ``PERIOD`` is the control period in seconds: a command times out on the first tick at
    which its budget is spent to within half a period.
    """

    PERIOD: float
    time: float
    """Adapter clock in seconds since the start of the run (an attribute or a property)."""

    def start(self, commands: Sequence[Command]) -> list[Started]:
        """Check every command's arguments, then start them in order."""
        raise NotImplementedError

    def tick(self) -> None:
        """Advance one control period; an ``AdapterError`` says why the device cannot."""
        raise NotImplementedError

    def live(self) -> Snapshot:
        """The sensor values of this tick, as stop predicates and tick listeners read them."""
        raise NotImplementedError

    def ended(self, command: Command) -> None:
        """``command`` has ended while others go on: its device holds still."""

    def stopped(self) -> None:
        """The loop is over, normally or by a fault: every device holds still."""

    def execute(
        self, commands: Sequence[Command], on_tick: TickListener | None = None
    ) -> list[CommandResult]:
        """Start the commands in order and tick them in one loop, each until its own stop
        condition or budget."""
        devices = [c.device for c in commands]
        if len(set(devices)) < len(devices):
            raise AdapterError(f"two commands at once for one device: {', '.join(devices)}")
        for c in commands:
            budget = c.budget
            if not (isinstance(budget, int | float) and budget >= 0 and math.isfinite(budget)):
                message = f"budget must be a finite number of seconds >= 0, got {budget!r}"
                raise AdapterError(message)
        started = self.start(commands)
        now = self.time
        slack = self.PERIOD / 2
        results: list[CommandResult | None] = [None] * len(commands)
        pending = [
            (index, c, run.settled, run.value, _first_holding(run.stop), now + c.budget - slack)
            for index, (c, run) in enumerate(zip(commands, started, strict=True))
        ]
        remaining = len(pending)
        running = commands[0]
        tick, live = self.tick, self.live
        try:
            while remaining:
                tick()
                now = self.time
                tell = None  # on_tick, once a command's stop conditions held none
                for entry in pending:
                    index, c, settled, value, first_holding, end = entry
                    running = c
                    result = None
                    if settled():
                        fired = first_holding(live())
                        if fired is not None:
                            result = CommandResult(fired, value())
                        else:
                            tell = on_tick
                    if result is None:
                        if now < end:
                            continue
                        result = CommandResult(TIMEOUT)
                    results[index] = result
                    remaining -= 1
                    if remaining:
                        self.ended(c)
                if len(pending) > remaining:
                    pending = [entry for entry in pending if results[entry[0]] is None]
                if tell is not None:
                    try:
                        tell(live())
                    except Exception as exc:
                        raise AdapterError(f"tick listener failed: {exc!r}") from exc
        except AdapterError:
            raise
        except Exception as exc:
            where = f"{running.device}.{running.command}"
            raise AdapterError(f"stop condition of {where} failed: {exc!r}") from exc
        finally:
            self.stopped()
        return results  # type: ignore[return-value]


def _first_holding(stops: Sequence[StopCondition]) -> Callable[[Snapshot], str | None]:
    """The stop conditions as one function, evaluated every tick: the name of the first that
    holds, in declaration order, or None."""
    checks = tuple((stop.holds, stop.name) for stop in stops)

    def first_holding(snapshot: Snapshot) -> str | None:
        for holds, name in checks:
            if holds(snapshot):
                return name
        return None

    return first_holding
