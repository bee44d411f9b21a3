"""``run --monitor … --abort-at STATE``: the run stops safely on entering that state."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from lightrocks.app.cli import main

pytest.importorskip("starlette", reason="the monitor needs the 'monitor' extra")

ROOT = Path(__file__).resolve().parents[2]
SCREW_TASK = str(ROOT / "examples" / "screwing" / "tasks" / "ScrewTask.lr")


def test_the_run_is_aborted_where_asked(tmp_path: Path, tmp_path_factory) -> None:
    trace = tmp_path / "run.jsonl"
    env = {**os.environ, "XDG_CACHE_HOME": str(tmp_path_factory.getbasetemp() / "cache")}
    command = [sys.executable, "-m", "lightrocks.app.cli", "run", SCREW_TASK]
    command += ["--adapter", "dryrun", "--trace", str(trace), "--monitor", "0"]
    command += ["--abort-at", "ScrewTask.Carry"]
    done = subprocess.run(command, env=env, capture_output=True, text=True, timeout=300)
    assert done.returncode == 1, done.stderr
    assert "outcome: preempted" in done.stdout
    run = [json.loads(line) for line in trace.read_text().splitlines()]
    entered = [r["state"] for r in run if r["kind"] == "enter"]
    assert entered[-1] == "ScrewTask/Carry", "the run went on"
    assert [r["kind"] for r in run[-2:]] == ["aborted", "finished"]
    assert run[-2]["active"] == ["ScrewTask", "ScrewTask/Carry"]
    assert run[-1]["outcome"] == "preempted"
    assert not [r for r in run if r["kind"] == "error"]


def test_abort_at_needs_the_monitor(capsys) -> None:
    status = main(["run", SCREW_TASK, "--adapter", "dryrun", "--abort-at", "ScrewTask.DriveIn"])
    assert status == 2
    assert "--abort-at" in " ".join(capsys.readouterr().err.split())
