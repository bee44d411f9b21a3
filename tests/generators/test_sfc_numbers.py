"""Integers (DINT) and Reals (REAL) in the SFC target: IEC 61131-3 converts neither into the
other, so every place they meet gets an explicit conversion that computes what the Python
runtime computes. MatIEC judges the same constructs in test_matiec.py (model Hopper)."""

from __future__ import annotations

from pathlib import Path

import pytest
from generation import generate
from mix_models import ASSIGNMENTS, GUARDS, PARAMETERS, mix_model

from lightrocks.workbench.check import check
from lightrocks.workbench.generators import GenerationError, GenerationRequest, load_generator


def _mix(tmp_path: Path, parameters: str, entry: str = "", more: str = "") -> str:
    model = mix_model(tmp_path, parameters, entry, more)
    return generate("sfc", [model], search=[tmp_path])["Mix.st"]


@pytest.mark.parametrize(("entry", "found"), ASSIGNMENTS)
def test_an_integer_that_meets_a_real_becomes_real(tmp_path, entry: str, found: str) -> None:
    assert found in _mix(tmp_path, PARAMETERS, entry)


def test_integer_division_is_true_division_as_at_run_time(tmp_path) -> None:
    text = _mix(tmp_path, "Real ratio = 0;", "ratio = count / 2; ratio = 7 / 2;")
    assert "ratio := DINT_TO_REAL(count) / 2.0;" in text
    assert "ratio := 3.5;" in text  # a constant is folded as the runtime computes it


def test_the_remainder_is_floored_as_at_run_time(tmp_path) -> None:
    text = _mix(
        tmp_path,
        "Integer rest = 0;\n    Real ratio = 0;",
        "rest = count % 4; ratio = ratio % count;",
    )
    assert "rest := (count MOD 4 + 4) MOD 4;" in text
    truncated = "ratio - DINT_TO_REAL(count) * DINT_TO_REAL(TRUNC(ratio / DINT_TO_REAL(count)))"
    assert f"({truncated} + DINT_TO_REAL(count)) - DINT_TO_REAL(count)" in text


def test_floored_remainder_formula_matches_python() -> None:
    """``((a MOD b) + b) MOD b`` with ST's truncated MOD is Python's ``%``."""

    def st_mod(a: int, b: int) -> int:
        return abs(a) % abs(b) * (1 if a >= 0 else -1)

    for a in range(-9, 10):
        for b in (-4, -3, -1, 1, 3, 4):
            assert st_mod(st_mod(a, b) + b, b) == a % b, (a, b)


@pytest.mark.parametrize(
    ("guard", "found"),
    GUARDS,
)
def test_guards_compare_integers_with_reals_as_real(tmp_path, guard: str, found: str) -> None:
    text = _mix(tmp_path, "Length x = 5 mm;\n    Real ratio = 0;", more=f"B -> A {guard} back;")
    assert found in text


def test_a_time_event_of_an_integer_times_a_duration(tmp_path) -> None:
    text = _mix(tmp_path, "Real ratio = 0;", more="B -> A after(count * 100 ms);")
    assert "PT := REAL_TO_TIME(DINT_TO_REAL(count) * 0.1)" in text


def test_defaults_are_written_as_their_declared_type(tmp_path) -> None:
    text = _mix(
        tmp_path,
        "Real ratio = 2;\n    Length x = 0;\n    Integer whole = -4;\n"
        "    Damping6 v = [1, 0.5, 0, 0, 0, 2];",
    )
    for declaration in (
        "ratio : REAL := 2.0;",
        "x : REAL := 0.0;",
        "whole : DINT := -4;",
        "count : DINT := 3;",
        "v : Damping6 := [1.0, 0.5, 0.0, 0.0, 0.0, 2.0];",
    ):
        assert declaration in text


def test_vector_literal_elements_take_the_element_type(tmp_path) -> None:
    text = _mix(tmp_path, "Damping6 v = [0, 0, 0, 0, 0, 0];", "v = [count, 1, 0.5, 0, 0, 0];")
    assert "v[0] := DINT_TO_REAL(count);" in text
    assert "v[1] := 1.0;" in text
    assert "v[2] := 0.5;" in text


def test_arguments_take_the_declared_type(tmp_path) -> None:
    more = '<<import="Dose">> state D(factor = count, reach = 0);\n  A -> D next;\n  D -> A;'
    text = _mix(tmp_path, "Real ratio = 0;", more=more)
    assert "execute := TRUE, factor := DINT_TO_REAL(count), reach := 0.0" in text


def test_device_commands_take_the_declared_type(tmp_path) -> None:
    more = '<<import="Weigh">> state W;\n  A -> W next;\n  W -> A;'
    text = _mix(tmp_path, "Real ratio = 0;", more=more)
    # command defaults, then the call of the inlined action
    for declaration in ("weigh_factor : REAL := 1.0;", "weigh_rounds : DINT := 2;"):
        assert declaration in text
    assert "weigh_factor := DINT_TO_REAL(W_rounds), weigh_rounds := W_rounds" in text
    assert "weigh_span := 0.0" in text
    assert "W_factor : REAL := 2.0;" in text
    assert "DINT_TO_REAL(scale_2.ticks) > (W_factor * 0.5)" in text


def test_an_integer_a_command_returns_is_stored_as_real(tmp_path) -> None:
    more = '<<import="Tally">> state T;\n  A -> T next;\n  T -> A;'
    text = _mix(tmp_path, "Real ratio = 0;", more=more)
    assert "T_1_total := DINT_TO_REAL(scale_2.tally_result);" in text


@pytest.mark.parametrize(
    ("parameters", "entry", "place"),
    [
        ("Real ratio = 0;", "count = count / 2;", "Mix.lr:9:23"),
        ("Real ratio = 0;", "count = ratio;", "Mix.lr:9:23"),
        ("Integer whole = 2.5;", "", "Mix.lr:6:21"),
    ],
)
def test_a_real_where_an_integer_is_declared_is_reported_where_the_target_refuses_it(
    tmp_path, parameters: str, entry: str, place: str
) -> None:
    """The checker reports what the SFC target refuses, at the same place."""
    model = mix_model(tmp_path, parameters, entry)
    context = check([model], [tmp_path])
    found = [
        (d.code, f"{Path(d.file).name}:{d.line}:{d.column}") for d in context.diagnostics.items
    ]
    assert found == [("LR0308", place)]
    request = GenerationRequest(context, [model.resolve()])
    with pytest.raises(GenerationError, match=rf"{place}: a Real value where an Integer"):
        load_generator("sfc").generate(request)
