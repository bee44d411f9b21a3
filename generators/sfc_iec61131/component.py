"""The FUNCTION_BLOCK of one task, skill or plain statechart, with its SFC network.

Its initial step ``Idle`` waits for ``execute`` and a start condition; a child that imports
a skill is a function-block instance called from its step (started P1, run N, reset P0); a
child that imports an elemental action is inlined: P1 starts the device command through
the device function block, a settle step stops it and runs the action's exit statements
(μ). Outcomes become transition conditions, exclusive in declaration order as at run time;
the action's time budget is ``Step.T``. An end condition is an exit step that raises
``done`` and the outcome's output until ``execute`` falls.
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import TYPE_CHECKING

from lightrocks.generators.selection import is_action
from lightrocks.generators.sfc_iec61131.children import Children
from lightrocks.generators.sfc_iec61131.conditions import group, negate
from lightrocks.generators.sfc_iec61131.expressions import Scope, initial_value
from lightrocks.generators.sfc_iec61131.hierarchy import Hierarchy, Node
from lightrocks.generators.sfc_iec61131.ir import Block, Variable
from lightrocks.generators.sfc_iec61131.network import Branch, Network
from lightrocks.generators.sfc_iec61131.regions import OrthogonalRegions, Parallel
from lightrocks.generators.sfc_iec61131.timers import TimeEvents, Timer
from lightrocks.languages.domain.types import DeviceT, ObjectT
from lightrocks.languages.lightrocks.model import BUILTIN_OUTCOMES, Component, Region
from lightrocks.metamodel import ast
from lightrocks.workbench.generators import GenerationError

if TYPE_CHECKING:
    from lightrocks.generators.sfc_iec61131.unit import UnitBuilder


def _lineage(component: Component) -> Iterator[Component]:
    """A component and the bases it extends."""
    current: Component | None = component
    while current is not None:
        yield current
        current = current.base


class ComponentBuilder(Network, Hierarchy, TimeEvents, OrthogonalRegions, Children):
    """The FUNCTION_BLOCK of one task, skill or plain statechart.

    Composite states are flattened: every leaf is a step, a transition of a composite leaves
    from each of its leaves after their own transitions (innermost first, as at run time),
    and the exit, transition and entry statements of a transition run in a step of their own
    between source and target. An action's outcome is taken in a settle step that stops the
    command and runs the action's exit statements before any guard reads their effect.
    Internal transitions run in their step's N action; time events are TON timers; history
    is a variable per composite; an orthogonal state is one simultaneous divergence and one
    simultaneous convergence (docs/generators.md).
    """

    def __init__(self, unit: UnitBuilder, component: Component) -> None:
        self.unit = unit
        self.component = component
        self.region = component.region
        for layer in _lineage(component):
            unit.extensions.refuse_unmapped(layer.unit)
        layer = component.layer or "statechart"
        documented = unit.extensions.documentation(
            element for region in self.region.regions() for element in region.extensions
        )
        heading = f"<<{layer}>> {component.qualified_name}"
        block = Block(unit.globals.claim(component.name), "\n".join([heading, *documented]))
        super().__init__(block, unit.globals.scope())
        self.scope = self._scope(self.region, {})
        self.events: dict[str, str] = {}
        self.leaves: dict[int, str] = {}  # id(node) -> step of a resting leaf
        self.exits: dict[str, str] = {}
        self.stops: dict[int, list[str]] = {}  # id(node) -> lines that stop its command
        self.memories: dict[int, str] = {}  # id(composite) -> its history variable
        self.timers: dict[int | None, list[Timer]] = {}  # id(node), None: the statechart
        self.parallels: dict[int, Parallel] = {}  # id(orthogonal state) -> its steps

    def _scope(self, region: Region, names: dict[str, str]) -> Scope:
        env = self.unit.typing.environment(region)
        members = {n: v.name for n, v in self.unit.cell_members.items()}

        def sensor(device: DeviceT, name: str) -> str:
            return self.unit.device_block(device).members.get(name, name)

        return Scope(
            {**members, **names},
            lambda e: self.unit.typing.infer(e, env),
            sensor,
            self.unit.globals.field,
            self.unit.extensions.expression,
        )

    def build(self) -> Block:
        block, region = self.block, self.region
        self._refuse_unmapped()
        block.externals = [Variable(v.name, v.type) for v in self.unit.cell_members.values()]
        self.execute = self.names.claim("execute")
        block.inputs.append(Variable(self.execute, "BOOL", comment="TRUE runs, FALSE resets"))
        for parameter in region.parameters.values():
            declared = self.unit.typing.types.resolve(region.loaded, parameter.type)
            variable = Variable(self.names.claim(parameter.name), self.unit.st_type(declared))
            block.parameters[parameter.name] = variable.name
            if isinstance(declared, ObjectT):
                block.in_outs.append(variable)
            else:
                what = f"'{parameter.name}' of {self.component.qualified_name}"
                variable.initial = initial_value(parameter.default, declared, what)
                block.inputs.append(variable)
        self.scope.names.update(block.parameters)
        spent = ("timeout",) if self.component.budget is not None else ()
        for outcome in ("done", "error", *spent, *region.outcomes):
            if outcome not in block.outcomes:
                block.outcomes[outcome] = self.names.claim(outcome)
                block.outputs.append(Variable(block.outcomes[outcome], "BOOL"))
        self.idle = self._step("Idle", initial=True)
        self._body(self.idle.name, "P1", [f"{v.name} := FALSE;" for v in block.outputs])
        self.nodes = self._nodes(region, None)
        self._declare_memories()
        self._declare_timers()
        for node in self._all(self.nodes):
            if node.children is None and not node.info.state.is_final:
                self.leaves[id(node)] = self._step("_".join(node.path)).name
                block.states[self.leaves[id(node)]] = ("/".join(node.path), "")
        orthogonal = [n for n in [None, *self._all(self.nodes)] if self._orthogonal(n)]
        for node in orthogonal:
            self._declare_parallel(node)
        self._start()
        for node in self._all(self.nodes):
            if id(node) in self.leaves:
                self._leaf(node)
        for node in orthogonal:
            self._parallel(node)
        for name, variable in self.events.items():
            block.inputs.append(Variable(variable, "BOOL", comment=f"event {name}: one cycle"))
        block.events = dict(self.events)
        return block

    def _refuse_unmapped(self) -> None:
        """Constructs the SFC mapping does not cover end generation with their place,
        instead of a network that would mean something else."""
        for region in self.region.regions():
            for info in region.states.values():
                inner = info.region
                if region.orthogonal and inner is not None:
                    for nested in inner.regions()[1:]:
                        if nested.orthogonal:
                            self._refuse(nested.position, "orthogonal regions inside a region")
            deep = [p for p in region.pseudostates.values() if p.kind == "deep history"]
            if deep and any(r.orthogonal for r in region.regions()[1:]):
                self._refuse(deep[0].position, "deep history over orthogonal regions")

    def _refuse(self, position: ast.Position, what: str) -> None:
        raise GenerationError(
            f"{position}: {self.component.qualified_name}: the SFC target does not map {what}"
        )

    def _exit(self, outcome: str) -> str:
        """The step that raises ``done`` and ``outcome`` until ``execute`` falls."""
        if outcome not in self.exits:
            step = self._step(f"Exit_{outcome}").name
            self.exits[outcome] = step
            self.block.states[step] = ("", outcome)
            raised = [self.block.outcomes["done"], self.block.outcomes.get(outcome, "")]
            self._body(step, "P1", [f"{v} := TRUE;" for v in raised if v])
            self._go(step, self.idle.name, f"NOT {self.execute}")
        return self.exits[outcome]

    def _statements(self, statements, scope: Scope | None = None) -> list[str]:
        return [line for s in statements for line in self._statement(s, scope or self.scope)]

    def _statement(self, statement: ast.Statement, scope: Scope) -> list[str]:
        if isinstance(statement, ast.ExtensionNode):
            return self.unit.extensions.statement(statement, scope)
        if isinstance(statement, ast.Assignment):
            return scope.assign(statement.target, statement.value)
        return [f"{scope.compile(statement.expression)};"]

    def _guard(self, expression: ast.Expression | None, scope: Scope | None = None) -> str:
        if expression is None:
            return ""
        text = (scope or self.scope).compile(expression)
        return f"({text})" if isinstance(expression, ast.Binary) else text

    # -- the start ----------------------------------------------------------------------------

    def _start(self) -> None:
        """Idle waits for ``execute``; then the first start condition whose transition is
        enabled, or the initial state; ``error`` when none holds."""
        entry = self._entry(None)
        starts = self.region.start_conditions
        branches: list[Branch] = []
        if starts:
            for start in starts:
                holds = self._guard(start.expression)
                for transition in self.region.transitions:
                    if transition.source == start.name:
                        guard = self._guard(transition.guard)
                        branches += self._fire(
                            None, transition, entry, [self.execute, holds, guard]
                        )
            branches += [Branch([self.execute], [], self._exit("error"))]
        elif self.region.orthogonal:
            branches = [Branch([self.execute], entry, self.parallels[id(None)].fork)]
        else:
            initial = next((n for n in self.nodes if n.info.state.is_initial), None)
            if initial is None:
                branches = [Branch([self.execute], [], self._exit("error"))]
            else:
                branches = self._to(initial, entry, [self.execute])
        self._branches(self.idle.name, branches)

    # -- leaves -------------------------------------------------------------------------------

    def _leaf(self, node: Node) -> None:
        """The ways out of a resting leaf: a broken invariant, the end of its command or
        child, external events."""
        step = self.leaves[id(node)]
        branches = self._invariant_branches(node)
        imported = node.info.imported
        if imported is not None and is_action(imported):
            branches += self._inline_action(step, node)
        elif imported is not None:
            branches += self._instance(step, node)
        stop = self.stops.get(id(node), [])
        branches += self._events(node, stop)
        owners = self._owners(node)
        if owners[-1] is not None:  # in a region: ending every region comes first
            region = owners[-1].parent
            parallel = self.parallels[id(region.parent)]
            end = self._end(region)
            branches.insert(0, Branch([parallel.abort], stop + self._exits(owners), end))
        staying = self._branches(step, branches, self._timed(node))
        self._run(step, staying + self._ticks(step, node))

    def _invariant_branches(self, node: Node) -> list[Branch]:
        """A broken invariant of ``node`` or of a state around it ends that state."""
        branches: list[Branch] = []
        owners = [o for o in self._owners(node) if o is not None]
        for depth, owner in enumerate(owners):
            for invariant in self._invariants(owner):
                exits = self._exits(owners[: depth + 1])
                branches += self._react(owner, "error", exits, [negate(invariant)])
        return branches

    def _events(self, node: Node, stop: list[str], inner: str = "") -> list[Branch]:
        """Transitions on external events and time events: the innermost state first, its
        internal transitions before those leaving it, declaration order. From an orthogonal
        state, an event fires only when no state inside it takes the event, and a time
        event only when none inside it is due (``inner``)."""
        waiting = [negate(inner)] if inner else []
        branches = []
        imported = node is None or node.info.imported is not None or self._orthogonal(node)
        for owner in self._owners(node):
            region = owner.info.region if owner else self.region
            for transition in region.internal if region else ():
                if imported and transition.delay is None:
                    raise GenerationError(
                        f"{transition.position}: {self.component.qualified_name}: the SFC "
                        "target does not map an internal transition over a running child "
                        "or over orthogonal regions"
                    )
                guard = self._guard(transition.guard)
                statements = self._statements(transition.action or ())
                stimulus = self._stimulus(owner, transition)
                timed = transition.delay is not None
                if timed:  # its deadline is taken, whatever else took the scan
                    statements.append(f"{self._timer(owner, transition).passed} := TRUE;")
                condition = [*stimulus, *(waiting if timed else []), guard]
                once = not timed or owner is not node  # around the leaf: once it rests
                branches.append(Branch(condition, statements, None, taken_once=once))
            if owner is None:
                branches += self._budget_branches(node, stop, waiting)
                break
            outcomes = {*(owner.info.outcomes or ()), *BUILTIN_OUTCOMES}  # never events
            for transition in owner.region.transitions:
                if transition.source != owner.name or not transition.stimulus:
                    continue
                if transition.stimulus in outcomes:
                    continue
                guard = self._guard(transition.guard)
                chain = node.chain()[: node.chain().index(owner) + 1]
                exits = stop + self._exits(chain)
                condition = [*self._stimulus(owner, transition), guard]
                if self._orthogonal(node) and transition.delay is None:
                    condition += self._untaken(node, transition.stimulus)
                elif transition.delay is not None:
                    condition += waiting
                branches += self._fire(owner.parent, transition, exits, condition)
        return branches

    def _untaken(self, node: Node, event: str) -> list[str]:
        """The condition that no resting leaf inside ``node`` takes ``event``."""
        takers = []
        for leaf in self._all(node.nested):
            if id(leaf) not in self.leaves:
                continue
            guards = []
            for owner in self._owners(leaf):
                if owner is None:
                    break
                region = owner.info.region
                own = [t for t in (region.internal if region else ()) if t.stimulus == event]
                own += [
                    t
                    for t in owner.region.transitions
                    if t.source == owner.name and t.stimulus == event
                ]
                guards += [self._guard(t.guard) or "TRUE" for t in own]
            if guards:
                enabled = " OR ".join(group(g) for g in guards)
                takers.append(f"{self.leaves[id(leaf)]}.X AND {group(enabled)}")
        return [negate(" OR ".join(f"({t})" for t in takers))] if takers else []

    def _stimulus(self, owner: Node | None, transition) -> list[str]:
        """The condition of a transition's event: its event input, or the scan in which
        its time event falls due."""
        if transition.delay is not None:
            timer = self._timer(owner, transition)
            return [f"{timer.instance}.Q", f"NOT {timer.passed}"]
        event = self.events.get(transition.stimulus)
        if event is None:
            event = self.events[transition.stimulus] = self.names.claim(transition.stimulus)
        return [event]
