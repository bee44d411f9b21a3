"""A watched run: the page's feed and the execution control, a listener of the trace's records
and of the control ticks of its commands."""

from __future__ import annotations

from collections.abc import Iterable
from pathlib import Path
from typing import Any

from lightrocks.app.monitor.control import RunControl
from lightrocks.app.monitor.feed import Feed
from lightrocks.app.monitor.server import Monitor
from lightrocks.runtime import Abort, Snapshot, Trace


class Watch:
    """Publishes every record to the page and holds the run's thread while it is paused;
    the pauses, resumptions and an abort are written into the trace."""

    OWN = ("paused", "resumed")
    """The kinds of record the watch writes itself."""

    def __init__(self, monitor: Monitor) -> None:
        self.monitor = monitor
        self.control = monitor.control
        self.trace: Trace | None = None
        self.state = ""
        """The innermost state entered last."""

    def attach(self, trace: Trace) -> None:
        self.trace = trace
        trace.listeners.append(self.on_record)
        trace.tick_listeners.append(self.on_tick)

    def on_record(self, record: dict[str, Any]) -> None:
        self.monitor.feed.publish(record)
        if record["kind"] in self.OWN:
            return
        if record["kind"] == "enter":
            self.state = record["state"]
        self.control.stops_at(record)
        self._hold(record["time"])

    def on_tick(self, snapshot: Snapshot) -> None:
        self._hold(snapshot.time)

    def _hold(self, time: float) -> None:
        if self.control.paused and self.trace is not None:
            self.trace.write(time, "paused", at=self.control.where or self.state)
            self.control.wait()
            if not self.control.aborting:
                self.trace.write(time, "resumed")
        if self.control.aborting:
            self.control.aborting = False
            raise Abort("aborted from the monitor")

    def finish(self, measurements: dict[str, Any]) -> None:
        """Show the measurements and let open pages catch up before the process ends."""
        self.monitor.summary["measurements"] = measurements
        self.monitor.drain()


def task_svg(model: Path, search_path: list[Path], name: str) -> str:
    """The diagram of the model's statechart, one picture per level (see ``app.diagram``)."""
    from lightrocks.app.diagram import drawn

    return drawn(model, search_path, name).bundle()


def monitor_for(
    model: Path,
    search_path: list[Path],
    name: str,
    breakpoints: Iterable[str] = (),
    paused: bool = False,
    aborts: Iterable[str] = (),
) -> tuple[Monitor, Watch]:
    control = RunControl(breakpoints, paused, aborts)
    feed = Feed()
    monitor = Monitor(feed, control, task_svg(model, search_path, name), name)
    return monitor, Watch(monitor)


def replay_for(
    model: Path, search_path: list[Path], name: str, records: list[dict[str, Any]]
) -> Monitor:
    """A monitor that replays recorded records instead of watching a run."""
    svg = task_svg(model, search_path, name)
    return Monitor(Feed(), RunControl(), svg, f"{name} (replay)", replay=records)
