"""Canonical text of domain interfaces (``.lrd``), used by ``lightrocks fmt``.

Declarations keep their order; one-line declarations of one kind (quantities, vectors) stay
together, blocks (structures, devices, cells) are set apart by blank lines, and the members
of a block come one per line. Comments are re-attached as described in
:mod:`metamodel.printer`.
"""

from __future__ import annotations

from lightrocks.languages.domain.syntax import parse_domain
from lightrocks.metamodel import ast
from lightrocks.metamodel.comments import Comments
from lightrocks.metamodel.printer import Writer, expression, fit, header, parameter, stereotypes


def format_domain_text(text: str, file: str) -> str:
    """The canonical text of a ``.lrd`` file with its comments; raises ``SyntaxProblem``."""
    return print_domain(parse_domain(text, file), Comments(text))


def print_domain(unit: ast.DomainUnit, comments: Comments | None = None) -> str:
    """The canonical text of ``unit``; ``comments`` are those of the text it was parsed from."""
    writer = Writer(comments)
    header(writer, unit)
    for declaration in unit.declarations:
        _declaration(writer, declaration)
    return writer.finish()


def _declaration(writer: Writer, node: ast.Declaration) -> None:
    where = node.position
    match node:
        case ast.QuantityType(name=name, unit=unit):
            writer.item(where, "quantity")
            writer.line([f"quantity {name}{f' [{unit}]' if unit else ''};"], where.line)
        case ast.VectorType(name=name, units=(_, *_) as units):
            writer.item(where, "vector")
            writer.line([f"vector {name} [{', '.join(units)}];"], where.line)
        case ast.VectorType(name=name, element_type=element, size=size):
            writer.item(where, "vector")
            writer.line([f"vector {name} of {element} [{size}];"], where.line)
        case ast.StructureType(name=name, fields=fields):
            writer.item(where, "structure", spaced=True)
            _members(writer, f"structure {name}", where, fields)
        case ast.Device(name=name, members=members, stereotypes=marks):
            writer.item(where, "device", spaced=True)
            _members(writer, _prefixed(marks, f"device {name}"), where, members)
        case ast.Cell(name=name, members=members, stereotypes=marks):
            writer.item(where, "cell", spaced=True)
            _members(writer, _prefixed(marks, f"cell {name}"), where, members)


def _prefixed(items: tuple[ast.Stereotype, ...], text: str) -> str:
    return f"{stereotypes(items)} {text}" if items else text


Member = ast.Field | ast.Command | ast.Sensor | ast.DeviceInstance | ast.SceneObject


def _members(
    writer: Writer, head: str, position: ast.Position, members: tuple[Member, ...]
) -> None:
    """``head { … }`` with one member per line, or ``head { }`` when empty."""
    if not members and not writer.comments_within(position):
        writer.line([f"{head} {{ }}"], position.line)
        return
    writer.open([f"{head} {{"], position.line)
    for member in members:
        _member(writer, member)
    writer.close(position)


def _member(writer: Writer, node: Member) -> None:
    where = node.position
    match node:
        case ast.Field(type=type_, name=name):
            writer.item(where, "field")
            writer.line([f"{type_} {name};"], where.line)
        case ast.Command(name=name, parameters=parameters, returns=returns):
            writer.item(where, "command")
            tail = f") returns {returns};" if returns else ");"
            items = [_command_parameter(p) for p in parameters]
            writer.line(fit(f"command {name}(", items, tail, writer.width), where.line)
        case ast.Sensor(type=type_, name=name):
            writer.item(where, "sensor")
            start = f" = {expression(node.start)}" if node.start is not None else ""
            text = f"sensor {type_} {name}{start}{_range(node.low, node.high)};"
            writer.line([text], where.line)
        case ast.DeviceInstance(name=name, type=type_):
            writer.item(where, "device")
            writer.line([f"{name} : {type_};"], where.line)
        case ast.SceneObject(name=name, attributes=()):
            writer.item(where, "object")
            writer.line([f"object {name};"], where.line)
        case ast.SceneObject(name=name, attributes=attributes):
            writer.item(where, "object", spaced=True)
            writer.open([f"object {name} {{"], where.line)
            for attribute in attributes:
                writer.item(attribute.position, "attribute")
                text = _attribute(attribute) if attribute.low is not None else parameter(attribute)
                writer.line([text], attribute.position.line)
            writer.close(where)


def _range(low: ast.Expression | None, high: ast.Expression | None) -> str:
    """`` in low .. high``, or nothing when no range is declared."""
    if low is None or high is None:
        return ""
    return f" in {expression(low)} .. {expression(high)}"


def _attribute(node: ast.Parameter) -> str:
    """An attribute with a declared range of values."""
    default = f" = {expression(node.default)}" if node.default is not None else ""
    return f"{node.type} {node.name}{default}{_range(node.low, node.high)};"


def _command_parameter(node: ast.CommandParameter) -> list[str]:
    """The parts of a command parameter, which may go on separate lines when too long."""
    parts = [f"{node.type} {node.name}"]
    if node.default is not None:
        default = expression(node.default)
        # `3 in` would read `in` as the unit of 3: a range after a bare number needs parentheses
        if node.low is not None and default[-1].isdigit():
            default = f"({default})"
        parts.append(f"= {default}")
    if node.low is not None and node.high is not None:
        parts += [f"in {expression(node.low)}", f".. {expression(node.high)}"]
    return parts
