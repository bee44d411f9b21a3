"""Safe ranges hold on every path a value takes to a command. Constants (literals, defaults,
bindings, constant expressions) are findings; a run parameter that reaches a ranged argument
is a usage error before anything starts; a value computed during the run is refused when its
command is about to be sent: outcome ``error`` with its origin, the devices held."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from lightrocks.app.cli import main
from lightrocks.app.errors import RunError
from lightrocks.app.loading import load_component
from lightrocks.app.pipeline import run_model
from lightrocks.app.values import parameters

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"

CELL = """package t;

<<timeout="2 s">> device Arm {
  command move(Length x in 0 mm .. 50 mm,
               Stiffness3 k = [100 N/m, 100 N/m, 10 Nm/rad]
                 in [0 N/m, 0 N/m, 0 Nm/rad] .. [500 N/m, 500 N/m, 20 Nm/rad]);
  sensor Boolean goalReached;
}

vector Stiffness3 [N/m, N/m, Nm/rad];

<<scene="none">> cell Cell {
  arm : Arm;
}
"""

MOVE = """package t;

import t.Cell;

<<action>> statechart Move {
  parameters { Length x = 10 mm; Stiffness3 k = [100 N/m, 100 N/m, 10 Nm/rad]; }
  do / arm.move(x = x * 2, k = k);
  end condition reached [arm.goalReached];
}
"""

PICK = """package t;

import t.Cell;
import t.Move;

<<skill>> statechart Pick {
  parameters { Stiffness3 soft = [100 N/m, 100 N/m, 10 Nm/rad]; }
  start condition go;
  end condition done;
  <<import="Move">> state Reach(x = 5 mm, k = soft);
  go -> Reach;
  Reach -> done reached;
}
"""


@pytest.fixture(autouse=True)
def cache(tmp_path_factory: pytest.TempPathFactory, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path_factory.getbasetemp() / "xdg"))


@pytest.fixture
def folder(tmp_path: Path) -> Path:
    (tmp_path / "t").mkdir()
    for name, text in (("Cell.lrd", CELL), ("Move.lr", MOVE), ("Pick.lr", PICK)):
        (tmp_path / "t" / name).write_text(text, encoding="utf-8")
    return tmp_path


def _run(folder: Path, chart: str, *extra: str) -> list[str]:
    return ["run", str(folder / "t" / chart), "--path", str(folder), "--adapter", "dryrun", *extra]


def test_a_computed_value_out_of_range_is_refused_at_run_time(
    folder: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    trace = folder / "trace.jsonl"
    status = main(_run(folder, "Move.lr", "--param", "x=30mm", "--trace", str(trace)))
    out = capsys.readouterr().out
    assert status == 1
    assert "outcome: error" in out
    assert "refused: arm.move(x) = 60 mm is outside its safe range 0 mm .. 50 mm" in out
    assert "via Move" in out
    records = [json.loads(line) for line in trace.read_text(encoding="utf-8").splitlines()]
    assert not any(r["kind"] == "command" for r in records), "nothing was sent"
    assert records[-1] == {"time": 0.0, "kind": "finished", "outcome": "error"}


def test_a_computed_value_in_range_runs(folder: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(_run(folder, "Move.lr", "--param", "x=20mm")) == 0
    assert "outcome: reached" in capsys.readouterr().out


def test_the_refusal_holds_the_devices(folder: Path) -> None:
    from lightrocks.adapters.dryrun import DryRunAdapter
    from lightrocks.runtime.binding import bind

    cls = load_component(folder / "t" / "Move.lr", [folder])
    held = []
    adapter = DryRunAdapter()
    adapter.hold = lambda: held.append(True)  # type: ignore[method-assign]
    bind(adapter, cls.CELL)
    chart = cls(x=0.03)
    chart.start(adapter)
    assert chart.outcome == "error"
    assert chart.fault.origin == ["Move"]
    assert held


@pytest.mark.parametrize(
    ("given", "words"),
    [
        (
            "k=[1e9 N/m, 100 N/m, 10 Nm/rad]",
            "arm.move(k[0]) = 1e+09 N/m is outside its safe range 0 N/m .. 500 N/m",
        ),
        (
            "k=[100 N/m, 100 N/m, 25 Nm/rad]",
            "arm.move(k[2]) = 25 Nm/rad is outside its safe range 0 Nm/rad .. 20 Nm/rad",
        ),
    ],
)
def test_a_run_parameter_out_of_range_is_a_usage_error(
    folder: Path, given: str, words: str, capsys: pytest.CaptureFixture[str]
) -> None:
    trace = folder / "trace.jsonl"
    for seeds in ([], ["--seeds", "2"]):
        status = main(_run(folder, "Move.lr", "--param", given, "--trace", str(trace), *seeds))
        err = capsys.readouterr().err
        assert status == 2
        expected = "k expects Stiffness3, 3 values within the safe range of the command it reaches;"
        assert f"--param {given}: {expected}" in " ".join(err.split())
        assert words in " ".join(err.split())
        assert not trace.exists()


def test_a_run_parameter_reaching_a_range_through_a_binding(folder: Path) -> None:
    pick = load_component(folder / "t" / "Pick.lr", [folder])
    with pytest.raises(RunError, match=r"soft=.*arm\.move\(k\[1\]\) = 600 N/m .* 0 N/m .. 500"):
        parameters(pick, ["soft=[100 N/m, 600 N/m, 10 Nm/rad]"])
    assert parameters(pick, ["soft=[400 N/m, 100 N/m, 10 Nm/rad]"])


def test_run_once_refuses_the_same_way(folder: Path) -> None:
    with pytest.raises(RunError, match=r"arm\.move\(k\[0\]\)"):
        run_model(folder / "t" / "Move.lr", [folder], ["k=[501 N/m, 1 N/m, 1 Nm/rad]"], "dryrun")
    result = run_model(folder / "t" / "Move.lr", [folder], ["x=10 mm"], "dryrun")
    assert result.outcome == "reached"


@pytest.mark.parametrize(
    ("binding", "message"),
    [
        (
            "Reach(x = 5 mm, k = [1e9 N/m, 100 N/m, 10 Nm/rad])",
            "'k' of Move reaches arm.move(k[0]) = 1e+09 N/m is outside its safe range "
            "0 N/m .. 500 N/m",
        ),
        (
            "Reach(x = 5 mm, k = [100 N/m, 100 N/m, 2 * 15 Nm/rad])",
            "arm.move(k[2]) = 30 Nm/rad is outside its safe range 0 Nm/rad .. 20 Nm/rad",
        ),
    ],
)
def test_a_binding_out_of_range_is_a_finding(
    folder: Path, binding: str, message: str, capsys: pytest.CaptureFixture[str]
) -> None:
    pick = folder / "t" / "Pick.lr"
    pick.write_text(PICK.replace("Reach(x = 5 mm, k = soft)", binding), encoding="utf-8")
    assert main(["check", str(pick), "--path", str(folder)]) == 1
    out = capsys.readouterr().out
    assert "error LR0505: " in out and message in out


def test_a_default_reaching_a_range_through_a_binding_is_a_finding(
    folder: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    pick = folder / "t" / "Pick.lr"
    pick.write_text(PICK.replace("[100 N/m, 100 N/m", "[100 N/m, 900 N/m"), encoding="utf-8")
    assert main(["check", str(pick), "--path", str(folder)]) == 1
    out = capsys.readouterr().out
    assert "Pick.lr:7:" in out
    assert "default of 'soft' reaches arm.move(k[1]) = 900 N/m" in out


def test_the_example_turn_tool_binding(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """The reported reproduction: a skill binds a huge stiffness to the example TurnTool."""
    (tmp_path / "mine").mkdir()
    skill = tmp_path / "mine" / "Turn.lr"
    skill.write_text(
        "package mine;\n\nimport screwing.cell.ScrewingCell;\nimport screwing.actions.*;\n\n"
        "<<skill>> statechart Turn {\n  start condition go;\n  end condition done;\n"
        '  <<import="TurnTool">> state Turn(angle = 10 deg, stiffness = [1e9 N/m, 500 N/m, '
        "800 N/m, 150 Nm/rad, 150 Nm/rad, 30 Nm/rad]);\n  go -> Turn;\n  Turn -> done done;\n}\n",
        encoding="utf-8",
    )
    assert main(["check", str(skill), "--path", str(EXAMPLES), "--path", str(tmp_path)]) == 1
    out = capsys.readouterr().out
    assert (
        "'stiffness' of TurnTool reaches robot.moveCartesian(stiffness[0]) = 1e+09 N/m is "
        "outside its safe range 0 N/m .. 5000 N/m"
    ) in out
