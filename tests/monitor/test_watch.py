"""The monitor's pausing is a listener of the run: a pause at a control tick holds the run
at that simulated time, Resume goes on from there, and Abort at a tick stops the run safely;
but for its ``paused`` and ``resumed`` records the trace is the one of an unwatched run."""

from __future__ import annotations

import json
import threading
from pathlib import Path

from lightrocks.adapters.dryrun import DryRunAdapter
from lightrocks.app.loading import load_component
from lightrocks.app.monitor.control import RunControl
from lightrocks.app.monitor.feed import Feed
from lightrocks.app.monitor.server import Monitor
from lightrocks.app.monitor.watch import Watch
from lightrocks.runtime import Sampler, Trace, bind

ROOT = Path(__file__).resolve().parents[2]
SCREW_TASK = ROOT / "examples" / "screwing" / "tasks" / "ScrewTask.lr"
SCRIPT = ROOT / "examples" / "screwing" / "screwed.dryrun.json"
AT = 1.0
"""Seconds of simulated time after which the page asks for a pause or an abort."""


def run(watch: Watch | None = None, ask=None) -> list[dict]:
    """The screwing task on the scripted dry run; ``ask(control)`` once, at the first tick
    after AT, as a click on the page would."""
    cls = load_component(SCREW_TASK, [])
    adapter = DryRunAdapter(**json.loads(SCRIPT.read_text()))
    bind(adapter, cls.CELL)
    trace = Trace()
    asked = []

    def page(snapshot) -> None:
        if snapshot.time >= AT and not asked:
            asked.append(snapshot.time)
            ask(watch.control)

    if watch is not None:
        trace.tick_listeners.append(page)
        watch.attach(trace)
    Sampler(trace, adapter).attach()
    return cls().start(adapter, trace=trace).trace


def watch() -> Watch:
    return Watch(Monitor(Feed(), RunControl(), "<svg/>", "ScrewTask"))


def test_a_pause_at_a_tick_holds_the_run_there_and_changes_nothing_else() -> None:
    def pause(control: RunControl) -> None:
        control.pause()
        threading.Timer(0.05, control.resume).start()

    watched = run(watch(), pause)
    paused = next(i for i, r in enumerate(watched) if r["kind"] == "paused")
    record, after = watched[paused], watched[paused + 1]
    assert AT <= record["time"] < AT + 0.02
    assert record["at"] == next(
        r["state"] for r in reversed(watched[:paused]) if r["kind"] == "enter"
    )
    assert after == {"time": record["time"], "kind": "resumed"}
    assert [r for r in watched if r["kind"] not in ("paused", "resumed")] == run()


def test_abort_at_a_tick_stops_the_run_safely() -> None:
    watched = run(watch(), RunControl.abort)
    assert [r["kind"] for r in watched[-2:]] == ["aborted", "finished"]
    assert watched[-1]["outcome"] == "preempted"
    assert AT <= watched[-1]["time"] < AT + 0.02
