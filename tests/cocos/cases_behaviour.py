"""Passing and failing models for the CoCos on behaviour: guards, start and end conditions
judged by the SMT solver over the declared ranges of sensors and attributes."""

from __future__ import annotations

from cocos.cases import BASE, CELL, DEVICES, MOVE, PICK, Case, replace

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

BEHAVIOUR_CASES: list[Case] = [
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
        ok={},
        bad={"skills/Pick.lr": replace(PICK, "<<skill>>", '<<skill, @@timeout="3 s">>')},
        message="<<timeout>> has no effect on a skill",
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
            "skills/Pick.lr": replace(
                replace(
                    TWICE,
                    "state Reach(x = 5 mm);",
                    'state Reach(x = 5 mm);\n  <<import="Move">> state Again;',
                ),
                "  Again -> failed blocked;\n",
                "  Again -> failed blocked;\n  Again -> failed timeout;\n",
            ).replace("Reach -> picked done;", "Reach -> Again done;")
        },
        bad={
            "skills/Pick.lr": replace(
                TWICE,
                "state Reach(x = 5 mm);",
                'state Reach(x = 5 mm);\n  @@<<import="Move">> state Again;',
            ).replace("Reach -> picked done;", "Reach -> Again done;")
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
