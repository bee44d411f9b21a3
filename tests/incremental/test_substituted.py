"""A check with a substituted file: a text or a parsed unit stands in for the file on disk for
that check only; neither the parse cache nor the findings cache keeps it, and no check without
it is answered with its findings."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import pytest

from lightrocks.workbench import checkcache, parsecache
from lightrocks.workbench.check import check

DEVICES = """\
package robots;

device Arm {
  command move(Length x);
  sensor Boolean done;
}
"""

MOVE = """\
package actions;

import robots.*;

<<action>> statechart Move {
  parameters { Length x = 10 mm; }
  do / arm.move(x = x);
  end condition done [arm.done];
}
"""

CELL = """\
package actions;

import robots.*;

cell Cell {
  arm : Arm;
}
"""

WRONG = MOVE.replace("arm.done", "arm.gone")


@pytest.fixture
def models(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    monkeypatch.chdir(tmp_path)
    root = tmp_path / "models"
    for name, text in {
        "robots/Arm.lrd": DEVICES,
        "actions/Cell.lrd": CELL,
        "actions/Move.lr": MOVE,
    }.items():
        (root / name).parent.mkdir(parents=True, exist_ok=True)
        (root / name).write_text(text, encoding="utf-8")
    checkcache._memory.clear()
    return root


def codes(context) -> list[str]:
    return [d.code for d in context.diagnostics.items]


def test_a_substituted_text_is_checked_in_place_of_the_file(models: Path) -> None:
    move = (models / "actions/Move.lr").resolve()
    clean = check([models])
    parsed = len(parsecache._memory)
    found = check([models], substituted={move: WRONG})
    assert found is not clean
    assert any("gone" in d.message for d in found.diagnostics.items)
    assert len(parsecache._memory) == parsed
    assert check([models]) is clean


def test_a_substituted_check_is_never_remembered(models: Path) -> None:
    move = (models / "actions/Move.lr").resolve()
    substituted = check([models], substituted={move: WRONG})
    assert not any(value is substituted for _, value in checkcache._memory.values())
    assert codes(check([models])) == []


def test_a_substituted_unit_is_taken_as_it_is(models: Path) -> None:
    cell = (models / "actions/Cell.lrd").resolve()
    loaded = check([models]).workspace.files[cell]
    declared = loaded.unit.declarations[0]
    renamed = replace(declared, members=(replace(declared.members[0], type="Hand"),))
    unit = replace(loaded.unit, declarations=(renamed,))
    found = check([models], substituted={cell: unit})
    assert found.workspace.files[cell].unit is unit
    assert any("Hand" in d.message for d in found.diagnostics.items)
    assert codes(check([models])) == []


@pytest.mark.parametrize(
    ("text", "code"),
    [("", "LR0003"), ("statechart {", "LR0001"), ("package a;\x00", "LR0002")],
)
def test_a_bad_substituted_text_is_a_finding_like_a_bad_file(
    models: Path, text: str, code: str
) -> None:
    move = (models / "actions/Move.lr").resolve()
    parsed = len(parsecache._memory)
    found = check([models], substituted={move: text})
    assert code in codes(found)
    assert len(parsecache._memory) == parsed
    assert codes(check([models])) == []
