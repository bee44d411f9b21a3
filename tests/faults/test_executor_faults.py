"""Every fault ends a run with one ``error`` outcome, never a loop; Ctrl-C holds the arm.

Each test runs under a deadline (see ``conftest``): before, several of these runs never
returned while their trace grew without bound.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from lightrocks.adapters.dryrun import DryRunAdapter
from lightrocks.app.cli import main
from lightrocks.runtime.contract import AdapterError

from .fault_runs import cli, trace_records, within, write_models

EXIT_DIVIDES = """package t;

statechart ExitDivides {
  parameters {
    Integer n = 0;
  }

  initial state A {
    exit / { n = 1 % n; }
  }
  final state B;

  A -> B go;
}
"""

MOVE = """package t;

import t.Cell;

<<action>> statechart Move {
  parameters {
    Real q = 0;
  }

  do / arm.move(x = 1 mm);

  end condition reached [arm.goalReached];
}
"""

SKILL = """package t;

import t.Cell;

<<skill>> statechart Skill {
  parameters {
    Integer n = 0;
  }

  start condition go;
  end condition done;

  <<import="Move">> state M;

  go -> M;
  M -> done reached;
}
"""


def errors(chart) -> list[dict]:
    return [r for r in chart.trace if r["kind"] == "error"]


def assert_ends_in_one_error(chart) -> None:
    assert chart.finished and chart.outcome == "error"
    assert len(errors(chart)) == 1, errors(chart)
    assert chart.trace[-1] == {**chart.trace[-1], "kind": "finished", "outcome": "error"}


def test_exit_action_fault_on_the_command_line_ends_the_run(tmp_path: Path):
    write_models(tmp_path, {"ExitDivides": EXIT_DIVIDES})
    trace = tmp_path / "trace.jsonl"
    model = str(tmp_path / "t" / "ExitDivides.lr")
    done = cli("run", model, "--events", "go", "--trace", str(trace), cwd=tmp_path)
    assert done.returncode == 1, done.stderr
    assert "ZeroDivisionError" in done.stdout
    records = trace_records(trace)
    assert [r["kind"] for r in records].count("error") == 1
    assert records[-1]["kind"] == "finished" and records[-1]["outcome"] == "error"


def test_exit_action_fault_is_the_parents_error_and_runs_once(build):
    chart = within(lambda: build({"ExitDivides": EXIT_DIVIDES}, "ExitDivides")().start())
    within(lambda: chart.send("go"))
    assert_ends_in_one_error(chart)
    assert chart.fault.origin == ["ExitDivides"]
    assert "ZeroDivisionError" in chart.fault.message
    assert [r["state"] for r in chart.trace if r["kind"] == "exit"] == [
        "ExitDivides/A",
        "ExitDivides",
    ]


def test_elemental_exit_dividing_by_a_zero_sensor_ends_the_run(build):
    move = MOVE.replace("end condition", "exit / { q = 1 / (arm.z / 1 m); }\n\n  end condition")
    cls = build({"Move": move, "Skill": SKILL}, "Skill")
    chart = within(lambda: cls().start(DryRunAdapter()))
    assert_ends_in_one_error(chart)
    assert chart.fault.origin == ["Skill"]


@pytest.mark.parametrize(
    ("where", "text"),
    [
        ("guard", SKILL.replace("M -> done reached;", "M -> done [1 / n > 0] reached;")),
        (
            "entry",
            SKILL.replace(
                '<<import="Move">> state M;',
                '<<import="Move">> state M {\n    entry / { n = 1 % n; }\n  }',
            ),
        ),
        ("transition action", SKILL.replace("go -> M;", "go -> M / { n = 1 % n; };")),
        ("binding", SKILL.replace("state M;", "state M(q = 1 / n);")),
        (
            "end-condition watchdog",
            SKILL.replace(
                "end condition done;", "end condition done;\n  end condition odd [1 / n > 0];"
            ),
        ),
    ],
)
def test_model_code_fault_is_one_error_with_its_location(build, where, text):
    cls = build({"Move": MOVE, "Skill": text}, "Skill")
    adapter = DryRunAdapter()
    chart = within(lambda: cls().start(adapter))
    assert_ends_in_one_error(chart)
    assert "ZeroDivisionError in model code" in chart.fault.message, where
    assert chart.fault.location, where


def test_end_condition_predicate_fault_stops_and_holds_the_command(build):
    move = MOVE.replace("[arm.goalReached]", "[1 / q > 0]")
    cls = build({"Move": move, "Skill": SKILL}, "Skill")
    adapter = DryRunAdapter(duration=5.0)
    chart = within(lambda: cls().start(adapter))
    assert_ends_in_one_error(chart)
    assert "ZeroDivisionError in model code" in chart.fault.message
    assert chart.fault.origin == ["Skill/M", "Skill"]
    assert adapter.holds == 1
    assert chart.trace[-1]["time"] < 1.0  # stopped at the first tick, not after the budget


class Failing(DryRunAdapter):
    """A dry run whose ``what`` raises ``fault`` (from the ``after``-th call on)."""

    def __init__(self, what: str, fault: BaseException, after: int = 0) -> None:
        super().__init__()
        self.what, self.fault, self.after, self.count = what, fault, after, 0

    def _maybe(self) -> None:
        self.count += 1
        if self.count > self.after:
            raise self.fault

    def snapshot(self):
        if self.what == "snapshot":
            self._maybe()
        return super().snapshot()

    def execute(self, *args, **kwargs):
        if self.what == "execute":
            self._maybe()
        return super().execute(*args, **kwargs)

    def hold(self) -> None:
        super().hold()
        if self.what == "hold":
            raise self.fault


class Unusual(BaseException):
    """Neither an Exception nor Ctrl-C."""


@pytest.mark.parametrize("after", [1, 2, 3, 4, 5])  # the 1st read is the binding check
def test_failing_snapshot_ends_the_run(build, after):
    cls = build({"Move": MOVE, "Skill": SKILL}, "Skill")
    chart = within(lambda: cls().start(Failing("snapshot", RuntimeError("sensor bus"), after)))
    assert chart.finished and chart.outcome == "error"
    assert chart.trace[-1]["kind"] == "finished"
    assert "sensor bus" in chart.fault.message


@pytest.mark.parametrize("fault", [AdapterError("arm"), SystemExit(3), Unusual("odd")])
def test_adapter_fault_of_any_kind_is_an_error_and_holds(build, fault):
    cls = build({"Move": MOVE, "Skill": SKILL}, "Skill")
    adapter = Failing("execute", fault)
    chart = within(lambda: cls().start(adapter))
    assert_ends_in_one_error(chart)
    assert "adapter fault in arm.move" in chart.fault.message
    assert chart.fault.origin == ["Skill/M", "Skill"]
    assert adapter.holds == 1


def test_failing_hold_is_reported_and_the_run_still_ends(build):
    cls = build({"Move": MOVE, "Skill": SKILL}, "Skill")
    adapter = Failing("hold", SystemExit(1))
    adapter._outcomes = {"arm.move": ["error"]}
    chart = within(lambda: cls().start(adapter))
    assert chart.finished and chart.outcome == "error"
    assert any("hold failed" in r["message"] for r in errors(chart))


RECOVER = SKILL.replace(
    '<<import="Move">> state M;',
    '<<import="Move">> state M;\n  state R {\n    entry / { n = 1 % n; }\n  }',
).replace("M -> done reached;", "M -> done reached;\n  M -> R error;")


def test_fault_while_handling_an_error_ends_the_run(build):
    cls = build({"Move": MOVE, "Skill": RECOVER}, "Skill")
    chart = within(lambda: cls().start(DryRunAdapter(outcomes={"arm.move": ["error"]})))
    assert chart.finished and chart.outcome == "error"
    assert [r["message"][:17] for r in errors(chart)] == [
        "adapter fault in ",
        "ZeroDivisionError",
    ]
    assert chart.trace[-1] == {**chart.trace[-1], "kind": "finished", "outcome": "error"}


def test_ctrl_c_holds_the_arm_and_ends_the_trace_with_interrupted(build):
    cls = build({"Move": MOVE, "Skill": SKILL}, "Skill")
    adapter = Failing("execute", KeyboardInterrupt())
    chart = cls()
    with pytest.raises(KeyboardInterrupt):
        within(lambda: chart.start(adapter))
    assert adapter.holds == 1
    assert chart.trace[-1]["kind"] == "interrupted"
    assert chart.trace[-1]["active"] == ["Skill", "Skill/M"]
    assert chart.finished and chart.outcome == "interrupted"


def test_ctrl_c_on_the_command_line_exits_130_with_a_finished_trace(tmp_path, monkeypatch, capsys):
    write_models(tmp_path, {"Move": MOVE, "Skill": SKILL})
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    holds = []

    def interrupted(self, *args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(DryRunAdapter, "execute", interrupted)
    monkeypatch.setattr(DryRunAdapter, "hold", lambda self: holds.append(1))
    trace = tmp_path / "trace.jsonl"
    model = str(tmp_path / "t" / "Skill.lr")
    code = within(lambda: main(["run", model, "--adapter", "dryrun", "--trace", str(trace)]))
    assert code == 130
    assert "interrupted" in capsys.readouterr().err
    assert holds == [1]
    *_, interrupted, finished = trace_records(trace)
    assert interrupted["kind"] == "interrupted"
    assert finished == {"time": interrupted["time"], "kind": "finished", "outcome": "interrupted"}


class ClockFails(DryRunAdapter):
    """A dry run whose clock raises from its ``after``-th reading on."""

    def __init__(self, after: int) -> None:
        super().__init__()
        self.after, self.readings = after, 0

    @property
    def time(self) -> float:
        self.readings += 1
        if self.readings > self.after:
            raise SystemExit("clock gone")
        return self._time


@pytest.mark.parametrize("after", [0, 1, 3, 6])
def test_failing_clock_ends_the_run_with_closing_records(build, after):
    cls = build({"Move": MOVE, "Skill": SKILL}, "Skill")
    chart = within(lambda: cls().start(ClockFails(after)))
    assert chart.finished and chart.outcome == "error"
    assert chart.trace[-1]["kind"] == "finished" and chart.trace[-1]["outcome"] == "error"
    assert "clock gone" in chart.fault.message
