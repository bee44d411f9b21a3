"""Orthogonal regions: one simultaneous divergence (the fork) and one simultaneous
convergence (the join) per orthogonal state, and a watch for what leaves it from outside
its regions (docs/generators.md)."""

from __future__ import annotations

from dataclasses import dataclass, replace

from lightrocks.generators.sfc_iec61131.hierarchy import Node
from lightrocks.generators.sfc_iec61131.ir import Transition, Variable
from lightrocks.generators.sfc_iec61131.network import Branch


@dataclass
class Parallel:
    """The steps of an orthogonal state: every entry goes to ``fork``, whose simultaneous
    divergence starts each region and ``watch``; a region rests in ``ends[i]`` once final,
    or once ``abort`` asks every region to end; the simultaneous convergence of the ends and
    of ``watched`` leads to ``left``, which goes on by ``way``: 0 the join, 1 an error of a
    region, from 2 on the transitions the watch takes."""

    fork: str
    watch: str
    watched: str
    left: str
    ends: list[str]
    abort: str
    way: str
    final: str  # which final state of the first region it rests in


class OrthogonalRegions:
    """The part of :class:`~.component.ComponentBuilder` that forks, watches and joins the
    regions of orthogonal states."""

    parallels: dict[int, Parallel]  # id(orthogonal state) -> its steps

    def _declare_parallel(self, node: Node | None) -> None:
        """The steps and variables of an orthogonal state (None: the statechart), before
        anything leads there."""
        where = "_".join(node.path) if node else self.component.name
        variables = [
            Variable(self.names.claim(f"{where}_abort"), "BOOL", comment="every region ends"),
            Variable(self.names.claim(f"{where}_way"), "DINT", comment="how it is left"),
            Variable(self.names.claim(f"{where}_final"), "DINT", comment="first region's end"),
        ]
        self.block.locals += variables
        abort, way, final = (v.name for v in variables)
        fork = self._step(f"{where}_fork").name
        ends = [self._step(f"{'_'.join(r.path)}_end").name for r in self._nested(node)]
        watch = self._step(f"{where}_watch").name
        watched = self._step(f"{where}_watched").name
        left = self._step(f"{where}_left").name
        self.parallels[id(node)] = Parallel(fork, watch, watched, left, ends, abort, way, final)
        self.block.regions += ["/".join(r.path) for r in self._nested(node)]

    def _rest(self, region: Node, outcome: str, statements: list[str], condition) -> Branch:
        """A region ends: resting in a final state, or with ``error``, which ends them all."""
        parallel = self.parallels[id(region.parent)]
        end = self._end(region)
        finals = [n.name for n in region.nested if n.info.state.is_final]
        if outcome in finals:
            first = region is self._nested(region.parent)[0]
            chosen = [f"{parallel.final} := {finals.index(outcome) + 1};"] if first else []
            return Branch(condition, statements + chosen, end)
        return Branch(condition, statements + self._abort(parallel, 1), end)

    def _end(self, region: Node) -> str:
        """The step in which ``region`` rests until every region has ended."""
        return self.parallels[id(region.parent)].ends[self._nested(region.parent).index(region)]

    @staticmethod
    def _abort(parallel: Parallel, way: int) -> list[str]:
        """Ask every region to end; the first way out asked for is taken."""
        return [
            f"IF NOT {parallel.abort} THEN",
            f"  {parallel.way} := {way};",
            f"  {parallel.abort} := TRUE;",
            "END_IF;",
        ]

    def _parallel(self, node: Node | None) -> None:
        """Fork, watch, join: the network of an orthogonal state (None: the statechart,
        whose entry statements run before its fork)."""
        parallel = self.parallels[id(node)]
        lines = [f"{parallel.abort} := FALSE;", f"{parallel.way} := 0;", f"{parallel.final} := 0;"]
        due = self._inner_deadlines(node) if self._timed(node) else ""
        inner = self._inner_flag(node) if due else ""
        lines += [f"{inner} := FALSE;"] if inner else []
        lines += self._entry(node) if node else []
        targets = []
        regions = self._nested(node)
        for index, region in enumerate(regions):
            entries, leaf = self._enter(region)
            lines += entries
            if leaf.info.state.is_final:
                branch = self._rest(region, leaf.name, [], [])
                lines += branch.statements
                targets.append(parallel.ends[index])
            else:
                targets.append(self.leaves[id(leaf)])
        targets.append(parallel.watch)
        self._body(parallel.fork, "P1", lines)
        name = self.names.claim(f"{parallel.fork}_to_regions")
        self.block.transitions.append(
            Transition(name, parallel.fork, targets[0], "TRUE", targets=targets)
        )
        # the watch: what leaves the orthogonal state from outside its regions
        ended = " AND ".join(f"{end}.X" for end in parallel.ends)
        outside = self._invariant_branches(node) + self._events(node, [], inner)
        before = len(self.block.transitions)
        staying = self._branches(
            parallel.watch,
            [
                Branch([f"{parallel.abort} OR ({ended})"], [], parallel.watched),
                *(
                    replace(b, statements=self._abort(parallel, n), target=parallel.watched,
                            postcondition="", violated=[], following=None)
                    if b.target is not None else b
                    for n, b in enumerate(outside, 2)
                ),
            ],
            self._timed(node),
        )  # fmt: skip
        ticks = self._ticks(parallel.watch, node, inner)
        self._run(parallel.watch, staying + ticks + ([f"{inner} := {due};"] if inner else []))
        # declared first, the watch reads the regions' step flags before any region moves:
        # MatIEC clears a step's flag as soon as one of its transitions fires
        added = self.block.transitions[before:]
        first = [t for t in added if t.source == parallel.watch]
        rest = [t for t in self.block.transitions if t not in first]
        self.block.transitions[:] = first + rest
        name = self.names.claim(f"{parallel.left}_join")
        sources = [*parallel.ends, parallel.watched]
        self.block.transitions.append(
            Transition(name, sources[0], parallel.left, "TRUE", sources=sources)
        )
        # leaving: the regions' own exits (last region first), then the way taken
        exits = [line for r in reversed(regions) for line in self._exits([r])]
        first = regions[0]
        finals = [n.name for n in first.nested if n.info.state.is_final]
        ways = [
            branch
            for number, outcome in enumerate(finals, 1)
            for branch in self._complete(
                node, outcome, exits, [f"{parallel.way} = 0", f"{parallel.final} = {number}"]
            )
        ]
        ways += self._complete(node, "error", exits, [f"{parallel.way} = 1"])
        for n, b in enumerate(outside, 2):
            if b.target is not None:
                ways.append(replace(b, condition=[f"{parallel.way} = {n}"],
                                    statements=exits + b.statements))  # fmt: skip
        self._branches(parallel.left, ways)

    def _inner_flag(self, node: Node | None) -> str:
        """A flag that a time event inside the regions of ``node`` was due and not yet taken
        at the end of the scan before: the time events of the watch wait while it is set,
        as at run time the innermost fire first. The watch's N action sets it last; it runs
        after the N actions of the regions' leaves, which are declared before it, so it
        reads the state the next scan starts from."""
        where = "_".join(node.path) if node else self.component.name
        flag = self.names.claim(f"{where}_inner")
        comment = "a time event inside its regions is due: its own time events wait"
        self.block.locals.append(Variable(flag, "BOOL", comment=comment))
        return flag

    def _inner_deadlines(self, node: Node | None) -> str:
        """The condition that a time event inside the regions of ``node`` is due and not
        yet taken: a state's timer counts while a leaf under it is active, and a region
        between two leaves (in a step that runs a transition's statements) may be on its
        way to one that takes a time event due at this instant."""
        due = []
        for region in self._nested(node):
            leaves = [n for n in self._all(region.nested) if id(n) in self.leaves]
            resting = [self.leaves[id(n)] for n in leaves] + [self._end(region)]
            due.append(f"NOT ({' OR '.join(f'{step}.X' for step in resting)})")
            for leaf in leaves:
                timers = [t for owner in self._owners(leaf) for t in self.timers.get(id(owner), [])]
                if timers:
                    live = " OR ".join(f"({t.instance}.Q AND NOT {t.passed})" for t in timers)
                    due.append(f"({self.leaves[id(leaf)]}.X AND ({live}))")
        return " OR ".join(due)
