"""Plain charts run by LightRocks and by sismic on the same event sequences.

Each chart is written once as LightRocks text; :mod:`statecharts.sismic_chart` derives the
sismic statechart from its AST. After every event both active configurations must be equal.
The one documented design difference (docs/language.md §15) is an unhandled outcome: it ends
the parent with ``error`` in LightRocks, while sismic stays in the final state.
"""

from __future__ import annotations

import random

import pytest
from sismic.interpreter import Interpreter

from lightrocks.languages.lightrocks.syntax import parse_statechart
from statecharts.conftest import AGREEMENT
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
LENGTH = 10


def alphabet(text: str) -> list[str]:
    """Every stimulus of the chart, so outcome names are sent as events too, and an unknown one."""
    chart = parse_statechart(text, "chart.lr").statechart
    found: set[str] = set()

    def walk(elements) -> None:
        for element in elements:
            if getattr(element, "stimulus", ""):
                found.add(element.stimulus)
            if getattr(element, "body", None):
                walk(element.body)

    walk(chart.elements)
    return [*sorted(found), "unknown"]


def ours(cls: type, events: list[str]) -> tuple[list[tuple[str, ...]], object]:
    chart = cls().start()
    seen = [_paths(chart.active_configuration)]
    for event in events:
        chart.send(event)
        seen.append(_paths(chart.active_configuration))
    return seen, chart


def _paths(names: tuple[str, ...]) -> tuple[str, ...]:
    return tuple(sorted("/".join(names[: i + 1]) for i in range(len(names))))


def theirs(text: str, events: list[str]) -> list[tuple[str, ...]]:
    interpreter = Interpreter(to_sismic(parse_statechart(text, "chart.lr").statechart))
    interpreter.execute()
    seen = [tuple(sorted(interpreter.configuration))]
    for event in events:
        interpreter.queue(event)
        interpreter.execute()
        seen.append(tuple(sorted(interpreter.configuration)))
    return seen


@pytest.mark.parametrize("name", CHARTS)
def test_configurations_agree_with_sismic(name: str, build) -> None:
    text = CHARTS[name]
    cls = build(name, text)
    letters = alphabet(text)
    rng = random.Random(name)
    sequences = [[rng.choice(letters) for _ in range(LENGTH)] for _ in range(SEQUENCES)]
    disagreements = []
    for events in sequences:
        mine, chart = ours(cls, events)
        reference = theirs(text, events)
        AGREEMENT["sequences"] += 1
        if mine == reference:
            AGREEMENT["agree"] += 1
        elif _unhandled_outcome(chart):
            AGREEMENT["documented"] += 1
        else:
            disagreements.append((events, mine, reference))
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
