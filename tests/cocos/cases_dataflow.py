"""Passing and failing models for the CoCos on data flow: races between orthogonal regions
(LR0614, LR0615) and guards that never hold where their transition is taken (LR0616)."""

from __future__ import annotations

from cocos.models import JOB, PICK, Case, replace

PAIR = """\
package misc;

statechart Pair {
  parameters { Integer n = 0; Integer m = 0; }
  initial state Both {
    region Left {
      initial state A;
      final state B;
      A -> B tick / { n = 1; };
    }
    region Right {
      initial state C;
      final state D;
      C -> D tock / { m = 2; };
    }
  }
  final state Done;
  Both -> Done [n > m];
  Both -> Done;
}
"""

STARTED = replace(PICK, "start condition go;", "start condition go [part.depth > 2 mm];")
RETRIED = replace(
    PICK,
    "  Reach -> failed blocked;\n",
    "  Reach -> failed [arm.force > 25 N] blocked;\n"
    "  Reach -> Reach [arm.force < 25 N] blocked;\n  Reach -> failed blocked;\n",
)

MARKED = replace(PICK, "Reach -> picked done;", "Reach -> picked done / { part.depth = 5 mm; };")


def _job(transitions: str) -> str:
    job = replace(JOB, "import skills.*;", "import cell.Cell;\nimport skills.*;")
    return replace(job, "  PickPart -> ok picked;\n", transitions)


DATAFLOW_CASES: list[Case] = [
    Case(
        "LR0614",
        ok={"misc/Pair.lr": PAIR},
        bad={"misc/Pair.lr": replace(PAIR, "{ m = 2; }", "{ @@n = 2; }")},
        message="region 'Right' writes 'n', and so does region 'Left' at 9:23: which value "
        "stays depends on the order the regions run in",
        hint="let one region write it",
    ),
    Case(
        "LR0614",
        ok={
            "misc/Pair.lr": replace(
                replace(PAIR, "{ m = 2; }", "{ n = n + 2; }"), "{ n = 1; }", "{ n = n - 1; }"
            )
        },
        bad={
            "misc/Pair.lr": replace(
                replace(PAIR, "{ m = 2; }", "{ @@n = 2 * n; }"), "{ n = 1; }", "{ n = n - 1; }"
            )
        },
        message="region 'Right' writes 'n', and so does region 'Left'",
        variant="accumulating",
    ),
    Case(
        "LR0615",
        ok={"misc/Pair.lr": replace(PAIR, "C -> D tock", "C -> D [m == 0] tock")},
        bad={
            "misc/Pair.lr": replace(
                replace(PAIR, "C -> D tock", "C -> D [n == 0] tock"), "{ n = 1; }", "{ @@n = 1; }"
            )
        },
        message="region 'Left' writes 'n', which region 'Right' tests at 14:15: whether the "
        "test sees the old or the new value depends on timing",
        hint="test it after the regions meet",
    ),
    Case(
        "LR0616",
        ok={
            "skills/Pick.lr": replace(
                PICK,
                "Reach -> failed blocked;",
                "Reach -> failed [arm.force > 30 N] blocked;\n  Reach -> failed blocked;",
            )
        },
        bad={
            "skills/Pick.lr": replace(
                PICK,
                "Reach -> failed blocked;",
                "Reach -> failed [@@arm.force < 10 N] blocked;\n  Reach -> failed blocked;",
            )
        },
        message="this guard never holds when the transition is taken: 'Reach' ended with "
        "'blocked', so [arm.force > 20 N] held",
        hint="correct the guard or what it contradicts",
    ),
    Case(
        "LR0616",
        ok={
            "skills/Pick.lr": replace(
                STARTED, "go -> Reach;", "go -> Reach [part.depth > 3 mm];\n  go -> failed;"
            )
        },
        bad={
            "skills/Pick.lr": replace(
                STARTED, "go -> Reach;", "go -> Reach [@@part.depth < 1 mm];\n  go -> failed;"
            )
        },
        message="start condition 'go' [part.depth > 2 mm] holds",
        variant="start",
    ),
    Case(
        "LR0616",
        ok={"skills/Pick.lr": RETRIED},
        bad={
            "skills/Pick.lr": replace(
                RETRIED, "[arm.force < 25 N]", "[@@arm.force < 20 N || arm.force > 25 N]"
            )
        },
        message="'Reach' ended with 'blocked', so [arm.force > 20 N] held; the transition at "
        "13:3 did not fire",
        also=frozenset({"LR0605"}),
        variant="earlier",
    ),
    Case(
        "LR0616",
        ok={
            "skills/Pick.lr": MARKED,
            "tasks/Job.lr": _job(
                "  PickPart -> failed [part.depth > 4 mm] picked;\n  PickPart -> ok picked;\n"
            ),
        },
        bad={
            "skills/Pick.lr": MARKED,
            "tasks/Job.lr": _job(
                "  PickPart -> failed [@@part.depth > 6 mm] picked;\n  PickPart -> ok picked;\n"
            ),
        },
        message="'PickPart' ended with 'picked', so [part.depth == 5 mm] held",
        variant="reached",
    ),
]
