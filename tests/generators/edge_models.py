"""Models at the edges of the SFC target that MatIEC and Beremiz judge alike: strings holding
comment delimiters, a chart name as long as a file name may be, Integer durations of time
events, time events due at one instant, and the vector models; each with the script it steps
through, where it has one."""

from __future__ import annotations

from pathlib import Path

from plc import Scenario
from vector_models import vector_models

LONG = "L" + "o" * 249  # a statechart's file, <name>.lr, takes up to 252 characters

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


def edge_model(folder: Path, name: str, text: str) -> Path:
    model = folder / "e" / f"{name}.lr"
    model.parent.mkdir(parents=True, exist_ok=True)
    model.write_text(text)
    return model


def edge_cases(folder: Path) -> dict[str, tuple[Path, Scenario | None]]:
    vectors = vector_models(folder)
    sensors = {"arm.reached": True}
    strings = edge_model(folder, "Quoted", STRINGS)
    durations = edge_model(folder, "Paced", DURATIONS)
    ties = edge_model(folder, "Tie", TIES)
    return {
        "vectors": (vectors, Scenario("vectors", vectors, sensors=sensors)),
        "strings": (strings, Scenario("strings", strings, events=["go", "go"])),
        "long name": (edge_model(folder, LONG, PLAIN.format(name=LONG)), None),
        "durations": (durations, Scenario("durations", durations, events=["+3000ms"])),
        "ties": (ties, Scenario("ties", ties, events=["+250ms", "a", "+500ms", "b", "+1s"])),
    }
