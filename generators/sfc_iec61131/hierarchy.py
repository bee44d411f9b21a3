"""Entering and leaving the states of a flattened hierarchy: entry and exit statements,
completion of composite states, the transitions on an outcome, choice and history."""

from __future__ import annotations

from dataclasses import dataclass, replace

from lightrocks.generators.sfc_iec61131.conditions import negate
from lightrocks.generators.sfc_iec61131.ir import Variable
from lightrocks.generators.sfc_iec61131.network import Branch
from lightrocks.languages.lightrocks.model import Region, StateInfo
from lightrocks.metamodel import ast


@dataclass
class Node:
    """A state of a component's hierarchy; composite states are flattened into their leaves."""

    info: StateInfo
    parent: Node | None  # the composite state whose region holds this one; None at the top
    region: Region  # the region that holds this state

    @property
    def name(self) -> str:
        return self.info.name

    @property
    def path(self) -> list[str]:
        return [*self.parent.path, self.name] if self.parent else [self.name]

    @property
    def children(self) -> Region | None:
        region = self.info.region
        return region if region is not None and region.states else None

    def chain(self) -> list[Node]:
        """This state and its enclosing states, innermost first."""
        return [self, *(self.parent.chain() if self.parent else [])]


class Hierarchy:
    """The part of :class:`~.component.ComponentBuilder` that walks the hierarchy of states:
    a transition becomes branches from a leaf through the exits of the states it leaves and
    the entries of the states it enters, down to a resting leaf, a fork or an exit."""

    nodes: list[Node]
    memories: dict[int, str]  # id(composite) -> its history variable

    def _nodes(self, region: Region, parent: Node | None) -> list[Node]:
        nodes = []
        for info in region.states.values():
            node = Node(info, parent, region)
            nodes.append(node)
            if node.children is not None:
                node.nested = self._nodes(node.children, node)
        return nodes

    def _all(self, nodes: list[Node]) -> list[Node]:
        found = []
        for node in nodes:
            found.append(node)
            found += self._all(getattr(node, "nested", []))
        return found

    def _declare_memories(self) -> None:
        """A DINT per composite that history re-enters (deep history: every composite below
        it too): the number of its child active when it was last left, 0 for none or final."""
        remembered: list[Node] = []
        for node in self._all(self.nodes):
            if node.children is None:
                continue
            kinds = {p.kind for p in node.info.region.pseudostates.values()}
            if not kinds & {"history", "deep history"}:
                continue
            below = self._all(node.nested) if "deep history" in kinds else []
            remembered += [node, *(n for n in below if n.children is not None)]
        for node in remembered:
            if id(node) not in self.memories:
                name = self.names.claim(f"{'_'.join(node.path)}_last")
                self.memories[id(node)] = name
                comment = f"history of {'/'.join(node.path)}: its child last active, 0 none"
                self.block.locals.append(Variable(name, "DINT", "0", comment))

    def _region_statements(self, region: Region | None, kind: str) -> list[str]:
        if region is None:
            return []
        return self._statements(s for a in region.actions if a.kind == kind for s in a.statements)

    def _entry(self, node: Node | None) -> list[str]:
        """The entry statements of one state (None: the statechart), then the start of its
        time events."""
        region = node.info.region if node else self.region
        lines = self._region_statements(region, "entry")
        for timer in self.timers.get(id(node) if node else None, []):
            lines += [f"{timer.instance}(IN := FALSE, PT := {timer.duration});",
                      f"{timer.passed} := FALSE;"]  # fmt: skip
        return lines

    def _enter(self, node: Node) -> tuple[list[str], Node]:
        """Entry statements from ``node`` down its initial states, and the leaf reached; an
        orthogonal state is a leaf here (its fork step enters it)."""
        lines = [] if self._orthogonal(node) else self._entry(node)
        while node.children is not None and not self._orthogonal(node):
            initial = next((n for n in node.nested if n.info.state.is_initial), node.nested[0])
            node = initial
            lines += [] if self._orthogonal(node) else self._entry(node)
        return lines, node

    def _orthogonal(self, node: Node | None) -> bool:
        """``node`` (None: the statechart) holds orthogonal regions."""
        region = node.info.region if node else self.region
        return region is not None and region.orthogonal

    def _in_region(self, node: Node) -> bool:
        """``node`` is a region of an orthogonal state or statechart."""
        return self._orthogonal(node.parent)

    def _nested(self, node: Node | None) -> list[Node]:
        return node.nested if node else self.nodes

    def _owners(self, node: Node | None) -> list[Node | None]:
        """The states whose transitions a leaf (or the watch of an orthogonal state) takes:
        up to its region, or up to the statechart itself (None)."""
        if node is None:
            return [None]
        owners: list[Node | None] = []
        for owner in node.chain():
            if self._in_region(owner):
                return owners
            owners.append(owner)
        return [*owners, None]

    def _exits(self, chain: list[Node]) -> list[str]:
        """Exit statements of ``chain`` (innermost first); each state left is remembered
        by the history of its parent."""
        lines = []
        for node in chain:
            lines += self._region_statements(node.info.region, "exit") + self._remember(node)
        return lines

    def _remember(self, node: Node) -> list[str]:
        """``node`` is left: the history of its parent records it (a final state as 0)."""
        parent = node.parent
        if parent is None or id(parent) not in self.memories:
            return []
        number = 0 if node.info.state.is_final else parent.nested.index(node) + 1
        return [f"{self.memories[id(parent)]} := {number};"]

    def _invariants(self, node: Node) -> list[str]:
        """The invariants of one state (not of its enclosing states)."""
        found = []
        if node.info.state.invariant is not None:
            found.append(self._guard(node.info.state.invariant))
        if node.info.region is not None:
            found += [self._guard(i.expression) for i in node.info.region.invariants]
        return found

    def _to(self, node: Node, statements: list[str], condition: list[str]) -> list[Branch]:
        """Branches that enter ``node``: a resting leaf, or a final state completing its owner."""
        entries, leaf = self._enter(node)
        if leaf.info.state.is_final:
            entries += self._remember(leaf)
            return self._complete(leaf.parent, leaf.name, statements + entries, condition)
        if self._orthogonal(leaf):
            return [Branch(condition, statements + entries, self.parallels[id(leaf)].fork)]
        return [Branch(condition, statements + entries, self.leaves[id(leaf)])]

    def _complete(
        self, owner: Node | None, outcome: str, statements: list[str], condition: list[str]
    ) -> list[Branch]:
        """``owner`` (None: the component) ends with ``outcome``; its parent reacts."""
        if owner is None:
            exits = self._region_statements(self.region, "exit")
            return [Branch(condition, statements + exits, self._exit(outcome))]
        if self._in_region(owner):
            return [self._rest(owner, outcome, statements, condition)]
        statements = statements + self._exits([owner])
        return self._react(owner, outcome, statements, condition)

    def _react(
        self, node: Node, outcome: str, statements: list[str], condition: list[str]
    ) -> list[Branch]:
        """``node`` has ended with ``outcome``: the first matching transition whose guard holds,
        else ``error`` of the enclosing state (an unhandled outcome is an error)."""
        declared = node.info.outcomes or ()
        branches: list[Branch] = []
        guards: list[str] = []
        for transition in node.region.transitions:
            if transition.source != node.name:
                continue
            if not (
                transition.stimulus == outcome or (not transition.stimulus and outcome in declared)
            ):
                continue
            guard = self._guard(transition.guard)
            branches += self._fire(node.parent, transition, statements, [*condition, guard])
            if not guard:
                return branches
            guards.append(guard)
        otherwise = [*condition, *(negate(g) for g in guards)]
        return branches + self._complete(node.parent, "error", statements, otherwise)

    def _fire(
        self, owner: Node | None, transition: ast.Transition, statements: list[str], condition
    ) -> list[Branch]:
        """Take ``transition`` of the region of ``owner``: action, postcondition, target."""
        lines = statements + self._statements(transition.action or ())
        siblings = owner.nested if owner else self.nodes
        region = owner.info.region if owner else self.region
        target = next((n for n in siblings if n.name == transition.target), None)
        post = self._guard(transition.postcondition)
        choice = region.pseudostates.get(transition.target)
        if choice is not None and choice.kind == "choice":
            branches = self._choose(owner, choice, lines, condition, bool(post))
        elif target is None:  # an outcome of the enclosing state, which forgets its history
            forget = [f"{self.memories[id(owner)]} := 0;"] if id(owner) in self.memories else []
            branches = self._complete(owner, transition.target, lines + forget, condition)
        elif transition.target_history:
            history = target.info.region.pseudostates[transition.target_history]
            deep = history.kind == "deep history"
            branches = self._history(target, deep, lines, condition)
        else:
            branches = self._to(target, lines, condition)
        if post:
            violated = self._complete(owner, "error", [], [])
            for branch in branches:
                branch.postcondition, branch.violated = post, violated
        return branches

    def _choose(
        self,
        owner: Node | None,
        choice: ast.Pseudostate,
        statements: list[str],
        condition: list[str],
        checked: bool,
    ) -> list[Branch]:
        """Leave ``choice`` at once by its first branch whose guard holds, else the state
        that holds it ends with ``error``. Statements before it (or a postcondition to check,
        ``checked``) run in a step of their own, so that its guards read their effect."""
        region = owner.info.region if owner else self.region
        branches: list[Branch] = []
        guards: list[str] = []
        for transition in region.transitions:
            if transition.source != choice.name:
                continue
            guard = self._guard(transition.guard)
            branches += self._fire(owner, transition, [], [guard])
            if not guard:
                break
            guards.append(guard)
        else:
            branches += self._complete(owner, "error", [], [negate(g) for g in guards])
        if statements or checked:
            return [Branch(condition, statements, choice.name, following=branches)]
        return [replace(b, condition=[*condition, *b.condition]) for b in branches]

    def _history(
        self, node: Node, deep: bool, statements: list[str], condition: list[str]
    ) -> list[Branch]:
        """Enter ``node`` through its history: the child it remembers (deep history: that
        child through its own history too), else as usual. When the statements before it
        record a memory it reads (the transition leaves ``node`` itself), they run in a step
        of their own, so that the choice of the child reads what they recorded."""
        read = [node, *(self._all(node.nested) if deep else [])]
        memories = {f"{self.memories[id(n)]} :=" for n in read if id(n) in self.memories}
        if any(line.startswith(tuple(memories)) for line in statements):
            following = self._history(node, deep, [], [])
            return [Branch(condition, statements, f"{node.name}_history", following=following)]
        memory = self.memories[id(node)]
        lines = statements + self._entry(node)
        branches: list[Branch] = []
        for number, child in enumerate(node.nested, 1):
            if child.info.state.is_final:
                continue
            remembered = [*condition, f"{memory} = {number}"]
            if deep and id(child) in self.memories:
                branches += self._history(child, True, lines, remembered)
            else:
                branches += self._to(child, lines, remembered)
        return branches + self._to(node, statements, condition)
