"""The SFC target judged by MatIEC: every generated file compiles and links, and the compiled
program steps through the same states and outcomes as the Python runtime on a dry run.

Needs MatIEC (``make judges``, ``MATIEC=<dir>`` or ``/opt/matiec``, see docs/generators.md)
and gcc; skipped with the reason where they are absent, failed in CI. Every file is compiled
with MatIEC's defaults and with Beremiz's options (see ``plc.iec2c``).
"""

from __future__ import annotations

import os
import re
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest
from generation import EXAMPLES, generate
from mix_models import every_mix
from plc import (
    Scenario,
    comparable,
    compile_c,
    driver_source,
    gcc,
    iec2c,
    python_trace,
    sfc_trace,
    sfc_unit,
    streams,
)

from lightrocks.generators.sfc_iec61131.ir import Unit
from lightrocks.generators.sfc_iec61131.reserved import is_reserved, is_reserved_for_unit

CASES = ("screwing", "din_rail", "din_rail_ahead", "plain")
SCREW_TASK = EXAMPLES / "screwing" / "tasks" / "ScrewTask.lr"
SCREW_IN = EXAMPLES / "screwing" / "skills" / "ScrewIn.lr"
RAIL_TASK = EXAMPLES / "din_rail" / "tasks" / "AssembleRail.lr"
AHEAD_TASK = EXAMPLES / "din_rail_ahead" / "tasks" / "AssembleRailAhead.lr"
TURNSTILE = EXAMPLES / "plain" / "Turnstile.lr"
MODELS = Path(__file__).parent / "models"
PLANT = MODELS / "plant"
PRESS = PLANT / "Press.lr"
SEARCH = [MODELS, EXAMPLES]

SCENARIOS = [
    Scenario("screw nominal", SCREW_TASK),
    Scenario("screw not gripped", SCREW_TASK, sensors={"gripper.holding": False}),
    Scenario("screw localize timeout", SCREW_TASK, {"camera.localize": ["timeout"]}),
    Scenario("screw gripper fault", SCREW_TASK, {"gripper.close": ["error"]}),
    Scenario("screw arm fault", SCREW_TASK, {"robot.moveCartesian": [None, None, "error"]}),
    Scenario("screw arm timeout", SCREW_TASK, {"robot.moveCartesian": [None, "timeout"]}),
    Scenario("screw-in alone", SCREW_IN),
    Scenario("screw-in regrasp fault", SCREW_IN, {"gripper.close": [None, "error"]}),
    Scenario("rail nominal", RAIL_TASK),
    Scenario("rail not gripped", RAIL_TASK, sensors={"gripper.holding": False}),
    Scenario("rail localize timeout", RAIL_TASK, {"camera.localize": [None, "timeout"]}),
    Scenario("rail arm fault", RAIL_TASK, {"robot.moveCartesian": [None] * 6 + ["error"]}),
    Scenario("rail release fault", RAIL_TASK, {"gripper.open": [None, None, "error"]}),
    Scenario(
        "turnstile passages",
        TURNSTILE,
        events=["coin", "push", "coin", "coin", "push", "service", "resume", "shutdown"],
    ),
    Scenario("turnstile ignored events", TURNSTILE, events=["push", "resume", "coin", "shutdown"]),
    Scenario("press job", PRESS, events=["go", "load", "again", "release", "go", "bail", "stop"]),
    Scenario(
        "press broken invariant", PRESS, events=["go", "load", *["again"] * 4, "fixed", "stop"]
    ),
    Scenario("press idle stop", PRESS, events=["load", "stop"]),
    Scenario("press stop in job", PRESS, events=["go", "load", "stop"]),
]


# Statechart constructs beyond plain states, each against the Python runtime.
CONSTRUCTS = [
    Scenario(name, PLANT / f"{model}.lr", events=events.split(","))
    for name, model, events in [
        ("internal transitions", "Counter",
         "tick,tick,check,tick,check,tick,check,hold,resume,hold,stop"),
        ("internal outer guard", "Counter", "tick,tick,tick,tick,tick,tick,check,stop"),
        ("choice branches and error", "Router", "go,back,go,back,go,go,go,back,stop"),
        ("choice else", "Router", "go,back,go,back,stop"),
        ("time events", "Lamp", "push,+150ms,push,+50ms,+100ms,+1000ms,off,push,+1300ms,quit"),
        ("time event left early", "Lamp", "push,+50ms,off,+200ms,push,+80ms,off,quit"),
        ("shallow and deep history", "Recorder",
         "go,start,faster,pause,jump,pause,resume,faster,finish,again,start,faster,pause,jump,"
         "pause,reset,go,pause,resume,finish"),
        ("history without memory", "Recorder", "again,pause,resume"),
        ("time events at one deadline", "Chime", "go,+150ms,+50ms,+100ms,go,+300ms,quit"),
        ("history forgets an end condition", "Recorder",
         "go,start,faster,abort,again,start,pause,jump,abort,go,pause,resume"),
        ("the player of the reference", "Player",
         "play,+600ms,next,pause,resume,pause,stop,play,pause,resume,+3200ms,stop"),
        ("regions take one event", "Crossing", "start,+150ms,press,press,press,press,quit"),
        ("regions join and are left", "Crossing", "start,go,close,stop,close,start,reset,quit"),
        ("an inner state takes the event first", "Crossing",
         "start,press,press,press,+150ms,press,go,quit"),
        ("regions of a statechart", "Junction", "press,+1100ms,press,go,close,stop,press,close"),
        ("regions of a statechart join", "Junction", "+1200ms,press,press,close"),
        ("integer times length in a guard", "Hopper",
         "open,add,add,take,open,add,add,add,take,take,quit"),
        ("integer times duration in a time event", "Hopper",
         "open,add,add,add,take,+250ms,take,open,add,take,+350ms,quit"),
        ("integer division and remainder", "Hopper",
         "open,add,add,add,take,+350ms,quit"),
        ("defaults folded to constants", "Dial", "up,up,down,up,up,stop,down,up,down,down"),
        ("object attributes start from their defaults", "Stock",
         "check,take,take,check,refill,take,check,stop"),
        ("an entering event is taken once", "Tally", "add,add,take,add,add,add,take"),
        ("an event moving inside a composite is taken once", "Tally",
         "fill,add,add,take,fill,add,add,add,take"),
        ("an event entering through history is taken once", "Tally",
         "keep,hold,add,add,take,quit"),
        ("an event entering a region is taken once", "Tally",
         "hold,add,take,hold,add,add,take"),
        ("an event a region takes is not taken around it", "Shuttle",
         "move,toggle,move,toggle,toggle,move,quit"),
        ("history of the state a transition leaves", "Rewind",
         "next,again,back,again,next,again,quit"),
        ("a budget ends a skill", "Oven", "quick,+900ms,slow,+1100ms,reset,quit"),
        ("a budget ties with an inner time event", "Oven", "tight,+1100ms,quick,+500ms,quit"),
    ]
] + [
    # Regions of a task: the arm snaps a terminal while the camera looks ahead. Only faults
    # whose place the runtime's rounds and the PLC's scans agree on (docs/generators.md).
    Scenario("ahead nominal", AHEAD_TASK),
    Scenario("ahead not gripped", AHEAD_TASK, sensors={"gripper.holding": False}),
    Scenario("ahead look-ahead timeout", AHEAD_TASK, {"camera.localize": [None, None, "timeout"]}),
    Scenario("ahead snap fault", AHEAD_TASK, {"robot.moveCartesian": [None] * 5 + ["error"]}),
]  # fmt: skip


def test_the_reserved_names_cover_matiecs_library(home: Path) -> None:
    """Every identifier of MatIEC's library is reserved for unit names, and every block or
    function it declares for every name."""
    words: set[str] = set()
    blocks: set[str] = set()
    for library in (home / "lib").glob("*.txt"):
        text = re.sub(r"\(\*.*?\*\)|'[^']*'|\{[^}]*\}", " ", library.read_text(errors="replace"),
                      flags=re.DOTALL)  # fmt: skip
        words |= set(re.findall(r"\b[A-Za-z_]\w*\b", text))
        blocks |= set(re.findall(r"\bFUNCTION(?:_BLOCK)?\s+([A-Za-z_]\w*)", text))
    assert len(blocks) > 100, "MatIEC's library declares its functions in lib/*.txt"
    assert sorted(w for w in words if not is_reserved_for_unit(w)) == []
    assert sorted(b for b in blocks if not is_reserved(b)) == []


def _compile(home: Path, source: Path, model: Path, search: list[Path] = SEARCH) -> str:
    """Empty when MatIEC accepts ``source`` and gcc links its C; else what went wrong."""
    out = source.with_suffix("")
    compiled = iec2c(home, source, out)
    if compiled.returncode != 0:
        return f"iec2c: {compiled.stderr}{compiled.stdout}"
    driver = driver_source(sfc_unit(model, search), Scenario("link", model), max_cycles=1)
    built = gcc(home, out, driver, out / "program")
    return "" if built.returncode == 0 else f"gcc: {built.stderr}"


@pytest.mark.slow
def test_every_generated_file_compiles_and_links(home: Path, tmp_path: Path, tally) -> None:
    jobs = []
    for case in CASES:
        models = sorted((EXAMPLES / case).rglob("*.lr"))
        for name, text in generate("sfc", models).items():
            source = tmp_path / case / name
            source.parent.mkdir(parents=True, exist_ok=True)
            source.write_text(text)
            jobs.append((source, next(m for m in models if m.stem == source.stem)))
    with ThreadPoolExecutor(max_workers=os.cpu_count() or 1) as pool:
        failures = list(pool.map(lambda job: _compile(home, *job), jobs))
    accepted = sum(not f.startswith("iec2c") for f in failures)
    linked = failures.count("")
    tally(
        "MatIEC accepted {accepted}/{files}, gcc compiled and linked {linked}/{files}",
        accepted=accepted,
        linked=linked,
        files=len(jobs),
    )
    assert linked == len(jobs) >= 16, [f for f in failures if f]


@pytest.mark.slow
def test_integers_meeting_reals_compile_and_link(home: Path, tmp_path: Path, tally) -> None:
    model = every_mix(tmp_path / "models")
    source = tmp_path / "Mix.st"
    source.write_text(generate("sfc", [model], search=[tmp_path / "models"])["Mix.st"])
    failure = _compile(home, source, model, [tmp_path / "models"])
    tally(
        "MatIEC accepted {accepted}/{files}, gcc compiled and linked {linked}/{files}",
        accepted=int(not failure.startswith("iec2c")),
        linked=int(not failure),
        files=1,
    )
    assert not failure


def _compiled(home: Path, out: Path, model: Path) -> tuple[Unit, Path]:
    """The unit of ``model`` and the folder of its compiled C, ready to link with drivers."""
    unit = sfc_unit(model, SEARCH)
    out.mkdir()
    source = out / "unit.st"
    source.write_text(generate("sfc", [model], search=SEARCH)[f"{unit.top.name}.st"])
    assert iec2c(home, source, out / "c").returncode == 0, model.name
    objects = compile_c(home, out / "c")
    assert isinstance(objects, list), objects.stderr
    return unit, out / "c"


def _steps_alike(home: Path, out: Path, scenario: Scenario, unit: Unit, c: Path) -> bool:
    out.mkdir()
    built = gcc(home, c, driver_source(unit, scenario, 400_000), out / "run")
    assert built.returncode == 0, built.stderr
    expected = comparable(python_trace(scenario, SEARCH), unit)
    assert expected, f"{scenario.name}: the dry run produced no comparable event"
    return streams(sfc_trace(out / "run", unit), unit) == streams(expected, unit)


def _differing(home: Path, folder: Path, scenarios: list, tally, what: str) -> list[str]:
    """The names of the scenarios whose compiled program steps unlike Python, run in
    parallel; the count of those alike goes to the summary as ``what``. Each model is
    compiled once, and linked with the driver of each of its scenarios."""
    models = sorted({s.model for s in scenarios})
    with ThreadPoolExecutor(max_workers=os.cpu_count() or 1) as pool:
        compiled = dict(
            zip(
                models,
                pool.map(
                    lambda i: _compiled(home, folder / f"unit{i}", models[i]), range(len(models))
                ),
                strict=True,
            )
        )
        alike = list(
            pool.map(
                lambda i: _steps_alike(
                    home, folder / str(i), scenarios[i], *compiled[scenarios[i].model]
                ),
                range(len(scenarios)),
            )
        )
    differing = [s.name for s, same in zip(scenarios, alike, strict=True) if not same]
    tally(
        "{alike}/{scenarios} " + what + " on MatIEC",
        alike=len(scenarios) - len(differing),
        scenarios=len(scenarios),
    )
    return differing


@pytest.mark.slow
def test_compiled_program_steps_like_python(home: Path, tmp_path: Path, tally) -> None:
    differing = _differing(home, tmp_path, SCENARIOS, tally, "scenarios step like Python")
    assert not differing, f"the compiled program steps differently in: {differing}"


@pytest.mark.slow
def test_statechart_constructs_step_like_python(home: Path, tmp_path: Path, tally) -> None:
    what = "statechart-construct scenarios step like Python"
    differing = _differing(home, tmp_path, CONSTRUCTS, tally, what)
    assert not differing, f"the compiled program steps differently in: {differing}"
