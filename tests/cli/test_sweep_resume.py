"""A sweep stopped by Ctrl-C keeps its finished runs (tables marked incomplete), a killed one
keeps them in its journal, and ``sweep --resume`` runs only the others, with the same seeds:
it ends with the tables of a sweep that was never stopped."""

from __future__ import annotations

import csv
import json
import logging
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pyarrow.parquet as pq
import pytest
from distributed import Client, LocalCluster

from lightrocks.app import sweeplog
from lightrocks.app.cli import main

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"
RAIL_TASK = EXAMPLES / "din_rail" / "tasks" / "AssembleRail.lr"
TABLES = ("results.csv", "runs.csv")
DEADLINE = 300.0
"""Seconds a sweep may take to get where a test waits for it (a limit, not a speed)."""


def arguments(output: Path, seeds: int) -> list[str]:
    return [
        *("sweep", str(RAIL_TASK), "--path", str(EXAMPLES), "--adapter", "dryrun"),
        *("--grid", "clearance=10mm,12mm", "--seeds", str(seeds), "-o", str(output)),
    ]


@pytest.fixture(scope="module")
def scheduler():
    with (
        LocalCluster(
            n_workers=2,
            threads_per_worker=1,
            dashboard_address=":0",
            silence_logs=logging.ERROR,
        ) as cluster,
        Client(cluster) as client,
    ):
        yield client.scheduler.address


def journaled(output: Path) -> int:
    path = output / sweeplog.NAME
    return max(0, path.read_bytes().count(b"\n") - 1) if path.exists() else 0


def tables(output: Path) -> dict[str, str]:
    found = {name: (output / name).read_text() for name in TABLES}
    for name in ("results.parquet", "runs.parquet"):
        found[name] = repr(pq.read_table(output / name).to_pylist())
    return found


def complete_column(output: Path) -> list[str]:
    with (output / "results.csv").open() as stream:
        return [row["complete"] for row in csv.DictReader(stream)]


def test_ctrl_c_keeps_the_finished_runs_and_resume_ends_as_if_never_stopped(
    tmp_path: Path, scheduler: str, monkeypatch, capsys
) -> None:
    reference, stopped = tmp_path / "reference", tmp_path / "stopped"
    cluster = ("--scheduler", scheduler)
    assert main([*arguments(reference, 4), *cluster]) == 0
    capsys.readouterr()

    journal_add = sweeplog.Journal.add

    def ctrl_c_after_three(self, point, result) -> None:
        journal_add(self, point, result)
        if len(self.done) == 3:
            raise KeyboardInterrupt

    monkeypatch.setattr(sweeplog.Journal, "add", ctrl_c_after_three)
    assert main([*arguments(stopped, 4), *cluster]) == 130
    said = capsys.readouterr()
    assert "(incomplete)" in said.out and "--resume" in said.err
    assert journaled(stopped) == 3
    assert "False" in complete_column(stopped)
    monkeypatch.undo()

    assert main([*arguments(stopped, 4), *cluster, "--resume"]) == 0
    assert tables(stopped) == tables(reference)
    assert complete_column(stopped) == ["True", "True"]
    assert journaled(stopped) == 8


def test_resume_refuses_a_sweep_with_other_arguments(tmp_path: Path, scheduler: str, capsys):
    output = tmp_path / "out"
    assert main([*arguments(output, 2), "--scheduler", scheduler]) == 0
    before = (output / sweeplog.NAME).read_bytes()
    assert main([*arguments(output, 3), "--scheduler", scheduler, "--resume"]) == 2
    assert "other arguments" in capsys.readouterr().err
    assert (output / sweeplog.NAME).read_bytes() == before


def test_a_journal_line_cut_off_by_a_kill_is_left_out(tmp_path: Path) -> None:
    path = tmp_path / sweeplog.NAME
    header = {"sweep": {"seeds": 2}}
    result = {
        "seed": 0,
        "outcome": "done",
        "success": True,
        "time": 1.5,
        "skills": [["T/S", 1.0]],
        "measurements": {},
        "fault": "",
        "active": [],
        "video": "",
    }
    whole = json.dumps({"point": 0, "result": result})
    path.write_text(f"{json.dumps(header)}\n{whole}\n{whole[:40]}")
    notes: list[str] = []
    done = sweeplog.finished_runs(tmp_path, header["sweep"], notes.append)
    assert list(done) == [(0, 0)] and done[0, 0].skills == [("T/S", 1.0)]
    assert "cut off" in notes[0]


def _interruptible() -> None:
    """Ctrl-C reaches the child as from a terminal (a test runner's worker may ignore it)."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


@pytest.mark.slow
@pytest.mark.parametrize("stop", [signal.SIGINT, signal.SIGKILL])
def test_a_sweep_stopped_from_outside_resumes_to_the_same_tables(
    tmp_path: Path, scheduler: str, stop: signal.Signals
) -> None:
    reference, stopped = tmp_path / "reference", tmp_path / "stopped"
    seeds = 60
    assert main([*arguments(reference, seeds), "--scheduler", scheduler]) == 0
    env = {**os.environ, "PYTHONIOENCODING": "utf-8"}
    command = [sys.executable, "-m", "lightrocks.app.cli", *arguments(stopped, seeds)]
    process = subprocess.Popen(  # its own local cluster, killed with it as one group
        [*command, "--workers", "2"],
        env=env,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        text=True,
        preexec_fn=_interruptible,
        start_new_session=True,
    )
    deadline = time.monotonic() + DEADLINE
    while journaled(stopped) < 5:
        assert process.poll() is None, process.stderr.read()
        assert time.monotonic() < deadline, "no run finished in time"
        time.sleep(0.05)
    if stop == signal.SIGKILL:
        os.killpg(process.pid, signal.SIGKILL)
    else:
        process.send_signal(signal.SIGINT)
    _, error = process.communicate(timeout=DEADLINE)
    if stop == signal.SIGINT:
        assert process.returncode == 130, error
        assert "Traceback" not in error
        assert "False" in complete_column(stopped)
    kept = journaled(stopped)
    assert 5 <= kept < 2 * seeds, "the sweep was not stopped half-way"
    assert main([*arguments(stopped, seeds), "--scheduler", scheduler, "--resume"]) == 0
    assert tables(stopped) == tables(reference)
