"""Context conditions of domain interfaces: names, types, defaults and safe ranges."""

from __future__ import annotations

import math
from collections.abc import Iterator

from lightrocks.languages.domain.ranges import command_ranges
from lightrocks.languages.domain.types import (
    BUILTIN_TYPES,
    QuantityT,
    Types,
    VectorT,
    compatible,
    describe,
    narrows,
    quantity_of,
)
from lightrocks.metamodel import ast
from lightrocks.metamodel.constants import beyond_a_real, overflow
from lightrocks.metamodel.units import UnitError, lookup
from lightrocks.workbench.check import CheckContext
from lightrocks.workbench.cocos import coco
from lightrocks.workbench.diagnostics import Severity, did_you_mean
from lightrocks.workbench.passes import Pass
from lightrocks.workbench.workspace import Loaded

Finding = tuple[ast.Position, str, str]


def _domain_units(context: object) -> Iterator[Loaded]:
    for loaded in context.workspace.checked_units():
        if isinstance(loaded.unit, ast.DomainUnit):
            yield loaded


class DomainTypes(Pass):
    """The types of this run's domain declarations, resolved once for every CoCo."""

    def __init__(self, context: CheckContext) -> None:
        super().__init__(context)
        self.types = Types(context.workspace)


def _types(context: CheckContext) -> Types:
    return context.result(DomainTypes).types


def _typed_members(unit: ast.DomainUnit) -> Iterator[tuple[str, ast.Position]]:
    """Every type name a declaration uses, with where it is used."""
    for declaration in unit.declarations:
        if isinstance(declaration, ast.VectorType) and declaration.element_type:
            yield declaration.element_type, declaration.position
        elif isinstance(declaration, ast.StructureType):
            yield from ((f.type, f.position) for f in declaration.fields)
        elif isinstance(declaration, ast.Device):
            for member in declaration.members:
                if isinstance(member, ast.Sensor):
                    yield member.type, member.position
                else:
                    yield from ((p.type, p.position) for p in member.parameters)
                    if member.returns:
                        yield member.returns, member.position
        elif isinstance(declaration, ast.Cell):
            yield from ((d.type, d.position) for d in declaration.devices)
            for obj in declaration.objects:
                yield from ((a.type, a.position) for a in obj.attributes)


@coco("LR0401", Severity.ERROR, "types used by domain declarations resolve")
def domain_types_resolve(context: object) -> Iterator[Finding]:
    types = _types(context)
    for loaded in _domain_units(context):
        for name, position in _typed_members(loaded.unit):
            if types.resolve(loaded, name) is None:
                candidates = [*BUILTIN_TYPES, *context.workspace.scope(loaded)]
                yield position, f"unknown type '{name}'", did_you_mean(name, candidates)


@coco("LR0402", Severity.ERROR, "members of a device or cell have unique names")
def unique_members(context: object) -> Iterator[Finding]:
    for loaded in _domain_units(context):
        for declaration in loaded.unit.declarations:
            members = getattr(declaration, "members", None) or getattr(declaration, "fields", ())
            seen: set[str] = set()
            for member in members:
                if member.name in seen:
                    yield member.position, f"'{member.name}' is declared twice", ""
                seen.add(member.name)


@coco("LR0403", Severity.ERROR, "units of quantity and vector types are known")
def type_units_known(context: object) -> Iterator[Finding]:
    for loaded in _domain_units(context):
        for declaration in loaded.unit.declarations:
            units = ()
            if isinstance(declaration, ast.QuantityType) and declaration.unit:
                units = (declaration.unit,)
            elif isinstance(declaration, ast.VectorType):
                units = declaration.units
            for unit in units:
                try:
                    lookup(unit)
                except UnitError as error:
                    hint = did_you_mean(unit, error.suggestions)
                    yield declaration.position, f"unknown unit '{unit}'", hint


def _commands(context: object) -> Iterator[tuple[Loaded, ast.Device, ast.Command]]:
    for loaded in _domain_units(context):
        for declaration in loaded.unit.declarations:
            if isinstance(declaration, ast.Device):
                for command in declaration.commands:
                    yield loaded, declaration, command


@coco("LR0404", Severity.ERROR, "command defaults and safe ranges fit the parameter type")
def command_defaults_fit(context: object) -> Iterator[Finding]:
    types = _types(context)
    for loaded in _domain_units(context):
        devices = [d for d in loaded.unit.declarations if isinstance(d, ast.Device)]
        for node in ast.walk(devices):  # a cell's objects are typed as LR0302
            if isinstance(node, ast.Quantity) and not math.isfinite(node.value):
                message = f"'{node.text}' is beyond the largest number a Real holds"
                yield node.position, f"{message} (about 1.8e308 in SI units)", ""
            elif isinstance(node, ast.Binary) and (beyond := overflow(node)) is not None:
                yield node.position, beyond_a_real(node, beyond), ""
    for loaded, _, command in _commands(context):
        for parameter in command.parameters:
            declared = types.resolve(loaded, parameter.type)
            if not isinstance(declared, QuantityT | VectorT):
                continue
            for value in (parameter.default, parameter.low, parameter.high):
                actual = _literal_type(value)
                if actual is None:
                    continue
                if not _fits(declared, actual):
                    yield value.position, f"'{parameter.name}' expects {describe(declared)}", ""
                elif narrows(declared, actual):
                    message = f"'{parameter.name}' expects {describe(declared)}, not a Real value"
                    yield value.position, message, ""


@coco("LR0405", Severity.ERROR, "a command default lies in the command's own safe range")
def command_defaults_safe(context: object) -> Iterator[Finding]:
    types = _types(context)
    for loaded, device, command in _commands(context):
        ranges = command_ranges(device.name, command)
        for parameter in command.parameters:
            if parameter.name not in ranges or not _typed(types, loaded, parameter):
                continue  # a default of the wrong kind is LR0404's
            breach = ranges[parameter.name].breach(parameter.default)
            if breach is not None:
                yield parameter.default.position, f"default {breach}", ""


def _typed(types: Types, loaded: Loaded, parameter: ast.CommandParameter) -> bool:
    """The parameter has a default and everything of it has the declared type."""
    declared = types.resolve(loaded, parameter.type)
    if parameter.default is None or not isinstance(declared, QuantityT | VectorT):
        return False
    values = (parameter.default, parameter.low, parameter.high)
    kinds = [_literal_type(v) for v in values if v is not None]
    return all(k is not None and _fits(declared, k) for k in kinds)


def _literal_type(value: ast.Expression | None) -> QuantityT | VectorT | None:
    if isinstance(value, ast.Quantity):
        kind = quantity_of(value)
        return kind if isinstance(kind, QuantityT) else None
    if isinstance(value, ast.VectorLiteral):
        elements = tuple(_literal_type(e) for e in value.elements)
        if all(e is not None for e in elements):
            return VectorT("vector", elements)
    return None


def _fits(declared: QuantityT | VectorT, actual: QuantityT | VectorT) -> bool:
    """A range bound may be one scalar for every element of a vector."""
    if isinstance(declared, VectorT) and isinstance(actual, QuantityT):
        return all(compatible(e, actual) for e in declared.elements)
    return compatible(declared, actual)
