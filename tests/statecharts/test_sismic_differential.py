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
from statecharts.sismic_charts import CHARTS

SEQUENCES = 40
LENGTH = 12
TICK = "+0.25"  # advances both clocks by 0.25 s: every delay is a multiple of it


def ours(cls: type, events: list[str]) -> tuple[list[tuple[str, ...]], object]:
    chart = cls().start()
    seen = [tuple(sorted(chart.active_paths))]
    for event in events:
        if event == TICK:
            chart.advance(0.25)
        else:
            chart.send(event)
        seen.append(tuple(sorted(chart.active_paths)))
    return seen, chart


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
