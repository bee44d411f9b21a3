"""Re-check time of one edit in a synthetic 1,000-file workspace, and cold/warm full checks.

The workspace has 100 packages of 10 plain statecharts; each chart imports one chart of the
previous package. The goal is < 100 ms to re-check one edited file that few files reach;
an edit reaching half the workspace re-checks that half and is shown for comparison.
Run: .venv/bin/python benchmarks/bench_incremental.py
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from lightrocks.workbench import parsecache
from lightrocks.workbench.app.parsestore import DiskStore
from lightrocks.workbench.incremental import IncrementalCheck

PACKAGES, FILES = 100, 10
GOAL_MS = 100.0


def chart(package: int, index: int) -> str:
    imports = f"import p{package - 1}.C{index};\n\n" if package else ""
    return (
        f"package p{package};\n\n{imports}statechart C{index} {{\n"
        "  parameters {\n    Integer count = 0;\n  }\n\n"
        "  initial state Idle;\n  state Busy;\n  final state Done;\n\n"
        "  Idle -> Busy [count < 10] start;\n"
        "  Busy -> Idle stop / { count = count + 1; };\n"
        "  Busy -> Done finish;\n}\n"
    )


def write_workspace(root: Path) -> None:
    for package in range(PACKAGES):
        folder = root / f"p{package}"
        folder.mkdir(parents=True)
        for index in range(FILES):
            (folder / f"C{index}.lr").write_text(chart(package, index), encoding="utf-8")


def timed_cli(root: Path, cache: Path) -> float:
    start = time.perf_counter()
    subprocess.run(
        [sys.executable, "-m", "lightrocks.workbench.app.cli", "check", str(root)],
        env={**os.environ, "XDG_CACHE_HOME": str(cache)},
        check=False,
        stdout=subprocess.DEVNULL,
    )
    return time.perf_counter() - start


def edit_ms(incremental: IncrementalCheck, edited: Path) -> float:
    """Median time of five edits of one file, each changing a guard."""
    text = edited.read_text(encoding="utf-8")
    times = []
    for round_ in range(5):
        new = text.replace("count < 10", f"count < {11 + round_}")
        start = time.perf_counter()
        incremental.update({edited: new})
        times.append(time.perf_counter() - start)
    return sorted(times)[len(times) // 2] * 1000


def main() -> None:
    with tempfile.TemporaryDirectory() as folder:
        root = Path(folder) / "models"
        write_workspace(root)
        cache = Path(folder) / "cache"
        cold, warm = timed_cli(root, cache), timed_cli(root, cache)
        parsecache.use_store(DiskStore(cache / "lightrocks" / "parse"))  # as `lightrocks lsp`
        incremental = IncrementalCheck([root])
        start = time.perf_counter()
        incremental.full()
        full_ms = (time.perf_counter() - start) * 1000
        print(f"files: {PACKAGES * FILES}")
        print(f"cold `lightrocks check`: {cold:.2f} s (baseline: empty parse cache)")
        print(f"warm `lightrocks check`: {warm:.2f} s ({cold / warm:.1f}x faster than cold)")
        print(f"full in-process check: {full_ms:.0f} ms (baseline for one edit)")
        for label, edited in (
            ("a chart nothing imports", root / f"p{PACKAGES - 1}" / "C0.lr"),
            ("a chart one package imports", root / f"p{PACKAGES - 2}" / "C0.lr"),
            ("a chart half the workspace reaches", root / f"p{PACKAGES // 2}" / "C0.lr"),
        ):
            recheck = edit_ms(incremental, edited)
            verdict = "met" if recheck < GOAL_MS else "MISSED"
            print(
                f"one edit of {label}: {recheck:.1f} ms, {len(incremental.rechecked)} files "
                f"re-checked (median of 5; goal < {GOAL_MS:.0f} ms: {verdict})"
            )


if __name__ == "__main__":
    main()
