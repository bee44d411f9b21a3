"""Values and paths a user gets wrong: each ends in a clear message and its exit code
(1 model error, 2 usage), never a traceback or a run with a value nobody meant."""

from __future__ import annotations

import errno
import io
import os
from pathlib import Path

import pytest

import lightrocks.runtime.trace as trace_module
from lightrocks.app.cli import main
from lightrocks.workbench.check import check

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


def test_trace_where_nothing_can_be_written(capsys: pytest.CaptureFixture[str]) -> None:
    target = "/sys/lightrocks-trace"
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
    [("(" * 120 + "1" + ")" * 120, 133), (" + ".join(["1"] * 492), None)],
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
    assert "LR0001: expression nested too deeply" in out
    assert "Deep.lr:5:" + (f"{column}:" if column else "") in out
    assert "1 error(s)" in out


def test_nesting_within_the_limit_is_no_finding(tmp_path: Path) -> None:
    """Eighty brackets stay within the depth the later passes can walk: the parser reads
    them too, and the model checks clean."""
    (tmp_path / "p").mkdir()
    expression = "(" * 80 + "1" + ")" * 80
    (tmp_path / "p" / "Deep.lr").write_text(_statechart(expression), encoding="utf-8")
    assert main(["check", str(tmp_path)]) == 0


@pytest.mark.parametrize(
    ("kind", "message"), [("fifo", "not a regular file"), ("symlink", "not a model file")]
)
def test_the_check_api_reads_no_fifo_or_device(kind: str, message: str, tmp_path: Path) -> None:
    """The command line refuses such paths up front; the library API reports them too."""
    target = tmp_path / "Model.lr"
    if kind == "fifo":
        os.mkfifo(target)
    else:
        target.symlink_to("/dev/zero")
    context = check([target], [])
    [finding] = context.diagnostics.items
    assert (finding.code, finding.message) == ("LR0004", message)


class _FullDisk(io.StringIO):
    def write(self, text: str) -> int:
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))


def test_trace_on_a_full_disk(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    """The disk fills up during the run: the run is not stopped half-way by its record, and
    ends in a usage error naming the file; no cut-off trace is left behind."""
    trace = tmp_path / "t.jsonl"
    trace.write_text("", encoding="utf-8")
    monkeypatch.setattr(trace_module, "open", lambda *_, **__: _FullDisk(), raising=False)
    status, output = run(capsys, str(SCREW_TASK), "--adapter", "dryrun", "--trace", str(trace))
    assert status == 2
    assert f"--trace: cannot write {trace}: No space left on device" in " ".join(output.split())
    assert not trace.exists()
