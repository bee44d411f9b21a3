"""The suite imports LightRocks as installed (``lightrocks.…``), never the repository's
folders as top-level packages: ``python -m pytest`` puts the working directory on
``sys.path``, where ``runtime`` or ``adapters`` would import by accident."""

from __future__ import annotations

import sys
from collections import Counter
from collections.abc import Callable
from pathlib import Path

import pytest
from hypothesis import HealthCheck, settings

ROOT = Path(__file__).resolve().parents[1]
sys.path[:] = [entry for entry in sys.path if Path(entry or ".").resolve() != ROOT]

settings.register_profile("suite", deadline=None, suppress_health_check=[HealthCheck.too_slow])
settings.load_profile("suite")
"""Property tests judge behaviour, never speed: a busy machine must not fail them."""


@pytest.fixture(autouse=True, scope="session")
def _private_run_cache(tmp_path_factory: pytest.TempPathFactory):
    """Runs cache their generated code under a temporary folder, not the user's cache."""
    patch = pytest.MonkeyPatch()
    patch.setenv("XDG_CACHE_HOME", str(tmp_path_factory.mktemp("user-cache")))
    yield
    patch.undo()


@pytest.fixture
def tally(record_property) -> Callable[..., None]:
    """``tally(line, **counts)``: counts summed over the whole run and printed as ``line``
    (a format string) in the terminal summary; they travel in the test reports, so the sum
    also covers tests run by other pytest-xdist workers."""

    def add(line: str, **counts: int) -> None:
        record_property("tally", (line, counts))

    return add


JUDGED = {
    "MatIEC": ("tests/generators/test_matiec",),
    "Beremiz": ("tests/generators/test_beremiz",),
    "Chromium": ("tests/monitor/test_monitor_page",),
    "TextMate grammar (node)": ("tests/vscode/",),
}
"""The tests each outside judge decides (see judges.py), counted in the summary."""


def _judged(terminalreporter) -> None:
    counts = {judge: Counter() for judge in JUDGED}
    for outcome in ("passed", "failed", "skipped", "error"):
        for report in terminalreporter.stats.get(outcome, []):
            where = getattr(report, "nodeid", "")
            for judge, prefixes in JUDGED.items():
                if where.startswith(prefixes) and (report.when == "call" or outcome != "passed"):
                    counts[judge][outcome] += 1
    for judge, count in counts.items():
        if not count:
            continue
        said = ", ".join(f"{count[o]} {o}" for o in ("passed", "failed", "skipped", "error"))
        terminalreporter.write_line(f"judged by {judge}: {said}")


def pytest_terminal_summary(terminalreporter) -> None:
    _judged(terminalreporter)
    totals: dict[str, Counter] = {}
    for reports in terminalreporter.stats.values():
        for report in reports:
            if getattr(report, "when", None) != "call":
                continue
            for key, value in report.user_properties:
                if key == "tally":
                    line, counts = value
                    totals.setdefault(line, Counter()).update(counts)
    for line, counts in totals.items():
        terminalreporter.write_line(line.format_map(counts))
