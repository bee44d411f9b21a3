"""Samples of the devices' wrench and TCP, written into the trace while commands run.

A tick listener of the trace: every adapter reports the control ticks of its commands, so
every adapter gets sampled, and a plot or a monitor can draw any run's forces and motion.
"""

from __future__ import annotations

from lightrocks.runtime.contract import Adapter, Snapshot
from lightrocks.runtime.trace import Trace, to_json

PERIOD = 0.01
"""Seconds of adapter time between two samples (100 Hz)."""

SAMPLED = ("tcp", "wrench")
"""The sensors a sample holds, read off every device that has them."""


class Sampler:
    """Writes a ``sample`` record into ``trace`` at the first tick of every ``PERIOD``, of
    the devices the adapter has by then (a dry run learns them when the run binds it)."""

    def __init__(self, trace: Trace, adapter: Adapter) -> None:
        self._trace = trace
        self._adapter = adapter
        self._next = 0.0

    def attach(self) -> None:
        """Start sampling the ticks the trace is told of."""
        self._trace.tick_listeners.append(self.on_tick)

    def on_tick(self, snapshot: Snapshot) -> None:
        time = snapshot.time
        if time + 1e-9 < self._next:
            return
        self._next = time + PERIOD
        fields = {
            f"{name}.{sensor}": to_json(getattr(state, sensor))
            for name in self._adapter.devices()
            for sensor in SAMPLED
            if hasattr(state := getattr(snapshot, name, None), sensor)
        }
        if fields:
            self._trace.write(time, "sample", **fields)
