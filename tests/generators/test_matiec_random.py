"""The SFC target judged by MatIEC on random plain statecharts nobody hand-wrote.

:mod:`statecharts.random_charts` writes a chart per seed (composites, orthogonal regions,
history, choices, finals, end conditions, internal transitions, Integer parameters, time
events); the generated SFC is compiled by MatIEC, linked with the step harness of
:mod:`plc`, and must enter the same states and take the same outcomes as the Python runtime
on a few random scripts of events and time passing, time events that fall due together in
nested or orthogonal states included (the harness runs the PLC on the virtual clock of the
Python side). :mod:`tied_charts` writes charts in which such time events are common. A
chart using a construct the SFC target refuses (docs/generators.md) is counted apart. A
failure names the seed and the script, so it can be replayed with :func:`steps_alike`.
"""

from __future__ import annotations

import os
import random
from collections import Counter
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import pytest
from generation import generate
from plc import (
    Scenario,
    comparable,
    driver_source,
    gcc,
    iec2c,
    python_trace,
    sfc_trace,
    sfc_unit,
    steps,
    streams,
)
from statecharts.random_charts import TICK, random_chart
from tied_charts import tied_chart

from lightrocks.app.loading import load_component
from lightrocks.app.run import drive
from lightrocks.workbench.generators import GenerationError

CHARTS = 6
SWEEP = int(os.environ.get("LIGHTROCKS_MATIEC_SWEEP", "48"))
TIED = 12
TIED_SWEEP = SWEEP // 2
"""The slow sweeps' sizes: every seed compiles a chart with MatIEC and gcc (seconds each);
``LIGHTROCKS_MATIEC_SWEEP=400 pytest -m slow tests/generators/test_matiec_random.py`` runs a
wider one."""
SEQUENCES = 3
SETTLING = f"+{round(TICK * 4000)}ms"  # every script ends letting the longest delay pass
REFUSED = "the SFC target does not map"


@dataclass(frozen=True)
class Kind:
    """Random charts of one writer: the chart's name, and how its scripts let time pass."""

    write: Callable[[int], str]
    name: str
    passing: tuple[str, ...]
    length: int


RANDOM = Kind(random_chart, "R", (f"+{round(TICK * 1000)}ms", f"+{round(TICK * 2000)}ms"), 8)
TIES = Kind(tied_chart, "T", (f"+{round(TICK * 1000)}ms",) * 2, 11)  # time events due together


def scripts(events: list[str], seed: int, kind: Kind = RANDOM) -> list[list[str]]:
    """Random scripts of the chart's events and time passing in multiples of ``TICK``.

    Each ends with time passing, so the Python side runs on its virtual clock and the time
    events still due fire on both sides."""
    rng = random.Random(seed)
    letters = [*events, *kind.passing]
    return [
        [*(rng.choice(letters) for _ in range(kind.length - 1)), SETTLING] for _ in range(SEQUENCES)
    ]


def ties(trace: list[dict]) -> set[str]:
    """The kinds of time events the run took at one instant: ``nested`` where one's state
    lies inside the other's, ``parallel`` where the states lie in orthogonal regions. The
    runtime takes the innermost first (and regions in declaration order); the harness runs
    the PLC on the same virtual clock, so both fall due in one scan there too."""
    found: set[str] = set()
    due: dict[float, list[str]] = {}
    for record in trace:
        if record["kind"] == "event" and record["name"] == "after":
            due.setdefault(record["time"], []).append(record["state"])
    for paths in due.values():
        for index, path in enumerate(paths):
            for other in paths[index + 1 :]:
                inside = path.startswith(f"{other}/") or other.startswith(f"{path}/")
                found.add("nested" if inside else "parallel")
    return found


def chart_model(folder: Path, seed: int, kind: Kind = RANDOM) -> Path:
    """The chart of ``seed`` as ``d/<name>.lr`` under ``folder``."""
    model = folder / "d" / f"{kind.name}.lr"
    model.parent.mkdir(parents=True)
    model.write_text(kind.write(seed))
    return model


def steps_alike(
    home: Path, folder: Path, seed: int, kind: Kind = RANDOM
) -> tuple[str, list[list[str]], Counter]:
    """``("refused", [], …)`` for a chart the SFC target does not map, else ``("ran", scripts
    the compiled program steps unlike Python, scripts with time events due together by kind)``."""
    model = chart_model(folder, seed, kind)
    tied: Counter = Counter()
    try:
        text = generate("sfc", [model], search=[folder])[f"{kind.name}.st"]
    except GenerationError as error:
        assert REFUSED in str(error), str(error)
        return "refused", [], tied
    unit = sfc_unit(model, [folder])
    source = folder / "unit.st"
    source.write_text(text)
    compiled = iec2c(home, source, folder / "c")
    assert compiled.returncode == 0, f"seed {seed}: {compiled.stderr}{compiled.stdout}"
    differing = []
    events = [v.comment.removeprefix("event ") for v in unit.program.inputs[1:]]
    for number, script in enumerate(scripts(sorted(events), seed, kind)):
        scenario = Scenario(f"seed {seed} script {number}", model, events=script)
        run = drive(load_component(model, [folder]), {}, None, steps(script), None)
        tied.update(ties(run.trace))
        exe = folder / f"run{number}"
        built = gcc(home, folder / "c", driver_source(unit, scenario, 400_000), exe)
        assert built.returncode == 0, built.stderr
        expected = streams(comparable(python_trace(scenario, [folder]), unit), unit)
        if streams(sfc_trace(exe, unit), unit) != expected:
            differing.append(script)
    return "ran", differing, tied


def _judge(home: Path, folder: Path, seed: int, tally, kind: Kind = RANDOM) -> None:
    ran, differing, tied = steps_alike(home, folder, seed, kind)
    scripts = SEQUENCES if ran == "ran" else 0
    tally(
        "random charts on MatIEC: {alike} of {scripts} scripts on {charts} charts step like "
        "Python ({nested} with time events of nested states due together, {parallel} of "
        "parallel states), {refused} charts use a construct the SFC target does not map",
        charts=int(ran == "ran"),
        scripts=scripts,
        alike=scripts - len(differing),
        nested=tied["nested"],
        parallel=tied["parallel"],
        refused=int(ran == "refused"),
    )
    assert not differing, f"{kind.name} chart {seed} steps unlike Python on {differing[0]}"


@pytest.mark.parametrize("seed", range(CHARTS))
def test_random_charts_step_like_python(home: Path, tmp_path: Path, seed: int, tally) -> None:
    _judge(home, tmp_path, seed, tally)


@pytest.mark.slow
@pytest.mark.parametrize("seed", range(CHARTS, CHARTS + SWEEP))
def test_more_random_charts_step_like_python(home: Path, tmp_path: Path, seed: int, tally) -> None:
    _judge(home, tmp_path, seed, tally)


@pytest.mark.parametrize("seed", range(TIED))
def test_time_events_due_together_step_like_python(
    home: Path, tmp_path: Path, seed: int, tally
) -> None:
    """Charts whose time events of nested and orthogonal states often fall due at one
    instant: the innermost fires first, as at run time, and none is lost."""
    _judge(home, tmp_path, seed, tally, TIES)


@pytest.mark.slow
@pytest.mark.parametrize("seed", range(TIED, TIED + TIED_SWEEP))
def test_more_time_events_due_together_step_like_python(
    home: Path, tmp_path: Path, seed: int, tally
) -> None:
    _judge(home, tmp_path, seed, tally, TIES)
