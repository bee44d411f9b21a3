"""A watched run: the page's feed and the execution control, hooked into the trace's
listeners (one call per record) and the adapter's control ticks."""

from __future__ import annotations

from collections.abc import Iterable
from pathlib import Path
from typing import Any

from lightrocks.workbench.app.monitor.control import RunControl
from lightrocks.workbench.app.monitor.feed import Feed
from lightrocks.workbench.app.monitor.server import Monitor

DEPTH = "3"
"""Task, skill and action: the levels the page highlights."""


class Watch:
    def __init__(self, monitor: Monitor) -> None:
        self.monitor = monitor

    def on_record(self, record: dict[str, Any]) -> None:
        self.monitor.feed.publish(record)
        self.monitor.control.on_record(record)

    def on_tick(self) -> None:
        self.monitor.control.on_tick()

    def finish(self, measurements: dict[str, Any]) -> None:
        """Show the measurements and let open pages catch up before the process ends."""
        self.monitor.summary["measurements"] = measurements
        self.monitor.drain()


def task_svg(model: Path, search_path: list[Path], name: str) -> str:
    """The Graphviz SVG of the model's statechart, nested down to its actions."""
    from lightrocks.workbench.check import check
    from lightrocks.workbench.generators import GenerationRequest, load_generator

    context = check([model], search_path)
    request = GenerationRequest(context, [model], {"render": "svg", "depth": DEPTH}, None)
    drawn = load_generator("dot").generate(request)
    svg = next(v for k, v in drawn.items() if k.endswith(f"{name}.svg"))
    text = svg.decode("utf-8") if isinstance(svg, bytes) else svg
    return text[text.index("<svg") :]


def monitor_for(
    model: Path,
    search_path: list[Path],
    name: str,
    breakpoints: Iterable[str] = (),
    paused: bool = False,
) -> tuple[Monitor, Watch]:
    control = RunControl(breakpoints, paused)
    feed = Feed()
    monitor = Monitor(feed, control, task_svg(model, search_path, name), name)
    return monitor, Watch(monitor)
