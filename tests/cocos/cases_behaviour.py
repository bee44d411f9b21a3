"""Passing and failing models for the CoCos on behaviour: guards, start and end conditions
judged by the SMT solver over the declared ranges of sensors and attributes."""

from __future__ import annotations

from cocos.models import BASE, CELL, DEVICES, JOB, MOVE, PICK, Case, replace

RANGED = replace(
    replace(DEVICES, "sensor Force force;", "sensor Force force in 0 N .. 100 N;"),
    "sensor Boolean done;",
    "sensor Boolean done = false;\n  sensor Length travel = 0 mm;",
)
COUNTED = replace(CELL, "Length depth = 0 mm;", "Length depth = 0 mm; Integer tries = 0 in 0 .. 5;")


def _move(condition: str) -> str:
    return replace(MOVE, "  end condition blocked [arm.force > 20 N];\n", condition)


def _pick(transitions: str) -> str:
    return replace(PICK, "  Reach -> picked done;\n", transitions)


TWICE = replace(
    PICK,
    "  Reach -> failed blocked;\n",
    "  Reach -> failed blocked;\n  Reach -> failed timeout;\n  Again -> picked done;\n"
    "  Again -> failed blocked;\n",
)

OTHER_MOVE = replace(MOVE, "package actions;", "package more;")
BUDGETED = replace(MOVE, "<<action>>", '<<action, timeout="5 s">>')
REACHING = replace(
    DEVICES,
    "  sensor Boolean done;",
    "  command reach(Frame goal, Velocity speed = 0.1 m/s in 1 mm/s .. 0.5 m/s,\n"
    "                Stiffness6 stiffness = [2000 N/m, 2000 N/m, 2000 N/m, 150 Nm/rad, "
    "150 Nm/rad, 150 Nm/rad]);\n"
    "  sensor Boolean done;\n  sensor Frame tcp;\n  sensor Wrench wrench;",
)
REACH = """\
package actions;

import cell.Cell;

<<action, timeout="5 s">> statechart Move {
  parameters { Length x = 10 mm; Angle turn = 90 deg; }
  do / arm.reach(goal = transl(0 mm, 0 mm, -20 mm) * arm.tcp, speed = 10 mm/s);
  end condition done [arm.done];
  end condition blocked [arm.wrench.force.z > 5 N];
}
"""
PLAUSIBLE = {
    "robots/Devices.lrd": REACHING,
    "actions/Move.lr": REACH,
    "skills/Pick.lr": _pick("  Reach -> picked done;\n  Reach -> failed timeout;\n"),
}

BEHAVIOUR_CASES: list[Case] = [
    Case(
        "LR0607",
        ok=PLAUSIBLE,
        bad={
            **PLAUSIBLE,
            "actions/Move.lr": replace(
                REACH, '<<action, timeout="5 s">>', '<<action, @@timeout="1 s">>'
            ),
        },
        message="the time budget 1 s is shorter than the motion takes: 20 mm at 10 mm/s is 2 s",
    ),
    Case(
        "LR0608",
        ok=PLAUSIBLE,
        bad={
            **PLAUSIBLE,
            "actions/Move.lr": replace(
                REACH,
                "speed = 10 mm/s);",
                "speed = 10 mm/s,\n    stiffness = @@[2 N/m, 2 N/m, 2 N/m, "
                "150 Nm/rad, 150 Nm/rad, 150 Nm/rad]);",
            ),
        },
        message="arm.reach(stiffness[0]) = 2 (SI) is 1000 times below its typical 2000",
    ),
    Case(
        "LR0609",
        ok=PLAUSIBLE,
        bad={
            **PLAUSIBLE,
            "actions/Move.lr": replace(REACH, "Angle turn = 90 deg;", "Angle turn = @@1.5708 deg;"),
        },
        message="1.5708 deg is π/2 degrees: radians were meant",
    ),
    Case(
        "LR0610",
        ok=PLAUSIBLE,
        bad={
            **PLAUSIBLE,
            "actions/Move.lr": replace(
                REACH,
                "end condition blocked [arm.wrench.force.z > 5 N];",
                "end condition blocked [@@arm.wrench.force.z < -5 N];",
            ),
        },
        message="end condition 'blocked' needs arm.wrench.force.z < 0 while the arm moves -z",
    ),
    Case(
        "LR0112",
        ok={
            "more/Move.lr": OTHER_MOVE,
            "skills/Pick.lr": replace(
                PICK, "import actions.*;", "import actions.*;\nimport more.*;\nimport actions.Move;"
            ),
        },
        bad={
            "more/Move.lr": OTHER_MOVE,
            "skills/Pick.lr": replace(
                replace(PICK, "import actions.*;", "import actions.*;\nimport more.*;"),
                '<<import="Move">> state Reach',
                '<<@@import="Move">> state Reach',
            ),
        },
        message="'Move' is ambiguous: import actions.* (",
        hint="qualified name",
    ),
    Case(
        "LR0221",
        ok={
            "skills/Pick.lr": replace(PICK, "<<skill>>", '<<skill, timeout="3 s">>'),
            "tasks/Job.lr": replace(
                JOB,
                "  PickPart -> failed failed;\n",
                "  PickPart -> failed failed;\n  PickPart -> failed timeout;\n",
            ),
        },
        bad={
            "skills/Pick.lr": replace(
                PICK,
                '<<import="Move">> state Reach',
                '<<import="Move", @@timeout="3 s">> state Reach',
            )
        },
        message="<<timeout>> has no effect on a state",
    ),
    Case(
        "LR0221",
        ok={},
        bad={
            "actions/Move.lr": replace(
                MOVE, "  end condition done", "  @@history H;\n  end condition done"
            )
        },
        message="history 'H' in an action has no effect",
        variant="history",
    ),
    Case(
        "LR0209",
        ok={
            "actions/Move.lr": BUDGETED,
            "skills/Pick.lr": replace(
                replace(
                    TWICE,
                    "state Reach(x = 5 mm);",
                    'state Reach(x = 5 mm);\n  <<import="Move">> state Again;',
                ),
                "  Again -> failed blocked;\n",
                "  Again -> failed blocked;\n  Again -> failed timeout;\n",
            ).replace("Reach -> picked done;", "Reach -> Again done;"),
        },
        bad={
            "actions/Move.lr": BUDGETED,
            "skills/Pick.lr": replace(
                TWICE,
                "state Reach(x = 5 mm);",
                'state Reach(x = 5 mm);\n  @@<<import="Move">> state Again;',
            ).replace("Reach -> picked done;", "Reach -> Again done;"),
        },
        message="outcome 'timeout' of 'Again' is not handled",
        variant="timeout",
    ),
    Case(
        "LR0601",
        ok={"robots/Devices.lrd": RANGED},
        bad={
            "robots/Devices.lrd": RANGED,
            "actions/Move.lr": _move("  end condition blocked [@@arm.force > 200 N];\n"),
        },
        message="end condition 'blocked' never holds: no value satisfies it (arm.force in 0 N",
    ),
    Case(
        "LR0601",
        ok={
            "cell/Cell.lrd": COUNTED,
            "skills/Pick.lr": _pick(
                "  Reach -> picked [part.tries < 5] done;\n  Reach -> failed done;\n"
            ),
        },
        bad={
            "cell/Cell.lrd": COUNTED,
            "skills/Pick.lr": _pick(
                "  Reach -> picked [@@part.tries > 5] done;\n  Reach -> failed done;\n"
            ),
        },
        message="this guard never holds",
        variant="guard",
    ),
    Case(
        "LR0602",
        ok={"robots/Devices.lrd": RANGED},
        bad={
            "robots/Devices.lrd": RANGED,
            "skills/Pick.lr": _pick("  Reach -> picked [@@arm.force >= 0 N] done;\n"),
        },
        message="this guard always holds",
    ),
    Case(
        "LR0603",
        ok={
            "robots/Devices.lrd": RANGED,
            "actions/Move.lr": _move("  end condition blocked [arm.travel < -2 mm];\n"),
        },
        bad={
            "robots/Devices.lrd": RANGED,
            "actions/Move.lr": _move("  end condition blocked [@@arm.travel > -2 mm];\n"),
        },
        message="end condition 'blocked' already holds when the command starts (arm.travel = 0 mm)",
    ),
    Case(
        "LR0604",
        ok={
            "skills/Pick.lr": _pick(
                "  Reach -> picked [part.depth > 1 mm] done;\n  Reach -> failed done;\n"
            )
        },
        bad={
            "skills/Pick.lr": _pick(
                "  Reach -> picked [part.depth > 1 mm] done;\n"
                "  Reach -> failed [@@part.depth > 2 mm] done;\n"
                "  Reach -> failed done;\n"
            )
        },
        message="never fires: the transition at 12:3 takes every case",
    ),
    Case(
        "LR0604",
        ok={
            "actions/Move.lr": _move(
                "  end condition blocked [arm.force > 20 N];\n"
                "  end condition stuck [arm.force > 10 N];\n"
            )
        },
        bad={
            "actions/Move.lr": _move(
                "  end condition blocked [arm.force > 10 N];\n"
                "  end condition stuck [@@arm.force > 20 N];\n"
            )
        },
        message="is never the one that holds first: whenever it holds, 'done' or 'blocked'",
        base={
            **BASE,
            "skills/Pick.lr": _pick("  Reach -> picked done;\n  Reach -> failed stuck;\n"),
        },
        variant="end",
    ),
    Case(
        "LR0605",
        ok={
            "skills/Pick.lr": _pick(
                "  Reach -> picked [part.depth > 2 mm] done;\n"
                "  Reach -> failed [part.depth <= 2 mm] done;\n"
            )
        },
        bad={
            "skills/Pick.lr": _pick(
                "  Reach -> picked [part.depth > 1 mm] done;\n"
                "  Reach -> failed [@@part.depth < 3 mm] done;\n"
            )
        },
        message="both guards hold when part.depth = 2 mm",
    ),
    Case(
        "LR0606",
        ok={"actions/Move.lr": _move("  end condition blocked [abs(arm.force - 20 N) < 1 N];\n")},
        bad={"actions/Move.lr": _move("  end condition blocked [@@arm.force == 20 N];\n")},
        message="'==' on the measured value arm.force",
        hint="compare with a tolerance",
    ),
]

WAITING = _pick("  Reach -> picked done;\n  Reach -> failed after(2 s);\n")
TIMED_JOB = replace(
    JOB,
    "  PickPart -> failed failed;\n",
    "  PickPart -> failed failed;\n  PickPart -> failed timeout;\n",
)


def _budget(pick: str, timeout: str) -> dict[str, str]:
    """``pick`` with a skill budget, in a job that handles its timeout."""
    return {
        "skills/Pick.lr": replace(pick, "<<skill>>", f"<<skill, {timeout}>>"),
        "tasks/Job.lr": TIMED_JOB,
    }


STARTED = replace(
    MOVE,
    "  end condition done",
    "  start condition ready [arm.force < 10 N];\n  end condition done",
)
BOUNDED = _pick("  Reach -> picked done;\n  Reach -> failed timeout;\n")

DURATION_CASES: list[Case] = [
    Case(
        "LR0611",
        ok={"skills/Pick.lr": WAITING},
        bad={"skills/Pick.lr": replace(WAITING, "after(2 s)", "after(@@-2 s)")},
        message="after(-2 s) waits -2 s: a duration is never positive here",
        hint="wait a positive duration",
    ),
    Case(
        "LR0611",
        ok=_budget(WAITING, 'timeout="3 s"'),
        bad=_budget(WAITING, '@@timeout="0 s"'),
        message="timeout '0 s' is no time",
        variant="budget",
    ),
    Case(
        "LR0612",
        ok=_budget(WAITING, 'timeout="3 s"'),
        bad=_budget(replace(WAITING, "after(2 s)", "after(@@5 s)"), 'timeout="3 s"'),
        message="after(5 s) waits 5 s, not less than the budget 3 s",
        hint="raise the <<timeout>>",
    ),
    Case(
        "LR0612",
        ok={"actions/Move.lr": BUDGETED, **_budget(BOUNDED, 'timeout="9 s"')},
        bad={
            "actions/Move.lr": BUDGETED,
            **_budget(
                replace(BOUNDED, '<<import="Move">>', '<<@@import="Move">>'), 'timeout="2 s"'
            ),
        },
        message="'actions.Move' has the budget 5 s, longer than the enclosing budget 2 s",
        variant="child",
    ),
    Case(
        "LR0613",
        ok={"actions/Move.lr": STARTED},
        bad={
            "actions/Move.lr": replace(
                replace(STARTED, "[arm.force > 20 N]", "[@@arm.force > 20 N]"),
                "[arm.force < 10 N]",
                "[arm.force > 30 N]",
            )
        },
        message="end condition 'blocked' holds whenever the start condition 'ready' does",
        hint="end on what the command changes",
    ),
]

PROVED = replace(
    PICK, "  go -> Reach;\n", "  property held: picked ensures [arm.done];\n  go -> Reach;\n"
)

PROPERTY_CASES: list[Case] = [
    Case(
        "LR0717",
        ok={"skills/Pick.lr": PROVED},
        bad={"skills/Pick.lr": replace(PROVED, "held: picked", "held: @@pickd")},
        message="'pickd' is no outcome of 'Pick'",
        hint="picked",
    ),
    Case(
        "LR0718",
        ok={"skills/Pick.lr": PROVED},
        bad={
            "actions/Move.lr": replace(
                MOVE,
                "  end condition done",
                "  @@property quick: done ensures [arm.done];\n  end condition done",
            )
        },
        message="property 'quick' of the action 'Move'",
        hint="state it in a skill",
    ),
]
