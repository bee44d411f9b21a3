"""``verify``: the shipped examples verify clean; each property of the outcome flow is
refuted on a broken copy of an example at the expected position, with its counterexample;
regions, history, choice and time events are explored without trouble."""

from __future__ import annotations

from pathlib import Path

import pytest

from behaviour.broken_models import EXAMPLES, broken
from lightrocks.languages.lightrocks.behaviour.script import describe, script
from lightrocks.languages.lightrocks.behaviour.verify import verify


def test_the_examples_verify_clean() -> None:
    result = verify([EXAMPLES])
    assert [str(d) for d in result.diagnostics] == []
    assert not result.failed


@pytest.mark.parametrize(
    ("case", "message", "steps"),
    [
        ("41-LR0701-ScrewTask", "no run of 'ScrewTask' ends with 'screwed'", ["FindScrew/Look"]),
        ("44-LR0702-GraspScrew", "'GraspScrew' never ends", ["Open: timeout"]),
        ("46-LR0703-SnapOnRail", "possible endless retry in 'SnapOnRail'", ["Free: lifted"]),
    ],
)
def test_a_refuted_property_has_its_position_and_path(
    case: str, message: str, steps: list[str], tmp_path: Path
) -> None:
    root, file, expect = broken(case, tmp_path)
    result = verify([file], [root])
    mine = [(d, c) for d, c in result.counterexamples if d.code == expect["code"]]
    assert mine, [str(d) for d in result.diagnostics]
    diagnostic, counterexample = mine[0]
    assert Path(diagnostic.file).resolve() == file.resolve()
    assert (diagnostic.line, diagnostic.column) == (expect["line"], expect["column"])
    assert message in diagnostic.message
    shown = "\n".join(describe(counterexample))
    assert all(step in shown for step in steps), shown
    assert script(counterexample)["outcomes"]


def test_an_error_in_check_stops_before_the_model_checker(tmp_path: Path) -> None:
    root, file, _ = broken("36-LR0221-LocalizeScrew", tmp_path)
    result = verify([file], [root])
    assert result.failed
    assert {d.code for d in result.diagnostics} == {"LR0221"}
    assert result.counterexamples == []


def test_strict_fails_on_warnings(tmp_path: Path) -> None:
    root, file, _ = broken("46-LR0703-SnapOnRail", tmp_path)
    assert not verify([file], [root]).failed
    assert verify([file], [root], strict=True).failed


PLAYER = """\
package p;

statechart Player {
  events { play; pause; resume; next; stop; quit; }
  parameters { Integer skips = 0; }
  initial state Stopped;
  state Playing {
    initial state Intro;
    state Song {
      internal next / { skips = skips + 1; };
      internal after(3 s) / { skips = 0; };
    }
    history Back;
    deep history Exact;
    Intro -> Song after(500 ms);
  }
  state Paused;
  choice Resume;
  final state Off;
  Stopped -> Playing play;
  Playing -> Paused pause;
  Paused -> Resume resume;
  Resume -> Playing.Exact [skips < 3];
  Resume -> Playing.Back;
  Paused -> Stopped stop;
  Playing -> Stopped stop;
  Stopped -> Off quit;
}
"""

CROSSING = """\
package p;

statechart Crossing {
  parameters { Integer calls = 0; }
  initial state Both {
    region Traffic {
      initial state Red;
      state Green;
      final state Closed;
      Red -> Green after(1 s);
      Green -> Red press;
      Red -> Closed close;
    }
    region Walker {
      initial state Wait {
        internal [calls < 3] press / { calls = calls + 1; };
      }
      final state Gone;
      Wait -> Gone leave;
    }
  }
  final state Done;
  Both -> Done;
}
"""


@pytest.mark.parametrize("text", [PLAYER, CROSSING], ids=["history-choice-time", "regions"])
def test_regions_history_choice_and_time_events_verify(text: str, tmp_path: Path) -> None:
    name = text.split("statechart ")[1].split()[0]
    (tmp_path / "p").mkdir()
    (tmp_path / "p" / f"{name}.lr").write_text(text, encoding="utf-8")
    result = verify([tmp_path])
    assert [str(d) for d in result.diagnostics] == []


SPIRAL_CELL = """\
package p;

cell Cell {
  object hole {
    Integer steps = 0;
    Length radius = 1.25 mm;
  }
}
"""

SPIRAL = """\
package p;

import p.Cell;

statechart Spiral {
  events { arrived; }
  initial state Step;
  final state Done;
  Step -> Step [hole.radius < 16 mm && hole.steps < 150] arrived / {
    hole.steps = hole.steps + 1;
    hole.radius = hole.radius + 2.5 mm * (2.5 mm / hole.radius) / 6.2832;
  };
  Step -> Done [hole.radius >= 16 mm || hole.steps >= 150] arrived;
}
"""


def test_a_value_whose_digits_double_at_every_step_becomes_unknown(tmp_path: Path) -> None:
    """``radius + c / radius`` (a hole search's spiral) doubles the digits of the tracked
    fraction at every step: past a few dozen digits the radius is unknown, and the counter
    still bounds the loop. Tracked on, it failed with an internal error after a dozen steps
    (Python's limit on the digits of an int)."""
    (tmp_path / "p").mkdir()
    (tmp_path / "p" / "Cell.lrd").write_text(SPIRAL_CELL, encoding="utf-8")
    (tmp_path / "p" / "Spiral.lr").write_text(SPIRAL, encoding="utf-8")
    result = verify([tmp_path])
    assert [str(d) for d in result.diagnostics] == []
    assert not result.failed
