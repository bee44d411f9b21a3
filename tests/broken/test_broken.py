"""Broken inputs derived from the examples: the checker reports, never crashes, never writes.

Each case copies ``examples/`` to a temporary folder, breaks one thing and runs
``lightrocks check`` on the copy: exit code 1, findings with file:line:col, the expected
code at the expected place, no Python traceback, and the folder unchanged afterwards.
"""

from __future__ import annotations

import random
import re
import shutil
import subprocess
import sys
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import pytest

from lightrocks.app.cli import main

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"
FINDING = re.compile(
    r"^(?P<file>.+?):(?P<line>\d+):(?P<column>\d+): (?:error|warning|info) (?P<code>LR\d{4}): "
)


def copy_examples(target: Path) -> Path:
    root = target / "examples"
    shutil.copytree(EXAMPLES, root)
    return root


def snapshot(folder: Path) -> dict[str, bytes]:
    """Every file below ``folder`` with its content: what a read-only run must not change."""
    return {
        p.relative_to(folder).as_posix(): p.read_bytes()
        for p in sorted(folder.rglob("*"))
        if p.is_file()
    }


def edit(relative: str, change: Callable[[str], str]) -> Callable[[Path], None]:
    def apply(root: Path) -> None:
        path = root / relative
        path.write_text(change(path.read_text(encoding="utf-8")), encoding="utf-8")

    return apply


def replace(old: str, new: str) -> Callable[[str], str]:
    def change(text: str) -> str:
        assert old in text, old
        return text.replace(old, new, 1)

    return change


def delete_line(part: str) -> Callable[[str], str]:
    def change(text: str) -> str:
        lines = text.splitlines(keepends=True)
        index = next(i for i, line in enumerate(lines) if part in line)
        return "".join(lines[:index] + lines[index + 1 :])

    return change


def write(relative: str, content: bytes) -> Callable[[Path], None]:
    def apply(root: Path) -> None:
        (root / relative).write_bytes(content)

    return apply


def both(*changes: Callable[[Path], None]) -> Callable[[Path], None]:
    def apply(root: Path) -> None:
        for change in changes:
            change(root)

    return apply


def truncate_mid_statement(text: str) -> str:
    """Cut in the middle of the first transition with a guard."""
    start = text.index("Turn -> screwed [screw.depth")
    return text[: start + len("Turn -> screwed [screw.de")]


@dataclass(frozen=True)
class Broken:
    name: str
    break_it: Callable[[Path], None]
    code: str  # a finding of this code must be reported ...
    file: str  # ... in this file (relative to the copied examples) ...
    line: int | str | None = None  # ... at this line, or the last line containing this text
    hint: str = ""


SCREW_IN = "screwing/skills/ScrewIn.lr"
RELEASE = "screwing/skills/Release.lr"
RETREAT = "screwing/skills/Retreat.lr"

BROKEN = [
    Broken(
        "syntax-error",
        edit(
            "screwing/actions/Approach.lr", replace("[robot.goalReached];", "[robot.goalReached;")
        ),
        "LR0001",
        "screwing/actions/Approach.lr",
        "[robot.goalReached;",
    ),
    Broken(
        "truncated",
        edit(SCREW_IN, truncate_mid_statement),
        "LR0001",
        SCREW_IN,
        "Turn -> screwed [screw.de",
    ),
    Broken(
        "deleted-line",
        edit(SCREW_IN, delete_line("state Rewind(")),
        "LR0110",
        SCREW_IN,
        "LetGo -> Rewind done;",
    ),
    Broken(
        "duplicated-line",
        edit(SCREW_IN, replace("    Length depth = 12 mm;\n", "    Length depth = 12 mm;\n" * 2)),
        "LR0101",
        SCREW_IN,
        "Length depth = 12 mm;",
    ),
    Broken(
        "misspelled-import-target",
        edit("screwing/tasks/ScrewTask.lr", replace('"GraspScrew"', '"GraspScrw"')),
        "LR0104",
        "screwing/tasks/ScrewTask.lr",
        "GraspScrw",
        hint="did you mean 'GraspScrew'?",
    ),
    Broken(
        "misspelled-sensor",
        edit("screwing/actions/Approach.lr", replace("robot.goalReached]", "robot.goalReachd]")),
        "LR0106",
        "screwing/actions/Approach.lr",
        "goalReachd",
        hint="did you mean 'goalReached'?",
    ),
    Broken(
        "import-cycle",
        both(
            edit(
                RELEASE,
                replace(
                    "  go -> Open;",
                    '  <<import="Retreat">> state Away;\n'
                    "  go -> Open;\n  Open -> Away error;\n  Away -> released;",
                ),
            ),
            edit(
                RETREAT,
                replace(
                    "  go -> Up;",
                    '  <<import="Release">> state Drop;\n'
                    "  go -> Up;\n  Up -> Drop error;\n  Drop -> retreated;",
                ),
            ),
        ),
        "LR0210",
        RELEASE,
        '<<import="Retreat">>',
    ),
    Broken(
        "extends-cycle",
        both(
            edit(RELEASE, replace("<<skill>>", '<<skill, extends="Retreat">>')),
            edit(RETREAT, replace("<<skill>>", '<<skill, extends="Release">>')),
        ),
        "LR0210",
        RELEASE,
        'extends="Retreat"',
    ),
    Broken(
        "random-bytes",
        write("screwing/skills/Noise.lr", random.Random(7).randbytes(512)),
        "LR0002",
        "screwing/skills/Noise.lr",
    ),
    Broken(
        "nul-bytes",
        write("screwing/skills/Zeros.lr", b"package screwing.skills;\n" + b"\x00" * 64),
        "LR0002",
        "screwing/skills/Zeros.lr",
        2,
    ),
    Broken(
        "empty-file",
        write("screwing/skills/Empty.lr", b""),
        "LR0003",
        "screwing/skills/Empty.lr",
        1,
    ),
    Broken(
        "whitespace-only",
        write("screwing/skills/Blank.lr", b"  \n\t\n\r\n   \n"),
        "LR0003",
        "screwing/skills/Blank.lr",
        1,
    ),
]


def findings(output: str) -> list[re.Match]:
    return [m for line in output.splitlines() if (m := FINDING.match(line))]


def _relative(file: str, root: Path, cwd: Path | None = None) -> str:
    path = Path(file)
    if not path.is_absolute():
        path = (cwd or Path.cwd()) / path
    return path.resolve().relative_to(root.resolve()).as_posix()


def assert_reported(case: Broken, output: str, root: Path, cwd: Path | None = None) -> None:
    assert "Traceback" not in output
    found = findings(output)
    assert found, output
    for match in found:
        assert int(match["line"]) >= 1 and int(match["column"]) >= 1
    expected = [
        m for m in found if m["code"] == case.code and _relative(m["file"], root, cwd) == case.file
    ]
    assert expected, output
    if case.line is not None:
        line = case.line
        if isinstance(line, str):
            text = (root / case.file).read_text(encoding="utf-8").splitlines()
            line = max(i for i, t in enumerate(text, 1) if case.line in t)
        assert any(int(m["line"]) == line for m in expected), output
    if case.hint:
        assert any(case.hint in line for line in output.splitlines() if case.code in line)


@pytest.mark.parametrize("case", BROKEN, ids=lambda c: c.name)
def test_check_reports_broken_input(
    case: Broken, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    root = copy_examples(tmp_path)
    case.break_it(root)
    before = snapshot(tmp_path)
    status = main(["check", str(root)])
    captured = capsys.readouterr()
    assert status == 1, captured.out + captured.err
    assert "Traceback" not in captured.err
    assert "internal error" not in captured.err
    assert_reported(case, captured.out, root)
    assert snapshot(tmp_path) == before


@pytest.mark.parametrize("name", ["syntax-error", "random-bytes", "import-cycle"])
def test_check_subprocess_reports_broken_input(name: str, tmp_path: Path) -> None:
    case = next(c for c in BROKEN if c.name == name)
    root = copy_examples(tmp_path)
    case.break_it(root)
    before = snapshot(tmp_path)
    result = subprocess.run(
        [sys.executable, "-m", "lightrocks.app.cli", "check", str(root)],
        capture_output=True,
        text=True,
        cwd=tmp_path,
        timeout=120,
    )
    assert result.returncode == 1, result.stdout + result.stderr
    assert "Traceback" not in result.stderr
    assert_reported(case, result.stdout, root, tmp_path)
    assert snapshot(tmp_path) == before


def test_fmt_leaves_broken_input_alone(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """``fmt`` on a folder with a binary and an empty file reports them and writes nothing."""
    root = copy_examples(tmp_path)
    for case in BROKEN:
        if case.name in ("random-bytes", "nul-bytes", "syntax-error"):
            case.break_it(root)
    before = snapshot(tmp_path)
    status = main(["fmt", str(root)])
    captured = capsys.readouterr()
    assert status == 1, captured.out + captured.err
    assert "Traceback" not in captured.out + captured.err
    assert findings(captured.out)
    assert snapshot(tmp_path) == before
