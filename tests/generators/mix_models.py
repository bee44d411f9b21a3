"""Models where Integers and Reals meet, which the SFC target's tests and MatIEC judge alike:
a skill that assigns, compares and passes them every way (``every_mix``)."""

from __future__ import annotations

from pathlib import Path

DOMAIN = """package t;

device Scale {
  command weigh(Real factor = 1, Integer rounds = 2, Length span = 0 mm);
  command tally() returns Integer;
  sensor Integer ticks;
}

<<scene="none">> cell Bench {
  scale : Scale;
}
"""


WEIGH = """package t;

import t.Bench;

<<action>> statechart Weigh {
  parameters {
    Integer rounds = 3;
    Real factor = 2;
  }

  do / scale.weigh(factor = rounds, rounds = rounds, span = 0);

  end condition settled [scale.ticks > factor * 0.5];
}
"""


TALLY = """package t;

import t.Bench;

<<action>> statechart Tally {
  parameters {
    Real total = 0;
  }

  do / total = scale.tally();

  end condition counted [scale.ticks > 0];
}
"""


DOSE = """package t;

<<skill>> statechart Dose {
  parameters {
    Real factor = 1;
    Length reach = 0;
  }
  initial state A;
  final state Z;
  A -> Z go;
}
"""


PARAMETERS = "Length x = 5 mm;\n    Real ratio = 0;\n    Damping6 v = [0, 0, 0, 0, 0, 0];"
ASSIGNMENTS = [
    ("x = count * 2 mm;", "x := DINT_TO_REAL(count) * 0.002;"),
    ("x = 2 mm * count;", "x := 0.002 * DINT_TO_REAL(count);"),
    ("x = count * 1 mm + x;", "x := (DINT_TO_REAL(count) * 0.001) + x;"),
    ("x = x - count * 1 mm;", "x := x - (DINT_TO_REAL(count) * 0.001);"),
    ("ratio = ratio + count;", "ratio := ratio + DINT_TO_REAL(count);"),
    ("ratio = count;", "ratio := DINT_TO_REAL(count);"),
    ("ratio = 2;", "ratio := 2.0;"),
    ("ratio = -count;", "ratio := DINT_TO_REAL(-count);"),
    ("ratio = -(count * 0.5);", "ratio := -(DINT_TO_REAL(count) * 0.5);"),
    ("ratio = max(count, 0.5);", "ratio := MAX(DINT_TO_REAL(count), 0.5);"),
    (
        "ratio = min(count, 4) + abs(ratio);",
        "ratio := DINT_TO_REAL(MIN(count, 4)) + ABS(ratio);",
    ),
    ("ratio = v[ratio] + v[count];", "ratio := v[TRUNC(ratio)] + v[count];"),
    ("count = count * 2 + 1;", "count := (count * 2) + 1;"),
    ("count = count - min(-3, 2);", "count := count - (-3);"),
]
GUARDS = [
    ("[count * 2 mm > x]", "(DINT_TO_REAL(count) * 0.002) > x"),
    ("[count == ratio]", "DINT_TO_REAL(count) = ratio"),
    ("[ratio > 0]", "ratio > 0.0"),
    ("[count > 0]", "count > 0"),
    ("[count <= 2.5]", "DINT_TO_REAL(count) <= 2.5"),
]


def mix_model(tmp_path: Path, parameters: str, entry: str = "", more: str = "") -> Path:
    """A skill ``t.Mix`` with an Integer ``count`` (3) and the given declarations, its
    entry statements and further states or transitions; the cell, an action and a skill it
    may use lie beside it."""
    package = tmp_path / "t"
    package.mkdir(parents=True, exist_ok=True)
    (package / "Bench.lrd").write_text(DOMAIN)
    (package / "Weigh.lr").write_text(WEIGH)
    (package / "Dose.lr").write_text(DOSE)
    (package / "Tally.lr").write_text(TALLY)
    model = package / "Mix.lr"
    model.write_text(
        "package t;\n\n<<skill>> statechart Mix {\n"
        f"  parameters {{\n    Integer count = 3;\n    {parameters}\n  }}\n"
        f"  initial state A {{\n    entry / {{ {entry} }}\n  }}\n"
        f"  state B;\n  final state Z;\n  A -> B go;\n  B -> Z stop;\n  {more}\n}}\n"
    )
    return model


def every_mix(tmp_path: Path) -> Path:
    """One model with every kind of meeting above, for MatIEC to judge."""
    entry = " ".join(e for e, _ in ASSIGNMENTS)
    entry += " ratio = count / 2; rest = count % 4; ratio = ratio % count;"
    more = [f"B -> A {guard} back;" for guard, _ in GUARDS]
    more += [
        "B -> A after(count * 100 ms);",
        '<<import="Dose">> state D(factor = count, reach = 0);',
        '<<import="Weigh">> state W(rounds = count, factor = count);',
        "A -> D next;",
        '<<import="Tally">> state T;',
        "D -> W;",
        "W -> T;",
        "T -> A;",
    ]
    parameters = f"{PARAMETERS}\n    Integer rest = 0;"
    return mix_model(tmp_path, parameters, entry, "\n  ".join(more))
