"""The vector models the SFC tests and MatIEC's edge cases share: a bench whose arm takes and
senses vectors, and skills that pass, compare and forward them."""

from __future__ import annotations

from pathlib import Path

DOMAIN = """package v;

device Arm {
  command move(Damping6 damping = [0.7, 0.7, 0.7, 0.7, 0.7, 0.7], Integer n = 1);
  sensor Boolean reached;
  sensor Damping6 felt;
}

<<scene="none">> cell Bench {
  arm : Arm;
}
"""


PUSH = """package v;

import v.Bench;

<<action>> statechart Push {
  parameters {
    Real k = 0.5;
  }

  do / arm.move(damping = [0.8, k, 0.8, 0.8, 0.8, 1], n = 2);

  end condition reached [arm.reached];
}
"""


HOLD = """package v;

import v.Bench;

<<action>> statechart Hold {
  do / arm.move([0.9, 0.9, 0.9, 0.9, 0.9, 0.9]);

  end condition reached [arm.reached && arm.felt == [0, 0, 0, 0, 0, 0]];
}
"""


PRESS = """package v;

<<skill>> statechart Press {
  parameters {
    Integer times = 1;
    Damping6 gains = [0, 0, 0, 0, 0, 0];
  }

  <<import="Hold">> initial state H;
  final state Z;
  H -> Z [gains != [0, 0, 0, 0, 0, 0]] reached;
}
"""


WORK = """package v;

<<skill>> statechart Work {
  parameters {
    Real k = 0.25;
  }

  <<import="Push">> initial state P(0.75);
  <<import="Hold">> state H;
  <<import="Press">> state S(2, [k, 1, 1, 1, 1, 1]);
  final state Z;
  P -> H reached;
  H -> S reached;
  S -> Z;
}
"""


def vector_models(folder: Path) -> Path:
    """The package ``v`` under ``folder``; returns the skill ``Work``."""
    package = folder / "v"
    package.mkdir(parents=True, exist_ok=True)
    for name, text in {"Bench.lrd": DOMAIN, "Push.lr": PUSH, "Hold.lr": HOLD}.items():
        (package / name).write_text(text)
    (package / "Press.lr").write_text(PRESS)
    (package / "Work.lr").write_text(WORK)
    return package / "Work.lr"
