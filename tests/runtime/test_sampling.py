"""Listeners of a run: the adapter tells of its control ticks, the trace passes them on, and
the sampler writes ``sample`` records from them, one command at a time or a round of
commands of several regions at once."""

from __future__ import annotations

import pytest

from lightrocks.adapters.dryrun import DryRunAdapter
from lightrocks.runtime import Abort, Sampler, Trace
from lightrocks.runtime.contract import AdapterError, Command, StopCondition
from lightrocks.runtime.sampling import PERIOD


class Robot:
    DEVICE_TYPE = "Robot"

    def move(self) -> None: ...

    @property
    def wrench(self) -> float: ...


class Camera:
    DEVICE_TYPE = "Camera"

    def localize(self) -> None: ...


def dry_run() -> DryRunAdapter:
    adapter = DryRunAdapter(duration=0.5, step=0.001)
    adapter.emulate({"robot": Robot, "camera": Camera})
    return adapter


def settled(s) -> bool:
    return s.time >= 0.5 - 1e-9


def sampled() -> tuple[Trace, list[dict]]:
    trace = Trace(None)
    records: list[dict] = []
    trace.listeners.append(records.append)
    return trace, records


def test_one_command_is_sampled_at_every_period():
    adapter = dry_run()
    trace, records = sampled()
    Sampler(trace, adapter).attach()
    (result,) = adapter.execute(
        [Command("robot", "move", {}, [StopCondition("done", settled)], 5.0)], trace.tick
    )
    assert result.outcome == "done"
    samples = [r for r in records if r["kind"] == "sample"]
    assert len(samples) == round(0.5 / PERIOD)
    assert samples[0] == {"time": 0.001, "kind": "sample", "robot.wrench": 0.0}
    assert [s["time"] for s in samples[:3]] == [0.001, 0.011, 0.021]


def test_a_round_of_commands_is_sampled_once_per_tick():
    adapter = dry_run()
    ticks: list[float] = []
    trace, records = sampled()
    trace.tick_listeners.append(lambda s: ticks.append(s.time))
    Sampler(trace, adapter).attach()
    commands = [
        Command("robot", "move", {}, [StopCondition("done", settled)], 5.0),
        Command("camera", "localize", {}, [StopCondition("done", settled)], 5.0),
    ]
    results = adapter.execute(commands, trace.tick)
    assert [r.outcome for r in results] == ["done", "done"]
    assert len(ticks) == len(set(ticks)) == 499  # the last tick ends both commands
    assert len([r for r in records if r["kind"] == "sample"]) == round(0.5 / PERIOD)


def test_no_tick_is_told_where_a_stop_condition_holds():
    adapter = dry_run()
    ticks: list[float] = []
    at_once = [StopCondition("now", lambda s: True)]
    adapter.execute([Command("robot", "move", {}, at_once, 5.0)], lambda s: ticks.append(s.time))
    assert ticks == []


def test_a_failing_tick_listener_is_an_adapter_fault():
    def broken(snapshot) -> None:
        raise ValueError("listener")

    with pytest.raises(AdapterError, match="tick listener failed"):
        dry_run().execute([Command("robot", "move", {}, [], 5.0)], broken)


def test_abort_from_a_tick_listener_passes_through_the_adapter():
    def abort(snapshot) -> None:
        if snapshot.time >= 0.1:
            raise Abort

    adapter = dry_run()
    with pytest.raises(Abort):
        adapter.execute([Command("robot", "move", {}, [], 5.0)], abort)
    assert adapter.time == pytest.approx(0.1)


def test_the_sampler_reads_the_devices_a_dry_run_learns_when_it_is_bound():
    adapter = DryRunAdapter(duration=0.5, step=0.001)
    trace, records = sampled()
    Sampler(trace, adapter).attach()
    adapter.emulate({"robot": Robot, "camera": Camera})
    adapter.execute(
        [Command("robot", "move", {}, [StopCondition("done", settled)], 5.0)], trace.tick
    )
    assert "robot.wrench" in next(r for r in records if r["kind"] == "sample")


def test_the_adapter_is_told_of_ticks_only_when_someone_listens():
    trace = Trace(None)
    assert trace.on_tick is None
    first = []
    trace.tick_listeners.append(first.append)
    assert trace.on_tick == first.append  # the one listener itself: a call less per tick
    second = []
    trace.tick_listeners.append(second.append)
    trace.on_tick("tick")
    assert first == second == ["tick"]
