"""Values and paths a user gets wrong: each ends in a clear message and its exit code
(1 model error, 2 usage), never a traceback or a run with a value nobody meant."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from lightrocks.workbench.app.cli import main
from lightrocks.workbench.app.errors import RunError
from lightrocks.workbench.app.run import run_once
from lightrocks.workbench.app.values import parse_noise

ROOT = Path(__file__).resolve().parents[2]
SCREW_TASK = ROOT / "examples" / "screwing" / "tasks" / "ScrewTask.lr"


@pytest.fixture(autouse=True)
def cache(tmp_path_factory: pytest.TempPathFactory, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path_factory.getbasetemp() / "xdg"))


def run(capsys: pytest.CaptureFixture[str], *argv: str) -> tuple[int, str]:
    status = main(["run", *argv])
    captured = capsys.readouterr()
    assert "internal error" not in captured.err
    return status, captured.out + captured.err


@pytest.mark.parametrize(
    ("param", "message"),
    [
        ("depth=20", "expects Length [m] with its unit; given '20' (Real)"),
        ("depth=2N", "given '2N' (N [kg·m/s²])"),
        ("depth=5 Nm", "given '5 Nm'"),
        ("depth=true", "given 'true' (Boolean)"),
        ('depth="ten"', "(String)"),
        ("depth=[1 mm, 2 mm]", "given '[1 mm, 2 mm]'"),
        ("depth=1e999 mm", "not a finite number"),
        ("retries=2.5", "expects Integer; given '2.5'"),
    ],
)
def test_run_parameters_are_typed(
    param: str, message: str, capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    trace = tmp_path / "t.jsonl"
    status, output = run(
        capsys, str(SCREW_TASK), "--adapter", "dryrun", "--param", param, "--trace", str(trace)
    )
    name = param.partition("=")[0]
    assert status == 2
    assert f"parameter '{name}'" in output
    assert message.split(" [kg")[0] in output
    assert not trace.exists()


def test_well_typed_parameters_run(capsys: pytest.CaptureFixture[str]) -> None:
    status, output = run(
        capsys,
        str(SCREW_TASK),
        "--adapter",
        "dryrun",
        "--param",
        "depth=12mm",
        "--param",
        "retries=3",
    )
    assert status == 0, output


def test_the_python_api_checks_the_same_way() -> None:
    with pytest.raises(RunError, match="parameter 'depth': expects Length"):
        run_once(SCREW_TASK, [], ["depth=20"], "dryrun")
    result = run_once(SCREW_TASK, [], ["depth=10 mm"], "dryrun")
    assert result.outcome == "screwed"


def test_seeds_check_parameters_before_starting(capsys: pytest.CaptureFixture[str]) -> None:
    status, output = run(
        capsys, str(SCREW_TASK), "--adapter", "dryrun", "--seeds", "2", "--param", "depth=20"
    )
    assert status == 2
    assert "parameter 'depth'" in output


def test_perception_noise_must_be_finite() -> None:
    with pytest.raises(RunError, match="finite"):
        parse_noise("1e999mm,2deg")


@pytest.mark.parametrize(
    "model",
    [
        str(ROOT / "examples" / "screwing"),
        str(ROOT / "examples" / "screwing" / "cell" / "ScrewingCell.lrd"),
        "/dev/null",
    ],
)
def test_run_needs_a_statechart_file(model: str, capsys: pytest.CaptureFixture[str]) -> None:
    status, output = run(capsys, model)
    assert status == 2
    assert "run needs a statechart file (.lr)" in output


def test_trace_into_a_folder_or_fifo_is_refused(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    fifo = tmp_path / "fifo"
    os.mkfifo(fifo)
    for target in (tmp_path, fifo):
        status, output = run(capsys, str(SCREW_TASK), "--adapter", "dryrun", "--trace", str(target))
        assert status == 2
        assert "is not a regular file" in output


@pytest.mark.parametrize("target", ["/proc/x", "/sys/x"])
def test_trace_where_nothing_can_be_written(target: str, capsys: pytest.CaptureFixture[str]):
    if not Path(target).parent.is_dir():
        pytest.skip(f"{Path(target).parent} is not mounted")
    status, output = run(capsys, str(SCREW_TASK), "--adapter", "dryrun", "--trace", target)
    assert status == 2
    assert target in output


def test_unknown_scene_is_a_clear_error(tmp_path: Path, capsys: pytest.CaptureFixture[str]):
    pytest.importorskip("mujoco")
    folder = tmp_path / "t"
    folder.mkdir()
    (folder / "Cell.lrd").write_text(
        "package t;\n\ndevice Arm {\n  command move(Length x);\n  sensor Boolean done;\n}\n\n"
        '<<scene="nowhere">> cell Cell {\n  arm : Arm;\n}\n',
        encoding="utf-8",
    )
    (folder / "Move.lr").write_text(
        "package t;\n\nimport t.Cell;\n\n<<action>> statechart Move {\n"
        "  do / arm.move(x = 1 mm);\n  end condition done [arm.done];\n}\n",
        encoding="utf-8",
    )
    status, output = run(
        capsys, str(folder / "Move.lr"), "--path", str(tmp_path), "--adapter", "mujoco"
    )
    assert status == 2
    assert "unknown scene 'nowhere'" in output


def test_template_error_is_a_usage_error(tmp_path: Path, capsys: pytest.CaptureFixture[str]):
    templates = tmp_path / "templates"
    templates.mkdir()
    (templates / "statechart.dot.jinja").write_text("{% if %}\n", encoding="utf-8")
    status = main(
        [
            "generate",
            str(ROOT / "examples" / "plain"),
            "--target",
            "dot",
            "-o",
            str(tmp_path / "out"),
            "--templates",
            str(templates),
        ]
    )
    err = capsys.readouterr().err
    assert status == 2
    assert "statechart.dot.jinja:1: Expected an expression" in err
    assert not (tmp_path / "out").exists()


def _statechart(expression: str) -> str:
    return (
        "package p;\n\n<<task>> statechart Deep {\n  parameters {\n"
        f"    Real x = {expression};\n  }}\n  start condition go;\n  end condition done;\n"
        "  go -> done;\n}\n"
    )


@pytest.mark.parametrize(
    ("expression", "column"),
    [("(" * 53 + "1" + ")" * 53, 66), (" + ".join(["1"] * 492), None)],
    ids=["parentheses", "sum"],
)
def test_deep_nesting_is_a_finding(
    expression: str, column: int | None, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    (tmp_path / "p").mkdir()
    (tmp_path / "p" / "Deep.lr").write_text(_statechart(expression), encoding="utf-8")
    (tmp_path / "p" / "Fine.lr").write_text(
        _statechart("1").replace("Deep", "Fine"), encoding="utf-8"
    )
    status = main(["check", str(tmp_path)])
    out = capsys.readouterr().out
    assert status == 1
    assert "LR0001: nested too deeply" in out
    assert "Deep.lr:5:" + (f"{column}:" if column else "") in out
    assert "1 error(s)" in out


@pytest.mark.parametrize("kind", ["fifo", "symlink"])
def test_check_on_what_is_not_a_file(
    kind: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    target = tmp_path / "Model.lr"
    if kind == "fifo":
        os.mkfifo(target)
    else:
        target.symlink_to("/dev/zero")
    status = main(["check", str(target)])
    out = capsys.readouterr().out
    assert status == 1
    assert "LR0004" in out
