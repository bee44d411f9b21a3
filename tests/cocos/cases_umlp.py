"""Passing and failing models for the CoCos of UML/P statecharts as MontiCore writes them
(``.sc``, languages/umlp): MontiCore's 0xCC100–0xCC114 as LR2100–LR2114, its type check's
0xFD118 as LR2115 and LR2116. The models are written here; none is MontiCore's."""

from __future__ import annotations

from cocos.models import Case, replace

DOOR = """\
package sc;

statechart Door {
  event open();
  event close(boolean force);

  initial state Closed;
  state Opened [true] {
    entry / { ring(); }
    initial state Ajar;
  };

  Closed -> Opened [1 < 2] open() / { count = count + 1; };
  Opened -> Closed close(true);
}
"""

FILE = "sc/Door.sc"


def _case(code: str, old: str, new: str, message: str, **more: object) -> Case:
    return Case(
        code,
        ok={FILE: DOOR},
        bad={more.pop("file", FILE): replace(DOOR, old, new)},
        message=message,
        base={},
        **more,
    )


UMLP_CASES: list[Case] = [
    _case(
        "LR2100",
        "  state Opened [true] {",
        "  @@state Closed;\n  state Opened [true] {",
        "state names must be unique, but Closed is also declared at 7:3",
    ),
    _case(
        "LR2101",
        "  state Opened [true] {",
        "  @@state Opened [1 + 2] {",
        "invariant of Opened is of type int, not boolean",
    ),
    _case(
        "LR2102",
        "statechart Door {\n  event open();\n  event close(boolean force);\n\n  initial state",
        "@@statechart Door {\n  event open();\n  event close(boolean force);\n\n  state",
        "statecharts need at least one initial state",
    ),
    _case(
        "LR2103",
        "  Opened -> Closed close(true);",
        "  @@Openend -> Closed close(true);",
        "source state Openend of the transition is missing",
        hint="did you mean 'Opened'?",
    ),
    _case(
        "LR2104",
        "  Opened -> Closed close(true);",
        "  @@Opened -> Close close(true);",
        "target state Close of the transition is missing",
        hint="did you mean 'Closed'?",
    ),
    _case(
        "LR2105",
        "    initial state Ajar;",
        "    @@initial state ajar;",
        "state ajar should start with a capital letter",
        hint="did you mean 'Ajar'?",
    ),
    _case(
        "LR2106",
        "package sc;",
        "@@package sc;",
        "file extension is 'aut', but should be 'sc'",
        file="sc/Door.aut",
    ),
    _case(
        "LR2107",
        "package sc;",
        "@@package other;",
        "package name 'other' does not correspond to the file path",
        also=frozenset({"LR0108"}),  # the workbench's own rule for every model file
    ),
    _case(
        "LR2108",
        "statechart Door {",
        "@@statechart Gate {",
        "the statechart name Gate does not match the artifact name Door",
    ),
    _case(
        "LR2109",
        "  event close(boolean force);",
        "  event close(@@boolean Force);",
        "the parameter name Force should start with a lower-case letter",
    ),
    _case(
        "LR2110",
        "  event open();",
        "  @@event Open();",
        "the event name Open should start with a lower-case letter",
    ),
    _case(
        "LR2111",
        "[1 < 2]",
        "[@@1 + 2]",
        "guard expressions must be boolean; [1 + 2] is of type 'int'",
    ),
    _case(
        "LR2112",
        "  initial state Closed;",
        "  initial state Closed;\n  @@{ ring(); } state Locked;",
        "initialization actions may only be specified for initial states, but 'Locked' is "
        "not initial",
    ),
    _case(
        "LR2114",
        "  initial state Closed;",
        "  initial state Closed;\n  @@initial state Locked;",
        "statecharts must not have more than one initial state",
    ),
    _case(
        "LR2115",
        "[1 < 2]",
        "[@@String]",
        "'String' is a type, not a value",
    ),
    _case(
        "LR2116",
        "[1 < 2]",
        "[@@authorized]",
        "'authorized' is not declared in the statechart",
        hint="UML/P takes it from the class the chart describes",
    ),
]
