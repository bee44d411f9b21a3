"""Checks in several threads at once (a thread pool, a server) share z3's one global context:
they take turns, so each gets the findings it gets alone."""

from __future__ import annotations

import shutil
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

from lightrocks.workbench.check import check

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
BROKEN = Path(__file__).parent / "corpus/05-LR0602-PullOut"


def test_checks_in_threads_find_what_they_find_alone(tmp_path: Path) -> None:
    folders = []
    for number in range(4):
        folder = tmp_path / str(number)
        shutil.copytree(EXAMPLES, folder)
        for model in BROKEN.rglob("*.lr"):
            shutil.copyfile(model, folder / model.relative_to(BROKEN))
        folders.append(folder)

    def codes(folder: Path) -> list[str]:
        return sorted(d.code for d in check([folder]).diagnostics.items)

    with ThreadPoolExecutor(max_workers=4) as pool:
        found = list(pool.map(codes, folders))
    assert "LR0602" in found[0]
    assert found == [found[0]] * 4
