"""``generate`` writes all files or none even when killed; ``fmt`` keeps modes and symlinks."""

from __future__ import annotations

import os
import stat
import subprocess
import sys
from pathlib import Path

import pytest

from lightrocks.app.cli import main
from lightrocks.workbench.files import JOURNAL, STAGING, recover

from .fault_runs import DEADLINE

ROOT = Path(__file__).resolve().parents[2]
OLD = ROOT / "examples" / "plain"
NEW = ROOT / "examples" / "screwing"

KILLED = """
import os, signal, sys, types
from pathlib import Path
from lightrocks.workbench import files
from lightrocks.app.cli import main

calls = 0

def patch(owner, name, when):
    real = getattr(owner, name)

    def killing(*args, **kwargs):
        global calls
        calls += 1
        if calls == when:
            os.kill(os.getpid(), signal.SIGKILL)
        return real(*args, **kwargs)

    setattr(owner, name, killing)

if sys.argv[1] == "replace":  # only the writer's renames count, not the parse cache's
    files.os = types.SimpleNamespace(**vars(os))
    owner = files.os
else:
    owner = Path
patch(owner, sys.argv[1], int(sys.argv[2]))
sys.exit(main(sys.argv[3:]))
"""


def generate(out: Path, models: Path) -> None:
    assert main(["generate", "--target", "python", str(models), "-o", str(out)]) == 0


def generate_killed(out: Path, models: Path, operation: str, nth: int) -> None:
    """``generate`` in a process that SIGKILLs itself at the ``nth`` call of ``operation``."""
    command = [sys.executable, "-c", KILLED, operation, str(nth)]
    command += ["generate", "--target", "python", str(models), "-o", str(out)]
    done = subprocess.run(command, capture_output=True, text=True, timeout=DEADLINE)
    assert done.returncode == -9, done.stdout + done.stderr


def contents(folder: Path) -> dict[str, bytes]:
    """The files below ``folder``, without a staging folder a killed run left inside."""
    return {
        p.relative_to(folder).as_posix(): p.read_bytes()
        for p in sorted(folder.rglob("*"))
        if p.is_file() and not p.relative_to(folder).parts[0].startswith(STAGING)
    }


@pytest.fixture(scope="module")
def expected(tmp_path_factory) -> dict[str, dict[str, bytes]]:
    """What a complete ``generate`` of the old models, then the new models, gives."""
    out = tmp_path_factory.mktemp("expected") / "out"
    generate(out, OLD)
    old = contents(out)
    generate(out, NEW)
    return {"old": old, "new": contents(out)}


@pytest.mark.parametrize("nth", [1, 5, 20])
def test_kill_while_writing_leaves_the_old_output_untouched(tmp_path, expected, nth):
    out = tmp_path / "out"
    generate(out, OLD)
    generate_killed(out, NEW, "write_text", nth)
    assert contents(out) == expected["old"]
    generate(out, NEW)
    assert contents(out) == expected["new"]
    assert not list(out.glob(".lightrocks-*"))  # no staging folder left


def test_kill_while_writing_a_new_output_creates_nothing(tmp_path):
    out = tmp_path / "out"
    generate_killed(out, NEW, "write_text", 5)
    assert not out.exists()
    recover(out)
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("nth", [2, 6, 15])
def test_kill_while_moving_in_is_completed_by_the_next_write(tmp_path, expected, nth):
    out = tmp_path / "out"
    generate(out, OLD)
    generate_killed(out, NEW, "replace", nth)  # the 1st replace writes the journal
    assert (out / JOURNAL).exists()
    recover(out)
    assert contents(out) == expected["new"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out"]


MESSY = "package t;\n\nstatechart   Messy{\ninitial state A;\n}\n"


def test_fmt_keeps_the_file_mode(tmp_path):
    model = tmp_path / "Messy.lr"
    model.write_text(MESSY)
    model.chmod(0o640)
    assert main(["fmt", str(model)]) == 0
    assert model.read_text() != MESSY
    assert stat.S_IMODE(model.stat().st_mode) == 0o640


def test_fmt_writes_through_a_symlink(tmp_path):
    target = tmp_path / "real" / "Messy.lr"
    target.parent.mkdir()
    target.write_text(MESSY)
    target.chmod(0o604)
    link = tmp_path / "Messy.lr"
    link.symlink_to(target)
    assert main(["fmt", str(link)]) == 0
    assert link.is_symlink() and os.readlink(link) == str(target)
    assert "statechart Messy {" in target.read_text()
    assert stat.S_IMODE(target.stat().st_mode) == 0o604
    assert sorted(p.name for p in target.parent.iterdir()) == ["Messy.lr"]


def test_a_forged_journal_moves_nothing_outside_the_folder(tmp_path):
    out = tmp_path / "out"
    staging = out / f"{STAGING}forged"
    (staging / "sub").mkdir(parents=True)
    (staging / "sub" / "x.py").write_text("planted")
    (out / JOURNAL).write_text('["../../elsewhere", ["../sub/x.py", "/etc/x", 3]]')
    recover(out)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out"]
    assert list(out.iterdir()) == []
