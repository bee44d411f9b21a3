"""Random plain charts run by LightRocks and by sismic on the same random event sequences.

:mod:`statecharts.random_charts` writes charts nobody hand-wrote; after every event (or
clock tick) both interpreters must have the same active configuration and the same values
of the Integer parameters. The documented design differences of docs/language.md §15.1 are
counted apart: an unhandled outcome ends the parent with ``error`` (as in
:mod:`statecharts.test_sismic_differential`), and so does a choice none of whose branches
holds, where sismic stalls in the choice. A failure prints the chart and the events, so
it can be replayed with :func:`divergence`.
"""

from __future__ import annotations

import random
from collections.abc import Iterator

import pytest
from sismic.clock import SimulatedClock
from sismic.model import MacroStep

from lightrocks.languages.lightrocks.syntax import parse_statechart
from lightrocks.metamodel import ast
from statecharts.late_chart import LATE
from statecharts.random_charts import TICK, VARIABLES, random_chart
from statecharts.sismic_chart import Reference, to_sismic

CHARTS = 40
SWEEP = 400
SEQUENCES = 6
LENGTH = 14
STEP = f"+{TICK}"

Observation = tuple[tuple[str, ...], tuple[int, ...] | None]


def ours(cls: type, events: list[str]) -> tuple[list[Observation], object]:
    chart = cls().start()
    seen = [_ours(chart)]
    for event in events:
        if event == STEP:
            chart.advance(TICK)
        else:
            chart.send(event)
        seen.append(_ours(chart))
    return seen, chart


def _ours(chart) -> Observation:
    values = None if chart.outcome else tuple(getattr(chart, v) for v in VARIABLES)
    return tuple(sorted(chart.active_paths)), values


def theirs(text: str, events: list[str]) -> tuple[list[Observation], list[set[str]]]:
    """sismic's observations and, for every step, the states it stalled in (see
    :func:`_stalled`)."""
    interpreter = Reference(
        to_sismic(parse_statechart(text, "chart.lr").statechart), clock=SimulatedClock()
    )
    stalled = [_stalled(interpreter.execute())]
    seen = [_theirs(interpreter)]
    for event in events:
        if event == STEP:
            interpreter.clock.time += TICK
        else:
            interpreter.queue(event)
        stalled.append(_stalled(interpreter.execute()))
        seen.append(_theirs(interpreter))
    return seen, stalled


def _stalled(steps: list[MacroStep]) -> set[str]:
    """The states entered in ``steps`` and not left afterwards by a transition of their own:
    still active, or left by an enclosing transition. A choice none of whose branches held
    is one."""
    stalled: set[str] = set()
    for micro in (micro for macro in steps for micro in macro.steps):
        if micro.transition is not None:
            stalled.discard(micro.transition.source)
        stalled.update(micro.entered_states)
    return stalled


def _theirs(interpreter: Reference) -> Observation:
    values = tuple(interpreter.context[v] for v in VARIABLES)
    return tuple(sorted(interpreter.configuration)), values


def divergence(cls: type, text: str, events: list[str]) -> str | None:
    """``None`` when both agree step by step, the name of a documented design difference
    (:data:`DOCUMENTED`), else a report that replays the disagreement."""
    mine, chart = ours(cls, events)
    reference, stalled = theirs(text, events)
    pairs = enumerate(zip(mine, reference, strict=True))
    step = next((i for i, (a, b) in pairs if not _same(a, b)), None)
    if step is None:
        return None
    if _unhandled_outcome(chart):
        return UNHANDLED
    if _no_branch_holds(chart, mine[step], stalled[step]):
        return NO_BRANCH
    return (
        f"after {events[:step]} (step {step}):\n  LightRocks {mine[step]}\n"
        f"  sismic     {reference[step]}\nevents {events}\n{text}"
    )


UNHANDLED, NO_BRANCH = "unhandled outcome", "no branch of a choice holds"
DOCUMENTED = (UNHANDLED, NO_BRANCH)


def _same(mine: Observation, reference: Observation) -> bool:
    """Equal configurations, and equal values while the LightRocks run goes on."""
    return mine[0] == reference[0] and (mine[1] is None or mine[1] == reference[1])


def _unhandled_outcome(chart) -> bool:
    return chart.outcome == "error" and chart.fault.message.startswith("unhandled outcome")


def _no_branch_holds(chart, mine: Observation, stalled: set[str]) -> bool:
    """LightRocks ended with ``error`` because no branch of a choice held, in the step where
    sismic stalled in that very choice: it rests there, or a transition of an enclosing
    state due at the same time took it out."""
    fault = chart.fault
    if chart.outcome != "error" or not fault.message.startswith("no branch of choice"):
        return False
    choice = fault.message.split("'")[1]
    return mine == ((), None) and f"{fault.origin[0]}/{choice}" in stalled


def sequences(cls: type, seed: int) -> list[list[str]]:
    letters = [*sorted(cls().start().events), STEP]
    rng = random.Random(seed)
    return [[rng.choice(letters) for _ in range(LENGTH)] for _ in range(SEQUENCES)]


AGREEMENT = (
    "random sismic differential: {agree} of {sequences} event sequences on {charts} random "
    "charts agree, {documented} differ by a documented design difference ({no_branch} of "
    "them a choice without a branch that holds)"
)


def _agrees(seed: int, build, tally) -> None:
    text = random_chart(seed)
    cls = build("R", text)
    found = [divergence(cls, text, events) for events in sequences(cls, seed)]
    tally(
        AGREEMENT,
        charts=1,
        sequences=len(found),
        agree=found.count(None),
        documented=sum(found.count(kind) for kind in DOCUMENTED),
        no_branch=found.count(NO_BRANCH),
    )
    wrong = [f for f in found if f is not None and f not in DOCUMENTED]
    assert not wrong, f"random chart {seed} disagrees with sismic {wrong[0]}"


@pytest.mark.parametrize("seed", range(CHARTS))
def test_random_charts_agree_with_sismic(seed: int, build, tally) -> None:
    _agrees(seed, build, tally)


@pytest.mark.slow
@pytest.mark.parametrize("seed", range(CHARTS, CHARTS + SWEEP))
def test_more_random_charts_agree_with_sismic(seed: int, build, tally) -> None:
    _agrees(seed, build, tally)


PICK = """package d;

statechart Pick {
  parameters {
    Integer n = 0;
    Integer m = 0;
    Integer k = 0;
  }

  initial state Idle;
  state Done;
  choice Which;

  Idle -> Which go / { n = n + 1; };
  Which -> Done [n == 2];
  Idle -> Idle bump / { n = n + 1; };
}
"""


@pytest.mark.parametrize(
    ("events", "found"), [(["bump", "go"], None), (["go"], NO_BRANCH), (["bump"], None)]
)
def test_a_choice_without_a_branch_that_holds_is_a_documented_difference(
    build, events: list[str], found: str | None
) -> None:
    """Counted apart only where LightRocks ends with ``error`` and sismic rests in the choice."""
    assert divergence(build("Pick", PICK), PICK, events) == found


def test_only_sismic_resting_in_that_choice_makes_the_difference_documented(build) -> None:
    mine, chart = ours(build("Pick", PICK), ["go"])
    assert mine[-1] == ((), None)
    assert _no_branch_holds(chart, mine[-1], theirs(PICK, ["go"])[1][-1])
    assert not _no_branch_holds(chart, mine[-1], theirs(PICK, ["bump", "go"])[1][-1])


def test_a_choice_left_by_an_enclosing_time_event_is_the_same_difference(build) -> None:
    """At one deadline sismic enters the choice, finds no branch, and leaves it by the
    enclosing time event; LightRocks ends with ``error`` at the choice."""
    events = [STEP, STEP]
    assert theirs(LATE, events)[0][-1] == (("Late", "Late/Away"), (0, 0, 0))
    assert divergence(build("Late", LATE), LATE, events) == NO_BRANCH


OVER = """package d;

statechart Over {
  parameters {
    Integer n = 0;
    Integer m = 0;
    Integer k = 0;
  }

  initial state Outer {
    internal after(500 ms) / { n = n + 1; };
    initial state Wait;
    final state Done;
    Wait -> Done after(500 ms);
  }
  state Next;

  Outer -> Next;
}
"""


def test_a_state_that_completes_drops_its_internal_time_event_due_at_that_time(build) -> None:
    """The inner time event completes ``Outer``, which is left before its own internal one
    at the same deadline fires; the sismic translation must not offer both."""
    events = [STEP, STEP]
    assert theirs(OVER, events)[0][-1] == (("Over", "Over/Next"), (0, 0, 0))
    assert divergence(build("Over", OVER), OVER, events) is None


def _constructs(seed: int) -> set[str]:
    """Which of the constructs the generator is meant to write a random chart holds."""
    chart = parse_statechart(random_chart(seed), "chart.lr").statechart
    found = set()
    if any(isinstance(e, ast.InternalTransition) for e in chart.elements):
        found.add("internal transition of the statechart")
    for body in _bodies(chart.elements):
        transitions = [e for e in body if isinstance(e, ast.Transition)]
        composites = {e.name for e in body if isinstance(e, ast.State) and _levels(e.body or ())}
        if any(t.source == t.target and t.source in composites for t in transitions):
            found.add("self-transition of a composite")
        for choice in (e.name for e in body if _pseudostate(e, "choice")):
            if all(t.guard is not None for t in transitions if t.source == choice):
                found.add("choice without else")
        for memory in ("history", "deep history"):
            if any(_pseudostate(e, memory) for e in body) and _levels(body) >= 3:
                found.add(f"{memory} over three levels of states")
    return found


def _pseudostate(element: object, kind: str) -> bool:
    return isinstance(element, ast.Pseudostate) and element.kind == kind


def _inner(element: object) -> tuple:
    if isinstance(element, ast.Region):
        return element.elements
    return (element.body or ()) if isinstance(element, ast.State) else ()


def _bodies(elements: tuple) -> Iterator[tuple]:
    """``elements`` and every body of a state or region below."""
    yield elements
    for element in elements:
        if _inner(element):
            yield from _bodies(_inner(element))


def _levels(elements: tuple) -> int:
    """How many levels of states nest in ``elements`` (regions add none)."""
    levels = [
        _levels(_inner(e)) + isinstance(e, ast.State)
        for e in elements
        if isinstance(e, (ast.State, ast.Region))
    ]
    return max(levels, default=0)


def test_the_quick_charts_hold_every_construct_the_generator_writes() -> None:
    found = set().union(*(_constructs(seed) for seed in range(CHARTS)))
    assert found == {
        "internal transition of the statechart",
        "self-transition of a composite",
        "choice without else",
        "history over three levels of states",
        "deep history over three levels of states",
    }
