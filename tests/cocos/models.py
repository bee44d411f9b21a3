"""The model set every CoCo case starts from, and how a case is written and materialized.

Every case is a small model set written to a temporary model-path root: the shared ``BASE``
(a tiny device interface, a cell, one action, one skill and one task, all clean) with some
files replaced or added. In the failing variant the marker ``@@`` stands right before the
token where the finding is expected; the marker is removed before the file is written.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

MARK = "@@"

DEVICES = """\
package robots;

device Arm {
  command move(Length x, Force force = 10 N in 1 N .. 50 N);
  sensor Boolean done;
  sensor Force force;
}
"""

CELL = """\
package cell;

import robots.*;

cell Cell {
  arm : Arm;
  object part { Length depth = 0 mm; }
}
"""

MOVE = """\
package actions;

import cell.Cell;

<<action>> statechart Move {
  parameters { Length x = 10 mm; }
  do / arm.move(x = x);
  end condition done [arm.done];
  end condition blocked [arm.force > 20 N];
}
"""

PICK = """\
package skills;

import cell.Cell;
import actions.*;

<<skill>> statechart Pick {
  start condition go;
  end condition picked;
  end condition failed;
  <<import="Move">> state Reach(x = 5 mm);
  go -> Reach;
  Reach -> picked done;
  Reach -> failed blocked;
}
"""

JOB = """\
package tasks;

import skills.*;

<<task>> statechart Job {
  start condition go;
  end condition ok;
  end condition failed;
  <<import="Pick">> state PickPart;
  go -> PickPart;
  PickPart -> ok picked;
  PickPart -> failed failed;
}
"""

LONE = """\
package misc;

statechart Lone {
  initial state A;
  final state B;
  A -> B tick;
}
"""

BASE: dict[str, str | bytes] = {
    "robots/Devices.lrd": DEVICES,
    "cell/Cell.lrd": CELL,
    "actions/Move.lr": MOVE,
    "skills/Pick.lr": PICK,
    "tasks/Job.lr": JOB,
}


def skill(body: str, name: str = "Pick") -> str:
    """A skill of package ``skills`` with the given body."""
    return (
        "package skills;\n\nimport cell.Cell;\nimport actions.*;\n\n"
        f"<<skill>> statechart {name} {{\n{body}}}\n"
    )


def action(body: str, name: str = "Move") -> str:
    """An action of package ``actions`` with the given body."""
    return f"package actions;\n\nimport cell.Cell;\n\n<<action>> statechart {name} {{\n{body}}}\n"


PICK_BODY = """\
  start condition go;
  end condition picked;
  end condition failed;
  <<import="Move">> state Reach(x = 5 mm);
  go -> Reach;
  Reach -> picked done;
  Reach -> failed blocked;
"""

MOVE_BODY = """\
  parameters { Length x = 10 mm; }
  do / arm.move(x = x);
  end condition done [arm.done];
  end condition blocked [arm.force > 20 N];
"""


@dataclass
class Case:
    """A CoCo code with a passing and a failing model set."""

    code: str
    ok: dict[str, str | bytes]
    bad: dict[str, str | bytes]
    message: str  # a fragment of the expected message
    hint: str = ""  # a fragment of the expected hint
    at: tuple[str, int, int] | None = None  # position for binary files (no marker possible)
    paths: tuple[str, ...] = ()  # what to check, relative to the root (default: the root)
    base: dict[str, str | bytes] = field(default_factory=lambda: dict(BASE))
    also: frozenset[str] = frozenset()  # other codes the failing model reports by necessity
    variant: str = ""  # tells apart several failing models of one code

    @property
    def id(self) -> str:
        return f"{self.code}-{self.variant}" if self.variant else self.code


def replace(text: str, old: str, new: str) -> str:
    assert old in text, old
    return text.replace(old, new, 1)


def materialize(root: Path, files: dict[str, str | bytes]) -> tuple[str, int, int] | None:
    """Write ``files`` below ``root``; return the marked position (file, line, column)."""
    marked = None
    for relative, content in files.items():
        path = root / relative
        path.parent.mkdir(parents=True, exist_ok=True)
        if isinstance(content, bytes):
            path.write_bytes(content)
            continue
        if MARK in content:
            before = content[: content.index(MARK)]
            line = before.count("\n") + 1
            column = len(before) - (before.rfind("\n") + 1) + 1
            marked = (relative, line, column)
            content = content.replace(MARK, "", 1)
        path.write_text(content, encoding="utf-8")
    return marked
