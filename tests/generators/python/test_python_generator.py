"""The python target on the examples: deterministic, clean, and runnable on the dry run."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from lightrocks.adapters.dryrun import DryRunAdapter
from lightrocks.app.cli import main
from lightrocks.app.loading import component_class, generated_package
from lightrocks.app.values import parse_value
from lightrocks.generators.python import GENERATOR
from lightrocks.runtime import Vector3
from lightrocks.workbench.check import check
from lightrocks.workbench.generators import GenerationRequest

EXAMPLES = Path(__file__).parents[3] / "examples"


@pytest.fixture(scope="module")
def package(tmp_path_factory):
    context = check([EXAMPLES])
    assert not context.diagnostics.has_errors
    return generated_package(context, [], tmp_path_factory.mktemp("cache"))


def _generate() -> dict[str, str]:
    return GENERATOR.generate(GenerationRequest(check([EXAMPLES]), []))


def test_output_is_deterministic_clean_and_never_evaluates(tmp_path):
    first, second = _generate(), _generate()
    assert first == second
    for relative, text in first.items():
        for builtin in ("eval", "exec"):
            assert f"{builtin}(" not in text
        (tmp_path / relative).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / relative).write_text(text)
    ruff = Path(sys.executable).with_name("ruff")
    result = subprocess.run([str(ruff), "check", "--isolated", "--line-length", "100",
                             "--select", "E,F,W,I,B,UP,SIM,RUF", str(tmp_path)],
                            capture_output=True, text=True, check=False)  # fmt: skip
    assert result.returncode == 0, result.stdout


def _states(chart, kind="enter"):
    return [r["state"] for r in chart.trace if r["kind"] == kind]


def test_screw_task_runs_to_success_on_the_dry_run(package):
    cls = component_class(package, "screwing.tasks.ScrewTask")
    # the arm's motions end as in the cell: the touch meets the cube with the tip in the hole,
    # the push and the tug feel the caught thread; every turn drives the screw 5 mm deeper
    # (the hand travels down with it)
    motions = ["reached", "reached", "lifted", "reached", "contact", "pressing", "held"]
    adapter = DryRunAdapter(
        outcomes={"robot.moveCartesian": motions},
        sensors={"robot.travel": Vector3(0.0, 0.0, -0.005)},
    )
    chart = cls().start(adapter)
    assert chart.outcome == "screwed"
    skills = [s for s in _states(chart) if s.count("/") == 1]
    assert skills == [
        "ScrewTask/FindScrew",
        "ScrewTask/PickScrew",
        "ScrewTask/Carry",
        "ScrewTask/Insert",
        "ScrewTask/DriveIn",
        "ScrewTask/LetGo",
        "ScrewTask/MoveAway",
    ]
    commands = [r["state"] for r in chart.trace if r["kind"] == "command"]
    assert commands[:6] == [
        "ScrewTask/FindScrew/Look",
        "ScrewTask/FindScrew/LookAtCube",
        "ScrewTask/PickScrew/Open",
        "ScrewTask/PickScrew/Hover",
        "ScrewTask/PickScrew/Descend",
        "ScrewTask/PickScrew/Close",
    ]
    assert chart.env.screw.depth == pytest.approx(0.015)


def test_assemble_rail_runs_to_success_on_the_dry_run(package):
    # the arm's motions end as on a real rail: Touch finds the lips, SnapOn hears the click
    # (the force peaked, then fell), Seat feels the housing sit on the lips and Hold presses
    # it down (the script ends Hold with its end condition, before the parent's time event)
    per_terminal = ["reached", "reached", "lifted", "reached", "reached"]
    per_terminal += ["touched", "latched", "seated", "pressed", "lifted"]
    adapter = DryRunAdapter(
        outcomes={"robot.moveCartesian": per_terminal * 3},
        sensors={"robot.peakForce": 30.0},
    )
    chart = component_class(package, "din_rail.tasks.AssembleRail")().start(adapter)
    assert chart.outcome == "assembled"
    tasks = [s for s in _states(chart) if s.count("/") == 1]
    assert tasks == [f"AssembleRail/PlugTerminal{i}" for i in (1, 2, 3)]
    assert all(getattr(chart.env, f"terminal{i}").latched for i in (1, 2, 3))


def test_turnstile_from_python(package):
    chart = component_class(package, "plain.Turnstile")().start()
    chart.send("coin")
    assert chart.active_configuration == ("Turnstile", "Operating", "Unlocked")
    chart.send("push")
    assert chart.passages == 1
    chart.send("shutdown")
    assert chart.outcome == "Off"


def test_turnstile_from_the_cli(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "user-cache"))
    for loaded in [m for m in sys.modules if m.startswith("lightrocks_")]:
        # a package another test of this process imported would be reused, cache untouched
        monkeypatch.delitem(sys.modules, loaded)
    trace = tmp_path / "t.jsonl"
    model = str(EXAMPLES / "plain" / "Turnstile.lr")
    assert main(["run", model, "--events", "coin,push,shutdown", "--trace", str(trace)]) == 0
    assert '"outcome": "Off"' in trace.read_text().splitlines()[-1]
    assert [p.name for p in tmp_path.iterdir() if p.name != "user-cache"] == ["t.jsonl"]
    assert any((tmp_path / "user-cache" / "lightrocks").glob("*/manifest.json"))


def test_cli_reports_unknown_adapter_and_parameter(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    model = str(EXAMPLES / "screwing" / "tasks" / "ScrewTask.lr")
    assert main(["run", model, "--adapter", "nope"]) == 2
    assert main(["run", model, "--adapter", "dryrun", "--param", "dept=12mm"]) == 2
    errors = capsys.readouterr().err
    assert "unknown adapter 'nope'" in errors and "no parameter 'dept'" in errors


def test_param_values_are_literals():
    assert parse_value("12mm") == pytest.approx(0.012)
    assert parse_value("0.32 Nm") == pytest.approx(0.32)
    assert parse_value("3") == 3 and parse_value("true") is True
    with pytest.raises(Exception, match="not a literal"):
        parse_value("__import__('os')")


def test_the_package_exports_every_class_by_its_model_name(package):
    """The app asks the generated package for a class by name; it never rebuilds the
    package's file layout."""
    names = sorted(package.COMPONENTS)
    assert "screwing.tasks.ScrewTask" in names and "plain.Turnstile" in names
    for name in names:
        simple = name.rpartition(".")[2]
        assert simple == package.component(name).NAME
    with pytest.raises(KeyError):
        package.component("screwing.tasks.NoSuchTask")
