"""The texts of a level's boxes and arrows, broken into lines that keep a diagram narrow."""

from __future__ import annotations

import sys
from collections.abc import Sequence

from lightrocks.languages.lightrocks.model import StateInfo
from lightrocks.metamodel import ast, printer

WIDTH = 32
"""Characters per line of a label: long guards and arguments wrap instead of widening the
whole level. At 40 the rail's SnapOnRail, with its twist reactions, was drawn with 7.1 px text
in the studio's panel; at 32 the smallest text of every example level is 8.1 px or more."""


def wrap(parts: Sequence[str], width: int = WIDTH) -> str:
    """The non-empty ``parts`` on one line when they fit, else one part per line, each
    broken at spaces where it is longer than ``width``."""
    parts = [p for p in parts if p]
    single = " ".join(parts)
    if len(single) <= width:
        return single
    return "\n".join(line for part in parts for line in _fill(part, width))


def listed(items: Sequence[str], width: int = WIDTH) -> list[str]:
    """``a = 1, b = 2``: items separated by commas, as many per line as fit."""
    lines: list[str] = []
    for index, item in enumerate(items):
        text = item + ("," if index < len(items) - 1 else "")
        if lines and len(lines[-1]) + 1 + len(text) <= width:
            lines[-1] += " " + text
        else:
            lines += _fill(text, width)
    return lines


def _fill(text: str, width: int) -> list[str]:
    lines: list[str] = []
    for word in text.split(" "):
        if lines and len(lines[-1]) + 1 + len(word) <= width:
            lines[-1] += " " + word
        else:
            lines.append(word)
    return lines


def stereotypes(items: Sequence[ast.Stereotype]) -> str:
    """``«skill»``, ``«import="TurnTool"»``: UML's guillemets."""
    text = printer.stereotypes(items)
    return f"«{text[2:-2]}»" if text else ""


def heading(items: Sequence[ast.Stereotype], name: str) -> str:
    return " ".join(filter(None, [stereotypes(items), name]))


def state_lines(info: StateInfo) -> list[str]:
    """A state's box: stereotypes, name and invariant, arguments, then (for a state whose
    body is not a level of its own) its actions and internal transitions, as in UML."""
    state = info.state
    lines = [stereotypes(state.stereotypes)] if state.stereotypes else []
    invariant = f" [{printer.expression(state.invariant)}]" if state.invariant else ""
    lines.append(state.name + invariant)
    if state.arguments:
        lines += listed(printer.arguments(state.arguments))
    region = info.region
    if region is not None:
        lines += [line for a in region.actions for line in action_lines(a)]
        lines += [transition_label(t).replace("\n", " ") for t in region.internal]
    return lines


def action_lines(action: ast.Action, width: int = WIDTH + 10) -> list[str]:
    """``entry / …``, ``do / robot.moveCartesian(…)`` with its arguments one per line."""
    lines: list[str] = []
    for index, statement in enumerate(action.statements):
        prefix = f"{action.kind} / " if index == 0 else "  "
        lines += printer.statement(statement, prefix, width)
    return lines or [f"{action.kind} /"]


def transition_label(transition: ast.Transition | ast.InternalTransition) -> str:
    """``stimulus(arguments) [guard] / action``; a time event reads ``after(500 ms)``."""
    arguments = ", ".join(printer.expression(a) for a in transition.stimulus_arguments)
    stimulus = transition.stimulus + (f"({arguments})" if arguments else "")
    guard = f"[{printer.expression(transition.guard)}]" if transition.guard is not None else ""
    action = ""
    if transition.action:
        statements = (printer.statement(s, width=sys.maxsize)[0] for s in transition.action)
        action = "/ " + " ".join(statements)
    return wrap([stimulus, guard, action])
