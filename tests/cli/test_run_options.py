"""``lightrocks run`` options: noise, video, success outcome, measurements and exit codes.

Exit codes: 0 the run ended with the success outcome, 1 it did not, 2 wrong use.
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import pytest

from lightrocks.app.cli import main
from lightrocks.app.display import format_measurement
from lightrocks.app.errors import RunError
from lightrocks.app.seeds import wilson
from lightrocks.app.specs import seed_trace
from lightrocks.app.values import parse_noise, parse_value

ROOT = Path(__file__).resolve().parents[2]
SCREW_TASK = str(ROOT / "examples" / "screwing" / "tasks" / "ScrewTask.lr")
TURNSTILE = str(ROOT / "examples" / "plain" / "Turnstile.lr")


DOMAIN = """package t;

<<timeout="2 s">> device Arm {
  command move(Length x);
  sensor Boolean goalReached;
}

<<scene="none">> cell Cell {
  arm : Arm;
}
"""

MOVE = """package t;

import t.Cell;

<<action>> statechart Move {
  do / arm.move(x = 1 mm);

  end condition reached [arm.goalReached];
}
"""

JOB = """package t;

import t.Cell;
import t.Move;

<<skill>> statechart Job {
  start condition go;
  end condition done;
  end condition failed;

  <<import="Move">> state Step;

  go -> Step;
  Step -> done reached;
  Step -> failed timeout;
}
"""


@pytest.fixture(autouse=True)
def cache(tmp_path_factory: pytest.TempPathFactory, monkeypatch: pytest.MonkeyPatch) -> None:
    """One generated-code cache for the module, outside the repository."""
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path_factory.getbasetemp() / "xdg"))


@pytest.fixture(scope="module")
def job(tmp_path_factory: pytest.TempPathFactory) -> list[str]:
    """``MODEL --path ROOT`` of a one-step skill that the dry run finishes with ``done``."""
    root = tmp_path_factory.mktemp("models")
    (root / "t").mkdir()
    for name, text in (("Cell.lrd", DOMAIN), ("Move.lr", MOVE), ("Job.lr", JOB)):
        (root / "t" / name).write_text(text, encoding="utf-8")
    return [str(root / "t" / "Job.lr"), "--path", str(root)]


def run(capsys: pytest.CaptureFixture[str], *argv: str) -> tuple[int, str, str]:
    status = main(["run", *argv])
    captured = capsys.readouterr()
    return status, captured.out, captured.err


def test_noise_is_a_length_and_an_angle() -> None:
    assert parse_noise("2mm,2deg") == pytest.approx((0.002, math.radians(2)))
    assert parse_noise("0.5 mm, 0.01 rad") == pytest.approx((0.0005, 0.01))
    for bad in ("2mm", "2deg,2mm", "2mm,2", "2mm,2deg,1", "-1mm,2deg", "x,y"):
        with pytest.raises(RunError, match="perception-noise"):
            parse_noise(bad)
    with pytest.raises(RunError, match="unknown unit 'dge'"):
        parse_noise("2mm,2dge")


def test_param_value_with_an_unknown_unit_is_refused() -> None:
    with pytest.raises(RunError, match="unknown unit 'foo'"):
        parse_value("2 foo")


def test_measurements_are_readable() -> None:
    assert format_measurement("screw_depth", 0.01204) == "12.0 mm"
    assert format_measurement("terminal1_height", 0.0) == "0.0 mm"
    assert format_measurement("terminal1_latched", True) == "yes"
    assert format_measurement("screw_bottomed", False) == "no"
    assert format_measurement("terminals_latched", 3.0) == "3"
    assert format_measurement("screw_x", 0.5501) == "550.1 mm"
    assert format_measurement("screw_tilt", 0.0349) == "2.0 deg"
    assert format_measurement("ring_offset", 0.000102503) == "0.1 mm"
    assert format_measurement("peg_distance", 0.0123) == "12.3 mm"


@pytest.mark.parametrize(
    ("options", "message"),
    [
        (["--adapter", "dryrun", "--perception-noise", "2mm"], "is not LENGTH,ANGLE"),
        (["--adapter", "dryrun", "--perception-noise", "2mm,2deg"], "has no perception noise"),
        (["--adapter", "dryrun", "--video", "run.mp4"], "cannot record a video"),
        (["--video", "run.mp4"], "need an adapter"),
        (["--adapter", "mujoco", "--video", "run.mp4", "--seeds", "2"], "single run"),
        (["--adapter", "dryrun", "--workers", "2"], "--workers needs --seeds"),
        (["--adapter", "dryrun", "--seeds", "0"], "--seeds must be at least 1"),
        (
            ["--adapter", "dryrun", "--success", "over"],
            "Job has no outcome 'over'; outcomes: done, failed",
        ),
    ],
)
def test_usage_errors_exit_2_and_write_nothing(
    options: list[str],
    message: str,
    job: list[str],
    tmp_path: Path,
    capsys: pytest.CaptureFixture[str],
) -> None:
    trace = tmp_path / "run.jsonl"
    status, out, err = run(capsys, *job, "--trace", str(trace), *options)
    assert status == 2
    assert message in err
    assert "Traceback" not in err + out
    assert list(tmp_path.iterdir()) == []


def test_dry_run_succeeds_with_the_first_end_condition(
    job: list[str], tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    trace = tmp_path / "run.jsonl"
    status, out, _ = run(capsys, *job, "--adapter", "dryrun", "--seed", "4", "--trace", str(trace))
    assert status == 0
    assert re.search(r"Job\W+0\.100", out)  # the skill table
    assert out.splitlines()[-1] == "outcome: done after 0.100 s"
    assert "measurement" not in out  # the dry run measures nothing
    assert '"outcome": "done"' in trace.read_text().splitlines()[-1]


def test_another_outcome_counts_as_failure(
    job: list[str], capsys: pytest.CaptureFixture[str]
) -> None:
    status, out, _ = run(capsys, *job, "--adapter", "dryrun", "--success", "failed")
    assert status == 1
    assert "outcome: done" in out


def test_plain_chart_succeeds_with_its_final_state(capsys: pytest.CaptureFixture[str]) -> None:
    assert run(capsys, TURNSTILE, "--events", "coin,push,shutdown")[0] == 0
    status, out, _ = run(capsys, TURNSTILE, "--events", "coin")
    assert status == 1
    assert "active: Turnstile / Operating / Unlocked" in out


def test_wilson_interval() -> None:
    assert wilson(0, 3) == pytest.approx((0.0, 0.5615), abs=1e-4)
    assert wilson(5, 10) == pytest.approx((0.2366, 0.7634), abs=1e-4)
    assert wilson(10, 10) == pytest.approx((0.7225, 1.0), abs=1e-4)


def test_seeds_run_in_workers_with_a_trace_each(
    job: list[str], tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    trace = tmp_path / "run.jsonl"
    options = ["--adapter", "dryrun", "--seeds", "3", "--workers", "2", "--trace", str(trace)]
    status, out, err = run(capsys, *job, *options)
    assert status == 0, out + err
    rows = re.findall(r"^\W*(\d+)\W+done\W+0\.100\W*$", out, re.MULTILINE)
    assert rows == ["0", "1", "2"]
    assert "success (done): 3/3 = 100%, 95% Wilson interval 44%–100%" in out
    assert "simulated time: 0.100 ± 0.000 s, min 0.100 s, max 0.100 s" in out
    assert "3/3" in err  # the progress bar
    assert sorted(p.name for p in tmp_path.iterdir()) == [
        f"run.seed{seed}.jsonl" for seed in range(3)
    ]
    assert seed_trace(trace, 7) == tmp_path / "run.seed7.jsonl"


def test_seeds_count_the_failures(job: list[str], capsys: pytest.CaptureFixture[str]) -> None:
    options = ["--adapter", "dryrun", "--seeds", "2", "--seed", "5", "--success", "failed"]
    status, out, _ = run(capsys, *job, *options)
    assert status == 1
    assert re.findall(r"^\W*(\d+)\W+done", out, re.MULTILINE) == ["5", "6"]
    assert "success (failed): 0/2 = 0%" in out


@pytest.mark.slow
def test_screw_task_in_mujoco_reports_the_screw_depth(capsys: pytest.CaptureFixture[str]):
    status, out, _ = run(capsys, SCREW_TASK, "--adapter", "mujoco")
    assert status == 0, out
    depth = re.search(r"screw depth\W+([\d.]+) mm", out)
    assert depth is not None, out
    assert float(depth.group(1)) == pytest.approx(12.0, abs=0.6)
    assert re.search(r"screw bottomed\W+yes", out)


def test_plain_chart_without_final_state_resting_after_its_events_succeeds(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    (tmp_path / "Door.lr").write_text(
        "statechart Door {\n  initial state Shut;\n  state Open;\n"
        "  Shut -> Open open;\n  Open -> Shut close;\n}\n"
    )
    status, out, _ = run(capsys, str(tmp_path / "Door.lr"), "--events", "open")
    assert status == 0
    assert "active: Door / Open" in out


def test_the_active_states_of_every_region_are_shown(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    (tmp_path / "Pair.lr").write_text(
        "statechart Pair {\n  region Left {\n    initial state A;\n    state B;\n"
        "    A -> B go;\n  }\n  region Right {\n    initial state C;\n  }\n}\n"
    )
    status, out, _ = run(capsys, str(tmp_path / "Pair.lr"), "--events", "go")
    assert status == 0
    assert "active: Pair / Left / B | Pair / Right / C" in out


DELAYED = (
    "statechart Lamp {\n  initial state Off;\n  state On;\n"
    "  Off -> On on;\n  On -> Off after(1 s);\n}\n"
)


def test_events_advance_the_virtual_clock_and_unknown_events_are_usage_errors(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    model = tmp_path / "Lamp.lr"
    model.write_text(DELAYED)
    status, out, _ = run(capsys, str(model), "--events", "on,+500ms")
    assert status == 0 and "active: Lamp / On" in out
    status, out, _ = run(capsys, str(model), "--events", "on,+1s")
    assert status == 0 and "active: Lamp / Off" in out
    trace = tmp_path / "run.jsonl"
    status, _, err = run(capsys, str(model), "--events", "on,off", "--trace", str(trace))
    assert status == 2 and "unknown event 'off'; Lamp accepts: on" in err
    assert not trace.exists()
    status, _, err = run(capsys, str(model), "--events", "+2m")
    assert status == 2 and "'+2m' is not a time to wait" in err
