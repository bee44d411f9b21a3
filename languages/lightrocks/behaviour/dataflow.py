"""Data flow of a region: what concurrent regions write and test, and what is known when a
transition is taken.

Races (LR0614, LR0615): the regions of an orthogonal state run together, so a variable two
of them write ends with whichever wrote last, and a guard that tests what another region
writes sees the old or the new value by timing. What each region writes and tests, its
children's included, comes from the semantic model (``Component.touches``).

Dead transitions (LR0616): a guard is judged together with everything known where it is
taken: the start condition it leaves, the end condition of the child's outcome it reacts to
(an action's end conditions are a priority list: the earlier ones did not hold), and the
guards of the earlier transitions on that stimulus, which failed. A guard that never holds
alone is LR0601's, one that only those earlier guards exclude is LR0604's.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Iterator
from dataclasses import dataclass

import z3

from lightrocks.languages.lightrocks.access import access, names_of
from lightrocks.languages.lightrocks.behaviour.conditions import Conditions, Finding, start_of
from lightrocks.languages.lightrocks.model import Component, Region, StateInfo, Touch
from lightrocks.metamodel import ast
from lightrocks.metamodel.printer import expression as text


def races(component: Component, region: Region) -> Iterator[Finding]:
    """Variables two regions of the orthogonal ``region`` write (LR0614), and those one
    writes and another's guards, conditions or invariants test (LR0615).

    Each race is reported once, at an element written in this chart rather than inside a
    child it imports (a child is right on its own: its use here races): at the write the
    region makes that touches the variable least (the other region's is the one that uses
    it), at the later region's on a tie; a test races at the write, or at the test when only
    the test is written here."""
    if not region.orthogonal:
        return
    file = region.loaded.unit.package_position.file
    regions = [(n, component.touches(i.region)) for n, i in region.states.items() if i.region]
    for index, (name, mine) in enumerate(regions):
        for other, theirs in regions[:index]:
            both: set[str] = set()
            for touch in _first_per_path(t for t in mine if t.writes):
                found = _meeting(touch, (t for t in theirs if t.writes))
                if found is None or _commute(touch.path, (*mine, *theirs)):
                    continue
                both |= {touch.path, found.path}
                here, there = (name, touch), (other, found)
                if _prefer(there, here, mine, theirs):
                    here, there = there, here
                yield Finding(
                    "LR0614",
                    _position(here[1]),
                    f"region '{here[0]}' writes '{here[1].path}'{_via(here[1], file)}, and so "
                    f"does region '{there[0]}'{_via(there[1], file, True)}: which value "
                    "stays depends on the order the regions run in",
                    "let one region write it, or write it where the regions meet",
                )
            pairs = ((name, mine, other, theirs), (other, theirs, name, mine))
            for writer, writes, tester, tests in pairs:
                for touch in _first_per_path(t for t in writes if t.writes):
                    found = _meeting(touch, (t for t in tests if not t.writes))
                    if found is None or touch.path in both:
                        continue
                    if touch.child and not found.child:
                        said = f"region '{tester}' tests '{found.path}'{_via(found, file)}"
                        heard = f"which region '{writer}' writes{_via(touch, file, True)}"
                        at = _position(found)
                    else:
                        said = f"region '{writer}' writes '{touch.path}'{_via(touch, file)}"
                        heard = f"which region '{tester}' tests{_via(found, file, True)}"
                        at = _position(touch)
                    yield Finding(
                        "LR0615",
                        at,
                        f"{said}, {heard}: whether the test sees the old or the new value "
                        "depends on timing",
                        "test it after the regions meet, or in the region that writes it",
                    )


def _prefer(
    one: tuple[str, Touch],
    other: tuple[str, Touch],
    later: tuple[Touch, ...],
    earlier: tuple[Touch, ...],
) -> bool:
    """Whether the race is reported at ``one`` (the earlier region's write, among the
    touches ``earlier``) rather than at ``other`` (the later region's, among ``later``)."""
    if one[1].child != other[1].child and "" in (one[1].child, other[1].child):
        return not one[1].child
    uses = [
        sum(_overlap(t.path, w.path) for t in touches)
        for w, touches in ((one[1], earlier), (other[1], later))
    ]
    return uses[0] < uses[1]


def _commute(path: str, touches: tuple[Touch, ...]) -> bool:
    """Every write of ``path`` adds to it or takes from it what does not read it
    (``count = count + 1``): the writes commute, any order leaves the same value."""
    writes = [t for t in touches if t.writes and _overlap(t.path, path)]
    return all(_accumulates(t.node) for t in writes)


def _accumulates(node: object) -> bool:
    match node:
        case ast.Assignment(target=target, value=ast.Binary(operator="+" | "-", left=left)):
            chain = names_of(target)
            return (
                chain is not None
                and names_of(left) == chain
                and ".".join(chain) not in access(node.value.right).reads
            )
    return False


def _first_per_path(touches: Iterator[Touch]) -> list[Touch]:
    seen: dict[str, Touch] = {}
    for touch in touches:
        seen.setdefault(touch.path, touch)
    return list(seen.values())


def _meeting(touch: Touch, others: Iterator[Touch]) -> Touch | None:
    """The first of ``others`` on the same variable as ``touch`` (or a part of it)."""
    for other in others:
        if _overlap(touch.path, other.path):
            return other
    return None


def _overlap(one: str, other: str) -> bool:
    return one == other or one.startswith(f"{other}.") or other.startswith(f"{one}.")


def _position(touch: Touch) -> ast.Position:
    """Where a touch is reported: its statement or test here, or the importing state."""
    if touch.child or touch.writes:
        return touch.at
    return start_of(touch.node)


def _via(touch: Touch, file: str, always: bool = False) -> str:
    """Where a touch is, as the message names it: the child state and its element's place,
    or the line of the region's own element."""
    where = start_of(touch.node) if not touch.writes else touch.node.position
    shown = f"{where.line}:{where.column}" if where.file == file else str(where)
    if touch.child:
        return f" in '{touch.child}' (at {shown})"
    return f" at {shown}" if always else ""


# -- dead transitions ---------------------------------------------------------------------


@dataclass(frozen=True)
class Fact:
    """Something known where a transition is taken (a condition that held, or did not), and
    how the message names it."""

    expression: ast.Expression
    held: bool
    reason: str
    rank: int = 0  # the order reasons are named in: what held, what did not, what failed

    @property
    def reads(self) -> frozenset[str]:
        return access(self.expression).reads


class Context:
    """The transitions of one region judged with what is known where each is taken."""

    def __init__(self, conditions: Conditions) -> None:
        self.conditions = conditions
        self.region = conditions.region
        self.component = conditions.component
        self._file = self.region.loaded.unit.package_position.file
        self._kept: list[ast.Expression] = []  # rewritten conditions: their ids key guard terms

    def findings(self) -> Iterator[Finding]:
        leaving: dict[str, list[ast.Transition]] = {}
        for transition in self.region.transitions:
            leaving.setdefault(transition.source, []).append(transition)
        for source, transitions in leaving.items():
            for transition in transitions:
                if transition.guard is not None and transition.position.file == self._file:
                    found = self._dead(source, transition, transitions)
                    if found is not None:
                        yield found

    def _dead(
        self, source: str, transition: ast.Transition, leaving: list[ast.Transition]
    ) -> Finding | None:
        start = self.region.conditions.get(source)
        info = self.region.states.get(source)
        if start is None and (info is None or info.imported is None):
            return None  # nothing known but earlier guards: LR0604's
        contexts = []
        for key in self.conditions.keys(source, transition):
            earlier = [
                t
                for t in leaving[: leaving.index(transition)]
                if key in self.conditions.keys(source, t)
            ]
            if any(t.guard is None for t in earlier):
                return None  # an unguarded transition takes the stimulus first: LR0211, LR0604
            failed = [Fact(t.guard, False, self._at(t), 2) for t in earlier]
            known = _connected(transition.guard, self._known(start, info, key) + failed)
            if not any(f.rank < 2 for f in known):
                return None  # only earlier guards bear on it: LR0604's
            contexts.append((known, failed))
        judge, guard = self.conditions.judge, self.conditions.guard_term(transition.guard)
        if judge.never(guard):
            return None  # LR0601
        reasons: list[str] = []
        shadowed = True
        for known, failed in contexts:
            if not failed or not judge.never(guard, *self._terms(failed)):
                shadowed = False
            if judge.never(*self._terms(known)):
                return None  # a context that never arises
            needed = self._needed(guard, known)
            if needed is None:
                return None
            reasons += [r for r in needed if r not in reasons]
        if shadowed:
            return None  # LR0604
        return Finding(
            "LR0616",
            start_of(transition.guard),
            f"this guard never holds when the transition is taken: {'; '.join(reasons)}",
            "the transition never fires; correct the guard or what it contradicts",
        )

    def _needed(self, guard: z3.BoolRef, facts: list[Fact]) -> list[str] | None:
        """The reasons of the facts the guard contradicts, fewest first found; None when it
        contradicts none of them."""
        judge = self.conditions.judge
        if not judge.never(guard, *self._terms(facts)):
            return None
        kept = list(facts)
        for fact in facts:
            rest = [f for f in kept if f is not fact]
            if judge.never(guard, *self._terms(rest)):
                kept = rest
        kept.sort(key=lambda f: f.rank)
        found = [f.reason for f in kept if f.rank < 2]
        earlier = [f.reason for f in kept if f.rank == 2]
        if earlier:
            found.append(
                f"the transition{'s' if len(earlier) > 1 else ''} at "
                f"{', '.join(earlier)} did not fire"
            )
        return found

    def _known(self, start: ast.Condition | None, info: StateInfo | None, key: str) -> list[Fact]:
        if start is not None:
            if start.kind != "start" or start.expression is None:
                return []
            shown = f"[{text(start.expression)}]"
            return [Fact(start.expression, True, f"start condition '{start.name}' {shown} holds")]
        if info is None or info.imported is None:
            return []
        if info.imported.layer == "action":
            return self._outcome(info, key)
        return self._reached(info, key)

    def _reached(self, info: StateInfo, key: str) -> list[Fact]:
        """What a composite child guarantees when it ends with ``key``: one of the
        transitions into that end was taken, so its guard held and the constants its action
        assigns are the values now. A guard part that reads what is written on the way out
        (by the transition or the child's own actions) says nothing, and a way in that
        guarantees nothing leaves nothing known."""
        child = info.imported
        top = child.region
        if top.orthogonal or key not in top.outcomes:
            return []
        inner = [t for r in top.regions()[1:] for t in r.transitions if t.target == key]
        ways = [t for t in top.transitions if t.target == key]
        if inner or not ways:
            return []
        leaving = {w for a in top.actions for w in child.access(a).writes}
        cases = []
        for way in ways:
            written = leaving | {w for s in way.action or () for w in child.access(s).writes}
            parts = []
            if way.guard is not None and not _touches_any(way.guard, written):
                parts.append(way.guard)
            for statement in way.action or ():
                value = getattr(statement, "value", None)
                if isinstance(statement, ast.Assignment) and not access(value).reads:
                    path = next(iter(child.access(statement).writes), None)
                    later = [t for t in way.action if t is not statement]
                    again = any(path in child.access(t).writes for t in later)
                    if path is not None and path not in leaving and not again:
                        parts.append(ast.Binary("==", statement.target, value))
            if not parts:
                return []
            case = _joined("&&", parts)
            if all(text(case) != text(c) for c in cases):
                cases.append(case)
        expression = _joined("||", cases)
        rewritten = self._in_parent(expression, child, info)
        if rewritten is None:
            return []
        self._kept.append(rewritten)
        shown = f"[{text(expression)}]"
        return [Fact(rewritten, True, f"'{info.name}' ended with '{key}', so {shown} held")]

    def _outcome(self, info: StateInfo, key: str) -> list[Fact]:
        """What an action child's end conditions say when it ends with ``key``: that one
        held, the ones before it did not. A condition that reads what the action writes
        says nothing once it has written it."""
        child = info.imported
        ends = child.region.end_conditions if child.layer == "action" else []
        if key not in [c.name for c in ends]:
            return []
        written = {w for a in child.region.actions for w in child.access(a).writes}
        facts = []
        for condition in ends:
            held = condition.name == key
            if condition.expression is not None and not _touches_any(condition.expression, written):
                rewritten = self._in_parent(condition.expression, child, info)
                if rewritten is not None:
                    self._kept.append(rewritten)
                    shown = f"[{text(condition.expression)}]"
                    if held:
                        reason = f"'{info.name}' ended with '{key}', so {shown} held"
                        facts.append(Fact(rewritten, True, reason))
                    else:
                        reason = (
                            f"'{info.name}' did not end with '{condition.name}' before, so "
                            f"{shown} did not hold"
                        )
                        facts.append(Fact(rewritten, False, reason, 1))
            if held:
                return facts
        return facts

    def _in_parent(
        self, expression: ast.Expression, child: Component, info: StateInfo
    ) -> ast.Expression | None:
        """A child's condition in the names of the region importing it: its parameters
        replaced by the values bound to them (or their constant defaults); None when one has
        no such value here (it may change while the child runs, or is not known)."""
        parameters = child.region.parameters
        names = list(parameters)
        bound: dict[str, ast.Expression] = {}
        for index, argument in enumerate(info.state.arguments):
            bound[argument.name or (names[index] if index < len(names) else "")] = argument.value
        own = self.conditions.scope.parameters
        fixed = self.component.assigned

        def value(name: str) -> ast.Expression | None:
            parameter = parameters[name]
            if name in child.assigned:
                return None  # the child's variable: its value is the child's by now
            given = bound.get(name)
            if parameter.type == "Object":
                return given if given is not None and names_of(given) is not None else None
            if given is None:
                given = parameter.default
                reads: frozenset[str] = access(given).reads if given is not None else frozenset()
                return given if given is not None and not reads else None
            reads = access(given).reads
            if all(r in own and own[r].type != "Object" and r not in fixed for r in reads):
                return given
            return None

        def rewrite(node: object) -> object:
            if isinstance(node, ast.Name):
                if node.name in parameters:
                    return value(node.name) or _MISSING
                return node if node.name not in own else _MISSING
            if isinstance(node, tuple):
                return tuple(rewrite(item) for item in node)
            if dataclasses.is_dataclass(node) and not isinstance(node, ast.Position):
                changes = {
                    f.name: rewrite(getattr(node, f.name))
                    for f in dataclasses.fields(node)
                    if f.name != "position"
                }
                if any(_missing(v) for v in changes.values()):
                    return _MISSING
                return dataclasses.replace(node, **changes)
            return node

        found = rewrite(expression)
        if _missing(found) or _touches_any(found, set(self.component.access(info.state).writes)):
            return None  # the state's own exit action has changed it before the guard reads it
        return found

    def _terms(self, facts: list[Fact]) -> list[z3.BoolRef]:
        terms = [self.conditions.guard_term(f.expression) for f in facts]
        return [t if f.held else z3.Not(t) for f, t in zip(facts, terms, strict=True)]

    def _at(self, transition: ast.Transition) -> str:
        position = transition.position
        if position.file == self._file:
            return f"{position.line}:{position.column}"
        return str(position)


_MISSING = object()


def _touches_any(expression: ast.Expression, written: set[str]) -> bool:
    return any(_overlap(r, w) for r in access(expression).reads for w in written)


def _joined(operator: str, parts: list[ast.Expression]) -> ast.Expression:
    joined = parts[0]
    for part in parts[1:]:
        joined = ast.Binary(operator, joined, part)
    return joined


def _connected(guard: ast.Expression, facts: list[Fact]) -> list[Fact]:
    """The facts that share a variable with the guard, directly or through one another: the
    others cannot make it fail (they only constrain variables it does not read)."""
    reached = set(access(guard).reads)
    pending = [(f, f.reads) for f in facts]
    found: set[int] = set()
    grew = True
    while grew:
        grew = False
        for fact, reads in pending:
            if id(fact) not in found and any(_overlap(r, s) for r in reads for s in reached):
                found.add(id(fact))
                reached |= reads
                grew = True
    return [f for f in facts if id(f) in found]


def _missing(value: object) -> bool:
    if value is _MISSING:
        return True
    return isinstance(value, tuple) and any(_missing(v) for v in value)
