"""``lightrocks sweep``: every grid point over the same seeds on a Dask cluster, one table
row per point with its success rate and Wilson interval, in CSV, Parquet and a plot."""

from __future__ import annotations

import csv
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

from lightrocks.app.cli import main
from lightrocks.app.errors import RunError
from lightrocks.app.pipeline import spec_for
from lightrocks.app.seeds import wilson
from lightrocks.app.sweep import grid_points, parse_grid, split_values, sweep

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"
RAIL_TASK = EXAMPLES / "din_rail" / "tasks" / "AssembleRail.lr"

GATE = """package g;

statechart Gate {
  parameters {
    Integer n = 0;
    Length gap = 1 mm;
  }
  initial state Job {
    initial final state Done;
  }
  final state Ok;
  final state Bad;
  Job -> Ok [n > 1];
  Job -> Bad [n <= 1];
}
"""
"""Succeeds exactly when ``n`` exceeds 1, whatever the seed."""


@pytest.fixture(scope="module")
def client():
    with (
        LocalCluster(
            n_workers=2,
            threads_per_worker=1,
            dashboard_address=":0",  # any free port: several clusters may run at once
            silence_logs=logging.ERROR,
        ) as cluster,
        Client(cluster) as client,
    ):
        yield client


@pytest.fixture
def gate(tmp_path: Path) -> Path:
    model = tmp_path / "models" / "g" / "Gate.lr"
    model.parent.mkdir(parents=True)
    model.write_text(GATE)
    return model


def _sweep(gate: Path, *options: str) -> int:
    return main(["sweep", str(gate), "--path", str(gate.parents[1]), *options])


def test_values_split_at_commas_outside_brackets():
    assert split_values("1 mm, [1 mm, 2 mm],3") == ["1 mm", "[1 mm, 2 mm]", "3"]
    with pytest.raises(RunError, match="not a comma-separated list"):
        split_values("1,,2")
    with pytest.raises(RunError, match="not a comma-separated list"):
        split_values("[1 mm, 2 mm")


@pytest.mark.parametrize(
    ("options", "message"),
    [(["n"], "is not NAME=VALUE"), (["n=1", "n=2"], "names 'n' twice"), (["=1"], "NAME=VALUE")],
)
def test_malformed_grids_are_refused(options: list[str], message: str):
    with pytest.raises(RunError, match=message):
        parse_grid(options)


def test_grid_points_cover_every_combination_once():
    grid = parse_grid(["n=1,2,3", "gap=1mm,2mm"])
    noises = [(0.0, 0.0), (0.002, 0.03)]
    points = grid_points(grid, noises)
    assert len(points) == len(set(points)) == 3 * 2 * 2
    assert {p.params for p in points} == {
        (f"n={n}", f"gap={g}") for n in "123" for g in ("1mm", "2mm")
    }
    assert points[0].noise != points[1].noise  # noise varies fastest


def test_sweep_writes_the_rate_of_every_grid_point(gate: Path, client: Client, capsys):
    output = gate.parents[2] / "out"
    address = client.scheduler.address
    code = _sweep(
        gate, "--grid", "n=0,1,2,3", "--seeds", "3", "--scheduler", address, "-o", str(output)
    )
    assert code == 0
    with (output / "results.csv").open() as stream:
        rows = list(csv.DictReader(stream))
    assert [(r["n"], r["successes"], r["runs"]) for r in rows] == [
        ("0", "0", "3"),
        ("1", "0", "3"),
        ("2", "3", "3"),
        ("3", "3", "3"),
    ]
    low, high = wilson(0, 3)
    assert float(rows[0]["wilson_low"]) == pytest.approx(low)
    assert float(rows[0]["wilson_high"]) == pytest.approx(high)
    table = pq.read_table(output / "results.parquet").to_pylist()
    assert [row["successes"] for row in table] == [int(r["successes"]) for r in rows]
    runs = pq.read_table(output / "runs.parquet").to_pylist()
    assert sorted((r["n"], r["seed"], r["outcome"]) for r in runs) == sorted(
        (n, seed, "Ok" if int(n) > 1 else "Bad") for n in "0123" for seed in range(3)
    )
    assert (output / "success.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    shown = capsys.readouterr().out
    assert "3/3 = 100%" in shown and "0/3 = 0%" in shown


def test_sweep_on_its_own_local_cluster(gate: Path, tmp_path: Path):
    output = tmp_path / "local"
    code = _sweep(gate, "--grid", "n=2", "--seeds", "2", "--workers", "2", "-o", str(output))
    assert code == 0
    with (output / "results.csv").open() as stream:
        assert [(r["n"], r["successes"]) for r in csv.DictReader(stream)] == [("2", "2")]


@pytest.mark.parametrize(
    ("options", "message"),
    [
        (["--grid", "m=1,2"], "has no parameter 'm'"),
        (["--grid", "n=1,2.5"], "expects Integer"),
        (["--grid", "gap=1mm,2"], "needs its unit"),
        (["--perception-noise", "1mm,1deg;2mm"], "is not LENGTH,ANGLE"),
        (["--scheduler", "tcp://127.0.0.1:9", "--grid", "n=1"], "--scheduler"),
        (["--workers", "0"], "--workers"),
        (["--seeds", "0"], "--seeds must be at least 1"),
    ],
)
def test_bad_sweeps_are_usage_errors_that_write_nothing(
    gate: Path, tmp_path: Path, capsys, options: list[str], message: str
):
    output = tmp_path / "never"
    arguments = ["--seeds", "1", *options, "-o", str(output)]
    assert _sweep(gate, *arguments) == 2
    error = capsys.readouterr().err
    assert message in error and "Traceback" not in error
    assert not output.exists()


@pytest.mark.slow
def test_a_worker_lost_mid_sweep_costs_no_run(client: Client):
    specs = [spec_for(RAIL_TASK, [EXAMPLES], [], "dryrun")]
    arguments = (grid_points([], [(0.0, 0.0)]), specs, range(8))
    undisturbed = sweep(client, *arguments)
    killed = []

    def kill_a_worker(*_) -> None:
        if not killed:
            address, pid = next(iter(client.run(os.getpid).items()))
            os.kill(pid, signal.SIGKILL)
            killed.append(address)

    disturbed = sweep(client, *arguments, done=kill_a_worker)
    assert killed
    assert [(r.seed, r.outcome, r.time) for _, r in disturbed] == [
        (r.seed, r.outcome, r.time) for _, r in undisturbed
    ]


def _interruptible() -> None:
    """Ctrl-C reaches the child as it would from a terminal: a test runner's worker may
    ignore SIGINT, and a child inherits that."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


@pytest.mark.slow
def test_ctrl_c_cancels_the_sweep_and_keeps_only_finished_runs(tmp_path: Path):
    output = tmp_path / "cancelled"
    command = [
        *(sys.executable, "-m", "lightrocks.app.cli", "sweep", str(RAIL_TASK)),
        *("--path", str(EXAMPLES), "--adapter", "dryrun", "--seeds", "400", "--workers", "2"),
        *("-o", str(output)),
    ]
    log = tmp_path / "stderr.txt"
    with log.open("w") as stderr:
        process = subprocess.Popen(command, stderr=stderr, text=True, preexec_fn=_interruptible)
    journal, deadline = output / "sweep.jsonl", time.monotonic() + 120
    while not journal.exists() and process.poll() is None and time.monotonic() < deadline:
        time.sleep(0.05)  # until the first run has finished: the sweep is running
    assert journal.exists(), f"no run finished within 120 s: {log.read_text()}"
    process.send_signal(signal.SIGINT)
    process.wait(timeout=60)
    error = log.read_text()
    assert process.returncode == 130, error
    assert "Traceback" not in error
    with (output / "results.csv").open() as stream:  # the finished runs, marked incomplete
        assert [row["complete"] for row in csv.DictReader(stream)] == ["False"]


def test_sweep_without_its_extra_names_the_install(gate: Path, monkeypatch, capsys):
    from lightrocks.app.commands import sweep

    real = sweep.find_spec
    monkeypatch.setattr(sweep, "find_spec", lambda name: None if name == "pyarrow" else real(name))
    assert _sweep(gate, "--seeds", "1") == 2
    assert "pip install 'lightrocks[sweep]'" in capsys.readouterr().err
