"""Orthogonal regions at run time: one event in every region, the join, leaving all regions,
and actions of different regions whose commands run together on their devices."""

from __future__ import annotations

from pathlib import Path

import pytest

from lightrocks.adapters.dryrun import DryRunAdapter
from lightrocks.app.loading import component_class, generated_package
from lightrocks.runtime import AdapterError
from lightrocks.workbench import report
from lightrocks.workbench.check import check

DOMAIN = """package r;

device Arm {
  command move(Length x);
  sensor Boolean goalReached;
}

device Eye {
  command look();
  sensor Boolean done;
}

<<scene="none">> cell Cell {
  arm : Arm;
  eye : Eye;
}
"""

MOVE = """package r;

import r.Cell;

<<action>> statechart Move {
  do / arm.move(x = 1 mm);
  end condition reached [arm.goalReached];
}
"""

LOOK = """package r;

import r.Cell;

<<action>> statechart Look {
  do / eye.look();
  end condition seen [eye.done];
}
"""

BOTH = """package r;

import r.Cell;

<<skill>> statechart Both {
  end condition done;
  end condition failed;

  initial state Work {
    region Hand {
      <<import="Move">> initial state Reach;
      final state Reached;
      Reach -> Reached reached;
    }

    region Sight {
      <<import="Look">> initial state Find;
      final state Found;
      Find -> Found seen;
    }
  }

  Work -> done Reached;
  Work -> failed error;
}
"""

WATCH = """package r;

import r.Cell;

<<skill>> statechart Watch {
  end condition done;
  end condition failed;

  initial state Work {
    region Hand {
      <<import="Move">> initial state Reach;
      final state Reached;
      Reach -> Reached reached;
    }

    region Clock {
      initial state Tick;
      final state Rang;
      Tick -> Rang after(200 ms);
    }
  }

  Work -> done Reached;
  Work -> failed error;
}
"""

SWITCH = """package r;

statechart Switch {
  parameters {
    Integer n = 0;
  }

  initial state Idle;
  state Work {
    exit / { n = n + 10; }

    region Left {
      initial state A;
      final state Adone;
      choice Check;
      A -> Adone go / { n = n + 1; };
      A -> Adone early;
      A -> Check jam;
      Check -> A [n > 100];
    }

    region Right {
      initial state B;
      final state Bdone;
      B -> Bdone go;
      B -> B tick;
    }
  }
  state Broken;
  final state Done;

  Idle -> Work start;
  Work -> Done Adone;
  Work -> Broken error;
  Work -> Idle stop;
}
"""


@pytest.fixture
def build(tmp_path: Path):
    """``build(name)`` -> the generated class of ``r.<name>`` among the models above."""

    def make(name: str) -> type:
        (tmp_path / "r").mkdir(exist_ok=True)
        models = {"Cell.lrd": DOMAIN, "Move.lr": MOVE, "Look.lr": LOOK}
        models |= {"Both.lr": BOTH, "Switch.lr": SWITCH, "Watch.lr": WATCH}
        for file, text in models.items():
            (tmp_path / "r" / file).write_text(text)
        context = check([tmp_path])
        shown = report.text(context.diagnostics.items)
        assert not context.diagnostics.has_errors, shown
        model = tmp_path / "r" / f"{name}.lr"
        return component_class(generated_package(context, [model], tmp_path / "cache"), f"r.{name}")

    return make


def _kinds(chart, *kinds: str) -> list[tuple[str, str]]:
    return [(r["kind"], r.get("state", "")) for r in chart.trace if r["kind"] in kinds]


def test_every_region_is_entered_in_declaration_order(build) -> None:
    chart = build("Switch")().start()
    chart.send("start")
    assert chart.active_paths == (
        "Switch",
        "Switch/Work",
        "Switch/Work/Left",
        "Switch/Work/Left/A",
        "Switch/Work/Right",
        "Switch/Work/Right/B",
    )
    entered = [state for kind, state in _kinds(chart, "enter")]
    assert entered[-4:] == [
        "Switch/Work/Left",
        "Switch/Work/Left/A",
        "Switch/Work/Right",
        "Switch/Work/Right/B",
    ]


def test_one_event_moves_every_region_then_the_join_leaves_them_all(build) -> None:
    chart = build("Switch")().start()
    chart.send("start")
    assert chart.send("go")
    assert chart.finished and chart.outcome == "Done"
    assert chart.n == 11  # the action of Left's transition, then Work's exit action
    records = _kinds(chart, "transition", "outcome", "exit")
    assert records.index(("transition", "Switch/Work/Left")) < records.index(
        ("transition", "Switch/Work/Right")
    )
    joined = records.index(("outcome", "Switch/Work"))
    exits = [state for kind, state in records[joined:] if kind == "exit"]
    assert exits[:5] == [
        "Switch/Work/Right/Bdone",
        "Switch/Work/Right",
        "Switch/Work/Left/Adone",
        "Switch/Work/Left",
        "Switch/Work",
    ]


def test_a_region_that_is_final_waits_for_the_others(build) -> None:
    chart = build("Switch")().start()
    chart.send("start")
    chart.send("early")
    assert "Switch/Work/Left/Adone" in chart.active_paths
    assert "Switch/Work/Right/B" in chart.active_paths
    chart.send("go")
    assert chart.outcome == "Done"


def test_an_event_that_no_region_takes_goes_to_the_orthogonal_state(build) -> None:
    chart = build("Switch")().start()
    chart.send("start")
    chart.send("tick")  # only Right reacts, and stays in B
    assert "Switch/Work/Left/A" in chart.active_paths
    chart.send("stop")  # Work's own transition: no region has one for 'stop'
    assert chart.active_paths == ("Switch", "Switch/Idle")
    assert chart.n == 10


def test_an_error_in_one_region_leaves_the_whole_orthogonal_state(build) -> None:
    chart = build("Switch")().start()
    chart.send("start")
    chart.send("jam")
    assert chart.active_paths == ("Switch", "Switch/Broken")
    error = next(r for r in chart.trace if r["kind"] == "outcome" and r["state"] == "Switch/Work")
    assert error["outcome"] == "error"
    assert error["origin"] == ["Switch/Work/Left", "Switch/Work"]


def test_commands_of_two_regions_run_together_on_their_devices(build) -> None:
    adapter = DryRunAdapter(duration=0.5, step=0.01)
    chart = build("Both")().start(adapter)
    assert chart.outcome == "done"
    assert sorted(device for device, _, _ in adapter.calls) == ["arm", "eye"]
    commands = [r for r in chart.trace if r["kind"] == "command"]
    assert [r["time"] for r in commands] == [0.0, 0.0]
    assert adapter.time == pytest.approx(0.5)  # together, not one after the other


def test_an_adapter_that_runs_one_command_at_a_time_ends_the_regions_in_error(build) -> None:
    class OneAtATime(DryRunAdapter):
        def execute(self, commands, on_tick=None):
            if len(commands) > 1:
                raise AdapterError("one command at a time")
            return super().execute(commands, on_tick)

    adapter = OneAtATime()
    chart = build("Both")().start(adapter)
    assert chart.outcome == "failed"
    errors = [r for r in chart.trace if r["kind"] == "error"]
    assert errors[0]["message"] == (
        "adapter fault in arm.move, eye.look: AdapterError('one command at a time')"
    )
    assert adapter.calls == []


def test_a_time_event_of_one_region_stops_the_command_of_another_which_starts_again(
    build,
) -> None:
    adapter = DryRunAdapter(duration=0.5, step=0.01)
    chart = build("Watch")().start(adapter)
    assert chart.outcome == "done"
    stops = [r["outcome"] for r in chart.trace if r["kind"] == "stop"]
    assert stops == ["@timer", "reached"]
    assert [call[:2] for call in adapter.calls] == [("arm", "move"), ("arm", "move")]
    assert adapter.time == pytest.approx(0.7)  # stopped at 0.2 s, then 0.5 s again
    rang = next(r for r in chart.trace if r["kind"] == "enter" and r["state"].endswith("Rang"))
    assert rang["time"] == pytest.approx(0.2)
