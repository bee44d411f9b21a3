"""Vectors on the SFC target: ST has array literals as initial values only and compares no
arrays, so a vector literal passed to a command or a skill becomes a local array, vectors
are compared element by element, and what has no ST counterpart is a finding at its place.
MatIEC judges the same model in test_matiec_findings.py."""

from __future__ import annotations

from pathlib import Path

import pytest
from generation import generate

from lightrocks.generators.sfc_iec61131.checker import check_sfc
from lightrocks.workbench.generators import GenerationError

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


@pytest.fixture(scope="module")
def work(tmp_path_factory: pytest.TempPathFactory) -> str:
    folder = tmp_path_factory.mktemp("vectors")
    text = generate("sfc", [vector_models(folder)], search=[folder])["Work.st"]
    assert not check_sfc(text)
    return text


def test_a_vector_literal_argument_becomes_a_local_array(work: str) -> None:
    """Assigned element by element before the call when it reads variables, the literal
    as initial value when constant."""
    assert "  P_1_damping : Damping6;" in work
    lines = [f"  P_1_damping[{i}] := {v};" for i, v in enumerate(["0.8", "P_1_k", *["0.8"] * 3])]
    assert "\n".join([*lines, "  P_1_damping[5] := 1.0;"]) in work
    assert "arm_2(move_1 := TRUE, move_damping := P_1_damping, move_n := 2);" in work
    assert "  H_damping : Damping6 := [0.9, 0.9, 0.9, 0.9, 0.9, 0.9];" in work
    assert "S_1_gains[0] := k;" in work
    assert "S_1_fb(execute := TRUE, times := 2, gains := S_1_gains);" in work


def test_positional_arguments_name_the_parameters_in_order(work: str) -> None:
    assert "  P_1_k := 0.75;" in work


def test_vectors_are_compared_element_by_element(work: str) -> None:
    felt = " AND ".join(f"(arm_2.felt[{i}] = 0.0)" for i in range(6))
    assert f"arm_2.reached AND ({felt})" in work
    gains = " AND ".join(f"(gains[{i}] = 0.0)" for i in range(6))
    assert f"(NOT ({gains}))" in work


@pytest.mark.parametrize(
    ("guard", "what"),
    [
        (
            "[transl(0 m, 0 m, 0 m) == transl(0 m, 0 m, d)]",
            "compares numbers, Booleans, strings and vectors",
        ),
        ("[[k, 1][0] > 0]", "writes a vector literal where it is assigned, passed or compared"),
    ],
)
def test_what_st_cannot_say_is_a_finding_at_its_place(
    tmp_path: Path, guard: str, what: str
) -> None:
    model = tmp_path / "Odd.lr"
    model.write_text(
        "statechart Odd {\n  parameters {\n    Real k = 0;\n    Length d = 0 m;\n  }\n"
        f"  initial state A;\n  final state Z;\n  A -> Z {guard} go;\n}}\n"
    )
    with pytest.raises(GenerationError, match=rf"^{model}:8:\d+: the SFC target {what}"):
        generate("sfc", [model], search=[tmp_path])
