"""Constant folding on the AST agrees with the Python runtime's own evaluation.

Targets that need a value before anything runs (initial values on the PLC, bounds the CoCos
check) fold defaults with ``metamodel.constants.fold``; the runtime computes the same
expressions in generated Python. Seeded random expressions are run through both.
"""

from __future__ import annotations

import random
from pathlib import Path

import pytest

from lightrocks.app.loading import load_component
from lightrocks.languages.lightrocks.syntax import parse_statechart
from lightrocks.metamodel import ast
from lightrocks.metamodel.constants import fold

INTEGERS = ("0", "1", "2", "3", "7", "12")
REALS = ("0.5", "2.5", "1e1", "3.0")
DIVISORS = ("2", "3", "-4", "0.5", "2.5")


def _parameter_defaults(text: str) -> list[ast.Expression]:
    unit = parse_statechart(text, "P.lr")
    [block] = [e for e in unit.statechart.elements if isinstance(e, ast.ParameterBlock)]
    return [p.default for p in block.parameters]


@pytest.mark.parametrize(
    ("text", "value"),
    [
        ("2 * 3 - 1", 5),
        ("7 / 2", 3.5),
        ("-7 % 3", 2),
        ("7 % -3", -2),
        ("2 mm + 1 cm", 0.012),
        ("-(3)", -3),
        ("abs(-2)", 2),
        ("min(3, 0.5)", 0.5),
        ("max(2, 3)", 3),
        ("1 < 2 && !(3 == 4)", True),
        ("[1, 2.5]", (1, 2.5)),
        ('"ok"', "ok"),
    ],
)
def test_a_constant_folds_to_its_value(text: str, value: object) -> None:
    [default] = _parameter_defaults(f"statechart P {{ parameters {{ Real x = {text}; }} }}")
    folded = fold(default)
    assert folded == value
    assert type(folded) is type(value)


@pytest.mark.parametrize(
    "text", ["x", "1 / 0", "5 % 0", "rotZ(90 deg)", "abs(1, 2)", "true + 1", "[1, true]"]
)
def test_what_is_not_constant_folds_to_nothing(text: str) -> None:
    [default] = _parameter_defaults(f"statechart P {{ parameters {{ Real x = {text}; }} }}")
    assert fold(default) is None


def _number(rng: random.Random, depth: int) -> str:
    roll = rng.random()
    if depth == 0 or roll < 0.3:
        return rng.choice(INTEGERS + REALS)
    if roll < 0.4:
        return f"-({_number(rng, depth - 1)})"
    if roll < 0.5:
        return f"{rng.choice(['min', 'max'])}({_number(rng, depth - 1)}, {_number(rng, depth - 1)})"
    if roll < 0.55:
        return f"abs({_number(rng, depth - 1)})"
    operator = rng.choice(["+", "-", "*", "/", "%"])
    right = rng.choice(DIVISORS) if operator in "/%" else _number(rng, depth - 1)
    return f"({_number(rng, depth - 1)} {operator} {right})"


def _boolean(rng: random.Random, depth: int) -> str:
    roll = rng.random()
    if depth == 0 or roll < 0.5:
        operator = rng.choice(["<", "<=", ">", ">=", "==", "!="])
        return f"({_number(rng, 2)} {operator} {_number(rng, 2)})"
    if roll < 0.65:
        return f"!{_boolean(rng, depth - 1)}"
    operator = rng.choice(["&&", "||"])
    return f"({_boolean(rng, depth - 1)} {operator} {_boolean(rng, depth - 1)})"


def test_folding_agrees_with_the_runtime_on_random_constants(tmp_path: Path) -> None:
    rng = random.Random(20261123)
    numbers = [_number(rng, 4) for _ in range(80)]
    booleans = [_boolean(rng, 3) for _ in range(40)]
    lines = [f"Real r{i} = {text};" for i, text in enumerate(numbers)]
    lines += [f"Boolean b{i} = {text};" for i, text in enumerate(booleans)]
    text = "package p;\n\nstatechart P {\n  parameters {\n    " + "\n    ".join(lines)
    text += "\n  }\n  initial state A;\n}\n"
    path = tmp_path / "p" / "P.lr"
    path.parent.mkdir()
    path.write_text(text, encoding="utf-8")

    chart = load_component(path, [tmp_path])()
    chart.defaults(None)
    names = [f"r{i}" for i in range(len(numbers))] + [f"b{i}" for i in range(len(booleans))]
    for name, default in zip(names, _parameter_defaults(text), strict=True):
        folded, computed = fold(default), getattr(chart, name)
        assert folded == pytest.approx(computed, rel=1e-12, abs=1e-12), name
        assert type(folded) is type(computed), name
