"""Ctrl-C ends a watched run at once, paused or not: the arm holds, the trace ends with
``interrupted`` and ``finished``, and nothing pauses the run again while it ends."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest

from lightrocks.app.monitor.control import RunControl
from lightrocks.app.monitor.traces import read_trace

pytest.importorskip("starlette", reason="the monitor needs the 'monitor' extra")

ROOT = Path(__file__).resolve().parents[2]
SCREW_TASK = ROOT / "examples" / "screwing" / "tasks" / "ScrewTask.lr"
DEADLINE = 120.0
"""Seconds a process may take to get where the test waits for it (a limit, not a speed)."""


def _interruptible() -> None:
    """Ctrl-C reaches the child as from a terminal (a test runner's worker may ignore it)."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def _kinds(trace: Path) -> list[str]:
    return [r["kind"] for r in read_trace(trace)] if trace.exists() else []


@pytest.mark.parametrize("pause", [["--paused"], ["--break", "ScrewTask.Carry"]])
def test_one_ctrl_c_ends_a_paused_run_with_a_finished_trace(
    tmp_path: Path, pause: list[str]
) -> None:
    trace = tmp_path / "run.jsonl"
    command = [sys.executable, "-m", "lightrocks.app.cli", "run", str(SCREW_TASK)]
    command += ["--adapter", "dryrun", "--trace", str(trace), "--monitor", "0", *pause]
    env = {**os.environ, "XDG_CACHE_HOME": str(tmp_path / "cache")}
    process = subprocess.Popen(
        command, env=env, stderr=subprocess.PIPE, text=True, preexec_fn=_interruptible
    )
    deadline = time.monotonic() + DEADLINE
    while "paused" not in _kinds(trace):
        assert process.poll() is None, process.stderr.read()
        if time.monotonic() > deadline:
            process.kill()
            pytest.fail("the run did not pause in time")
        time.sleep(0.05)
    process.send_signal(signal.SIGINT)
    try:
        _, error = process.communicate(timeout=DEADLINE)
    except subprocess.TimeoutExpired:
        process.kill()
        pytest.fail("one Ctrl-C did not end the paused run")
    assert process.returncode == 130, error
    assert "Traceback" not in error
    records = read_trace(trace)
    kinds = [r["kind"] for r in records]
    assert kinds.count("paused") == 1, "the run paused again after Ctrl-C"
    assert kinds[-2:] == ["interrupted", "finished"]
    assert records[-1]["outcome"] == "interrupted"
    assert "error" not in kinds, "the arm did not hold"


def test_a_run_that_is_ending_pauses_no_more() -> None:
    control = RunControl(paused=True)
    control.stops_at({"time": 1.0, "kind": "interrupted", "active": []})
    assert not control.paused
    control.pause()
    assert not control.paused
    assert not control.stops_at({"time": 1.0, "kind": "enter", "state": "T"})


def test_ctrl_c_while_waiting_ends_the_pause() -> None:
    control = RunControl(paused=True)
    interrupted = threading.Event()
    waiting = threading.main_thread().ident

    def press_ctrl_c() -> None:
        time.sleep(0.2)
        interrupted.set()
        signal.pthread_kill(waiting, signal.SIGINT)

    # Python's own handler, as `lightrocks run` has it: a test worker may ignore SIGINT
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        threading.Thread(target=press_ctrl_c, daemon=True).start()
        with pytest.raises(KeyboardInterrupt):
            control.wait()
    finally:
        signal.signal(signal.SIGINT, previous)
    assert interrupted.is_set() and control.ending and not control.paused
