"""Fault injection's runs under a deadline: a run that hangs must fail its test instead of the
suite. In-process runs go through :func:`within` (a worker thread with a deadline),
command-line runs through :func:`cli` (a subprocess with a timeout); the models are written
beside one domain (:func:`write_models`)."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import threading
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

DEADLINE = 60.0
"""Seconds a run that should end at once may take before it counts as hanging (generous:
the machine is shared)."""


DOMAIN = """package t;

<<timeout="2 s">> device Arm {
  command move(Length x);
  sensor Boolean goalReached;
  sensor Length z;
}

<<scene="none">> cell Cell {
  arm : Arm;
}
"""


def within(run: Callable[[], Any], seconds: float = DEADLINE) -> Any:
    """``run()`` in a worker thread; fails the test when it has not returned in time."""
    outcome: dict[str, Any] = {}

    def work() -> None:
        try:
            outcome["value"] = run()
        except BaseException as exc:  # handed to the test below
            outcome["raised"] = exc

    worker = threading.Thread(target=work, daemon=True)
    worker.start()
    worker.join(seconds)
    if worker.is_alive():
        pytest.fail(f"did not return within {seconds} s")
    if "raised" in outcome:
        raise outcome["raised"]
    return outcome["value"]


def write_models(root: Path, charts: dict[str, str]) -> Path:
    """``charts`` (name -> text) as ``t/<name>.lr`` beside the domain ``t/Cell.lrd``."""
    (root / "t").mkdir(parents=True, exist_ok=True)
    (root / "t" / "Cell.lrd").write_text(DOMAIN, encoding="utf-8")
    for name, text in charts.items():
        (root / "t" / f"{name}.lr").write_text(text, encoding="utf-8")
    return root


def cli(*args: str, cwd: Path, timeout: float = DEADLINE) -> subprocess.CompletedProcess:
    """``lightrocks ARGS`` in a subprocess; a run that does not end in time fails the test.
    The run cache goes below ``cwd``."""
    env = {**os.environ, "XDG_CACHE_HOME": str(cwd / "cache"), "PYTHONIOENCODING": "utf-8"}
    command = [sys.executable, "-m", "lightrocks.app.cli", *args]
    try:
        return subprocess.run(
            command, cwd=cwd, env=env, capture_output=True, text=True, timeout=timeout
        )
    except subprocess.TimeoutExpired:
        pytest.fail(f"lightrocks {' '.join(args)} did not end within {timeout} s")


def trace_records(path: Path) -> list[dict[str, Any]]:
    return [json.loads(line) for line in path.read_text(encoding="utf-8").splitlines()]
