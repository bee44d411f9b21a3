"""An operation on constants whose result no Real holds (``1e300 * 1e300``, ``1e200 mm *
1e200``) is a finding, like a literal beyond a Real (LR0302 in a chart, LR0404 in a
domain's command), instead of a run with ``inf``; and a number that is not finite, computed
at run time, never reaches a device: the command is refused, whatever its safe range."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

from lightrocks.adapters.dryrun import DryRunAdapter
from lightrocks.app.cli import main
from lightrocks.languages.lightrocks.syntax import parse_statechart
from lightrocks.metamodel import ast
from lightrocks.metamodel.constants import overflow
from lightrocks.runtime.contract import Vector3
from lightrocks.runtime.safety import not_finite

from .fault_runs import DOMAIN, within, write_models

BEYOND = "beyond the largest number a Real holds"


def chart(default: str, kind: str = "Real") -> str:
    return (
        "package t;\n\nimport t.Cell;\n\n<<action>> statechart Big {\n  parameters {\n"
        f"    {kind} v = {default};\n  }}\n  do / arm.move(x = 1 mm);\n"
        "  end condition reached [arm.goalReached];\n}\n"
    )


@pytest.mark.parametrize(
    ("default", "kind", "shown"),
    [
        ("1e300 * 1e300", "Real", "'1e300 * 1e300' computes inf"),
        ("1e200 mm * 1e200", "Length", "'1e200 mm * 1e200' computes inf"),
        ("-1e300 * 1e300", "Real", "'-1e300 * 1e300' computes -inf"),
        ("1e308 + 1e308", "Real", "'1e308 + 1e308' computes inf"),
        ("1 / 1e-320 / 1e-10", "Real", "computes inf"),
        ("(1e300 * 1e300) * 0", "Real", "'1e300 * 1e300' computes inf"),
        ("abs(1e300 * 1e300)", "Real", "'1e300 * 1e300' computes inf"),
        ("1" + "0" * 200 + " * 1" + "0" * 200, "Integer", "...' computes inf"),
    ],
)
def test_a_constant_beyond_a_real_is_a_finding(
    tmp_path: Path, capsys, default: str, kind: str, shown: str
) -> None:
    write_models(tmp_path, {"Big": chart(default, kind)})
    assert main(["check", str(tmp_path)]) == 1
    out = " ".join(capsys.readouterr().out.split())
    assert "t/Big.lr:7:" in out and "error LR0302: " in out, out
    assert shown in out and BEYOND in out, out
    assert "internal error" not in out


def test_a_constant_beyond_a_real_in_a_command_default_is_a_finding(tmp_path: Path, capsys):
    write_models(tmp_path, {})
    domain = DOMAIN.replace("command move(Length x);", "command move(Length x = 1e200 mm * 1e200);")
    (tmp_path / "t" / "Cell.lrd").write_text(domain, encoding="utf-8")
    assert main(["check", str(tmp_path)]) == 1
    out = " ".join(capsys.readouterr().out.split())
    assert "Cell.lrd:4:27: error LR0404: '1e200 mm * 1e200' computes inf: " + BEYOND in out


@pytest.mark.parametrize("budget", ["1e999 s", "1e307 min"])
def test_a_timeout_beyond_a_real_is_a_finding(tmp_path: Path, capsys, budget: str) -> None:
    write_models(
        tmp_path, {"Big": chart("1").replace("<<action>>", f'<<action, timeout="{budget}">>')}
    )
    assert main(["check", str(tmp_path)]) == 1
    out = " ".join(capsys.readouterr().out.split())
    assert f"error LR0501: timeout '{budget}' is {BEYOND}" in out, out


def test_an_object_attribute_beyond_a_real_is_reported_once(tmp_path: Path, capsys) -> None:
    write_models(tmp_path, {})
    domain = DOMAIN.replace("arm : Arm;", "arm : Arm;\n  object part { Real w = 1e999; }")
    (tmp_path / "t" / "Cell.lrd").write_text(domain, encoding="utf-8")
    assert main(["check", str(tmp_path)]) == 1
    out = capsys.readouterr().out
    assert out.count(BEYOND) == 1, out


@pytest.mark.parametrize("text", ["1e300 * 1e300", "1e308 + 1e308", "1e200 mm * 1e200"])
def test_overflow_names_what_the_operation_computes(text: str) -> None:
    unit = parse_statechart(f"statechart P {{ parameters {{ Real x = {text}; }} }}", "P.lr")
    [block] = [e for e in unit.statechart.elements if isinstance(e, ast.ParameterBlock)]
    assert overflow(block.parameters[0].default) == math.inf


@pytest.mark.parametrize("text", ["1e300 * 1e10 / 1e20", "x * 1e300", "1 / 0", "1e999 * 2"])
def test_what_fits_or_is_not_constant_is_no_overflow(text: str) -> None:
    unit = parse_statechart(f"statechart P {{ parameters {{ Real x = {text}; }} }}", "P.lr")
    [block] = [e for e in unit.statechart.elements if isinstance(e, ast.ParameterBlock)]
    assert overflow(block.parameters[0].default) is None


RUNTIME = """package t;

import t.Cell;

<<action>> statechart Far {
  parameters {
    Real k = 1e300;
  }
  do / arm.move(x = k * k * 1 mm);
  end condition reached [arm.goalReached];
}
"""


def test_a_number_that_is_not_finite_never_reaches_a_device(build) -> None:
    run = build({"Far": RUNTIME}, "Far")()
    adapter = DryRunAdapter()
    within(lambda: run.start(adapter))
    assert run.outcome == "error"
    assert run.fault.message == "refused: arm.move(x) = inf, not a finite number"
    assert adapter.calls == [], "the command was sent"
    assert adapter.holds >= 1


@pytest.mark.parametrize(
    ("value", "said"),
    [
        (math.inf, "arm.move(x) = inf, not a finite number"),
        (math.nan, "arm.move(x) = nan, not a finite number"),
        (10**400, "arm.move(x) = inf, not a finite number"),
        ((1.0, -math.inf), "arm.move(x[1]) = -inf, not a finite number"),
        (np.array([0.0, math.nan]), "arm.move(x[1]) = nan, not a finite number"),
        (Vector3(0.0, math.inf, 0.0), "arm.move(x) holds inf, not a finite number"),
        (pin.SE3(np.eye(3), np.array([0.0, 0.0, math.nan])), "arm.move(x) holds nan"),
    ],
)
def test_every_kind_of_argument_is_held_to_finite_numbers(value: object, said: str) -> None:
    assert said in not_finite("arm", "move", {"name": "part", "x": value})


@pytest.mark.parametrize(
    "value", [0.5, 10**300, (1.0, 2.0), Vector3(1.0, 2.0, 3.0), pin.SE3.Identity(), "part", None]
)
def test_finite_arguments_pass(value: object) -> None:
    assert not_finite("arm", "move", {"x": value, "flag": True}) is None
