"""What ``run`` and ``check`` are given is refused clearly when it is not a model or a place to
write: exit 2, a message naming it, no traceback, nothing read from a device or a FIFO."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from lightrocks.app.cli import main

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"
TURNSTILE = EXAMPLES / "plain" / "Turnstile.lr"


def _refused(argv: list[str], capsys: pytest.CaptureFixture[str], words: str) -> None:
    assert main(argv) == 2
    error = capsys.readouterr().err
    assert words in " ".join(error.split()), error
    assert "internal error" not in error and "Traceback" not in error


@pytest.mark.parametrize(
    ("model", "words"),
    [
        (EXAMPLES / "screwing", "is a folder"),
        (EXAMPLES / "din_rail" / "cell" / "RailCell.lrd", "is not a statechart file"),
        (Path(os.devnull), "not a regular file"),
    ],
)
def test_run_takes_one_statechart_file(model: Path, words: str, capsys) -> None:
    _refused(["run", str(model)], capsys, words)


def test_run_of_a_file_without_statechart(tmp_path: Path, capsys) -> None:
    empty = tmp_path / "Empty.lr"
    empty.write_text("// nothing here\n")
    assert main(["run", str(empty)]) in (1, 2)
    error = capsys.readouterr()
    assert "internal error" not in error.err + error.out


def test_trace_into_a_folder_a_fifo_or_an_unwritable_place(tmp_path: Path, capsys) -> None:
    fifo = tmp_path / "trace.fifo"
    os.mkfifo(fifo)
    run = ["run", str(TURNSTILE), "--events", "shutdown", "--trace"]
    _refused([*run, str(tmp_path)], capsys, "is not a regular file")
    _refused([*run, str(fifo)], capsys, "is not a regular file")  # would block forever
    _refused([*run, "/proc/lightrocks-trace"], capsys, "cannot write /proc/lightrocks-trace")


@pytest.mark.parametrize("kind", ["fifo", "device link"])
def test_check_reads_no_fifo_or_device(tmp_path: Path, kind: str, capsys) -> None:
    special = tmp_path / "Model.lr"
    if kind == "fifo":
        os.mkfifo(special)
    else:
        special.symlink_to("/dev/zero")
    _refused(["check", str(special)], capsys, "not a regular file or folder")
