"""The sweep benchmark keeps up with the sweep's API: one dry-run seed on one and two workers."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]

pytest.importorskip("distributed")


def test_bench_sweep_runs_and_reports_same_outcomes() -> None:
    script = ROOT / "benchmarks/bench_sweep.py"
    done = subprocess.run(
        [sys.executable, str(script), "1", "dryrun"], capture_output=True, text=True, timeout=300
    )
    assert done.returncode == 0, done.stderr
    assert "sweep of 1 runs of AssembleRail on dryrun" in done.stdout
    assert "same outcomes per run: True" in done.stdout
