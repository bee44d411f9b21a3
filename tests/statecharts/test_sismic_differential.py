"""Plain charts run by LightRocks and by sismic on the same event sequences.

Each chart is written once as LightRocks text; :mod:`statecharts.sismic_chart` derives the
sismic statechart from its AST. After every event both active configurations must be equal.
The one documented design difference (docs/language.md §15) is an unhandled outcome: it ends
the parent with ``error`` in LightRocks, while sismic stays in the final state.
"""

from __future__ import annotations

import random

import pytest
from sismic.clock import SimulatedClock
from sismic.interpreter import Interpreter

from lightrocks.languages.lightrocks.syntax import parse_statechart
from statecharts.sismic_chart import to_sismic

CHARTS = {
    "Turnstile": """package d;

statechart Turnstile {
  parameters {
    Integer passages = 0;
    Integer capacity = 3;
  }

  initial state Operating {
    initial state Locked;
    state Unlocked;
    Locked -> Unlocked [passages < capacity] coin;
    Unlocked -> Unlocked coin;
    Unlocked -> Locked push / { passages = passages + 1; };
  }
  state Maintenance {
    entry / { passages = 0; }
  }
  final state Off;

  Operating -> Maintenance service;
  Maintenance -> Operating resume;
  Operating -> Off shutdown;
  Maintenance -> Off shutdown;
}
""",
    "Q": """package d;

statechart Q {
  initial state Idle;
  state Job {
    end condition out;
    initial state Load;
    final state Ok;
    Load -> Ok load;
    Load -> out bail;
  }
  state Other;

  Idle -> Job go;
  Job -> Idle Ok;
  Job -> Other out;
  Other -> Idle back;
}
""",
    "Line": """package d;

statechart Line {
  parameters {
    Integer scrapped = 0;
  }

  initial state Idle;
  state Process {
    initial state Work;
    state Check {
      initial state Measure;
      state Retry;
      final state Good;
      Measure -> Good pass;
      Measure -> Retry fail;
      Retry -> Measure pass;
    }
    final state Ok;
    Work -> Check done;
    Check -> Ok;
    Check -> Work fail;
  }
  state Scrap {
    entry / { scrapped = scrapped + 1; }
  }

  Idle -> Process go;
  Process -> Idle;
  Process -> Scrap bad;
  Scrap -> Idle [scrapped < 2] reset;
}
""",
    "Nest": """package d;

statechart Nest {
  parameters {
    Integer ticks = 0;
    Boolean armed = false;
  }

  initial state A {
    initial state B {
      initial state C;
      state D;
      C -> D tick / { ticks = ticks + 1; };
      D -> C tick;
    }
    state E;
    B -> E [ticks >= 2] tick;
    B -> E jump;
    E -> B jump / { armed = !armed; };
  }
  state F;

  A -> F [armed && ticks % 2 == 0] leave;
  A -> F reset;
  F -> A back / { ticks = 0; };
}
""",
    "Pump": """package d;

statechart Pump {
  events {
    start;
    stop;
    tick;
  }

  parameters {
    Integer strokes = 0;
  }

  initial state Off;
  state On {
    initial state Priming;
    state Running {
      internal [strokes < 3] tick / { strokes = strokes + 1; };
    }
    Priming -> Running after(500 ms);
    Running -> Priming [strokes >= 3] tick / { strokes = 0; };
  }
  state Cooling {
    entry / { strokes = 0; }
  }

  Off -> On start;
  On -> Cooling stop;
  Cooling -> Off after(750 ms);
}
""",
    "Router": """package d;

statechart Router {
  parameters {
    Integer n = 0;
  }

  initial state Idle;
  state Small;
  state Large;
  state Huge;
  choice Size;

  Idle -> Size go / { n = n + 1; };
  Size -> Small [n < 2];
  Size -> Large [n < 4];
  Size -> Huge;
  Small -> Idle back;
  Large -> Idle back;
  Huge -> Idle back / { n = 0; };
}
""",
    "Player": """package d;

statechart Player {
  initial state Stopped;
  state Playing {
    initial state Intro;
    state Song {
      initial state Verse;
      state Chorus;
      Verse -> Chorus next;
      Chorus -> Verse next;
    }
    history H;
    deep history D;
    Intro -> Song next;
  }
  state Paused;

  Stopped -> Playing play;
  Playing -> Paused pause;
  Paused -> Playing.H resume;
  Paused -> Playing.D deepresume;
  Paused -> Stopped stop;
  Playing -> Stopped stop;
}
""",
    "Unhandled": """package d;

statechart Unhandled {
  initial state Idle;
  state Job {
    initial state Load;
    final state Ok;
    final state Late;
    Load -> Ok load;
    Load -> Late wait;
  }

  Idle -> Job go;
  Job -> Idle Ok;
}
""",
}

SEQUENCES = 40
LENGTH = 12
TICK = "+0.25"  # advances both clocks by 0.25 s: every delay is a multiple of it


def ours(cls: type, events: list[str]) -> tuple[list[tuple[str, ...]], object]:
    chart = cls().start()
    seen = [_paths(chart.active_configuration)]
    for event in events:
        if event == TICK:
            chart.advance(0.25)
        else:
            chart.send(event)
        seen.append(_paths(chart.active_configuration))
    return seen, chart


def _paths(names: tuple[str, ...]) -> tuple[str, ...]:
    return tuple(sorted("/".join(names[: i + 1]) for i in range(len(names))))


def theirs(text: str, events: list[str]) -> list[tuple[str, ...]]:
    chart = to_sismic(parse_statechart(text, "chart.lr").statechart)
    interpreter = Interpreter(chart, clock=SimulatedClock())
    interpreter.execute()
    seen = [tuple(sorted(interpreter.configuration))]
    for event in events:
        if event == TICK:
            interpreter.clock.time += 0.25
        else:
            interpreter.queue(event)
        interpreter.execute()
        seen.append(tuple(sorted(interpreter.configuration)))
    return seen


AGREEMENT = (
    "sismic differential: {agree} of {sequences} event sequences agree, "
    "{documented} differ by a documented design difference"
)


@pytest.mark.parametrize("name", CHARTS)
def test_configurations_agree_with_sismic(name: str, build, tally) -> None:
    text = CHARTS[name]
    cls = build(name, text)
    letters = [*sorted(cls().start().events), TICK]
    rng = random.Random(name)
    sequences = [[rng.choice(letters) for _ in range(LENGTH)] for _ in range(SEQUENCES)]
    agree, documented, disagreements = 0, 0, []
    for events in sequences:
        mine, chart = ours(cls, events)
        reference = theirs(text, events)
        if mine == reference:
            agree += 1
        elif _unhandled_outcome(chart):
            documented += 1
        else:
            disagreements.append((events, mine, reference))
    tally(AGREEMENT, sequences=len(sequences), agree=agree, documented=documented)
    assert not disagreements, disagreements[0]


def _unhandled_outcome(chart) -> bool:
    return chart.outcome == "error" and chart.fault.message.startswith("unhandled outcome")


def test_the_unhandled_outcome_difference_is_exercised(build) -> None:
    cls = build("Unhandled", CHARTS["Unhandled"])
    mine, chart = ours(cls, ["go", "wait"])
    assert _unhandled_outcome(chart) and mine[-1] == ()
    assert theirs(CHARTS["Unhandled"], ["go", "wait"])[-1] == (
        "Unhandled",
        "Unhandled/Job",
        "Unhandled/Job/Late",
    )
