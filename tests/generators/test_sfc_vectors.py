"""Vectors on the SFC target: ST has array literals as initial values only and compares no
arrays, so a vector literal passed to a command or a skill becomes a local array, vectors
are compared element by element, and what has no ST counterpart is a finding at its place.
MatIEC judges the same model in test_matiec_findings.py."""

from __future__ import annotations

from pathlib import Path

import pytest
from generation import generate
from vector_models import vector_models

from lightrocks.generators.sfc_iec61131.checker import check_sfc
from lightrocks.workbench.generators import GenerationError


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
