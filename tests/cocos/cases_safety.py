"""Passing and failing models for the CoCos that catch values and forms a model's author
did not mean: stereotype values, actions without an end, misplaced guards, unsafe values that
reach a command through parameters."""

from __future__ import annotations

from cocos.models import CELL, DEVICES, MOVE, PICK, Case, replace

FORCED_MOVE = replace(
    replace(MOVE, "Length x = 10 mm;", "Length x = 10 mm; Force f = 10 N;"),
    "arm.move(x = x)",
    "arm.move(x = x, force = f)",
)

SAFETY_CASES: list[Case] = [
    Case(
        "LR0501",
        ok={
            "actions/Move.lr": replace(MOVE, "<<action>>", '<<action, timeout="8 s">>'),
            # a budget written down is an outcome to handle (LR0209)
            "skills/Pick.lr": replace(
                PICK,
                "  Reach -> failed blocked;\n",
                "  Reach -> failed blocked;\n  Reach -> failed timeout;\n",
            ),
        },
        bad={"actions/Move.lr": replace(MOVE, "<<action>>", '<<action, @@timeout="8 mm">>')},
        also=frozenset({"LR0209"}),  # a budget, if not a valid one, is an outcome to handle
        message="timeout '8 mm' is not a duration",
        hint="time unit",
    ),
    Case(
        "LR0501",
        ok={},
        bad={
            "robots/Devices.lrd": replace(DEVICES, "device Arm", '<<@@timeout="eight">> device Arm')
        },
        message="timeout 'eight' is not a duration",
        variant="words",
    ),
    Case(
        "LR0502",
        ok={"cell/Cell.lrd": replace(CELL, "cell Cell", '<<scene="screwing">> cell Cell')},
        bad={
            "cell/Cell.lrd": replace(
                CELL, "cell Cell", '<<@@scene="../../../etc/passwd">> cell Cell'
            )
        },
        message="scene '../../../etc/passwd' is not a scene name",
    ),
    Case(
        "LR0503",
        ok={},
        bad={
            "actions/Move.lr": replace(
                replace(MOVE, "<<action>> statechart", "@@<<action>> statechart"),
                "  end condition done [arm.done];\n  end condition blocked [arm.force > 20 N];\n",
                "",
            ),
            "skills/Pick.lr": replace(
                replace(PICK, "  Reach -> picked done;\n", ""), "  Reach -> failed blocked;\n", ""
            ),
        },
        message="action 'Move' has no end condition",
        also=frozenset({"LR0206"}),
    ),
    Case(
        "LR0504",
        ok={
            "skills/Pick.lr": replace(PICK, "Reach -> picked done;", "Reach -> picked [true] done;")
        },
        bad={
            "skills/Pick.lr": replace(
                PICK, "Reach -> picked done;", "Reach -> picked done [@@true];"
            )
        },
        message="a [condition] after the stimulus is a postcondition, not a guard",
        hint="Reach -> picked [...] done;",
    ),
    Case(
        "LR0505",
        ok={"actions/Move.lr": FORCED_MOVE},
        bad={
            "actions/Move.lr": FORCED_MOVE,
            "skills/Pick.lr": replace(PICK, "Reach(x = 5 mm)", "Reach(x = 5 mm, f = @@100 N)"),
        },
        message="'f' of Move reaches arm.move(force) = 100 N is outside its safe range 1 N .. 50 N",
        variant="binding",
    ),
    Case(
        "LR0505",
        ok={},
        bad={"actions/Move.lr": replace(FORCED_MOVE, "Force f = 10 N;", "Force f = @@60 N;")},
        message="default of 'f' reaches arm.move(force) = 60 N is outside its safe range 1 N ..",
        variant="default",
    ),
]
