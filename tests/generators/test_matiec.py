"""The SFC target judged by MatIEC: every generated file compiles and links, and the compiled
program steps through the same states and outcomes as the Python runtime on a dry run.

Needs MatIEC (``MATIEC=<dir>`` or ``/opt/matiec``, see docs/generators.md) and gcc; skipped
with the reason where they are absent.
"""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest
from conftest import EXAMPLES, generate
from plc import (
    Scenario,
    comparable,
    driver_source,
    gcc,
    iec2c,
    matiec_home,
    python_trace,
    sfc_trace,
)

from lightrocks.generators.sfc_iec61131 import build_unit
from lightrocks.languages.lightrocks.analysis import analysis
from lightrocks.workbench.check import check

CASES = ("screwing", "din_rail", "plain")
SCREW_TASK = EXAMPLES / "screwing" / "tasks" / "ScrewTask.lr"
SCREW_IN = EXAMPLES / "screwing" / "skills" / "ScrewIn.lr"
RAIL_TASK = EXAMPLES / "din_rail" / "tasks" / "AssembleRail.lr"
TURNSTILE = EXAMPLES / "plain" / "Turnstile.lr"

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
]


@pytest.fixture(scope="module")
def home() -> Path:
    found = matiec_home()
    if found is None:
        pytest.skip("MatIEC not found: set MATIEC=<dir> or build it in /opt/matiec")
    if shutil.which("gcc") is None:
        pytest.skip("gcc not found")
    return found


def _unit(model: Path):
    context = check([model], [EXAMPLES])
    result = analysis(context)
    top = next(c for c in result.models.components if c.loaded.path == model.resolve())
    return build_unit(top, result.typing)


def test_every_generated_file_compiles_and_links(home: Path, tmp_path: Path) -> None:
    accepted = linked = total = 0
    for case in CASES:
        models = sorted((EXAMPLES / case).rglob("*.lr"))
        for name, text in generate("sfc", models).items():
            total += 1
            source = tmp_path / case / name
            source.parent.mkdir(parents=True, exist_ok=True)
            source.write_text(text)
            out = tmp_path / case / source.stem
            compiled = iec2c(home, source, out)
            assert compiled.returncode == 0, f"{case}/{name}: {compiled.stderr}{compiled.stdout}"
            accepted += 1
            model = next(m for m in models if m.stem == source.stem)
            driver = driver_source(_unit(model), Scenario("link", model), max_cycles=1)
            built = gcc(home, out, driver, out / "program")
            assert built.returncode == 0, f"{case}/{name}: {built.stderr}"
            linked += 1
    print(f"\nMatIEC accepted {accepted}/{total}, gcc compiled and linked {linked}/{total}")
    assert total >= 16


def test_compiled_program_steps_like_python(home: Path, tmp_path: Path) -> None:
    differing = []
    for index, scenario in enumerate(SCENARIOS):
        unit = _unit(scenario.model)
        text = generate("sfc", [scenario.model])[f"{unit.top.name}.st"]
        source = tmp_path / f"{index}.st"
        source.write_text(text)
        out = tmp_path / str(index)
        assert iec2c(home, source, out).returncode == 0, scenario.name
        built = gcc(home, out, driver_source(unit, scenario, 400_000), out / "run")
        assert built.returncode == 0, built.stderr
        expected = comparable(python_trace(scenario, [EXAMPLES]), unit)
        assert expected, f"{scenario.name}: the dry run produced no comparable event"
        if sfc_trace(out / "run", unit) != expected:
            differing.append(scenario.name)
    print(f"\n{len(SCENARIOS) - len(differing)}/{len(SCENARIOS)} scenarios step like Python")
    assert not differing, f"the compiled program steps differently in: {differing}"
