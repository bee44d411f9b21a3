"""The children of a state: an imported skill or task is a function-block instance, an
imported elemental action a device command inlined in the step of its state."""

from __future__ import annotations

from lightrocks.generators.sfc_iec61131.expressions import (
    Scope,
    convert,
    literal,
    number_type,
    time_literal,
)
from lightrocks.generators.sfc_iec61131.hierarchy import Node
from lightrocks.generators.sfc_iec61131.ir import Variable
from lightrocks.generators.sfc_iec61131.network import Branch
from lightrocks.languages.domain.types import DeviceT, ObjectT, Type
from lightrocks.languages.lightrocks.model import Region
from lightrocks.metamodel import ast
from lightrocks.metamodel.units import seconds
from lightrocks.workbench.generators import GenerationError


class Children:
    """The part of :class:`~.component.ComponentBuilder` that runs the children of states."""

    stops: dict[int, list[str]]  # id(node) -> lines that stop its command

    def _instance(self, step: str, node: Node) -> list[Branch]:
        """A skill or task child: an instance started P1, run N, reset P0."""
        info = node.info
        child = self.unit.blocks[info.imported.qualified_name]
        instance = self.names.claim(f"{step}_fb")
        self.block.locals.append(Variable(instance, child.name))
        self.block.instances[instance] = "/".join(node.path)
        signature = self.unit.typing.component_signature(info.imported)
        declared = {name: t for name, t, _ in signature.parameters}
        prepared: list[str] = []
        bound: list[str] = []
        for name, value in _arguments(node).items():
            if name in child.parameters:
                lines, text = self._passed(step, name, value, declared.get(name), self.scope)
                prepared += lines
                bound.append(f"{child.parameters[name]} := {text}")
        in_outs = {v.name for v in child.in_outs}
        kept = [b for b in bound if b.split(" := ")[0] in in_outs]
        started = f"{instance}({', '.join(['execute := TRUE', *bound])});"
        self._body(step, "P1", [*prepared, started])
        self._body(step, "N", [f"{instance}({', '.join(kept)});"])
        self._body(step, "P0", [f"{instance}({', '.join(['execute := FALSE', *kept])});"])
        branches = []
        for outcome in ("error", "timeout", *info.imported.region.outcomes):
            if outcome not in child.outcomes:
                continue  # a child without a budget never times out
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
        arguments = _arguments(node)
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
        start, stop, store, device, instance = self._command(step, region, scope)
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
        budget = time_literal(action.command_budget(device.device).seconds)
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

    def _command(self, step: str, region: Region, scope: Scope):
        """P1 lines that start the device command of ``do`` in ``step``, lines that stop it,
        lines that store its result, the device type and the device instance."""
        do = next(a for a in region.actions if a.kind == "do")
        statement = do.statements[0]
        call = ast.evaluated(statement)
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
        prepared: list[str] = []
        for position, argument in enumerate(call.arguments):
            name = argument.name or order[position]
            lines, text = self._passed(step, name, argument.value, declared[name], scope)
            prepared += lines
            bound.append(f"{parameters[name]} := {text}")
        instance = scope.compile(call.function.target)
        store = []
        if isinstance(statement, ast.Assignment) and result:
            returned = number_type(resolve(loaded, command.returns))
            wanted = number_type(scope.infer(statement.target))
            value = convert(f"{instance}.{result}", returned, wanted, statement.position)
            store.append(f"{scope.compile(statement.target)} := {value};")
        stop = [f"{instance}({flag} := FALSE);"]
        return [*prepared, f"{instance}({', '.join(bound)});"], stop, store, device, instance

    def _passed(
        self, step: str, name: str, value: ast.Expression, declared: Type | None, scope: Scope
    ) -> tuple[list[str], str]:
        """Lines that prepare an argument of a call in ``step``, and the value passed: a vector
        literal (ST has array literals as initial values only) becomes a local array, with
        the literal as its initial value when constant, else assigned element by element."""
        if not isinstance(value, ast.VectorLiteral):
            return [], scope.compile(value, declared)
        local = Variable(self.names.claim(f"{step}_{name}"), self.unit.st_type(declared))
        local.initial = literal(value, declared) or ""
        self.block.locals.append(local)
        return ([] if local.initial else scope.elements(local.name, value, declared)), local.name


def budget_seconds(stereotype: ast.Stereotype) -> float:
    """A checked ``<<timeout="…">>`` in seconds (LR0501 has refused any other)."""
    found = seconds(stereotype.value)
    if found is None:
        raise GenerationError(f"{stereotype.position}: timeout '{stereotype.value}' is not a time")
    return found


def _arguments(node: Node) -> dict[str, ast.Expression]:
    """The arguments of the state that imports a child, by parameter name: a positional one
    names the parameter declared at its place, as at run time."""
    order = list(node.info.imported.region.parameters)
    return {a.name or order[i]: a.value for i, a in enumerate(node.info.state.arguments)}
