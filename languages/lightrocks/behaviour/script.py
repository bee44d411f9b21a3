"""A counterexample as a dry-run script (``lightrocks run --adapter dryrun --script FILE``):
the outcome of every command the run ends, in order, per ``device.command``. A loop is
written out :data:`LOOPS` times. Events are not part of a script: a run that needs one is
replayed up to it."""

from __future__ import annotations

import json

from lightrocks.languages.lightrocks.behaviour.checker import Counterexample

LOOPS = 3


def script(counterexample: Counterexample) -> dict[str, dict[str, list[str]]]:
    outcomes: dict[str, list[str]] = {}
    steps = list(counterexample.steps) + list(counterexample.loop) * LOOPS
    for step in steps:
        if step.command:
            outcomes.setdefault(step.command, []).append(step.stimulus)
    return {"outcomes": outcomes}


def script_text(counterexample: Counterexample) -> str:
    """The script as the JSON text ``--script`` reads."""
    return json.dumps(script(counterexample), indent=2) + "\n"


def describe(counterexample: Counterexample) -> list[str]:
    """The run step by step, as a person reads it: ``Task/Skill/Action: outcome``."""
    lines = [f"{'/'.join(s.where)}: {s.stimulus}" for s in counterexample.steps]
    if counterexample.loop:
        lines.append("then, again and again:")
        lines += [f"  {'/'.join(s.where)}: {s.stimulus}" for s in counterexample.loop]
    if counterexample.end:
        lines.append(f"ends with '{counterexample.end}'")
    return lines
