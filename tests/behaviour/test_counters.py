"""Counters past the window of exact values: a retry loop over a range of a million is
judged by its range and its guards, not enumerated; a loop whose guard reads a counter
nothing on it moves is reported at that guard."""

from __future__ import annotations

from pathlib import Path

import pytest
from cocos.models import DEVICES, MOVE

from lightrocks.languages.lightrocks.behaviour.verify import verify

CELL = """\
package cell;

import robots.*;

cell Cell {
  arm : Arm;
  object part { Integer tries = 0 RANGE; Integer other = 0; }
}
"""

PICK = """\
package skills;

import cell.Cell;
import actions.*;

<<skill>> statechart Pick {
  parameters { Integer retries = 1000000; }
  start condition go;
  end condition picked;
  end condition failed;
  PROPERTY
  <<import="Move">> state Reach(x = 5 mm);
  go -> Reach / { part.tries = 0; };
  Reach -> picked done;
  Reach -> Reach [part.tries < retries] blocked / { RETRY };
  Reach -> failed [part.tries >= retries] blocked / { GIVE_UP };
  Reach -> failed timeout;
}
"""


def _verify(
    tmp_path: Path,
    *,
    ranged: bool,
    retry: str,
    give_up: str = "",
    prop: str = "",
    max_configurations: int = 200_000,
):
    files = {
        "robots/Devices.lrd": DEVICES,
        "cell/Cell.lrd": CELL.replace("RANGE", "in 0 .. 1000000" if ranged else ""),
        "actions/Move.lr": MOVE,
        "skills/Pick.lr": PICK.replace("RETRY", retry)
        .replace("GIVE_UP", give_up)
        .replace("PROPERTY", prop),
    }
    for name, text in files.items():
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / name).write_text(text, encoding="utf-8")
    return verify([tmp_path], max_configurations=max_configurations)


@pytest.mark.parametrize("ranged", [True, False], ids=["declared-range", "guard-only"])
def test_a_retry_over_a_million_is_proved_to_end(tmp_path: Path, ranged: bool) -> None:
    prop = "property fewTries: always [part.tries <= 1000000];" if ranged else ""
    result = _verify(tmp_path, ranged=ranged, retry="part.tries = part.tries + 1;", prop=prop)
    assert [str(d) for d in result.diagnostics] == []


def test_a_counter_moved_in_the_wrong_branch_is_reported_at_the_guard(tmp_path: Path) -> None:
    result = _verify(
        tmp_path,
        ranged=True,
        retry="part.other = part.other + 1;",
        give_up="part.tries = part.tries + 1;",
    )
    [finding] = [d for d in result.diagnostics if d.code == "LR0703"]
    assert (Path(finding.file).name, finding.line, finding.column) == ("Pick.lr", 15, 3)
    assert "its guard reads 'part.tries', which nothing on the loop moves" in finding.message


def test_a_counter_that_grows_without_a_bound_is_an_endless_retry(tmp_path: Path) -> None:
    """Past the window a counter raised on every round proves nothing where neither its
    range nor a guard bounds it: the loop may run forever."""
    result = _verify(
        tmp_path,
        ranged=False,
        retry="part.tries = 0; part.other = part.other + 1;",
        prop="property counted: always [part.other >= 0];",
    )
    assert [d.code for d in result.diagnostics] == ["LR0703"]


def test_an_exploration_past_its_limit_says_so_and_how_to_raise_it(tmp_path: Path) -> None:
    files = {"ranged": True, "retry": "part.tries = part.tries + 1;"}
    prop = "property fewTries: always [part.tries <= 1000000];"
    result = _verify(tmp_path, **files, prop=prop, max_configurations=50)
    by_code = {d.code: d for d in result.diagnostics}
    assert set(by_code) == {"LR0704", "LR0716"}
    for code in by_code:
        assert "limit of 50 configurations" in by_code[code].message
        assert "--max-configurations N" in by_code[code].hint
