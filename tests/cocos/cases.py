"""One passing and one failing model per CoCo code.

Every case is a small model set written to a temporary model-path root: the shared ``BASE``
(a tiny device interface, a cell, one action, one skill and one task, all clean) with some
files replaced or added. In the failing variant the marker ``@@`` stands right before the
token where the finding is expected; the marker is removed before the file is written.
"""

from __future__ import annotations

from dataclasses import dataclass, field

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

PAIR = """\
package misc;

statechart Pair {
  initial state Both {
    region Left {
      initial state A;
      final state B;
      A -> B tick;
    }
    region Right {
      initial state C;
      final state D;
      C -> D tock;
    }
  }
  final state Done;
  Both -> Done;
}
"""

TWIN = """\
package skills;

import cell.Cell;
import actions.*;

<<skill>> statechart Twin {
  end condition done;
  initial state Both {
    region Near {
      <<import="Move">> initial state Reach(x = 5 mm);
      final state Reached;
      Reach -> Reached;
    }
    region Far {
      <<import="Move">> initial state Reach(x = 9 mm);
      final state Reached;
      Reach -> Reached;
    }
  }
  Both -> done;
}
"""

TWICE = """\
package tasks;

import skills.*;

<<task>> statechart Twice {
  end condition ok;
  initial state Both {
    region One {
      <<import="Pick">> initial state First;
      final state Done1;
      First -> Done1;
    }
    region Two {
      initial state Wait;
      final state Done2;
      Wait -> Done2 tick;
    }
  }
  Both -> ok;
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


CASES: list[Case] = [
    # -- loader ------------------------------------------------------------------------------
    Case(
        "LR0001",
        ok={"misc/Lone.lr": LONE},
        bad={"misc/Lone.lr": replace(LONE, "  A -> B tick;", "  A -> B tick @@]")},
        message="syntax error: expected",
    ),
    Case(
        "LR0002",
        ok={"misc/Lone.lr": LONE},
        bad={"misc/Lone.lr": b"package misc;\n\nstatechart Lone {\x00\x01\x02}\n"},
        message="not a text file",
        at=("misc/Lone.lr", 3, 1),
    ),
    Case(
        "LR0003",
        ok={"misc/Lone.lr": LONE},
        bad={"misc/Lone.lr": "\n  \n\t\n"},
        message="empty model file",
        at=("misc/Lone.lr", 1, 1),
    ),
    Case(
        "LR0004",
        ok={"misc/Lone.lr": LONE},
        bad={"misc/Lone.txt": LONE},
        message="not a model file",
        at=("misc/Lone.txt", 1, 1),
        paths=("misc/Lone.txt",),
    ),
    Case(
        "LR0102",
        ok={},
        bad={
            "skills/Pick.lr": replace(
                PICK, "import actions.*;", "import actions.*;\n@@import actions.Mvoe;"
            )
        },
        message="cannot resolve import 'actions.Mvoe'",
        hint="did you mean 'Move'?",
    ),
    Case(
        "LR0104",
        ok={},
        bad={
            "skills/Pick.lr": replace(
                PICK, '<<import="Move">> state Reach(x = 5 mm)', '<<@@import="Mvoe">> state Reach'
            )
        },
        message="<<import>> target 'Mvoe' does not resolve to a statechart",
        hint="did you mean 'Move'?",
    ),
    # -- names and references ----------------------------------------------------------------
    Case(
        "LR0101",
        ok={},
        bad={"skills/Pick.lr": replace(PICK, "  go -> Reach;", "  @@state Reach;\n  go -> Reach;")},
        message="'Reach' is already declared in this scope at",
    ),
    Case(
        "LR0103",
        ok={},
        bad={"actions/Move.lr": replace(MOVE, "arm.move(x = x)", "arm.move(x = @@xx)")},
        message="unknown name 'xx'",
        hint="did you mean 'x'?",
    ),
    Case(
        "LR0105",
        ok={},
        bad={"actions/Move.lr": replace(MOVE, "{ Length x", "{ @@Lenght x")},
        message="unknown type 'Lenght'",
        hint="did you mean 'Length'?",
    ),
    Case(
        "LR0106",
        ok={},
        bad={"actions/Move.lr": replace(MOVE, "[arm.done]", "[arm@@.dne]")},
        message="has no member 'dne'",
        hint="did you mean 'done'?",
    ),
    Case(
        "LR0107",
        ok={},
        bad={"actions/Move.lr": replace(MOVE, "x = 10 mm;", "x = @@10 mmm;")},
        message="unknown unit 'mmm'",
    ),
    Case(
        "LR0108",
        ok={"misc/Lone.lr": LONE},
        bad={"misc/Lone.lr": replace(LONE, "package misc;", "@@package other;")},
        message="package 'other' does not match its folder: expected 'misc'",
    ),
    Case(
        "LR0109",
        ok={"misc/Lone.lr": LONE},
        bad={"misc/Lone.lr": replace(LONE, "statechart Lone", "@@statechart Alone")},
        message="statechart 'Alone' must be in a file named 'Alone.lr'",
        hint="the file is 'Lone.lr'",
    ),
    Case(
        "LR0110",
        ok={},
        bad={"skills/Pick.lr": skill(PICK_BODY + "  Reach -> @@pickd error;\n")},
        message="unknown state or condition 'pickd'",
        hint="did you mean 'picked'?",
    ),
    Case(
        "LR0111",
        ok={},
        bad={"skills/Pick.lr": skill(PICK_BODY + "  Reach -> picked @@dne;\n")},
        message="'dne' is not an outcome of 'Reach' (done, blocked)",
        hint="did you mean 'done'?",
    ),
    # -- layers and structure ----------------------------------------------------------------
    Case(
        "LR0201",
        ok={},
        bad={"actions/Move.lr": replace(MOVE, "<<action>>", "<<action, @@skill>>")},
        message="a statechart has exactly one layer stereotype",
    ),
    Case(
        "LR0202",
        ok={},
        bad={
            "tasks/Job.lr": replace(
                JOB,
                "  go -> PickPart;",
                '  @@<<import="actions.Move">> state Nudge;\n'
                "  go -> PickPart;\n  PickPart -> Nudge error;\n  Nudge -> failed done;\n"
                "  Nudge -> failed blocked;\n  Nudge -> failed error;",
            )
        },
        message="a task cannot use the action 'Move'",
        hint="a task uses skills and tasks",
    ),
    Case(
        "LR0203",
        ok={},
        bad={
            "actions/Move.lr": replace(MOVE, "<<action>>", "@@<<action>>").replace(
                "  do / arm.move(x = x);\n", ""
            )
        },
        message="action 'Move' must have exactly one do command, found 0",
    ),
    Case(
        "LR0204",
        ok={},
        bad={"skills/Pick.lr": skill(PICK_BODY + "  @@do / arm.move(x = 1 mm);\n")},
        message="a composite runs its children, not a command",
    ),
    Case(
        "LR0205",
        ok={},
        bad={
            "skills/Pick.lr": replace(
                replace(PICK, "<<skill>> statechart", "@@<<skill>> statechart"),
                "  start condition go;\n",
                "",
            ).replace("  go -> Reach;\n", "")
        },
        message="'Pick' has no initial state or start condition",
    ),
    Case(
        "LR0206",
        ok={},
        bad={
            "skills/Pick.lr": replace(
                replace(PICK, "<<skill>> statechart", "@@<<skill>> statechart"),
                "Reach -> picked done;\n  Reach -> failed blocked;",
                "Reach -> Reach done;\n  Reach -> Reach blocked;",
            )
        },
        message="no end condition of 'Pick' is reachable",
    ),
    Case(
        "LR0207",
        ok={},
        bad={
            "skills/Pick.lr": skill(
                PICK_BODY + '  @@<<import="Move">> state Spare;\n  Spare -> picked done;\n'
                "  Spare -> failed blocked;\n"
            )
        },
        message="state 'Spare' is unreachable",
    ),
    Case(
        "LR0208",
        ok={},
        bad={"skills/Pick.lr": skill(PICK_BODY + "  @@picked -> Reach;\n")},
        message="a transition cannot leave 'picked': it is an end",
    ),
    Case(
        "LR0209",
        ok={},
        bad={
            "skills/Pick.lr": replace(
                replace(PICK, "  Reach -> failed blocked;\n", ""),
                '<<import="Move">> state',
                '@@<<import="Move">> state',
            )
        },
        message="outcome 'blocked' of 'Reach' is not handled",
    ),
    Case(
        "LR0210",
        ok={},
        bad={
            "skills/Pick.lr": skill(
                PICK_BODY + '  <<@@import="Pick">> state Again;\n  Reach -> Again error;\n'
                "  Again -> failed;\n"
            )
        },
        message="cyclic <<import>>/<<extends>>: skills.Pick -> skills.Pick",
    ),
    Case(
        "LR0211",
        ok={},
        bad={"skills/Pick.lr": skill(PICK_BODY + "  @@Reach -> failed done;\n")},
        message="never fires: the transition at",
    ),
    Case(
        "LR0212",
        ok={},
        bad={
            "skills/Pick.lr": replace(
                PICK, '<<import="Move">>', '<<import="Move", @@timout="2 s">>'
            )
        },
        message="unknown stereotype <<timout>>",
        hint="did you mean 'timeout'",
    ),
    Case(
        "LR0213",
        ok={},
        bad={"skills/Pick.lr": skill(PICK_BODY + "  Reach -> @@go error;\n")},
        message="'go' is a start condition: it can only be a source",
    ),
    Case(
        "LR0214",
        ok={"misc/Lone.lr": LONE},
        bad={"misc/Lone.lr": replace(LONE, "  A -> B tick;", "  A -> B tick;\n  @@A -> B;")},
        message="never fires: 'A' has no final state or end condition",
        hint="name the event that leaves it",
    ),
    Case(
        "LR0215",
        ok={"misc/Lone.lr": LONE},
        bad={
            "misc/Lone.lr": replace(
                LONE,
                "  final state B;\n  A -> B tick;",
                "  state C { initial state D; history Back; }\n  final state B;\n"
                "  A -> @@C.Bak tick;\n  C -> B stop;",
            )
        },
        message="'Bak' is no history pseudostate of 'C'",
        hint="did you mean 'Back'?",
    ),
    Case(
        "LR0216",
        ok={"misc/Lone.lr": LONE},
        bad={
            "misc/Lone.lr": replace(
                LONE, "  A -> B tick;", "  choice C;\n  A -> C tick;\n  C -> B @@tock;"
            )
        },
        message="a branch of choice 'C' has no stimulus",
    ),
    Case(
        "LR0217",
        ok={"misc/Lone.lr": LONE},
        bad={
            "misc/Lone.lr": replace(
                LONE,
                "  initial state A;",
                "  events { tick; }\n  initial state A;\n  A -> A @@tock;",
            )
        },
        message="'tock' is no declared event (tick)",
        hint="did you mean 'tick'?",
    ),
    Case(
        "LR0218",
        ok={"misc/Pair.lr": PAIR},
        bad={"misc/Pair.lr": replace(PAIR, "C -> D tock;", "C -> D tock;\n      C -> @@B tick;")},
        message="'B' is in region 'Left': a transition cannot cross from region 'Right'",
    ),
    Case(
        "LR0219",
        ok={"misc/Pair.lr": PAIR},
        bad={
            "misc/Pair.lr": replace(
                PAIR, "    region Right {", "    @@state E;\n    region Right {"
            )
        },
        message="'E' stands beside the regions of 'Both'",
        hint="move it into one of the regions",
    ),
    Case(
        "LR0219",
        ok={"misc/Pair.lr": PAIR},
        bad={
            "misc/Pair.lr": replace(
                PAIR, "      C -> D tock;", "      C -> D tock;\n      @@entry / { }"
            )
        },
        message="an action cannot stand in region 'Right'",
        variant="inside",
    ),
    Case(
        "LR0220",
        ok={
            "skills/Twin.lr": TWIN,
            "robots/Devices.lrd": replace(DEVICES, "device Arm", "<<concurrent>> device Arm"),
        },
        bad={"skills/Twin.lr": replace(TWIN, "    region Far {", "    @@region Far {")},
        message="regions 'Near' and 'Far' both command 'arm'",
        hint="<<concurrent>>",
    ),
    Case(
        "LR0220",
        ok={"tasks/Twice.lr": TWICE},
        bad={
            "tasks/Twice.lr": replace(
                replace(TWICE, "    region Two {", "    @@region Two {"),
                "      initial state Wait;\n",
                '      <<import="Pick">> initial state Wait;\n',
            ).replace("Wait -> Done2 tick;", "Wait -> Done2;")
        },
        message="regions 'One' and 'Two' both command 'arm'",
        variant="through-skills",
    ),
    # -- typing ------------------------------------------------------------------------------
    Case(
        "LR0301",
        ok={},
        bad={"actions/Move.lr": replace(MOVE, "arm.move(x = x)", "arm.move(x = x, @@forse = 5 N)")},
        message="command 'Arm.move' has no parameter 'forse'",
        hint="did you mean 'force'?",
    ),
    Case(
        "LR0302",
        ok={},
        bad={
            "actions/Move.lr": replace(
                MOVE, "  parameters {", "  parameters { Boolean slow = @@2 mm;"
            )
        },
        message="default of 'slow': expected Boolean, found",
    ),
    Case(
        "LR0303",
        ok={},
        bad={"actions/Move.lr": replace(MOVE, "[arm.done]", "[arm@@.force]")},
        message="condition 'done' must be Boolean",
    ),
    Case(
        "LR0304",
        ok={},
        bad={"actions/Move.lr": replace(MOVE, "[arm.force > 20 N]", "[arm@@.force > 20 mm]")},
        message="'>' mixes",
    ),
    Case(
        "LR0305",
        ok={},
        bad={
            "actions/Move.lr": replace(MOVE, "arm.move(x = x)", "arm.move(x = x, force = @@100 N)")
        },
        message="arm.move(force) = 100 N is outside its safe range 1 N .. 50 N",
    ),
    Case(
        "LR0305",
        ok={
            "actions/Move.lr": replace(MOVE, "arm.move(x = x)", "arm.move(x = x, force = 2 * 20 N)")
        },
        bad={
            "actions/Move.lr": replace(
                MOVE, "arm.move(x = x)", "arm.move(x = x, force = @@2 * 40 N)"
            )
        },
        message="arm.move(force) = 80 N is outside its safe range 1 N .. 50 N",
        variant="expression",
    ),
    Case(
        "LR0306",
        ok={},
        bad={
            "actions/Move.lr": replace(
                MOVE,
                "  end condition done",
                "  exit / { arm@@.done = true; }\n  end condition done",
            )
        },
        message="'done' of device 'Arm' is a sensor: it cannot be assigned",
    ),
    Case(
        "LR0307",
        ok={},
        bad={
            "actions/Move.lr": replace(
                MOVE,
                "  end condition done",
                "  exit / { arm@@.move(x = x); }\n  end condition done",
            )
        },
        message="device command 'move' can only be called in a do action",
    ),
    Case(
        "LR0308",
        ok={
            "actions/Move.lr": replace(
                replace(MOVE, "  parameters {", "  parameters { Integer tries = 2; Real r = 1;"),
                "  end condition done",
                "  exit / { r = tries / 2; tries = tries * 2 + 1; }\n  end condition done",
            )
        },
        bad={
            "actions/Move.lr": replace(
                replace(MOVE, "  parameters {", "  parameters { Integer tries = 2;"),
                "  end condition done",
                "  exit / { tries = @@tries / 2; }\n  end condition done",
            )
        },
        message="assigned value: expected Integer, found Real",
        hint="declare the target Real",
    ),
    # -- domain interfaces -------------------------------------------------------------------
    Case(
        "LR0401",
        ok={},
        bad={
            "robots/Devices.lrd": replace(DEVICES, "sensor Boolean done;", "@@sensor Boolaen done;")
        },
        message="unknown type 'Boolaen'",
        hint="did you mean 'Boolean'?",
    ),
    Case(
        "LR0402",
        ok={},
        bad={
            "robots/Devices.lrd": replace(
                DEVICES, "  sensor Force force;", "  sensor Force force;\n  @@sensor Boolean done;"
            )
        },
        message="'done' is declared twice",
    ),
    Case(
        "LR0403",
        ok={"robots/Devices.lrd": DEVICES + "\nquantity Jerk [m/s];\n"},
        bad={"robots/Devices.lrd": DEVICES + "\n@@quantity Jerk [m/sss];\n"},
        message="unknown unit 'm/sss'",
    ),
    Case(
        "LR0404",
        ok={},
        bad={"robots/Devices.lrd": replace(DEVICES, "Force force = 10 N", "Force force = @@10 mm")},
        message="'force' expects",
    ),
]

CYCLE_A = """\
package skills;

import actions.*;

<<skill>> statechart A {
  start condition go;
  end condition done;
  <<@@import="B">> state Other;
  go -> Other;
  Other -> done done;
}
"""

EXTENDS_A = """\
package skills;

import actions.*;

<<skill, @@extends="B">> statechart A {
  start condition go;
  end condition done;
  <<import="Move">> state Reach;
  go -> Reach;
  Reach -> done done;
  Reach -> done blocked;
}
"""

# More failing models for codes with several distinct ways to fail.
CASES += [
    Case(
        "LR0405",
        ok={},
        bad={
            "robots/Devices.lrd": replace(
                DEVICES, "Force force = 10 N in", "Force force = @@100 N in"
            )
        },
        message="default Arm.move(force) = 100 N is outside its safe range 1 N .. 50 N",
    ),
    Case(
        "LR0104",
        variant="with-arguments",  # no second finding about the arguments of an unresolved state
        ok={},
        bad={"skills/Pick.lr": replace(PICK, '<<import="Move">>', '<<@@import="Mvoe">>')},
        message="<<import>> target 'Mvoe' does not resolve to a statechart",
        hint="did you mean 'Move'?",
    ),
    Case(
        "LR0002",
        variant="utf8",
        ok={"misc/Lone.lr": LONE},
        bad={"misc/Lone.lr": b"package misc;\n\n// caf\xe9\nstatechart Lone { }\n"},
        message="not a text file: invalid UTF-8",
        at=("misc/Lone.lr", 3, 1),
    ),
    Case(
        "LR0101",
        variant="package",
        ok={"robots/More.lrd": "package robots;\n\ndevice Hand { command open(); }\n"},
        bad={"robots/More.lrd": "package robots;\n\n@@device Arm { command open(); }\n"},
        message="'robots.Arm' is already declared at",
    ),
    Case(
        "LR0101",
        variant="parameter",
        ok={},
        bad={
            "actions/Move.lr": replace(
                MOVE, "{ Length x = 10 mm; }", "{ Length x = 10 mm; @@Length x = 2 mm; }"
            )
        },
        message="'x' is already declared in this scope at",
    ),
    Case(
        "LR0201",
        variant="missing",
        ok={},
        bad={"actions/Move.lr": replace(MOVE, "<<action>> statechart", "@@statechart")},
        message="'Move' uses conditions, commands or <<import>> but has no layer stereotype",
        hint="add <<task>>, <<skill>> or <<action>>",
    ),
    Case(
        "LR0202",
        variant="action-children",
        ok={},
        bad={"actions/Move.lr": action(MOVE_BODY + "  @@state Inner;\n")},
        message="an action has no child states",
        also=frozenset({"LR0205"}),
    ),
    Case(
        "LR0206",
        variant="no-end",
        ok={},
        bad={
            "skills/Pick.lr": replace(PICK, "<<skill>> statechart", "@@<<skill>> statechart")
            .replace("  end condition picked;\n  end condition failed;\n", "")
            .replace(
                "  Reach -> picked done;\n  Reach -> failed blocked;\n",
                "  Reach -> Reach done;\n  Reach -> Reach blocked;\n",
            )
        },
        message="'Pick' has no end condition or final state",
        base={k: v for k, v in BASE.items() if k != "tasks/Job.lr"},
    ),
    Case(
        "LR0210",
        variant="import-pair",
        ok={},
        bad={
            "skills/A.lr": CYCLE_A,
            "skills/B.lr": CYCLE_A.replace("statechart A", "statechart B").replace(
                '<<@@import="B">>', '<<import="A">>'
            ),
        },
        message="cyclic <<import>>/<<extends>>: skills.A -> skills.B -> skills.A",
    ),
    Case(
        "LR0210",
        variant="extends-pair",
        ok={},
        bad={
            "skills/A.lr": EXTENDS_A,
            "skills/B.lr": EXTENDS_A.replace("statechart A", "statechart B").replace(
                '@@extends="B"', 'extends="A"'
            ),
        },
        message="cyclic <<import>>/<<extends>>: skills.A -> skills.B -> skills.A",
    ),
]


def materialize(root, files: dict[str, str | bytes]) -> tuple[str, int, int] | None:
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


from cocos.cases_safety import SAFETY_CASES  # noqa: E402  (its models build on the ones above)

CASES += SAFETY_CASES

from cocos.cases_behaviour import BEHAVIOUR_CASES  # noqa: E402  (built on the models above)

CASES += BEHAVIOUR_CASES

from cocos.cases_umlp import UMLP_CASES  # noqa: E402  (UML/P statecharts, .sc)

CASES += UMLP_CASES
