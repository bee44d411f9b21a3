"""The SFC checker: a correct network passes, and each rule fires on a network that breaks it."""

from __future__ import annotations

import pytest

from lightrocks.generators.sfc_iec61131.checker import check_sfc

GOOD = """
TYPE
  Wrench : STRUCT force : REAL; torque : REAL; END_STRUCT;
END_TYPE
FUNCTION_BLOCK Demo
VAR_INPUT go : BOOL; load : Wrench; END_VAR
VAR_OUTPUT finished : BOOL; END_VAR
INITIAL_STEP Idle :
  Idle_entry(P1);
END_STEP
STEP Work :
  Work_run(N);
  Work_limit(L, T#5s);
END_STEP
STEP Grip :
END_STEP
STEP Lift :
END_STEP
STEP Done :
END_STEP
TRANSITION start (PRIORITY := 1) FROM Idle TO Work := go; END_TRANSITION
TRANSITION stay (PRIORITY := 2) FROM Idle TO Done := NOT go; END_TRANSITION
TRANSITION split FROM Work TO (Grip, Lift) := Work.T >= T#1s AND load.force > 1.0;
END_TRANSITION
TRANSITION join FROM (Grip, Lift) TO Done := TRUE; END_TRANSITION
TRANSITION again FROM Done TO Idle := NOT go; END_TRANSITION
ACTION Idle_entry : finished := FALSE; END_ACTION
ACTION Work_run : finished := FALSE; END_ACTION
ACTION Work_limit : finished := TRUE; END_ACTION
END_FUNCTION_BLOCK
"""

BROKEN = {
    "initial-step": ("INITIAL_STEP Idle", "STEP Idle"),
    "unique-name": ("STEP Grip :", "STEP finished :"),
    "reserved-name": ("STEP Lift :\nEND_STEP", "STEP Lift :\nEND_STEP\nSTEP TON :\nEND_STEP"),
    "undefined-step": ("FROM Done TO Idle", "FROM Done TO Nowhere"),
    "undefined-action": ("Work_run(N);", "Work_walk(N);"),
    "priority": ("TRANSITION stay (PRIORITY := 2)", "TRANSITION stay"),
    "timed-qualifier": ("Work_limit(L, T#5s);", "Work_limit(L);"),
    "empty-action": ("ACTION Work_limit : finished := TRUE;", "ACTION Work_limit :"),
    "simultaneous": ("FROM (Grip, Lift) TO Done", "FROM Grip TO Done"),
    "type-name": ("load : Wrench;", "wrench : Wrench;"),
    "macro-name": ("STEP Grip :", "STEP Force :"),
    "empty-body": ("END_TYPE\n", "END_TYPE\nFUNCTION_BLOCK Nothing\nEND_FUNCTION_BLOCK\n"),
    "string-literal": ("finished := FALSE; END_ACTION", "finished := 'a\nb' = 'c'; END_ACTION"),
}


def test_a_correct_network_passes() -> None:
    assert check_sfc(GOOD) == []


@pytest.mark.parametrize("rule", sorted(BROKEN))
def test_each_rule_fires(rule: str) -> None:
    old, new = BROKEN[rule]
    assert old in GOOD
    problems = check_sfc(GOOD.replace(old, new, 1))
    assert rule in {p.rule for p in problems}, problems


def test_two_initial_steps_and_duplicate_priorities() -> None:
    text = GOOD.replace("STEP Done :", "INITIAL_STEP Done :").replace(
        "(PRIORITY := 2)", "(PRIORITY := 1)"
    )
    assert {p.rule for p in check_sfc(text)} == {"initial-step", "priority"}


def test_comments_and_strings_are_not_read_as_sfc() -> None:
    text = GOOD.replace(
        "finished := FALSE; END_ACTION", "finished := FALSE; (* STEP x : *) END_ACTION"
    )
    assert check_sfc(text) == []
