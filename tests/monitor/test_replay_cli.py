"""``lightrocks replay``: what it refuses before serving anything."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from lightrocks.app.cli import main

pytest.importorskip("starlette", reason="the monitor needs the 'monitor' extra")


def write(path: Path, *records: dict) -> Path:
    path.write_text("".join(json.dumps(r) + "\n" for r in records), encoding="utf-8")
    return path


def said(capsys) -> str:
    """The error output with the terminal's line wrapping undone."""
    return " ".join(capsys.readouterr().err.split())


ENTER = {"time": 0.0, "kind": "enter", "state": "ScrewTask", "layer": "task"}


def test_a_trace_without_its_model_needs_model(tmp_path: Path, capsys) -> None:
    trace = write(tmp_path / "old.jsonl", ENTER)
    assert main(["replay", str(trace), "--monitor", "0"]) == 2
    assert "names no model" in said(capsys)


def test_a_model_that_is_gone_is_a_usage_error(tmp_path: Path, capsys) -> None:
    header = {"time": 0.0, "kind": "run", "model": str(tmp_path / "Gone.lr"), "path": []}
    trace = write(tmp_path / "run.jsonl", header, ENTER)
    assert main(["replay", str(trace), "--monitor", "0"]) == 2
    assert "is not on this machine: give the model with --model FILE" in said(capsys)


@pytest.mark.parametrize(
    ("content", "message"),
    [("not json\n", "run.jsonl:1: not a JSON line"), ("", "the trace enters no state")],
)
def test_a_file_that_is_no_trace_is_refused(
    tmp_path: Path, capsys, content: str, message: str
) -> None:
    trace = tmp_path / "run.jsonl"
    trace.write_text(content, encoding="utf-8")
    assert main(["replay", str(trace), "--monitor", "0"]) == 1
    assert message in said(capsys)


def test_a_bad_address_is_a_usage_error(tmp_path: Path, capsys) -> None:
    trace = write(tmp_path / "run.jsonl", ENTER)
    assert main(["replay", str(trace), "--monitor", "host:port"]) == 2
    assert "--monitor expects [HOST:]PORT" in said(capsys)
