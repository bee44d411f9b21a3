"""The SFC network of one function block: steps, their actions, and exclusive transitions.

A step's ways out are branches (:class:`Branch`) in priority order; :meth:`Network._branches`
makes them exclusive (each requires that no earlier one holds), so the network means the same on
a PLC that ignores priorities, and puts statements and postconditions in steps of their own.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

from lightrocks.generators.sfc_iec61131.conditions import conjunction, negate
from lightrocks.generators.sfc_iec61131.ir import Action, Block, Step, Transition, Variable
from lightrocks.generators.sfc_iec61131.names import Namer


@dataclass
class Branch:
    """One way out of a step: its condition, then the statements, then where it goes.

    A branch without target stays in its step (an internal transition); one on an event
    (``taken_once``) does not fire in the scan that enters its step, since the transition
    that entered it has taken that event; nor does a time event of a state around the
    step, which follows the time events that entered it. A branch with ``following`` runs
    its statements in a step of its own and goes on by those branches (a choice, whose
    guards read the effect of the statements)."""

    condition: list[str]
    statements: list[str]
    target: str | None
    postcondition: str = ""
    violated: list[Branch] = field(default_factory=list)  # where a broken postcondition goes
    following: list[Branch] | None = None
    taken_once: bool = False


class Network:
    """Steps, actions and transitions added to ``block``, named in ``names``."""

    def __init__(self, block: Block, names: Namer) -> None:
        self.block = block
        self.names = names
        self.resting: dict[str, str] = {}  # step -> its flag "active in the scan before"
        self.took: dict[str, str] = {}  # step -> which internal transition took the scan
        self.ways: dict[str, list[list[str]]] = {}  # timed step -> its ways out, in order

    def _step(self, name: str, initial: bool = False) -> Step:
        step = Step(self.names.claim_macro(name), initial)
        self.block.steps.append(step)
        return step

    def _body(self, step: str, qualifier: str, lines: list[str]) -> None:
        if not lines:
            return
        suffix = {"P1": "entry", "N": "run", "P0": "exit"}[qualifier]
        action = Action(self.names.claim_macro(f"{step}_{suffix}"), lines)
        self.block.actions.append(action)
        owner = next(s for s in self.block.steps if s.name == step)
        owner.actions.append((action.name, qualifier))

    def _go(self, source: str, target: str, condition: str) -> None:
        name = self.names.claim(f"{source}_to_{target}")
        self.block.transitions.append(Transition(name, source, target, condition or "TRUE"))

    def _branches(self, source: str, branches: list[Branch], timed: bool = False) -> list[str]:
        """Exclusive transitions from ``source``: each branch requires no earlier one to hold.

        Statements run in a step of their own between source and target, so that they
        finish before the target's entry and so that a postcondition reads their effect.
        Branches that stay in ``source`` come back as ST lines for its N action; in a step
        that runs timers (``timed``) each also records that it took the scan (:meth:`_took`)."""
        taken: list[str] = []
        covered: list[set[str]] = []
        staying: list[str] = []
        resting = ""
        if timed:
            self.ways[source] = [branch.condition for branch in branches]
        for place, branch in enumerate(branches, 1):
            needs = {c for c in branch.condition if c and c != "TRUE"}
            if any(earlier <= needs for earlier in covered):
                continue  # an earlier branch always wins: this one never fires
            covered.append(needs)
            condition = conjunction(branch.condition)
            whole = conjunction([condition, *(negate(t) for t in taken)])
            taken.append(condition)
            if branch.target is None:
                if branch.statements or timed:
                    if branch.taken_once:
                        resting = resting or self._resting(source)
                        whole = conjunction([condition, resting, *map(negate, taken[:-1])])
                    took = [f"{self._took(source)} := {place};"] if timed else []
                    indented = [f"  {line}" for line in [*branch.statements, *took]]
                    staying += [f"IF {whole} THEN", *indented, "END_IF;"]
                continue
            if branch.following is not None:
                between = self._step(f"{source}_to_{branch.target}_do").name
                self._body(between, "P1", branch.statements)
                self._go(source, between, whole)
                following = branch.following
                if branch.postcondition:
                    post = branch.postcondition
                    following = [
                        *(replace(f, condition=[post, *f.condition]) for f in following),
                        *(replace(v, condition=[negate(post), *v.condition])
                          for v in branch.violated),
                    ]  # fmt: skip
                self._branches(between, following)
                continue
            if not (branch.statements or branch.postcondition or branch.target == source):
                self._go(source, branch.target, whole)
                continue
            between = self._step(f"{source}_to_{branch.target}_do").name
            self._body(between, "P1", branch.statements)
            self._go(source, between, whole)
            if branch.postcondition:
                self._go(between, branch.target, branch.postcondition)
                violated = [
                    Branch(
                        [negate(branch.postcondition), *b.condition],
                        b.statements,
                        b.target,
                    )
                    for b in branch.violated
                ]
                self._branches(between, violated)
            else:
                self._go(between, branch.target, "")
        return staying

    def _resting(self, step: str) -> str:
        """A flag that ``step`` was active in the scan before, cleared when it is left: an
        SFC runs a step's actions in the scan that enters it, while the event input that
        entered it is still set, and while a time event due at the instant of that entry is
        still to be taken. The step's N action sets it last (:meth:`_run`)."""
        if step not in self.resting:
            flag = self.names.claim(f"{step}_resting")
            comment = "active in the scan before: the scan that entered it is not its own"
            self.block.locals.append(Variable(flag, "BOOL", comment=comment))
            self._body(step, "P0", [f"{flag} := FALSE;"])
            self.resting[step] = flag
        return self.resting[step]

    def _took(self, step: str) -> str:
        """A DINT that tells which way out staying in ``step`` (an internal transition) took
        this scan, by its place among the step's ways out (0: none): the ways out after it
        did not have their turn, so a time event of theirs due in this scan stays due for
        the next one, and fires after it, as at run time. The step's N action clears it
        first (:meth:`_run`)."""
        if step not in self.took:
            flag = self.names.claim(f"{step}_took")
            comment = "the internal transition that took this scan, by its place; 0 none"
            self.block.locals.append(Variable(flag, "DINT", comment=comment))
            self.took[step] = flag
        return self.took[step]

    def _run(self, step: str, lines: list[str]) -> None:
        """The N action of a resting step: which internal transition took the scan cleared,
        if it has one, ``lines``, then its resting flag, if it has one, raised."""
        took = self.took.get(step)
        flag = self.resting.get(step)
        cleared = [f"{took} := 0;"] if took else []
        self._body(step, "N", cleared + lines + ([f"{flag} := TRUE;"] if flag else []))
