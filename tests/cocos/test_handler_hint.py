"""The LR0209 hint offers a sibling's handling only where it is right for the outcome: the
siblings agree, without a guard or a history entry, and a device's ``timeout`` or ``error``
goes to an end, never back into the work (the language server applies the hint as a fix)."""

from __future__ import annotations

from pathlib import Path

import pytest

from cocos.cases_behaviour import BUDGETED, TWICE
from cocos.models import BASE, materialize, replace
from lightrocks.workbench.check import check

AGAIN = replace(
    TWICE, "state Reach(x = 5 mm);", 'state Reach(x = 5 mm);\n  <<import="Move">> state Again;'
).replace("Reach -> picked done;", "Reach -> Again done;")


def _hint(tmp_path: Path, pick: str) -> str:
    materialize(tmp_path, {**BASE, "actions/Move.lr": BUDGETED, "skills/Pick.lr": pick})
    found = [d for d in check([tmp_path]).diagnostics.items if d.code == "LR0209"]
    [finding] = [d for d in found if "'timeout' of 'Again'" in d.message]
    return finding.hint


def test_a_sibling_that_ends_the_region_on_timeout_is_the_fix(tmp_path: Path) -> None:
    assert _hint(tmp_path, AGAIN) == "add the transition 'Again -> failed timeout;'"


@pytest.mark.parametrize(
    ("handling", "why"),
    [
        ("Reach -> Reach timeout;", "a timeout sent back into the work is no fix to copy"),
        ("Reach -> failed [part.depth > 0 mm] timeout;", "a guarded handling is by case"),
    ],
)
def test_no_fix_is_offered_where_the_siblings_handling_is_wrong_for_it(
    tmp_path: Path, handling: str, why: str
) -> None:
    pick = replace(AGAIN, "Reach -> failed timeout;", handling)
    assert _hint(tmp_path, pick) == "", why
