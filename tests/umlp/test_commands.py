"""The UML/P language on the command line: ``convert``, ``check``, ``fmt`` and ``list``."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from lightrocks.app.cli import main

MODELS = Path(__file__).with_name("models")
DOOR = MODELS / "shared" / "Door.sc"
COUNTER = MODELS / "runnable" / "Counter.sc"


def run(capsys: pytest.CaptureFixture[str], *argv: str) -> tuple[int, str, str]:
    status = main(list(argv))
    captured = capsys.readouterr()
    return status, captured.out, captured.err


@pytest.fixture
def models(tmp_path: Path) -> Path:
    """A model-path root with the package folders of the test models."""
    for folder in ("shared", "runnable"):
        shutil.copytree(MODELS / folder, tmp_path / folder)
    return tmp_path


def test_convert_writes_the_lr_file_beside_and_it_checks(
    models: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    source = models / "runnable" / "Counter.sc"
    status, out, _ = run(capsys, "convert", str(source), "--to", "lr")
    assert status == 0, out
    written = models / "runnable" / "Counter.lr"
    assert f"wrote {written}" in out
    assert "info LR2123: 'count' is not declared in the UML/P chart" in out
    assert written.read_text().startswith("package runnable;\n\nstatechart Counter {\n")
    # both side by side: the .sc chart declares nothing the .lr one would clash with
    status, out, _ = run(capsys, "check", str(models / "runnable"))
    assert status == 0, out
    # the .lr chart checks clean; the .sc one's guards use the class's variables (LR2116)
    assert out.strip().endswith("0 error(s), 2 warning(s)")
    assert out.count("warning LR2116: 'count' is not declared") == 2


def test_convert_back_to_uml_p(models: Path, capsys: pytest.CaptureFixture[str]) -> None:
    source = models / "shared" / "Door.sc"
    assert run(capsys, "convert", str(source), "--to", "lr")[0] == 0
    lr = models / "shared" / "Door.lr"
    status, out, _ = run(capsys, "convert", str(lr), "--to", "sc")
    assert status == 1  # Door.sc is there
    assert "Door.sc exists; --force replaces it" in out
    status, out, _ = run(capsys, "convert", str(lr), "--to", "sc", "-o", str(models))
    assert status == 0, out
    status, out, _ = run(capsys, "fmt", "--check", str(models / "Door.sc"))
    assert status == 0, out


def test_convert_prints_with_stdout(capsys: pytest.CaptureFixture[str]) -> None:
    status, out, err = run(capsys, "convert", str(DOOR), "--to", "lr", "--stdout")
    assert status == 0, err
    assert out.startswith("package shared;\n")
    assert "LR2123" in err  # findings go to stderr, the model to stdout


def test_a_refused_conversion_exits_1_and_writes_nothing(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    source = tmp_path / "A.sc"
    source.write_text("statechart A {\n  initial state S {\n    entry / { return; }\n  };\n}\n")
    status, out, _ = run(capsys, "convert", str(source), "--to", "lr")
    assert status == 1
    assert f"{source}:3:15: error LR2120: the Java return statement 'return;'" in out
    assert not (tmp_path / "A.lr").exists()


def test_syntax_errors_are_findings(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    source = tmp_path / "A.sc"
    source.write_text("statechart A {\n  state S { }\n}\n")
    status, out, _ = run(capsys, "convert", str(source), "--to", "lr")
    assert status == 1
    assert f"{source}:3:1: error LR0001: syntax error" in out


def test_an_unknown_conversion_is_a_usage_error(capsys: pytest.CaptureFixture[str]) -> None:
    status, _, err = run(capsys, "convert", str(DOOR), "--to", "xyz")
    assert status == 2
    assert "no conversion from .sc to .xyz; known: .lr -> .sc, .sc -> .lr" in err


def test_from_reads_any_file_as_uml_p(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    source = tmp_path / "Machine.txt"
    source.write_text("statechart Machine { initial state A; A -> A go; }\n")
    status, out, err = run(capsys, "convert", str(source), "--from", "sc", "--to", "lr", "--stdout")
    assert status == 0, err
    assert "A -> A go;" in out


def test_check_and_fmt_know_sc_and_aut(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    (tmp_path / "Old.aut").write_text("statechart Old {\ninitial state A; state b;}\n")
    status, out, _ = run(capsys, "check", str(tmp_path))
    assert status == 0, out
    assert "Old.aut:1:1: warning LR2106: file extension is 'aut', but should be 'sc'" in out
    assert "Old.aut:2:18: warning LR2105: state b should start with a capital letter" in out
    assert run(capsys, "fmt", str(tmp_path))[0] == 0
    assert (tmp_path / "Old.aut").read_text() == (
        "statechart Old {\n  initial state A;\n  state b;\n}\n"
    )


def test_list_shows_the_language_and_its_cocos(capsys: pytest.CaptureFixture[str]) -> None:
    status, out, _ = run(capsys, "list", "languages")
    assert status == 0
    assert "umlp  .sc .aut  UML/P statecharts as MontiCore writes them" in out
    status, out, _ = run(capsys, "list", "cocos")
    assert status == 0
    for code in [f"LR21{i:02d}" for i in (*range(13), 14, 15, 16)]:
        assert code in out, code
    assert "LR2113" not in out  # MontiCore has no 0xCC113
