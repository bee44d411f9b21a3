"""Reports of runs over seeds and sweeps put the scene's judgement of the goal beside the
outcome: a ``goal`` column, how many runs the ground truth confirms next to the success count
(which stays the outcome's), a ``goal_met`` column in the sweep's rows; a hook of the scene
that raised is named per seed and fails the command."""

from __future__ import annotations

from pathlib import Path

import pytest

from lightrocks.app.cli import main
from lightrocks.app.display import show_seeds
from lightrocks.app.run import RunResult
from lightrocks.app.sweep import GridPoint, run_rows

ROOT = Path(__file__).resolve().parents[2]


def result(seed: int, outcome: str, goal: bool | None, scene_fault: str = "") -> RunResult:
    """A run that succeeded unless it ``failed``."""
    success = outcome != "failed"
    return RunResult(seed, outcome, success, 10.0 + seed, [], {}, "", (), "", goal, scene_fault)


def table_rows(out: str) -> list[list[str]]:
    return [
        [cell.strip() for cell in line.strip("│").split("│")]
        for line in out.splitlines()
        if line.startswith("│")
    ]


def test_the_seed_table_shows_the_goal_and_the_summary_counts_it_apart_from_success(
    capsys: pytest.CaptureFixture[str],
) -> None:
    results = [result(0, "placed", True), result(1, "placed", False), result(2, "failed", False)]
    status = show_seeds("RingOnPost", "placed", results)
    out = capsys.readouterr().out
    assert status == 1  # one run did not end placed; the goal does not change the exit
    assert [row[:3] for row in table_rows(out)] == [
        ["0", "placed", "yes"],
        ["1", "placed", "no"],
        ["2", "failed", "no"],
    ]
    assert (
        "success (placed): 2/3 = 67%, 95% Wilson interval 21%–94%; "
        "goal met (the scene's ground truth): 1/3"
    ) in out


def test_without_a_judged_goal_there_is_no_goal_column(
    capsys: pytest.CaptureFixture[str],
) -> None:
    assert show_seeds("Job", "done", [result(0, "done", None), result(1, "done", None)]) == 0
    out = capsys.readouterr().out
    assert "goal" not in out
    assert [len(row) for row in table_rows(out)] == [3, 3]


def test_a_scene_hook_that_raised_is_named_per_seed_and_fails_the_command(
    capsys: pytest.CaptureFixture[str],
) -> None:
    fault = "scene 'ring_post': measurements() raised KeyError: 'ring'"
    results = [result(0, "placed", True), result(1, "placed", None, fault)]
    assert show_seeds("RingOnPost", "placed", results) == 1
    out = capsys.readouterr().out
    assert f"seed 1: error: {fault}" in out
    assert [row[2] for row in table_rows(out)] == ["yes", ""]
    assert "success (placed): 2/2" in out and "goal met (the scene's ground truth): 1/2" in out


def test_the_sweep_rows_hold_the_goal_beside_the_success() -> None:
    point = GridPoint(("grip=18mm",), (0.002, 0.0))
    rows = run_rows([(point, result(0, "placed", False)), (point, result(1, "failed", None))])
    assert [(r["success"], r["goal_met"]) for r in rows] == [(True, False), (False, None)]
    assert list(rows[0]).index("goal_met") == list(rows[0]).index("success") + 1


@pytest.mark.slow
def test_runs_over_seeds_are_judged_in_their_workers(capsys: pytest.CaptureFixture[str]) -> None:
    action = ROOT / "examples" / "screwing" / "actions" / "OpenGripper.lr"
    arguments = ["--path", str(ROOT / "examples"), "--adapter", "mujoco"]
    status = main(["run", str(action), *arguments, "--seeds", "2", "--workers", "2"])
    out = capsys.readouterr().out
    assert status == 0
    assert [row[:3] for row in table_rows(out)] == [["0", "done", "no"], ["1", "done", "no"]]
    assert "success (done): 2/2" in out
    assert "goal met (the scene's ground truth): 0/2" in out  # the screw is not in the cube
