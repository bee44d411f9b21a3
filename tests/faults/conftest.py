"""Fault injection: models and adapters that fail on purpose, each run under a deadline.

A run that hangs must fail its test instead of the suite: in-process runs go through
:func:`within` (a worker thread with a deadline), command-line runs through :func:`cli`
(a subprocess with a timeout).
"""

from __future__ import annotations

import itertools
import json
import os
import subprocess
import sys
import threading
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

from lightrocks.app.loading import component_class, generated_package
from lightrocks.workbench import report
from lightrocks.workbench.check import check

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

_counter = itertools.count()


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


@pytest.fixture
def build(tmp_path: Path) -> Callable[..., type]:
    """``build({"Name": text, …}, "Name")`` -> the generated class of ``t.Name``."""

    def make(charts: dict[str, str], name: str) -> type:
        root = write_models(tmp_path / f"models{next(_counter)}", charts)
        context = check([root])
        assert not context.diagnostics.has_errors, report.text(context.diagnostics.items)
        files = sorted((root / "t").glob("*.lr"))
        package = within(lambda: generated_package(context, files, tmp_path / "cache"))
        return component_class(package, f"t.{name}")

    return make


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
