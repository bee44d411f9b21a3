"""Models at the edges of the SFC target, judged by MatIEC with its defaults and with Beremiz's
options: vector literals passed to commands and skills and compared, strings holding comment
delimiters, a chart name as long as a file name may be, Integer durations of time events, and
three time events of nested states due at one instant though different stimuli entered their
states (the innermost first, none lost). Each compiles and links; those with a script also
step like Python."""

from __future__ import annotations

from pathlib import Path

import pytest
from generation import generate
from plc import Scenario, comparable, driver_source, gcc, iec2c, python_trace, sfc_trace, streams
from test_file_names import LONG
from test_matiec import _unit
from test_sfc_vectors import vector_models

STRINGS = """package e;

statechart Quoted {
  parameters {
    String s = "a (* b";
    String t = "(* c *)";
  }

  initial state A;
  state C;
  final state B;
  A -> C [s == "a (* b"] go;
  C -> B [t != "d *)"] go;
}
"""

DURATIONS = """package e;

statechart Paced {
  parameters {
    Integer n = 2;
    Integer m = 3;
  }

  initial state A {
    internal after(n * 100 ms) / { n = n + 1; };
  }
  state C;
  state D;
  final state B;
  A -> C after((n + 1) * 250 ms);
  C -> D after(100 ms * (n % m) + 1 s);
  D -> B after(min(n, m) * 100 ms);
}
"""

TIES = """package e;

statechart Tie {
  parameters {
    Integer hits = 0;
  }

  initial state O {
    internal after(750 ms) / { hits = hits * 10 + 2; };
    initial state A;
    state I;
    state J;
    A -> I a;
    I -> J after(500 ms) / { hits = hits * 10 + 1; };
  }
  state X;
  final state Z;
  O -> X after(750 ms);
  X -> Z [hits == 12] b;
}
"""

PLAIN = """package e;

statechart {name} {{
  initial state A;
  final state B;
  A -> B go;
}}
"""


def _model(folder: Path, name: str, text: str) -> Path:
    model = folder / "e" / f"{name}.lr"
    model.parent.mkdir(parents=True, exist_ok=True)
    model.write_text(text)
    return model


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
    unit = _unit(model, [search])
    run = scenario or Scenario("link", model)
    built = gcc(home, out / "c", driver_source(unit, run, 400_000), out / "run")
    if built.returncode != 0:
        return f"gcc: {built.stderr}"
    if scenario is None:
        return ""
    expected = streams(comparable(python_trace(scenario, [search]), unit), unit)
    found = streams(sfc_trace(out / "run", unit), unit)
    return "" if found == expected else f"steps unlike Python: {found} != {expected}"


def _cases(folder: Path) -> dict[str, tuple[Path, Scenario | None]]:
    vectors = vector_models(folder)
    sensors = {"arm.reached": True}
    strings = _model(folder, "Quoted", STRINGS)
    durations = _model(folder, "Paced", DURATIONS)
    ties = _model(folder, "Tie", TIES)
    return {
        "vectors": (vectors, Scenario("vectors", vectors, sensors=sensors)),
        "strings": (strings, Scenario("strings", strings, events=["go", "go"])),
        "long name": (_model(folder, LONG, PLAIN.format(name=LONG)), None),
        "durations": (durations, Scenario("durations", durations, events=["+3000ms"])),
        "ties": (ties, Scenario("ties", ties, events=["+250ms", "a", "+500ms", "b", "+1s"])),
    }


@pytest.mark.slow
@pytest.mark.parametrize("case", ["vectors", "strings", "long name", "durations", "ties"])
def test_edge_models_compile_link_and_step(home: Path, tmp_path: Path, tally, case: str) -> None:
    model, scenario = _cases(tmp_path / "models")[case]
    failure = _judge(home, tmp_path / "out", model, tmp_path / "models", scenario)
    tally(
        "MatIEC accepted {accepted}/{files}, gcc compiled and linked {linked}/{files}",
        accepted=int(not failure.startswith("iec2c")),
        linked=int(not failure.startswith(("iec2c", "gcc"))),
        files=1,
    )
    assert not failure
