"""Semantics of the newer constructs that the sismic differential cannot show."""

from __future__ import annotations

import pytest

from lightrocks.adapters.dryrun import DryRunAdapter
from statecharts.late_chart import LATE

BLINK = """package d;

statechart Blink {
  parameters {
    Integer flashes = 0;
  }

  initial state Idle;
  state Lit {
    internal after(250 ms) / { flashes = flashes + 1; };
  }
  choice Enough;

  Idle -> Lit on;
  Lit -> Enough off;
  Enough -> Idle [flashes > 0];
}
"""


def test_an_internal_time_event_fires_once_per_entry(build) -> None:
    chart = build("Blink", BLINK)().start()
    chart.send("on")
    chart.advance(1.0)
    assert chart.flashes == 1
    assert chart.active_configuration == ("Blink", "Lit")
    chart.send("off")
    assert chart.active_configuration == ("Blink", "Idle")


def test_a_choice_without_a_branch_that_holds_is_an_error(build) -> None:
    chart = build("Blink", BLINK)().start()
    chart.send("on")
    chart.send("off")
    assert chart.outcome == "error"
    assert chart.fault.message == "no branch of choice 'Enough' holds"


def test_the_virtual_clock_only_runs_without_adapter(build) -> None:
    chart = build("Blink", BLINK)().start()
    with pytest.raises(ValueError, match="time cannot go back"):
        chart.advance(-1)
    bound = build("Blink", BLINK)().start(DryRunAdapter())
    with pytest.raises(RuntimeError, match="adapter's clock"):
        bound.advance(1)


RESUME = """package d;

statechart Resume {
  initial state Idle;
  state Job {
    end condition out;
    initial state Load;
    state Work;
    history H;
    Load -> Work next;
    Work -> out bail;
  }

  Idle -> Job go;
  Job -> Idle out;
  Idle -> Job.H back;
  Job -> Idle pause;
}
"""


@pytest.mark.parametrize(
    ("events", "resumed"),
    [(["go", "next", "pause", "back"], "Work"), (["go", "next", "bail", "back"], "Load")],
)
def test_history_forgets_a_composite_left_through_an_end_condition(
    build, events: list[str], resumed: str
) -> None:
    chart = build("Resume", RESUME)().start()
    for event in events:
        assert chart.send(event)
    assert chart.active_configuration == ("Resume", "Job", resumed)


AT_ONCE = """package d;

statechart AtOnce {
  parameters {
    Integer n = 0;
  }

  initial state Outer {
    initial state Wait {
      internal after(500 ms) / { n = n + 1; };
    }
    state Moved {
      entry / { n = n + 10; }
    }
    Wait -> Moved [n == 1] after(500 ms);
  }
  state Next;

  Outer -> Next [n == 11] after(500 ms);
}
"""


def test_time_events_at_one_deadline_fire_inner_and_internal_first(build) -> None:
    """The internal time event of ``Wait`` fires before the one leaving it, and both before
    the one leaving ``Outer``: each later guard sees what the earlier actions wrote."""
    chart = build("AtOnce", AT_ONCE)().start()
    chart.advance(0.5)
    assert chart.n == 11
    assert chart.active_configuration == ("AtOnce", "Next")


def test_a_choice_without_a_branch_that_holds_is_not_saved_by_a_later_time_event(build) -> None:
    """The inner time event fires first and reaches the choice; its failure ends the run
    before the enclosing time event due at the same deadline is taken (sismic would take it
    and leave the choice, docs/language.md §15.1)."""
    chart = build("Late", LATE)().start()
    chart.advance(0.5)
    assert chart.outcome == "error"
    assert chart.fault.message == "no branch of choice 'Which' holds"
    assert chart.fault.origin == ["Late/Outer", "Late"]
