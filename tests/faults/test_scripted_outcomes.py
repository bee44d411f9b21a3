"""A dry-run script's outcome belongs to the next call of its command, however that call
ends: a call that an event, a time event or an enclosing end condition stops first has used
it, so the next call of the command (maybe of another action, with other end conditions)
takes the next one instead of being handed an outcome it cannot end in ("adapter broke the
contract"). An outcome a call cannot end in is an adapter fault that says so."""

from __future__ import annotations

from pathlib import Path

import pytest

from lightrocks.adapters.dryrun import DryRunAdapter

from .fault_runs import cli, within, write_models

MOVE = """package t;

import t.Cell;

<<action>> statechart Move {
  do / arm.move(x = 1 mm);
  end condition reached [arm.goalReached];
}
"""

PRESS = """package t;

import t.Cell;

<<action>> statechart Press {
  do / arm.move(x = 2 mm);
  end condition pressed [arm.goalReached];
}
"""

GUARDED = """package t;

import t.Cell;

<<skill>> statechart Guarded {
  start condition go;
  end condition done;
  end condition halt [arm.z > 1 mm];

  <<import="Move">> state M;

  go -> M;
  M -> done reached;
}
"""


def twice(stop: str) -> str:
    """Move, stopped by ``stop`` (or ending ``reached``), then Press."""
    first = '<<import="Guarded">> state M;' if stop == "halt" else '<<import="Move">> state M;'
    stimulus = {"timer": "after(50 ms)", "event": "poke", "halt": "halt"}[stop]
    return f"""package t;

import t.Cell;

<<skill>> statechart Twice {{
  start condition go;
  end condition done;

  {first}
  <<import="Press">> state P;

  go -> M;
  M -> P {stimulus};
  M -> P {"done" if stop == "halt" else "reached"};
  P -> done pressed;
}}
"""


CHARTS = {"Move": MOVE, "Press": PRESS, "Guarded": GUARDED}


class Poking(DryRunAdapter):
    """Sends ``poke`` to the chart once the first command has run for 30 ms."""

    chart = None

    def snapshot(self):
        if self.chart is not None and self.time >= 0.03:
            chart, self.chart = self.chart, None
            chart.send("poke")
        return super().snapshot()


@pytest.mark.parametrize("stop", ["timer", "event", "halt"])
def test_a_preempted_call_uses_its_scripted_outcome(build, stop: str) -> None:
    chart = build({**CHARTS, "Twice": twice(stop)}, "Twice")()
    adapter = Poking(outcomes={"arm.move": ["reached", "pressed"]},
                     sensors={"arm.z": lambda t: 0.002 if 0.03 <= t < 0.1 else 0.0})  # fmt: skip
    if stop == "event":
        adapter.chart = chart
    within(lambda: chart.start(adapter))
    assert chart.outcome == "done", chart.fault
    stops = [r["outcome"] for r in chart.trace if r["kind"] == "stop"]
    assert stops[-1] == "pressed"
    assert stops[0] != "reached", "the first call was not preempted"


def test_the_command_line_walks_past_a_preempted_call(tmp_path: Path) -> None:
    write_models(tmp_path, {**CHARTS, "Twice": twice("timer")})
    (tmp_path / "script.json").write_text('{"outcomes": {"arm.move": ["reached", "pressed"]}}')
    run = cli("run", "t/Twice.lr", "--adapter", "dryrun", "--script", "script.json", cwd=tmp_path)
    assert run.returncode == 0, run.stdout + run.stderr
    assert "outcome: done" in run.stdout
    assert "broke the contract" not in run.stdout + run.stderr


def test_an_outcome_the_call_cannot_end_in_says_so(tmp_path: Path) -> None:
    write_models(tmp_path, {**CHARTS, "Twice": twice("timer")})
    (tmp_path / "script.json").write_text('{"outcomes": {"arm.move": ["pressed"]}}')
    run = cli("run", "t/Twice.lr", "--adapter", "dryrun", "--script", "script.json", cwd=tmp_path)
    assert run.returncode == 1
    out = " ".join(run.stdout.split())
    assert "the script's next outcome of arm.move, 'pressed', cannot end this call" in out
    assert "it ends in reached, timeout, error" in out
    assert "broke the contract" not in out
