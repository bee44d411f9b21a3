"""The sampler rides along every command the executor sends, one at a time or a round of
commands of several regions at once."""

from __future__ import annotations

from lightrocks.adapters.dryrun import DryRunAdapter
from lightrocks.app.monitor.sampling import PERIOD, SampledAdapter
from lightrocks.runtime import Trace
from lightrocks.runtime.contract import Command, StopCondition


class Robot:
    DEVICE_TYPE = "Robot"

    def move(self) -> None: ...

    @property
    def wrench(self) -> float: ...


class Camera:
    DEVICE_TYPE = "Camera"

    def localize(self) -> None: ...


def sampled(ticks: list[float]) -> tuple[SampledAdapter, list[dict]]:
    inner = DryRunAdapter(duration=0.5, step=0.001)
    inner.emulate({"robot": Robot, "camera": Camera})
    trace = Trace(None)
    records: list[dict] = []
    trace.listeners.append(records.append)
    return SampledAdapter(inner, trace, tick=ticks.append), records


def settled(s) -> bool:
    return s.time >= 0.5 - 1e-9


def test_one_command_is_sampled_at_every_tick():
    ticks: list[float] = []
    adapter, records = sampled(ticks)
    result = adapter.execute("robot", "move", {}, [StopCondition("done", settled)], 5.0)
    assert result.outcome == "done"
    assert len(ticks) >= 0.5 / 0.001 - 1
    samples = [r for r in records if r["kind"] == "sample"]
    assert len(samples) >= 0.5 / PERIOD - 1 and "robot.wrench" in samples[0]


def test_a_round_of_commands_is_sampled_too():
    ticks: list[float] = []
    adapter, records = sampled(ticks)
    commands = [
        Command("robot", "move", {}, [StopCondition("done", settled)], 5.0),
        Command("camera", "localize", {}, [StopCondition("done", settled)], 5.0),
    ]
    results = adapter.execute_all(commands)
    assert [r.outcome for r in results] == ["done", "done"]
    assert len(ticks) >= 0.5 / 0.001 - 1
    assert len([r for r in records if r["kind"] == "sample"]) >= 0.5 / PERIOD - 1
