"""Models at the edges of the SFC target, judged by MatIEC with its defaults and with Beremiz's
options: vector literals passed to commands and skills and compared, strings holding comment
delimiters, a chart name as long as a file name may be, Integer durations of time events, and
three time events of nested states due at one instant though different stimuli entered their
states (the innermost first, none lost). Each compiles and links; those with a script also
step like Python."""

from __future__ import annotations

from pathlib import Path

import pytest
from edge_models import edge_cases
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
    streams,
)


def _judge(home: Path, out: Path, model: Path, search: Path, scenario: Scenario | None) -> str:
    """Empty when MatIEC accepts the unit of ``model``, gcc links it and, given a scenario,
    the program steps like Python; else what went wrong."""
    [text] = generate("sfc", [model], search=[search]).values()
    out.mkdir(parents=True)
    source = out / "unit.st"
    source.write_text(text)
    compiled = iec2c(home, source, out / "c")
    if compiled.returncode != 0:
        return f"iec2c: {compiled.stderr}{compiled.stdout}"
    unit = sfc_unit(model, [search])
    run = scenario or Scenario("link", model)
    built = gcc(home, out / "c", driver_source(unit, run, 400_000), out / "run")
    if built.returncode != 0:
        return f"gcc: {built.stderr}"
    if scenario is None:
        return ""
    expected = streams(comparable(python_trace(scenario, [search]), unit), unit)
    found = streams(sfc_trace(out / "run", unit), unit)
    return "" if found == expected else f"steps unlike Python: {found} != {expected}"


@pytest.mark.slow
@pytest.mark.parametrize("case", ["vectors", "strings", "long name", "durations", "ties"])
def test_edge_models_compile_link_and_step(home: Path, tmp_path: Path, tally, case: str) -> None:
    model, scenario = edge_cases(tmp_path / "models")[case]
    failure = _judge(home, tmp_path / "out", model, tmp_path / "models", scenario)
    tally(
        "MatIEC accepted {accepted}/{files}, gcc compiled and linked {linked}/{files}",
        accepted=int(not failure.startswith("iec2c")),
        linked=int(not failure.startswith(("iec2c", "gcc"))),
        files=1,
    )
    assert not failure
