"""A run without ``--monitor`` carries no monitor code: sampling is the runtime's listener,
and nothing of ``lightrocks.app.monitor`` is imported."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SCREW_TASK = ROOT / "examples" / "screwing" / "tasks" / "ScrewTask.lr"
SCRIPT = ROOT / "examples" / "screwing" / "screwed.dryrun.json"

DRIVER = """
import sys
from lightrocks.app.cli import main

status = main(sys.argv[1:])
monitor = sorted(m for m in sys.modules if m.startswith("lightrocks.app.monitor"))
print("monitor modules:", monitor)
sys.exit(status)
"""


def test_a_run_without_monitor_imports_no_monitor_code(tmp_path: Path, tmp_path_factory) -> None:
    trace = tmp_path / "run.jsonl"
    env = {**os.environ, "XDG_CACHE_HOME": str(tmp_path_factory.getbasetemp() / "cache")}
    command = [sys.executable, "-c", DRIVER, "run", str(SCREW_TASK), "--adapter", "dryrun"]
    command += ["--script", str(SCRIPT), "--trace", str(trace)]
    done = subprocess.run(command, env=env, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    assert "outcome: screwed" in done.stdout
    assert "monitor modules: []" in done.stdout
    assert '"kind": "sample"' in trace.read_text(), "the run is sampled all the same"
