"""The one execute loop (runtime.control_loop) on a minimal adapter of its own: what every
adapter gets by supplying start, tick and live."""

from __future__ import annotations

from collections.abc import Sequence
from types import SimpleNamespace

import pytest

from lightrocks.adapters.dryrun import DryRunAdapter
from lightrocks.runtime.contract import AdapterError, Command, StopCondition
from lightrocks.runtime.control_loop import Started, TickingAdapter


class Counter(TickingAdapter):
    """A device whose one sensor counts ticks; a command settles after ``settle`` ticks."""

    PERIOD = 0.001

    def __init__(self, settle: int = 0, fail_at: int | None = None) -> None:
        self.time = 0.0
        self.ticks = 0
        self.settle = settle
        self.fail_at = fail_at
        self.log: list[str] = []

    def start(self, commands: Sequence[Command]) -> list[Started]:
        self.log.append("start " + ",".join(c.device for c in commands))
        begun = self.ticks
        return [
            Started(lambda: self.ticks - begun >= self.settle, lambda: self.ticks, c.stop)
            for c in commands
        ]

    def tick(self) -> None:
        self.ticks += 1
        self.time += self.PERIOD
        if self.ticks == self.fail_at:
            raise AdapterError("connection lost")

    def live(self) -> SimpleNamespace:
        return SimpleNamespace(time=self.time, dev=SimpleNamespace(n=self.ticks))

    def ended(self, command: Command) -> None:
        self.log.append(f"ended {command.device}")

    def stopped(self) -> None:
        self.log.append("stopped")


def command(device: str = "dev", budget: float = 1.0, **stops: int) -> Command:
    conditions = [StopCondition(name, lambda s, at=at: s.dev.n >= at) for name, at in stops.items()]
    return Command(device, "go", {}, conditions, budget)


def test_the_first_condition_that_holds_ends_the_command_with_its_value() -> None:
    adapter = Counter()
    [result] = adapter.execute([command(late=5, early=3)])
    assert (result.outcome, result.value) == ("early", 3)
    assert adapter.log == ["start dev", "stopped"]


def test_a_budget_ends_the_command_on_the_tick_it_is_spent() -> None:
    adapter = Counter()
    [result] = adapter.execute([command(budget=0.0042, never=10**9)])
    assert result.outcome == "timeout"
    assert adapter.ticks == 4  # 4.2 ms: the nearest tick


def test_conditions_wait_until_the_command_has_settled_and_the_listener_hears_each_tick() -> None:
    heard: list[int] = []
    adapter = Counter(settle=4)
    [result] = adapter.execute([command(at_once=0)], on_tick=lambda s: heard.append(s.dev.n))
    assert (result.outcome, result.value) == ("at_once", 4)
    assert heard == []  # no tick on which a settled command went on


def test_a_command_that_ends_first_holds_while_the_others_go_on() -> None:
    adapter = Counter()
    results = adapter.execute([command("a", done=2), command("b", done=5)])
    assert [r.outcome for r in results] == ["done", "done"]
    assert adapter.log == ["start a,b", "ended a", "stopped"]


@pytest.mark.parametrize(
    ("commands", "message"),
    [
        ([command("a"), command("a")], "two commands at once for one device: a, a"),
        ([command(budget=float("nan"))], "budget must be a finite number of seconds >= 0"),
        ([command(budget=-1.0)], "budget must be a finite number of seconds >= 0"),
    ],
)
def test_requests_the_loop_refuses_before_anything_starts(commands, message) -> None:
    adapter = Counter()
    with pytest.raises(AdapterError, match=message):
        adapter.execute(commands)
    assert adapter.log == []


def test_a_fault_of_the_device_ends_the_loop_holding() -> None:
    adapter = Counter(fail_at=3)
    with pytest.raises(AdapterError, match="connection lost"):
        adapter.execute([command(never=10**9)])
    assert adapter.log[-1] == "stopped"


def test_a_condition_that_raises_is_a_fault_naming_its_command() -> None:
    broken = Command("dev", "go", {}, [StopCondition("x", lambda s: s.missing)], 1.0)
    adapter = Counter()
    with pytest.raises(AdapterError, match=r"stop condition of dev\.go failed"):
        adapter.execute([broken])
    assert adapter.log[-1] == "stopped"


def test_a_listener_that_raises_is_a_fault() -> None:
    def listener(_snapshot) -> None:
        raise ValueError("bad listener")

    with pytest.raises(AdapterError, match="tick listener failed"):
        Counter().execute([command(never=10**9)], on_tick=listener)


def test_the_dry_run_refuses_a_bad_budget_as_the_cells_do() -> None:
    adapter = DryRunAdapter()
    adapter.emulate({"gripper": type("Gripper", (), {"close": lambda self: None})})
    with pytest.raises(AdapterError, match="budget must be a finite number"):
        adapter.execute([Command("gripper", "close", {}, [], float("inf"))])
