"""Samples of the arm's wrench and TCP, written into the trace while a command runs.

The adapter is wrapped rather than changed: one extra stop condition that never holds is
consulted at every control tick and records a ``sample`` every ``PERIOD`` seconds of
simulated time, so any adapter that honours stop conditions gets sampled.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import replace
from typing import Any

from lightrocks.runtime import Trace
from lightrocks.runtime.contract import Command, StopCondition
from lightrocks.runtime.trace import to_json

PERIOD = 0.01
"""Seconds of simulated time between two samples (100 Hz)."""

SAMPLED = ("tcp", "wrench")
"""The sensors a sample holds, read off every device that has them."""


class SampledAdapter:
    """An adapter that records ``sample`` records into ``trace`` while it executes and
    calls ``tick(time)`` at every control tick (where a paused run waits)."""

    def __init__(
        self, adapter: Any, trace: Trace, tick: Callable[[float], None] | None = None
    ) -> None:
        self._adapter = adapter
        self._trace = trace
        self._tick = tick
        self._next = 0.0

    def __getattr__(self, name: str) -> Any:
        return getattr(self._adapter, name)

    def execute(
        self,
        device: str,
        command: str,
        args: Mapping[str, Any],
        stop: Sequence[StopCondition],
        budget: float,
    ) -> Any:
        return self.execute_all([Command(device, command, args, stop, budget)])[0]

    def execute_all(self, commands: Sequence[Command]) -> list[Any]:
        """Commands of several regions run in one control loop: the first carries the
        sampler, so it is still consulted at every tick."""
        first, *others = commands
        sampled = replace(first, stop=[*first.stop, StopCondition("", self._sample)])
        if not others:
            c = sampled  # an adapter without execute_all still runs one command
            return [self._adapter.execute(c.device, c.command, c.args, c.stop, c.budget)]
        return list(self._adapter.execute_all([sampled, *others]))

    def _sample(self, snapshot: Any) -> bool:
        time = self._adapter.time
        if self._tick is not None:
            self._tick(time)
        if time + 1e-9 >= self._next:
            self._next = time + PERIOD
            fields = {
                f"{name}.{sensor}": to_json(getattr(state, sensor))
                for name in self._adapter.devices()
                for sensor in SAMPLED
                if hasattr(state := getattr(snapshot, name, None), sensor)
            }
            if fields:
                self._trace.write(time, "sample", **fields)
        return False
