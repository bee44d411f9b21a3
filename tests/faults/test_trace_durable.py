"""A trace reaches its file record by record: a paused run's trace holds everything up to the
pause, and a run killed at any moment leaves a trace that ``plot`` and ``replay`` read up to
the last record written (a line cut off by the kill is left out, with a note)."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from hypothesis import given
from hypothesis import strategies as st

from lightrocks.app.monitor.traces import TraceError, read_trace
from lightrocks.runtime import Trace

ROOT = Path(__file__).resolve().parents[2]
SCREW_TASK = ROOT / "examples" / "screwing" / "tasks" / "ScrewTask.lr"
RAIL_TASK = ROOT / "examples" / "din_rail" / "tasks" / "AssembleRail.lr"
DEADLINE = 120.0
"""Seconds a process may take to get where a test waits for it (a limit, not a speed)."""

RECORDS = [
    {"time": 0.0, "kind": "enter", "state": "T", "layer": "task"},
    {"time": 0.5, "kind": "enter", "state": "T/S", "layer": "skill"},
    {"time": 1.0, "kind": "exit", "state": "T/S"},
    {"time": 1.0, "kind": "finished", "outcome": "done"},
]


def on_disk(path: Path) -> list[dict]:
    return [json.loads(line) for line in path.read_text(encoding="utf-8").splitlines()]


def test_every_record_is_on_disk_as_soon_as_it_is_written(tmp_path: Path) -> None:
    path = tmp_path / "run.jsonl"
    trace = Trace(path)
    for count, record in enumerate(RECORDS, 1):
        trace.write(
            record["time"],
            record["kind"],
            **{k: v for k, v in record.items() if k not in ("time", "kind")},
        )
        assert on_disk(path) == RECORDS[:count]
    trace.close()


def test_records_given_to_an_open_stream_are_flushed(tmp_path: Path) -> None:
    path = tmp_path / "run.jsonl"
    with path.open("w", encoding="utf-8") as stream:
        trace = Trace(stream)
        trace.write(0.0, "enter", state="T", layer="task")
        assert on_disk(path) == [RECORDS[0]]


@given(cut=st.integers(min_value=0, max_value=10_000))
def test_a_trace_cut_anywhere_reads_up_to_its_last_whole_record(tmp_path_factory, cut: int):
    whole = "".join(json.dumps(r) + "\n" for r in RECORDS).encode()
    cut %= len(whole) + 1
    path = tmp_path_factory.mktemp("cut") / "run.jsonl"
    path.write_bytes(whole[:cut])
    notes: list[str] = []
    records = read_trace(path, notes.append)
    complete = whole[:cut].count(b"\n")
    tail = whole[:cut].rsplit(b"\n", 1)[-1]
    whole_but_its_break = whole[cut : cut + 1] == b"\n"
    assert records == RECORDS[: complete + whole_but_its_break]
    assert bool(notes) == bool(tail and not whole_but_its_break)


def test_a_broken_line_before_the_last_is_still_an_error(tmp_path: Path) -> None:
    path = tmp_path / "run.jsonl"
    path.write_text('{"time": 0, "kind": "enter", "sta\n' + json.dumps(RECORDS[1]) + "\n")
    with pytest.raises(TraceError, match=r"run\.jsonl:1: not a JSON line"):
        read_trace(path)


def _start(*arguments: str, cwd: Path) -> subprocess.Popen:
    env = {**os.environ, "XDG_CACHE_HOME": str(cwd / "cache")}
    command = [sys.executable, "-m", "lightrocks.app.cli", *arguments]
    return subprocess.Popen(
        command, cwd=cwd, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True
    )


def _wait_for(condition, process: subprocess.Popen) -> None:
    deadline = time.monotonic() + DEADLINE
    while not condition():
        if process.poll() is not None:
            pytest.fail(f"the process ended early: {process.stderr.read()}")
        if time.monotonic() > deadline:
            process.kill()
            pytest.fail("the process did not get there in time")
        time.sleep(0.05)


def _kinds(path: Path) -> list[str]:
    if not path.exists():
        return []
    return [r["kind"] for r in read_trace(path)]


def _replays(trace: Path, cwd: Path) -> None:
    """``replay`` serves the trace: it says so, then it is stopped."""
    process = _start("replay", str(trace), "--monitor", "0", cwd=cwd)
    try:
        deadline = time.monotonic() + DEADLINE
        said = ""
        while "replaying" not in said and time.monotonic() < deadline:
            line = process.stderr.readline()
            if not line:
                break
            said += line
        assert "replaying" in said, said
    finally:
        process.kill()
        process.wait()


def test_a_paused_run_killed_leaves_its_trace_up_to_the_pause(tmp_path: Path) -> None:
    pytest.importorskip("starlette", reason="the monitor needs the 'monitor' extra")
    trace = tmp_path / "run.jsonl"
    arguments = ("run", str(SCREW_TASK), "--adapter", "dryrun", "--trace", str(trace))
    process = _start(*arguments, "--monitor", "0", "--break", "ScrewTask.Carry", cwd=tmp_path)
    _wait_for(lambda: "paused" in _kinds(trace), process)
    os.kill(process.pid, signal.SIGKILL)
    process.wait()
    records = read_trace(trace)
    assert records[-1]["kind"] == "paused" and records[-1]["at"] == "ScrewTask/Carry"
    assert records[0]["kind"] == "run"
    _replays(trace, tmp_path)


def test_a_running_run_killed_leaves_a_readable_trace(tmp_path: Path) -> None:
    pytest.importorskip("mujoco", reason="a long run needs the simulated cell")
    pytest.importorskip("starlette", reason="replay needs the 'monitor' extra")
    trace = tmp_path / "run.jsonl"
    process = _start(
        "run", str(RAIL_TASK), "--adapter", "mujoco", "--trace", str(trace), cwd=tmp_path
    )
    _wait_for(lambda: trace.exists() and trace.stat().st_size > 20_000, process)
    os.kill(process.pid, signal.SIGKILL)
    process.wait()
    notes: list[str] = []
    records = read_trace(trace, notes.append)
    assert len(records) > 50 and "finished" not in {r["kind"] for r in records}
    assert len(records) >= trace.read_bytes().count(b"\n")
    _replays(trace, tmp_path)
