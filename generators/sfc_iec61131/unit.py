"""From resolved LightRocks components to the blocks of one IEC 61131-3 compilation unit.

Mapping (docs/generators.md has the long form): every task and skill becomes a
FUNCTION_BLOCK with an SFC network (:mod:`.component`); every device type a device block
whose inputs are its commands and their parameters and whose outputs are its sensors and
the handshake; the cell's devices and objects become globals; a PROGRAM runs the devices
and the top block. Names are claimed in a fixed order, so the unit is deterministic.
"""

from __future__ import annotations

from lightrocks.generators.outputs import shortened
from lightrocks.generators.selection import is_action, reachable
from lightrocks.generators.sfc_iec61131.component import ComponentBuilder
from lightrocks.generators.sfc_iec61131.expressions import initial_value, literal
from lightrocks.generators.sfc_iec61131.extensions import Extensions
from lightrocks.generators.sfc_iec61131.ir import Block, TypeDeclaration, Unit, Variable
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
from lightrocks.languages.lightrocks.model import Component, visible_cells
from lightrocks.languages.lightrocks.typing import Typing
from lightrocks.workbench.generators import GenerationError

# The handshake of a device block, written by the integrator's driver (docs/generators.md).
STATUS = {
    "busy": "TRUE from accepting a command (after clearing done and error) until its flag falls",
    "done": "TRUE once the accepted command has settled",
    "error": "TRUE when the accepted command failed",
}
FRAME_FUNCTIONS = ("FRAME_MUL", "ROT_X", "ROT_Y", "ROT_Z", "TRANSL")


class UnitBuilder:
    """Builds the unit for one top component; names are claimed in a fixed order."""

    def __init__(
        self, top: Component, typing: Typing, extensions: Extensions | None = None
    ) -> None:
        self.top = top
        self.typing = typing
        self.extensions = extensions or Extensions()
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
            for symbol in visible_cells(self.typing.models.workspace, component.loaded):
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
                        value = initial_value(attribute.default, attribute_type, what)
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
            self.globals.claim(shortened(f"{self.top.name}_Cell")),  # MatIEC: <name>.c
            self.globals.claim("Controller"),
            self.globals.claim("Cyclic"),
            {name: v.name for name, v in self.cell_members.items()},
        )
