"""Passing and failing models for the CoCos on typing, units and safe ranges (LR03xx) and
on device interfaces (LR04xx)."""

from __future__ import annotations

from cocos.models import DEVICES, MOVE, Case, replace

TYPE_CASES: list[Case] = [
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
]
