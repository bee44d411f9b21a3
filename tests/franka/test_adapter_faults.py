"""Every way a run on a real arm can go wrong ends as a robot expert expects: one clear line,
exit code 1, no traceback, and the trace written up to the fault.

The faults are provoked on the protocol simulator: an address that does not exist, one where
nothing listens, a simulator killed in the middle of a motion, a robot in the wrong mode at
the start, a user stop pressed during a motion, a goal outside the workspace; then Ctrl-C and
``--confirm``. The run is the command line's, in a process of its own.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from adapter_support import address, need_franka, simulator, stop

MODELS = Path(__file__).parent / "models"
TOUCH = MODELS / "touch" / "Touch.lr"


def run(where: str, trace: Path, *options: str, **popen) -> subprocess.Popen[str]:
    """``lightrocks run Touch.lr --adapter franka --robot-ip where``, started."""
    command = [
        *(sys.executable, "-m", "lightrocks.app.cli", "run", str(TOUCH), "--path", str(MODELS)),
        *("--adapter", "franka", "--robot-ip", where, "--trace", str(trace), *options),
    ]
    popen.setdefault("stdin", subprocess.DEVNULL)
    return subprocess.Popen(
        command,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL),
        **popen,
    )


def ended(process: subprocess.Popen[str]) -> tuple[int, str]:
    out, err = process.communicate(timeout=600)
    return process.returncode, out + err


def records(trace: Path) -> list[dict]:
    return [json.loads(line) for line in trace.read_text().splitlines()]


def assert_error(trace: Path, code: int, output: str, words: str) -> None:
    """Exit 1, the fault in one line of the output, no traceback, the trace up to it."""
    assert code == 1, output
    assert "Traceback" not in output
    lines = [line for line in output.splitlines() if words in line]
    assert len(lines) == 1, output
    kinds = [r["kind"] for r in records(trace)]
    assert kinds[0] == "run" and "enter" in kinds, kinds
    assert records(trace)[-1] == {
        "time": records(trace)[-1]["time"],
        "kind": "finished",
        "outcome": "error",
    }


def wait_for_motion(trace: Path, timeout: float = 300.0) -> None:
    """Until the trace shows the command sent and the arm moving (a sample of it)."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if trace.exists() and '"sample"' in trace.read_text():
            return
        time.sleep(0.2)
    raise AssertionError("the arm never moved")


def test_an_unknown_address_is_one_line(tmp_path: Path) -> None:
    need_franka()
    trace = tmp_path / "run.jsonl"
    code, output = ended(run("no-such-robot.invalid", trace))
    assert_error(trace, code, output, "unknown robot address 'no-such-robot.invalid'")


def test_a_refused_connection_is_one_line(tmp_path: Path) -> None:
    need_franka()
    trace = tmp_path / "run.jsonl"
    code, output = ended(run(address(9), trace))  # nothing listens there
    assert_error(trace, code, output, f"the robot at {address(9)} refused the connection")


@pytest.mark.slow
def test_a_simulator_killed_mid_motion_is_a_lost_connection(tmp_path: Path) -> None:
    trace = tmp_path / "run.jsonl"
    where = address(10)
    with simulator("empty", where) as server:
        process = run(where, trace)
        wait_for_motion(trace)
        stop(server)
        code, output = ended(process)
    assert_error(trace, code, output, f"lost the connection to the robot at {where}")
    assert any(r["kind"] == "command" for r in records(trace))


@pytest.mark.slow
@pytest.mark.parametrize(
    ("mode", "words"),
    [("Reflex", "is in mode Reflex, not Idle"), ("UserStopped", "is in mode UserStopped")],
)
def test_a_robot_in_the_wrong_mode_is_refused_at_the_start(
    tmp_path: Path, mode: str, words: str
) -> None:
    trace = tmp_path / "run.jsonl"
    where = address(11)
    with simulator("empty", where, mode):
        code, output = ended(run(where, trace))
    assert_error(trace, code, output, words)


@pytest.mark.slow
@pytest.mark.parametrize(
    ("mode", "words"),
    [("UserStopped", "was stopped by its user stop"), ("Reflex", "stopped with a reflex")],
)
def test_a_user_stop_or_a_reflex_during_the_motion_ends_it(
    tmp_path: Path, mode: str, words: str
) -> None:
    trace = tmp_path / "run.jsonl"
    where = address(12)
    with simulator("empty", where, mode, after=500):
        code, output = ended(run(where, trace))
    assert_error(trace, code, output, words)
    assert any(r["kind"] == "sample" for r in records(trace))


@pytest.mark.slow
def test_a_goal_outside_the_workspace_is_refused_before_the_arm_moves(tmp_path: Path) -> None:
    trace = tmp_path / "run.jsonl"
    where = address(13)
    with simulator("empty", where):
        code, output = ended(run(where, trace, "--param", "distance=400mm"))
    assert_error(trace, code, output, "is outside the workspace box")
    assert not any(r["kind"] == "sample" for r in records(trace))


@pytest.mark.slow
def test_ctrl_c_stops_the_arm_and_ends_the_run_interrupted(tmp_path: Path) -> None:
    trace = tmp_path / "run.jsonl"
    where = address(14)
    with simulator("empty", where):
        process = run(where, trace)
        wait_for_motion(trace)
        process.send_signal(signal.SIGINT)
        code, output = ended(process)
        assert code == 130, output
        assert "Traceback" not in output
        assert records(trace)[-1]["outcome"] == "interrupted"
        # the motion is over and the arm idle: a new run starts from where it stopped
        again = tmp_path / "again.jsonl"
        code, output = ended(run(where, again))
    assert code == 0, output
    assert records(again)[-1]["outcome"] == "contact"


@pytest.mark.slow
def test_confirm_refuses_a_stdin_that_is_no_terminal(tmp_path: Path) -> None:
    trace = tmp_path / "run.jsonl"
    where = address(15)
    with simulator("empty", where):
        code, output = ended(run(where, trace, "--confirm"))
    assert_error(trace, code, output, "--confirm needs a terminal to ask on")
    assert not any(r["kind"] == "sample" for r in records(trace))


@pytest.mark.slow
def test_confirm_asks_once_on_a_terminal(tmp_path: Path) -> None:
    where = address(16)
    with simulator("empty", where):
        for answer, code, outcome in (("n", 1, "error"), ("y", 0, "contact")):
            trace = tmp_path / f"{answer}.jsonl"
            terminal, user = os.openpty()
            process = run(where, trace, "--confirm", stdin=user)
            os.close(user)
            os.write(terminal, f"{answer}\n".encode())
            result, output = ended(process)
            os.close(terminal)
            assert result == code, output
            assert "is about to move" in output
            assert records(trace)[-1]["outcome"] == outcome
