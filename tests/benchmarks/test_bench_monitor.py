"""The monitor benchmark keeps up with the monitor's guard: its page client connects and
reads a whole run (a one-command action, so that the test is short)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def test_bench_monitor_page_connects_and_reads_the_run() -> None:
    script = ROOT / "benchmarks/bench_monitor.py"
    action = ROOT / "examples/screwing/actions/OpenGripper.lr"
    done = subprocess.run(
        [sys.executable, str(script), "1", str(action)], capture_output=True, text=True, timeout=300
    )
    assert done.returncode == 0, done.stderr
    assert "page got" in done.stdout and " records in " in done.stdout
    assert "with a page connected; ratio" in done.stdout
