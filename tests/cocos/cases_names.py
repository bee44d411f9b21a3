"""Passing and failing models for the findings of the loader (LR00xx, and LR0102 and LR0104,
reported while names are resolved) and the CoCos on names and references (LR01xx)."""

from __future__ import annotations

from cocos.models import LONE, MOVE, PICK, PICK_BODY, Case, replace, skill

NAME_CASES: list[Case] = [
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
]


# More failing models for codes with several distinct ways to fail.
NAME_VARIANTS: list[Case] = [
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
]
