"""Passing and failing models for the CoCos on layers, how components use one another and
the transitions of a region (LR0201–LR0217)."""

from __future__ import annotations

from cocos.models import (
    BASE,
    JOB,
    LONE,
    MOVE,
    MOVE_BODY,
    PICK,
    PICK_BODY,
    Case,
    action,
    replace,
    skill,
)

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

STRUCTURE_CASES: list[Case] = [
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
]


# More failing models for codes with several distinct ways to fail.
STRUCTURE_VARIANTS: list[Case] = [
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
