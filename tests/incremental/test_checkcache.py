"""The findings cache: an unchanged workspace is not checked again, and a change of anything a
check read (a file, a folder's model files, a package folder) is never answered from it."""

from __future__ import annotations

import json
import os
from collections.abc import Callable
from pathlib import Path

import pytest

from lightrocks.app import checkstore, cli
from lightrocks.workbench import checkcache
from lightrocks.workbench.cachestore import LEDGER
from lightrocks.workbench.check import check
from lightrocks.workbench.incremental import IncrementalCheck
from lightrocks.workbench.sources import sources_digest

DEVICES = """\
package robots;

device Arm {
  command move(Length x);
  sensor Boolean done;
}
"""

CELL = """\
package cell;

import robots.*;

cell Cell {
  arm : Arm;
}
"""

MOVE = """\
package actions;

import cell.Cell;

<<action>> statechart Move {
  parameters { Length x = 10 mm; }
  do / arm.move(x = x);
  end condition done [arm.done];
}
"""

LONE = """\
package misc;

import extra.*;

statechart Lone {
  initial state A;
  final state B;
  A -> B tick;
}
"""


@pytest.fixture
def models(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    monkeypatch.chdir(tmp_path)
    root = tmp_path / "models"
    for name, text in {
        "robots/Arm.lrd": DEVICES,
        "cell/Cell.lrd": CELL,
        "actions/Move.lr": MOVE,
        "misc/Lone.lr": LONE,
    }.items():
        (root / name).parent.mkdir(parents=True, exist_ok=True)
        (root / name).write_text(text, encoding="utf-8")
    checkcache._memory.clear()
    return root


def fresh(root: Path, **options) -> list:
    """The findings of a check that cannot take anything from the cache."""
    checkcache._memory.clear()
    return check([root], **options).diagnostics.items


def test_an_unchanged_workspace_is_answered_from_memory(models: Path) -> None:
    first = check([models])
    assert check([models]) is first
    assert check([models / "actions"], [models]) is not first


CHANGES: dict[str, Callable[[Path], object]] = {
    "an edit": lambda root: (root / "actions/Move.lr").write_text(
        MOVE.replace("arm.done", "arm.gone"), encoding="utf-8"
    ),
    "a new file in a package folder": lambda root: (root / "cell/Other.lrd").write_text(
        CELL, encoding="utf-8"
    ),
    "a deleted file": lambda root: (root / "robots/Arm.lrd").unlink(),
    "a new package folder": lambda root: (root / "extra").mkdir(),
    "a new model below a checked folder": lambda root: (
        (root / "misc/deep").mkdir()
        or (root / "misc/deep/Bad.lr").write_text("statechart {", encoding="utf-8")
    ),
    "a model turned into a folder": lambda root: (
        (root / "misc/Lone.lr").unlink() or (root / "misc/Lone.lr").mkdir()
    ),
}


@pytest.mark.parametrize("change", CHANGES)
def test_a_change_of_anything_read_is_checked_again(models: Path, change: str) -> None:
    before = check([models]).diagnostics.items
    CHANGES[change](models)
    after = check([models]).diagnostics.items
    assert after == fresh(models)
    assert after != before


def test_a_retargeted_symlink_is_checked_again(models: Path, tmp_path: Path) -> None:
    for copy in ("one", "two"):
        (tmp_path / copy).mkdir()
        (tmp_path / copy / "Move.lr").write_text(MOVE.replace("arm.done", "arm.gone"))
    link = models / "actions/Move.lr"
    link.unlink()
    link.symlink_to(tmp_path / "one/Move.lr")
    assert all("one" in d.file for d in check([models]).diagnostics.items if "Move" in d.file)
    link.unlink()
    link.symlink_to(tmp_path / "two/Move.lr")
    after = check([models]).diagnostics.items
    assert any("two" in d.file for d in after)
    assert after == fresh(models)


def test_editor_buffers_are_read_like_files(models: Path) -> None:
    move = (models / "actions/Move.lr").resolve()
    clean = check([models]).diagnostics.items
    edited = {move: MOVE.replace("arm.done", "arm.gone")}
    found = check([models], texts=edited).diagnostics.items
    assert found != clean
    assert found == fresh(models, texts=edited)
    assert check([models]).diagnostics.items == clean


def test_findings_are_shown_relative_to_the_working_folder(
    models: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    CHANGES["an edit"](models)
    here = check([models]).diagnostics.items
    monkeypatch.chdir(models)
    there = check([models]).diagnostics.items
    assert [d.file for d in here] == [os.path.join("models", d.file) for d in there]


def test_a_partial_check_of_files_taken_as_given_is_not_kept(models: Path) -> None:
    incremental = IncrementalCheck([models])
    incremental.full()
    move = (models / "actions/Move.lr").resolve()
    incremental.update({move: MOVE + "\n"})
    assert not incremental.context.workspace.reads.complete
    assert not any(value is incremental.context for _, value in checkcache._memory.values())


@pytest.fixture
def disk(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """Each command runs as a new process would: nothing in memory from the one before."""
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    yield tmp_path / "cache" / "lightrocks" / "check"
    checkcache.use_store(None)


def test_a_new_process_takes_the_findings_from_disk(
    models: Path, disk: Path, capsys: pytest.CaptureFixture, monkeypatch: pytest.MonkeyPatch
) -> None:
    CHANGES["an edit"](models)
    checkcache._memory.clear()
    first = cli.main(["check", str(models)]), capsys.readouterr().out
    assert first[0] == cli.EXIT_FINDINGS and "LR0106" in first[1]
    monkeypatch.setattr("lightrocks.workbench.check.check", _must_not_check)
    checkcache._memory.clear()
    assert (cli.main(["check", str(models)]), capsys.readouterr().out) == first


def test_a_planted_or_corrupt_entry_is_a_miss(
    models: Path, disk: Path, capsys: pytest.CaptureFixture
) -> None:
    CHANGES["an edit"](models)
    checkcache._memory.clear()
    first = cli.main(["check", str(models)]), capsys.readouterr().out
    [entry] = [p for p in disk.rglob("*") if p.is_file() and p.name != LEDGER]
    stored = json.loads(entry.read_text(encoding="utf-8"))
    for planted in (
        "{",
        json.dumps([stored]),
        json.dumps({**stored, "findings": [["x", "1", 1, "LR0001", "error", "m", ""]]}),
        json.dumps({**stored, "findings": [["x", 1, 1, "LR0001", "fatal", "m", ""]]}),
        json.dumps({**stored, "reads": {**stored["reads"], "roots": "/"}}),
        json.dumps({**stored, "reads": {**stored["reads"], "files": {"a": 1}}}),
    ):
        entry.write_text(planted, encoding="utf-8")
        checkcache._memory.clear()
        assert (cli.main(["check", str(models)]), capsys.readouterr().out) == first, planted


def test_stored_findings_are_used_only_while_their_reads_hold(
    models: Path, disk: Path, capsys: pytest.CaptureFixture
) -> None:
    checkcache._memory.clear()
    assert cli.main(["check", str(models)]) == cli.EXIT_FINDINGS
    assert "package 'extra' not found" in capsys.readouterr().out
    (models / "extra").mkdir()
    checkcache._memory.clear()
    assert cli.main(["check", str(models)]) == cli.EXIT_FINDINGS
    assert "package 'extra' has no models" in capsys.readouterr().out
    (models / "extra/Lone.lr").write_text(LONE.replace("misc", "extra"), encoding="utf-8")
    checkcache._memory.clear()
    assert cli.main(["check", str(models)]) == cli.EXIT_OK
    assert "0 error(s)" in capsys.readouterr().out


def test_a_store_that_cannot_be_written_costs_only_time(
    models: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture
) -> None:
    (tmp_path / "cache").write_text("a file where the cache folder should be", encoding="utf-8")
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    checkcache._memory.clear()
    assert cli.main(["check", str(models)]) == cli.EXIT_FINDINGS
    assert "1 error(s)" in capsys.readouterr().out
    assert checkstore.DiskStore().get("0" * 40) is None
    checkcache.use_store(None)


def _must_not_check(*args, **kwargs):
    raise AssertionError("the findings were on disk")


def test_an_edit_of_the_application_keeps_the_findings_cache_warm(tmp_path: Path) -> None:
    """The findings depend on the kernel, the metamodel and the languages: the application
    floor (CLI, monitor, language server) lies outside the code the cache key digests, while
    an edit inside that code changes the digest."""
    import lightrocks.app
    import lightrocks.workbench

    app = Path(lightrocks.app.__file__).resolve().parent
    kernel = Path(lightrocks.workbench.__file__).resolve().parent
    places = checkcache.checking_code()
    assert kernel in places
    assert not any(p == app or app in p.parents or p in app.parents for p in places)

    code = tmp_path / "code"
    code.mkdir()
    (code / "rule.py").write_text("LIMIT = 1\n")
    before = sources_digest({code}, (".py",))
    (code / "rule.py").write_text("LIMIT = 2\n")
    assert sources_digest({code}, (".py",)) != before
