"""``lightrocks verify`` from the command line: the shipped examples verify clean (strict, as
CI runs it); a refuted property fails with its finding in every format, prints the run that
shows it and writes that run as a dry-run script that ``run`` accepts."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest

from lightrocks.app.cli import main

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"
RETRY = ROOT / "tests/behaviour/corpus/47-LR0703-ScrewTask/screwing/tasks/ScrewTask.lr"


@pytest.fixture
def endless(tmp_path: Path) -> Path:
    """The examples with a screwing task that may retry forever."""
    shutil.copytree(EXAMPLES, tmp_path / "models")
    shutil.copyfile(RETRY, tmp_path / "models/screwing/tasks/ScrewTask.lr")
    return tmp_path / "models"


def test_the_examples_verify_clean_under_strict(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["verify", "--strict", str(EXAMPLES)]) == 0
    assert "0 error(s), 0 warning(s)" in capsys.readouterr().out


def test_a_refuted_property_shows_its_run_and_writes_it_as_a_script(
    endless: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    task = endless / "screwing/tasks/ScrewTask.lr"
    scripts = tmp_path / "cex"
    arguments = ["verify", str(task), "--path", str(endless), "--counterexamples", str(scripts)]
    assert main(arguments) == 0  # a possible endless retry is a warning
    assert main([*arguments, "--strict"]) == 1
    out = capsys.readouterr().out
    assert f"{task}:47:3: warning LR0703" in out
    assert "then, again and again:" in out
    [script] = scripts.glob("*.dryrun.json")
    assert script.name == "screwing.tasks.ScrewTask-LR0703-47.dryrun.json"  # as docs say
    assert json.loads(script.read_text())["outcomes"]
    run = ["run", str(task), "--path", str(endless), "--adapter", "dryrun", "--script", str(script)]
    assert main(run) in (0, 1)  # the script is one that run accepts: no usage error
    assert "error:" not in capsys.readouterr().err


@pytest.mark.parametrize("form", ["json", "sarif", "github"])
def test_every_format_carries_the_finding(
    endless: Path, form: str, capsys: pytest.CaptureFixture[str]
) -> None:
    task = endless / "screwing/tasks/ScrewTask.lr"
    assert main(["verify", str(task), "--path", str(endless), "--format", form, "--strict"]) == 1
    out = capsys.readouterr().out
    assert "LR0703" in out
    if form != "github":
        json.loads(out)


def test_a_file_as_the_counterexample_folder_is_a_usage_error(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    taken = tmp_path / "taken"
    taken.write_text("")
    assert main(["verify", str(EXAMPLES), "--counterexamples", str(taken)]) == 2
    err = capsys.readouterr().err
    assert "not a folder" in err and "Traceback" not in err


@pytest.mark.parametrize("limit", ["0", "-5", "many"])
def test_a_limit_that_is_no_positive_number_is_a_usage_error(
    limit: str, capsys: pytest.CaptureFixture[str]
) -> None:
    with pytest.raises(SystemExit) as stopped:
        main(["verify", str(EXAMPLES), "--max-configurations", limit])
    assert stopped.value.code == 2
    err = capsys.readouterr().err
    assert "is not a positive whole number" in err
    assert "Traceback" not in err
