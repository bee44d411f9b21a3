"""From resolved LightRocks components to the blocks of one IEC 61131-3 compilation unit.

Mapping (docs/generators.md has the long form): every task and skill becomes a
FUNCTION_BLOCK with an SFC network. Its initial step ``Idle`` waits for ``execute`` and a
start condition; a child that imports a skill is a function-block instance called from its
step (started P1, run N, reset P0); a child that imports an elemental action is inlined: P1
starts the device command through the device function block, P0 stops it and runs the
action's exit statements (μ). Outcomes become transition conditions, exclusive in
declaration order as at run time; the action's time budget is ``Step.T``. An end condition
is an exit step that raises ``done`` and the outcome's output until ``execute`` falls.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, field, replace

from lightrocks.generators.selection import is_action, reachable
from lightrocks.generators.sfc_iec61131.expressions import (
    Scope,
    convert,
    literal,
    number_type,
    time_literal,
)
from lightrocks.generators.sfc_iec61131.names import Namer
from lightrocks.languages.domain.types import (
    BOOLEAN,
    FRAME,
    NUMBER,
    STRING,
    DeviceT,
    ObjectT,
    QuantityT,
    StructT,
    Type,
    VectorT,
)
from lightrocks.languages.lightrocks.model import BUILTIN_OUTCOMES, Component, Region, StateInfo
from lightrocks.languages.lightrocks.typing import Typing
from lightrocks.metamodel import ast
from lightrocks.metamodel.units import UnitError, lookup
from lightrocks.workbench.generators import GenerationError, refuse_extensions

DEFAULT_TIMEOUT = 30.0
# The handshake of a device block, written by the integrator's driver (docs/generators.md).
STATUS = {
    "busy": "TRUE from accepting a command (after clearing done and error) until its flag falls",
    "done": "TRUE once the accepted command has settled",
    "error": "TRUE when the accepted command failed",
}
FRAME_FUNCTIONS = ("FRAME_MUL", "ROT_X", "ROT_Y", "ROT_Z", "TRANSL")


@dataclass
class Variable:
    name: str
    type: str
    initial: str = ""
    comment: str = ""


@dataclass
class Step:
    name: str
    initial: bool = False
    actions: list[tuple[str, str]] = field(default_factory=list)  # (action, qualifier)


@dataclass
class Transition:
    name: str
    source: str
    target: str
    condition: str
    priority: int | None = None
    sources: list[str] = field(default_factory=list)  # a simultaneous convergence
    targets: list[str] = field(default_factory=list)  # a simultaneous divergence


@dataclass
class Action:
    name: str
    body: list[str]


@dataclass
class Block:
    """A FUNCTION_BLOCK: a device interface (``body``) or a component's SFC network."""

    name: str
    comment: str
    inputs: list[Variable] = field(default_factory=list)
    outputs: list[Variable] = field(default_factory=list)
    in_outs: list[Variable] = field(default_factory=list)
    externals: list[Variable] = field(default_factory=list)
    locals: list[Variable] = field(default_factory=list)
    body: list[str] = field(default_factory=list)
    steps: list[Step] = field(default_factory=list)
    transitions: list[Transition] = field(default_factory=list)
    actions: list[Action] = field(default_factory=list)
    # for callers: LightRocks name -> ST name
    parameters: dict[str, str] = field(default_factory=dict)
    outcomes: dict[str, str] = field(default_factory=dict)
    commands: dict[str, tuple[str, dict[str, str], str]] = field(default_factory=dict)
    members: dict[str, str] = field(default_factory=dict)
    # what a step stands for: ST step -> (state path in the block, outcome taken or "")
    states: dict[str, tuple[str, str]] = field(default_factory=dict)
    instances: dict[str, str] = field(default_factory=dict)  # instance -> hosting state path
    events: dict[str, str] = field(default_factory=dict)  # LightRocks event -> input
    regions: list[str] = field(default_factory=list)  # state paths of orthogonal regions


@dataclass
class TypeDeclaration:
    name: str
    alias: str = ""
    fields: list[Variable] = field(default_factory=list)


@dataclass
class Unit:
    """Everything one ``.st`` file holds."""

    top: Component
    types: list[TypeDeclaration]
    devices: list[Block]
    blocks: list[Block]
    globals: list[Variable]
    object_fields: list[Variable]
    program: Block
    instance: str
    configuration: str
    resource: str
    task: str
    cell: dict[str, str] = field(default_factory=dict)  # device or object -> its global


class UnitBuilder:
    """Builds the unit for one top component; names are claimed in a fixed order."""

    def __init__(self, top: Component, typing: Typing) -> None:
        self.top = top
        self.typing = typing
        self.globals = Namer()
        for name in ("pose", "x", "y", "z", "xx", "xy", "xz", "yx", "yy", "yz", "zx", "zy", "zz"):
            self.globals.field(name)
        for name in ("Frame", "SceneObject", *FRAME_FUNCTIONS):
            self.globals.claim(name)
        self.types: dict[str, TypeDeclaration] = {}
        self.devices: dict[str, Block] = {}
        self.blocks: dict[str, Block] = {}
        self.cell_members: dict[str, Variable] = {}
        self.object_fields: dict[str, Variable] = {"pose": Variable("pose", "Frame")}

    # -- types ------------------------------------------------------------------------------

    def st_type(self, t: Type) -> str:
        if t == BOOLEAN:
            return "BOOL"
        if t == STRING:
            return "STRING"
        if t == FRAME:
            return "Frame"
        if isinstance(t, ObjectT):
            return "SceneObject"
        if isinstance(t, QuantityT):
            return "DINT" if t.name == "Integer" else "REAL"
        if isinstance(t, VectorT | StructT):
            if t.name not in self.types:  # parts first: a type is declared before its use
                declaration = TypeDeclaration("")
                if isinstance(t, VectorT):
                    element = self.st_type(t.elements[0]) if t.elements else "REAL"
                    declaration.alias = f"ARRAY[0..{len(t.elements) - 1}] OF {element}"
                else:
                    declaration.fields = [
                        Variable(self.globals.field(n), self.st_type(ft)) for n, ft in t.fields
                    ]
                declaration.name = self.globals.claim(t.name)
                self.types[t.name] = declaration
            return self.types[t.name].name
        raise GenerationError(f"type '{t}' has no IEC 61131-3 counterpart")

    # -- cells and devices -----------------------------------------------------------------

    def add_cells(self, components: list[Component]) -> None:
        cells: dict[str, tuple] = {}
        for component in components:
            for symbol in self.typing.models.workspace.scope(component.loaded).values():
                if isinstance(symbol.node, ast.Cell):
                    cells[symbol.qualified_name] = (symbol.loaded, symbol.node)
        for qualified in sorted(cells):
            loaded, cell = cells[qualified]
            for device in cell.devices:
                device_type = self.typing.types.resolve(loaded, device.type)
                if isinstance(device_type, DeviceT) and device.name not in self.cell_members:
                    block = self.device_block(device_type)
                    self.cell_members[device.name] = Variable(device.name, block.name)
            for obj in cell.objects:
                first = obj.name not in self.cell_members  # its defaults initialise it
                member = self.cell_members.setdefault(obj.name, Variable(obj.name, "SceneObject"))
                defaults = []
                for attribute in obj.attributes:
                    attribute_type = self.typing.types.resolve(loaded, attribute.type)
                    field_variable = self.object_fields.setdefault(
                        attribute.name,
                        Variable(self.globals.field(attribute.name), self.st_type(attribute_type)),
                    )
                    if first and attribute.default is not None:
                        what = f"'{obj.name}.{attribute.name}'"
                        value = _initial(attribute.default, attribute_type, what)
                        defaults.append(f"{field_variable.name} := {value}")
                if defaults:
                    member.initial = f"({', '.join(defaults)})"
        for member in self.cell_members.values():
            member.name = self.globals.claim(member.name)

    def device_block(self, device_type: DeviceT) -> Block:
        device = device_type.device
        if device.name in self.devices:
            return self.devices[device.name]
        block = Block(self.globals.claim(device.name), f"device interface of {device.name}")
        self.devices[device.name] = block
        names = self.globals.scope()
        loaded = self.typing._declaring(device)
        for sensor in device.sensors:
            name = names.claim(sensor.name)  # the integrator's name wins over a type's
            variable = Variable(name, self.st_type(self.typing.types.resolve(loaded, sensor.type)))
            block.members[sensor.name] = variable.name
            block.outputs.append(variable)
        for status, meaning in STATUS.items():  # a sensor of that name is that output
            if status not in block.members:
                block.members[status] = names.claim(status)
                block.outputs.append(Variable(block.members[status], "BOOL", comment=meaning))
        resets: list[str] = []
        for command in device.commands:
            flag = names.claim(command.name)
            block.inputs.append(Variable(flag, "BOOL", comment="TRUE runs the command"))
            parameters: dict[str, str] = {}
            for parameter in command.parameters:
                name = names.claim(f"{command.name}_{parameter.name}")
                parameter_type = self.typing.types.resolve(loaded, parameter.type)
                variable = Variable(name, self.st_type(parameter_type))
                parameters[parameter.name] = variable.name
                block.inputs.append(variable)
                initial = literal(parameter.default, parameter_type) if parameter.default else None
                if initial:
                    default = Variable(names.claim(f"{variable.name}_default"), variable.type)
                    default.initial = initial
                    block.locals.append(default)
                    variable.initial = initial
                    resets.append(f"  {variable.name} := {default.name};")
            result = ""
            if command.returns:
                returned = self.typing.types.resolve(loaded, command.returns)
                result = names.claim(f"{command.name}_result")
                block.outputs.append(Variable(result, self.st_type(returned)))
            block.commands[command.name] = (flag, parameters, result)
            if resets:
                block.body += [f"IF NOT {flag} THEN", *resets, "END_IF;"]
                resets = []
        running = " OR ".join(v[0] for v in block.commands.values()) or "FALSE"
        block.body += [
            f"IF NOT ({running}) THEN",
            f"  {block.members['busy']} := FALSE;",
            "END_IF;",
        ]
        return block

    # -- components ------------------------------------------------------------------------

    def build(self) -> Unit:
        components = [c for c in reachable(self.top) if not is_action(c)]
        if not components:
            raise GenerationError(f"'{self.top.name}' is an elemental action: nothing to sequence")
        self.add_cells(reachable(self.top))
        for component in components:
            self.blocks[component.qualified_name] = ComponentBuilder(self, component).build()
        top = self.blocks[self.top.qualified_name]
        program = Block(self.globals.claim(f"{self.top.name}_Program"), "runs the top task")
        names = self.globals.scope()
        program.externals = [Variable(v.name, v.type) for v in self.cell_members.values()]
        start = names.claim("start")
        instance = names.claim(f"{self.top.name}_fb")
        program.inputs = [Variable(start, "BOOL", comment="TRUE starts the task")]
        passed = [f"execute := {start}"]
        for event, name in top.events.items():
            program.inputs.append(Variable(names.claim(name), "BOOL", comment=f"event {event}"))
            passed.append(f"{name} := {program.inputs[-1].name}")
        program.locals = [Variable(instance, top.name)]
        calls = [f"{v.name}();" for v in self.cell_members.values() if v.type != "SceneObject"]
        program.body = [*calls, f"{instance}({', '.join(passed)});"]
        return Unit(
            self.top,
            [self.types[k] for k in self.types],
            list(self.devices.values()),
            list(self.blocks.values()),
            list(self.cell_members.values()),
            [self.object_fields[k] for k in sorted(self.object_fields)],
            program,
            names.claim("Main"),
            self.globals.claim(f"{self.top.name}_Cell"),
            self.globals.claim("Controller"),
            self.globals.claim("Cyclic"),
            {name: v.name for name, v in self.cell_members.items()},
        )


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


@dataclass
class Branch:
    """One way out of a step: its condition, then the statements, then where it goes.

    A branch without target stays in its step (an internal transition); one on an event
    (``taken_once``) does not fire in the scan that enters its step, since the transition
    that entered it has taken that event. A branch with ``following`` runs its statements in
    a step of its own and goes on by those branches (a choice, whose guards read the effect
    of the statements)."""

    condition: list[str]
    statements: list[str]
    target: str | None
    postcondition: str = ""
    violated: list[Branch] = field(default_factory=list)  # where a broken postcondition goes
    following: list[Branch] | None = None
    taken_once: bool = False


def _lineage(component: Component) -> Iterator[Component]:
    """A component and the bases it extends."""
    current: Component | None = component
    while current is not None:
        yield current
        current = current.base


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


@dataclass
class Timer:
    """A time event ``after(d)`` of one state: an on-delay timer started on entry and a flag
    raised once its deadline has passed, so that it fires at most once per entry."""

    transition: ast.Transition | ast.InternalTransition
    instance: str
    passed: str
    duration: str


class ComponentBuilder:
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
            refuse_extensions("SFC", layer.unit)
        layer = component.layer or "statechart"
        self.block = Block(
            unit.globals.claim(component.name), f"<<{layer}>> {component.qualified_name}"
        )
        self.names = unit.globals.scope()
        self.scope = self._scope(self.region, {})
        self.events: dict[str, str] = {}
        self.leaves: dict[int, str] = {}  # id(node) -> step of a resting leaf
        self.resting: dict[str, str] = {}  # step -> its flag "active in the scan before"
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
                variable.initial = _initial(parameter.default, declared, what)
                block.inputs.append(variable)
        self.scope.names.update(block.parameters)
        for outcome in ("done", "error", *region.outcomes):
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

    def _declare_timers(self) -> None:
        """A timer per time event: those of a state's own body and those leaving it."""
        owners: list[tuple[Node | None, list]] = [(None, list(self.region.internal))]
        for node in self._all(self.nodes):
            own = list(node.info.region.internal) if node.info.region else []
            leaving = [t for t in node.region.transitions if t.source == node.name]
            owners.append((node, own + leaving))
        for node, transitions in owners:
            for transition in transitions:
                if transition.delay is None:
                    continue
                where = "_".join(node.path) if node else self.component.name
                instance = self.names.claim(f"{where}_after")
                passed = self.names.claim(f"{instance}_passed")
                comment = f"after(…) at {transition.position.line}:{transition.position.column}"
                self.block.locals += [
                    Variable(instance, "TON", comment=comment),
                    Variable(passed, "BOOL", comment="its deadline has passed since the entry"),
                ]
                duration = literal(transition.delay)
                duration = (
                    time_literal(float(duration))
                    if duration is not None
                    else f"REAL_TO_TIME({self.scope.compile(transition.delay, NUMBER)})"
                )
                timer = Timer(transition, instance, passed, duration)
                self.timers.setdefault(id(node) if node else None, []).append(timer)

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

    # -- steps, actions, transitions -------------------------------------------------------

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

    # -- orthogonal regions ------------------------------------------------------------------

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
        outside = self._invariant_branches(node) + self._events(node, [])
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
        )  # fmt: skip
        self._run(parallel.watch, staying + self._ticks(parallel.watch, node))
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

    def _branches(self, source: str, branches: list[Branch]) -> list[str]:
        """Exclusive transitions from ``source``: each branch requires no earlier one to hold.

        Statements run in a step of their own between source and target, so that they
        finish before the target's entry and so that a postcondition reads their effect.
        Branches that stay in ``source`` come back as ST lines for its N action."""
        taken: list[str] = []
        covered: list[set[str]] = []
        staying: list[str] = []
        resting = ""
        for branch in branches:
            needs = {c for c in branch.condition if c and c != "TRUE"}
            if any(earlier <= needs for earlier in covered):
                continue  # an earlier branch always wins: this one never fires
            covered.append(needs)
            condition = _conjunction(branch.condition)
            whole = _conjunction([condition, *(_negate(t) for t in taken)])
            taken.append(condition)
            if branch.target is None:
                if branch.statements:
                    if branch.taken_once:
                        resting = resting or self._resting(source)
                        whole = _conjunction([condition, resting, *map(_negate, taken[:-1])])
                    indented = [f"  {line}" for line in branch.statements]
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
                        *(replace(v, condition=[_negate(post), *v.condition])
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
                        [_negate(branch.postcondition), *b.condition],
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

    def _run(self, step: str, lines: list[str]) -> None:
        """The N action of a resting step: ``lines``, then its flag, if it has one, raised."""
        flag = self.resting.get(step)
        self._body(step, "N", lines + ([f"{flag} := TRUE;"] if flag else []))

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
        if isinstance(statement, ast.Assignment):
            return scope.assign(statement.target, statement.value)
        return [f"{scope.compile(statement.expression)};"]

    def _guard(self, expression: ast.Expression | None, scope: Scope | None = None) -> str:
        if expression is None:
            return ""
        text = (scope or self.scope).compile(expression)
        return f"({text})" if isinstance(expression, ast.Binary) else text

    # -- entering and leaving states -------------------------------------------------------

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

    def _ticks(self, step: str, node: Node) -> list[str]:
        """N-action lines of a leaf's ``step`` that run the timers of its state and the states
        around it: the flag reads the timer's output of the scan before, so the scan in which
        the deadline shows is the one scan in which the time event fires. A transition leaving
        a state around the leaf keeps its event one scan longer when the leaf was entered in
        that scan: an inner transition due at the same deadline took it, and at run time the
        outer event follows at the same instant."""
        lines = []
        for owner in self._owners(node):
            for timer in self.timers.get(id(owner) if owner else None, []):
                due = f"{timer.instance}.Q"
                if owner is not node and isinstance(timer.transition, ast.Transition):
                    due = f"({due} AND {self._resting(step)})"
                lines += [f"{timer.passed} := {timer.passed} OR {due};",
                          f"{timer.instance}(IN := TRUE);"]  # fmt: skip
        return lines

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
        otherwise = [*condition, *(_negate(g) for g in guards)]
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
            branches += self._complete(owner, "error", [], [_negate(g) for g in guards])
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
        staying = self._branches(step, branches)
        self._run(step, staying + self._ticks(step, node))

    def _invariant_branches(self, node: Node) -> list[Branch]:
        """A broken invariant of ``node`` or of a state around it ends that state."""
        branches: list[Branch] = []
        owners = [o for o in self._owners(node) if o is not None]
        for depth, owner in enumerate(owners):
            for invariant in self._invariants(owner):
                exits = self._exits(owners[: depth + 1])
                branches += self._react(owner, "error", exits, [_negate(invariant)])
        return branches

    def _events(self, node: Node, stop: list[str]) -> list[Branch]:
        """Transitions on external events and time events: the innermost state first, its
        internal transitions before those leaving it, declaration order. From an orthogonal
        state, an event fires only when no state inside it takes the event."""
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
                once = transition.delay is None
                branches.append(Branch([*stimulus, guard], statements, None, taken_once=once))
            if owner is None:
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
                enabled = " OR ".join(_group(g) for g in guards)
                takers.append(f"{self.leaves[id(leaf)]}.X AND {_group(enabled)}")
        return [_negate(" OR ".join(f"({t})" for t in takers))] if takers else []

    def _stimulus(self, owner: Node | None, transition) -> list[str]:
        """The condition of a transition's event: its event input, or the scan in which
        its time event falls due."""
        if transition.delay is not None:
            timers = self.timers[id(owner) if owner else None]
            timer = next(t for t in timers if t.transition is transition)
            return [f"{timer.instance}.Q", f"NOT {timer.passed}"]
        event = self.events.get(transition.stimulus)
        if event is None:
            event = self.events[transition.stimulus] = self.names.claim(transition.stimulus)
        return [event]

    # -- children: device commands and function-block instances -------------------------------

    def _instance(self, step: str, node: Node) -> list[Branch]:
        """A skill or task child: an instance started P1, run N, reset P0."""
        info = node.info
        child = self.unit.blocks[info.imported.qualified_name]
        instance = self.names.claim(f"{step}_fb")
        self.block.locals.append(Variable(instance, child.name))
        self.block.instances[instance] = "/".join(node.path)
        signature = self.unit.typing.component_signature(info.imported)
        declared = {name: t for name, t, _ in signature.parameters}
        bound = [
            f"{child.parameters[a.name]} := {self.scope.compile(a.value, declared.get(a.name))}"
            for a in info.state.arguments
            if a.name in child.parameters
        ]
        in_outs = {v.name for v in child.in_outs}
        kept = [b for b in bound if b.split(" := ")[0] in in_outs]
        self._body(step, "P1", [f"{instance}({', '.join(['execute := TRUE', *bound])});"])
        self._body(step, "N", [f"{instance}({', '.join(kept)});"])
        self._body(step, "P0", [f"{instance}({', '.join(['execute := FALSE', *kept])});"])
        branches = []
        for outcome in ("error", *info.imported.region.outcomes):
            flag = f"{instance}.{child.outcomes[outcome]}"
            branches += self._react(node, outcome, self._remember(node), [flag])
        return branches

    def _inline_action(self, step: str, node: Node) -> list[Branch]:
        """An elemental action inlined: P1 starts the device command; each outcome (the
        device's error, an end condition, the time budget) goes to a settle step that stops
        the command, stores its result on a real outcome and runs the exit statements (μ)."""
        info = node.info
        action = info.imported
        region = action.region
        arguments = {a.name: a.value for a in info.state.arguments}
        substitutes: dict[str, str] = {}
        assignments: list[str] = []
        for parameter in region.parameters.values():
            declared = self.unit.typing.types.resolve(region.loaded, parameter.type)
            value = arguments.get(parameter.name, parameter.default)
            if isinstance(declared, ObjectT):
                substitutes[parameter.name] = self.scope.compile(value)
                continue
            name = self.names.claim(f"{step}_{parameter.name}")
            variable = Variable(name, self.unit.st_type(declared))
            substitutes[parameter.name] = variable.name
            self.block.locals.append(variable)
            initial = literal(parameter.default, declared) if parameter.default else None
            variable.initial = initial or ""
            if value is not None and (parameter.name in arguments or not initial):
                assignments += self.scope.assign(ast.Name(variable.name), value, declared)
        scope = self._scope(region, substitutes)
        start, stop, store, device, instance = self._command(region, scope)
        self.stops[id(node)] = stop
        self._body(step, "P1", assignments + start)
        exits = self._statements(
            (s for a in region.actions if a.kind == "exit" for s in a.statements), scope
        )
        members = self.unit.device_block(device).members
        # the device's outputs speak of this command only once it has seen it: busy
        acknowledged = f"{instance}.{members['busy']}"
        ends = [
            (c.name, [acknowledged, self._guard(c.expression, scope)])
            for c in region.end_conditions
        ]
        ends.insert(0, ("error", [acknowledged, f"{instance}.{members['error']}"]))
        budget = time_literal(self._timeout(action, device.device))
        ends.append(("timeout", [f"{step}.T >= {budget}"]))
        branches = []
        for outcome, condition in ends:
            settle = self._step(f"{step}_{outcome}").name
            self.block.states[settle] = ("/".join(node.path), outcome)
            real = outcome not in ("error", "timeout")
            self._body(settle, "P1", stop + (store if real else []) + exits)
            self._branches(settle, self._react(node, outcome, self._remember(node), []))
            branches.append(Branch(condition, [], settle))
        return branches

    def _command(self, region: Region, scope: Scope):
        """P1 lines that start the device command of ``do``, lines that stop it, lines that
        store its result, the device type and the device instance."""
        do = next(a for a in region.actions if a.kind == "do")
        statement = do.statements[0]
        call = statement.value if isinstance(statement, ast.Assignment) else statement.expression
        if not (isinstance(call, ast.Call) and isinstance(call.function, ast.Member)):
            raise GenerationError(f"{do.position}: 'do' must call a device command")
        device = scope.infer(call.function.target)
        if not isinstance(device, DeviceT):
            raise GenerationError(f"{do.position}: '{call.function.target}' is not a device")
        block = self.unit.device_block(device)
        flag, parameters, result = block.commands[call.function.name]
        command = next(c for c in device.device.commands if c.name == call.function.name)
        loaded = self.unit.typing._declaring(device.device)
        resolve = self.unit.typing.types.resolve
        declared = {p.name: resolve(loaded, p.type) for p in command.parameters}
        order = [p.name for p in command.parameters]
        bound = [f"{flag} := TRUE"]
        for position, argument in enumerate(call.arguments):
            name = argument.name or order[position]
            bound.append(f"{parameters[name]} := {scope.compile(argument.value, declared[name])}")
        instance = scope.compile(call.function.target)
        store = []
        if isinstance(statement, ast.Assignment) and result:
            returned = number_type(resolve(loaded, command.returns))
            wanted = number_type(scope.infer(statement.target))
            value = convert(f"{instance}.{result}", returned, wanted, statement.position)
            store.append(f"{scope.compile(statement.target)} := {value};")
        stop = [f"{instance}({flag} := FALSE);"]
        return [f"{instance}({', '.join(bound)});"], stop, store, device, instance

    def _timeout(self, action: Component, device: ast.Device) -> float:
        """The ``timeout`` stereotype of the action or of the one it extends, else its
        device's, else 30 s."""
        found = None
        extended: Component | None = action
        while found is None and extended is not None:
            found = ast.stereotype(extended.statechart.stereotypes, "timeout")
            extended = extended.base
        found = found or ast.stereotype(device.stereotypes, "timeout")
        if found is None or not found.value:
            return DEFAULT_TIMEOUT
        number, _, unit = found.value.strip().partition(" ")
        try:
            return float(number) * lookup(unit.strip() or "s").factor
        except (ValueError, UnitError):
            raise GenerationError(
                f"{found.position}: timeout '{found.value}' is not a time"
            ) from None


def _group(condition: str) -> str:
    """``condition`` safe to negate or combine."""
    if (
        not condition
        or condition.isidentifier()
        or (condition.startswith("(") and condition.endswith(")") and _balanced(condition[1:-1]))
    ):
        return condition
    return f"({condition})"


def _negate(condition: str) -> str:
    """``NOT condition``, without a double negation."""
    if condition.startswith("NOT "):
        rest = condition[4:]
        if _group(rest) == rest:
            return rest
    return f"NOT {_group(condition)}"


def _balanced(text: str) -> bool:
    depth = 0
    for character in text:
        depth += {"(": 1, ")": -1}.get(character, 0)
        if depth < 0:
            return False
    return depth == 0


def _conjunction(conditions: list[str]) -> str:
    parts = [c for c in conditions if c and c != "TRUE"]
    if not parts:
        return "TRUE"
    if len(parts) == 1:
        return parts[0]
    return " AND ".join(_group(p) for p in parts)


def _initial(default: ast.Expression | None, declared: Type | None, what: str) -> str:
    """A declaration's initial value: the default folded to a constant ("" without one)."""
    if default is None:
        return ""
    initial = literal(default, declared)
    if initial is None:
        raise GenerationError(
            f"{default.position}: the SFC target needs a constant default for {what}"
        )
    return initial
