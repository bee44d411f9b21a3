"""``<<timeout>>`` on a skill or task: a budget for the whole statechart. Once spent, the
running command is stopped, every state inside is left, and the statechart ends with the
outcome ``timeout``, which its parent handles like any other."""

from __future__ import annotations

import pytest

from lightrocks.adapters.dryrun import DryRunAdapter

SLOW = """package t;

<<skill, timeout="1 s">> statechart Slow {
  end condition moved;
  <<import="Move">> initial state M;
  M -> moved reached;
}
"""

JOB = """package t;

<<task>> statechart Job {
  end condition done;
  end condition late;
  <<import="Slow">> initial state S;
  S -> done moved;
  S -> late timeout;
}
"""


def test_a_spent_budget_stops_the_command_and_ends_the_skill_with_timeout(build) -> None:
    chart = build({"Slow": SLOW, "Job": JOB}, "Job")().start(DryRunAdapter(duration=5.0))
    assert chart.outcome == "late"
    outcomes = [(r["state"], r["outcome"]) for r in chart.trace if r["kind"] == "outcome"]
    assert ("Job/S/M", "preempted") in outcomes
    assert ("Job/S", "timeout") in outcomes
    assert chart.trace[-1]["time"] == pytest.approx(1.0)  # the skill's, not the device's 2 s


def test_a_skill_that_ends_within_its_budget_is_not_touched(build) -> None:
    chart = build({"Slow": SLOW, "Job": JOB}, "Job")().start(DryRunAdapter(duration=0.5))
    assert chart.outcome == "done"
    assert chart.trace[-1]["time"] == pytest.approx(0.5)


def test_the_budget_of_the_top_statechart_ends_the_run(build) -> None:
    chart = build({"Slow": SLOW}, "Slow")().start(DryRunAdapter(duration=5.0))
    assert chart.outcome == "timeout"
    assert chart.trace[-1]["kind"] == "finished"
    assert chart.trace[-1]["outcome"] == "timeout"


def test_an_actions_budget_stays_its_commands_and_arms_no_time_event(build) -> None:
    """An action's ``BUDGET`` is its command's: the command ends with ``timeout`` itself,
    never preempted by a time event at the same deadline."""
    chart = build({"Slow": SLOW.replace('<<skill, timeout="1 s">>', "<<skill>>")}, "Slow")
    run = chart().start(DryRunAdapter(duration=5.0))
    outcomes = [(r["state"], r["outcome"]) for r in run.trace if r["kind"] == "outcome"]
    assert ("Slow/M", "timeout") in outcomes
    assert not [o for o in outcomes if o[1] == "preempted"]
    assert run.trace[-1]["time"] == pytest.approx(2.0)  # the device's <<timeout="2 s">>
