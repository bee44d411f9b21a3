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

from dataclasses import dataclass, field

from lightrocks.generators.selection import is_action, reachable
from lightrocks.generators.sfc_iec61131.expressions import Scope, field_name, literal, time_literal
from lightrocks.generators.sfc_iec61131.names import Namer
from lightrocks.languages.domain.types import (
    BOOLEAN,
    FRAME,
    STRING,
    DeviceT,
    ObjectT,
    QuantityT,
    StructT,
    Type,
    VectorT,
)
from lightrocks.languages.lightrocks.model import Component, Region, StateInfo
from lightrocks.languages.lightrocks.typing import Typing
from lightrocks.metamodel import ast
from lightrocks.metamodel.units import UnitError, lookup
from lightrocks.workbench.generators import GenerationError

DEFAULT_TIMEOUT = 30.0
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


class UnitBuilder:
    """Builds the unit for one top component; names are claimed in a fixed order."""

    def __init__(self, top: Component, typing: Typing) -> None:
        self.top = top
        self.typing = typing
        self.globals = Namer()
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
                        Variable(field_name(n), self.st_type(ft)) for n, ft in t.fields
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
                self.cell_members.setdefault(obj.name, Variable(obj.name, "SceneObject"))
                for attribute in obj.attributes:
                    attribute_type = self.typing.types.resolve(loaded, attribute.type)
                    self.object_fields.setdefault(
                        attribute.name,
                        Variable(field_name(attribute.name), self.st_type(attribute_type)),
                    )
        for member in self.cell_members.values():
            member.name = self.globals.claim(member.name)

    def device_block(self, device_type: DeviceT) -> Block:
        device = device_type.device
        if device.name in self.devices:
            return self.devices[device.name]
        block = Block(self.globals.claim(device.name), f"device interface of {device.name}")
        self.devices[device.name] = block
        names = Namer(self.globals)
        loaded = self.typing._declaring(device)
        for sensor in device.sensors:
            sensor_type = self.typing.types.resolve(loaded, sensor.type)
            variable = Variable(names.claim(sensor.name), self.st_type(sensor_type))
            block.members[sensor.name] = variable.name
            block.outputs.append(variable)
        for status in ("busy", "done", "error"):  # a sensor of that name is that output
            if status not in block.members:
                block.members[status] = names.claim(status)
                block.outputs.append(Variable(block.members[status], "BOOL"))
        resets: list[str] = []
        for command in device.commands:
            flag = names.claim(command.name)
            block.inputs.append(Variable(flag, "BOOL", comment="TRUE runs the command"))
            parameters: dict[str, str] = {}
            for parameter in command.parameters:
                parameter_type = self.typing.types.resolve(loaded, parameter.type)
                variable = Variable(
                    names.claim(f"{command.name}_{parameter.name}"), self.st_type(parameter_type)
                )
                parameters[parameter.name] = variable.name
                block.inputs.append(variable)
                initial = literal(parameter.default) if parameter.default else None
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
        block.body.append(f"{block.members['busy']} := {running};")
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
        names = Namer(self.globals)
        program.externals = [Variable(v.name, v.type) for v in self.cell_members.values()]
        start = names.claim("start")
        instance = names.claim(f"{self.top.name}_fb")
        program.inputs = [Variable(start, "BOOL", comment="TRUE starts the task")]
        program.locals = [Variable(instance, top.name)]
        calls = [f"{v.name}();" for v in self.cell_members.values() if v.type != "SceneObject"]
        program.body = [*calls, f"{instance}(execute := {start});"]
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
        )


class ComponentBuilder:
    """The FUNCTION_BLOCK of one task or skill."""

    def __init__(self, unit: UnitBuilder, component: Component) -> None:
        self.unit = unit
        self.component = component
        self.region = component.region
        layer = component.layer or "statechart"
        self.block = Block(
            unit.globals.claim(component.name), f"<<{layer}>> {component.qualified_name}"
        )
        self.names = Namer(unit.globals)
        self.scope = self._scope(self.region, {})

    def _scope(self, region: Region, names: dict[str, str]) -> Scope:
        env = self.unit.typing.environment(region)
        members = {n: v.name for n, v in self.unit.cell_members.items()}

        def sensor(device: DeviceT, name: str) -> str:
            return self.unit.device_block(device).members.get(name, name)

        return Scope({**members, **names}, lambda e: self.unit.typing.infer(e, env), sensor)

    def build(self) -> Block:
        block, region = self.block, self.region
        block.externals = [Variable(v.name, v.type) for v in self.unit.cell_members.values()]
        for variable in block.externals:
            self.names.claim(variable.name)
        execute = self.names.claim("execute")
        block.inputs.append(Variable(execute, "BOOL", comment="TRUE runs, FALSE resets"))
        for parameter in region.parameters.values():
            declared = self.unit.typing.types.resolve(region.loaded, parameter.type)
            variable = Variable(self.names.claim(parameter.name), self.unit.st_type(declared))
            block.parameters[parameter.name] = variable.name
            if isinstance(declared, ObjectT):
                block.in_outs.append(variable)
            else:
                variable.initial = literal(parameter.default) if parameter.default else ""
                block.inputs.append(variable)
        self.scope.names.update(block.parameters)
        for outcome in ("done", "error", *(c.name for c in region.end_conditions)):
            if outcome not in block.outcomes:
                block.outcomes[outcome] = self.names.claim(outcome)
                block.outputs.append(Variable(block.outcomes[outcome], "BOOL"))
        if any(info.region is not None for info in region.states.values()):
            raise GenerationError(
                f"{self.component.qualified_name}: states with a body are not supported by "
                "the SFC target; import a statechart instead"
            )
        self.idle = self._step("Idle", initial=True)
        self._body("Idle", "P1", [f"{v.name} := FALSE;" for v in block.outputs])
        self.steps = {name: self._step(name) for name in region.states}
        self.exits: dict[str, str] = {}
        self._entries()
        for name, info in region.states.items():
            self._child(name, info)
        return block

    # -- steps, actions, transitions -------------------------------------------------------

    def _step(self, name: str, initial: bool = False) -> Step:
        step = Step(self.names.claim(name), initial)
        self.block.steps.append(step)
        return step

    def _body(self, step: str, qualifier: str, lines: list[str]) -> None:
        suffix = {"P1": "entry", "N": "run", "P0": "exit"}[qualifier]
        action = Action(self.names.claim(f"{step}_{suffix}"), lines)
        self.block.actions.append(action)
        owner = next(s for s in self.block.steps if s.name == step)
        owner.actions.append((action.name, qualifier))

    def _go(self, source: str, target: str, condition: str) -> None:
        name = self.names.claim(f"{source}_to_{target}")
        self.block.transitions.append(Transition(name, source, target, condition))

    def _target(self, transition: ast.Transition, source: str, condition: str) -> None:
        """Go to the transition's target; its statements run in a step of their own first."""
        target = self._state_or_exit(transition.target)
        if transition.action:
            lines = [line for s in transition.action for line in self._statement(s, self.scope)]
            between = self._step(f"{source}_{transition.target}_do").name
            self._body(between, "P1", lines)
            self._go(source, between, condition)
            self._go(between, target, "TRUE")
        else:
            self._go(source, target, condition)

    def _state_or_exit(self, name: str) -> str:
        if name in self.steps:
            return self.steps[name].name
        if name not in self.exits:
            exit_step = self._step(f"Exit_{name}").name
            self.exits[name] = exit_step
            raised = [self.block.outcomes["done"], self.block.outcomes.get(name, "")]
            self._body(exit_step, "P1", [f"{v} := TRUE;" for v in raised if v])
            execute = self.block.inputs[0].name
            self._go(exit_step, self.idle.name, f"NOT {execute}")
        return self.exits[name]

    def _statement(self, statement: ast.Statement, scope: Scope) -> list[str]:
        if isinstance(statement, ast.Assignment):
            return scope.assign(statement.target, statement.value)
        return [f"{scope.compile(statement.expression)};"]

    def _entries(self) -> None:
        execute = self.block.inputs[0].name
        starts = {c.name: c for c in self.region.start_conditions}
        for transition in self.region.transitions:
            if transition.source in starts:
                condition = [execute, self._guard(starts[transition.source].expression)]
                condition.append(self._guard(transition.guard))
                self._target(transition, self.idle.name, " AND ".join(c for c in condition if c))
        for name, info in self.region.states.items():
            if info.state.is_initial:
                self._go(self.idle.name, self.steps[name].name, execute)

    def _guard(self, expression: ast.Expression | None, scope: Scope | None = None) -> str:
        if expression is None:
            return ""
        text = (scope or self.scope).compile(expression)
        return f"({text})" if isinstance(expression, ast.Binary) else text

    # -- children --------------------------------------------------------------------------

    def _child(self, name: str, info: StateInfo) -> None:
        step = self.steps[name].name
        leaving = [t for t in self.region.transitions if t.source == name]
        if info.imported is not None and is_action(info.imported):
            outcomes, timeout = self._inline_action(step, info)
        elif info.imported is not None:
            outcomes, timeout = self._instance(step, info), None
        else:
            outcomes, timeout = {}, None
        for transition in leaving:
            if transition.stimulus == "timeout" and timeout:
                finished = timeout
            elif transition.stimulus:
                finished = outcomes.get(transition.stimulus, transition.stimulus)
            else:
                finished = outcomes.get("", "TRUE")
            guard = self._guard(transition.guard)
            self._target(transition, step, f"{finished} AND {guard}" if guard else finished)
        if info.imported is not None:
            self._go(step, self._state_or_exit("error"), outcomes[""])
            if timeout and not any(t.stimulus == "timeout" for t in leaving):
                self._go(step, self._state_or_exit("error"), timeout)

    def _instance(self, step: str, info: StateInfo) -> dict[str, str]:
        child = self.unit.blocks[info.imported.qualified_name]
        instance = self.names.claim(f"{step}_fb")
        self.block.locals.append(Variable(instance, child.name))
        bound = [
            f"{child.parameters[a.name]} := {self.scope.compile(a.value)}"
            for a in info.state.arguments
            if a.name in child.parameters
        ]
        in_outs = {v.name for v in child.in_outs}
        kept = [b for b in bound if b.split(" := ")[0] in in_outs]
        self._body(step, "P1", [f"{instance}({', '.join(['execute := TRUE', *bound])});"])
        self._body(step, "N", [f"{instance}({', '.join(kept)});"])
        self._body(step, "P0", [f"{instance}({', '.join(['execute := FALSE', *kept])});"])
        outcomes = {o: f"{instance}.{v}" for o, v in child.outcomes.items()}
        outcomes[""] = outcomes["done"]
        return outcomes

    def _inline_action(self, step: str, info: StateInfo) -> tuple[dict[str, str], str]:
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
            variable = Variable(
                self.names.claim(f"{step}_{parameter.name}"), self.unit.st_type(declared)
            )
            substitutes[parameter.name] = variable.name
            self.block.locals.append(variable)
            initial = literal(parameter.default) if parameter.default else None
            variable.initial = initial or ""
            if value is not None and (parameter.name in arguments or not initial):
                assignments += self.scope.assign(ast.Name(variable.name), value)
        scope = self._scope(region, substitutes)
        start, stop, device = self._command(region, scope)
        self._body(step, "P1", assignments + start)
        exits = [s for a in region.actions if a.kind == "exit" for s in a.statements]
        self._body(step, "P0", stop + [x for s in exits for x in self._statement(s, scope)])
        conditions = [
            (c.name, self._guard(c.expression, scope) or "TRUE") for c in region.end_conditions
        ]
        outcomes: dict[str, str] = {}
        for index, (outcome, condition) in enumerate(conditions):
            earlier = [
                f"NOT {c}" if c.startswith("(") else f"NOT ({c})" for _, c in conditions[:index]
            ]
            outcomes[outcome] = " AND ".join([condition, *earlier])
        outcomes[""] = " OR ".join(c for _, c in conditions) or "TRUE"
        if len(conditions) > 1:
            outcomes[""] = f"({outcomes['']})"
        return outcomes, f"{step}.T >= {time_literal(self._timeout(action, device))}"

    def _command(self, region: Region, scope: Scope) -> tuple[list[str], list[str], ast.Device]:
        """P1 lines that start the device command of ``do`` and P0 lines that stop it."""
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
        order = [p.name for p in command.parameters]
        bound = [f"{flag} := TRUE"]
        for position, argument in enumerate(call.arguments):
            name = argument.name or order[position]
            bound.append(f"{parameters[name]} := {scope.compile(argument.value)}")
        instance = scope.compile(call.function.target)
        stop = []
        if isinstance(statement, ast.Assignment) and result:
            stop.append(f"{scope.compile(statement.target)} := {instance}.{result};")
        stop.append(f"{instance}({flag} := FALSE);")
        return [f"{instance}({', '.join(bound)});"], stop, device.device

    def _timeout(self, action: Component, device: ast.Device) -> float:
        """The action's ``timeout`` stereotype, else its device's, else 30 s."""
        found = ast.stereotype(action.statechart.stereotypes, "timeout")
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
