"""One SFC compilation unit as a PLCopen TC6 XML v2.01 project, with graphical SFC bodies.

The POUs are those of the textual SFC target (``sfc_iec61131.unit``), so both exports mean
the same. Each component's network is drawn as columns, one per step: the step, its action
block, a selection divergence when it has several ways out, and under each transition a
jump to the target step. Bodies of actions, device blocks, functions and the program stay
Structured Text.
"""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from datetime import UTC, datetime
from itertools import count

from lightrocks.generators.sfc_iec61131.expressions import outside_strings
from lightrocks.generators.sfc_iec61131.frames import FRAME_FIELDS, FUNCTIONS
from lightrocks.generators.sfc_iec61131.ir import Block, Transition, Unit, Variable

NAMESPACE = "http://www.plcopen.org/xml/tc6_0201"
XHTML = "http://www.w3.org/1999/xhtml"
# ST elementary type -> its element in TC6 XML, where the string types alone are lowercase
ELEMENTARY = {
    **{name: name for name in ("BOOL", "REAL", "LREAL", "DINT", "INT", "SINT", "LINT", "TIME")},
    "STRING": "string",
    "WSTRING": "wstring",
}
ARRAY = re.compile(r"ARRAY\[(\d+)\.\.(\d+)\] OF (\w+)")
COLUMN, ROW = 200, 60

ET.register_namespace("", NAMESPACE)
ET.register_namespace("xhtml", XHTML)


def _q(tag: str) -> str:
    return f"{{{NAMESPACE}}}{tag}"


def _add(parent: ET.Element, tag: str, **attributes: str | int) -> ET.Element:
    return ET.SubElement(parent, _q(tag), {k: str(v) for k, v in attributes.items()})


def _position(parent: ET.Element, x: int, y: int, tag: str = "position") -> None:
    _add(parent, tag, x=x, y=y)


def _text(parent: ET.Element, tag: str, lines: list[str] | tuple[str, ...]) -> None:
    """Formatted text: one XHTML paragraph holding the lines."""
    paragraph = ET.SubElement(_add(parent, tag), f"{{{XHTML}}}p")
    paragraph.text = "\n".join(lines)


def _type(parent: ET.Element, tag: str, st_type: str) -> None:
    holder = _add(parent, tag)
    if st_type in ELEMENTARY:
        _add(holder, ELEMENTARY[st_type])
    else:
        _add(holder, "derived", name=st_type)


def _split(items: str) -> list[str]:
    """The comma-separated parts of a literal, ignoring commas inside brackets or strings."""
    cuts, depth = [], 0
    for index, character in outside_strings(items):
        depth += {"[": 1, "]": -1, "(": 1, ")": -1}.get(character, 0)
        if character == "," and depth == 0:
            cuts.append(index)
    parts = [
        items[a + 1 : b].strip() for a, b in zip([-1, *cuts], [*cuts, len(items)], strict=True)
    ]
    return parts if parts[-1] else parts[:-1]


def _value(parent: ET.Element, tag: str, literal: str, **attributes: str) -> None:
    """An ST initial value as a PLCopen value: ``[…]`` an array, ``(member := …, …)`` a
    structure, anything else a simple value."""
    holder = _add(parent, tag, **attributes)
    if literal.startswith("["):
        array = _add(holder, "arrayValue")
        for item in _split(literal[1:-1]):
            _value(array, "value", item)
    elif literal.startswith("("):
        structure = _add(holder, "structValue")
        for item in _split(literal[1:-1]):
            member, _, value = item.partition(":=")
            _value(structure, "value", value.strip(), member=member.strip())
    else:
        _add(holder, "simpleValue", value=literal)


def _variables(parent: ET.Element, tag: str, variables: list[Variable]) -> None:
    if not variables:
        return
    section = _add(parent, tag)
    for variable in variables:
        element = _add(section, "variable", name=variable.name)
        _type(element, "type", variable.type)
        if variable.initial:
            _value(element, "initialValue", variable.initial)
        if variable.comment:
            ET.SubElement(_add(element, "documentation"), f"{{{XHTML}}}p").text = variable.comment


def project(unit: Unit, interval: str, created: datetime) -> ET.ElementTree:
    root = ET.Element(_q("project"))
    stamp = created.astimezone(UTC).strftime("%Y-%m-%dT%H:%M:%S")
    _add(
        root,
        "fileHeader",
        companyName="LightRocks",
        productName="LightRocks workbench",
        productVersion="1",
        creationDateTime=stamp,
        contentDescription=f"generated from {unit.top.qualified_name}: do not edit",
    )
    header = _add(root, "contentHeader", name=unit.top.name, modificationDateTime=stamp)
    info = _add(header, "coordinateInfo")
    for language in ("fbd", "ld", "sfc"):
        _add(_add(info, language), "scaling", x=1, y=1)
    types = _add(root, "types")
    _data_types(_add(types, "dataTypes"), unit)
    pous = _add(types, "pous")
    for function in FUNCTIONS:
        pou = _add(pous, "pou", name=function.name, pouType="function")
        interface = _add(pou, "interface")
        _type(interface, "returnType", function.returns)
        _variables(interface, "inputVars", [Variable(n, t) for n, t in function.inputs])
        _text(_add(pou, "body"), "ST", function.body)
    for block in [*unit.devices, *unit.blocks]:
        _pou(pous, block, "functionBlock")
    _pou(pous, unit.program, "program")
    _configuration(_add(_add(root, "instances"), "configurations"), unit, interval)
    ET.indent(root, space="  ")
    return ET.ElementTree(root)


def _data_types(parent: ET.Element, unit: Unit) -> None:
    frame = _add(_add(_add(parent, "dataType", name="Frame"), "baseType"), "struct")
    _variables_plain(frame, [Variable(n, "REAL", i) for n, i in FRAME_FIELDS])
    scene = _add(_add(_add(parent, "dataType", name="SceneObject"), "baseType"), "struct")
    _variables_plain(scene, unit.object_fields)
    for declaration in unit.types:
        base = _add(_add(parent, "dataType", name=declaration.name), "baseType")
        if declaration.alias:
            lower, upper, element = ARRAY.fullmatch(declaration.alias).groups()
            array = _add(base, "array")
            _add(array, "dimension", lower=lower, upper=upper)
            _type(array, "baseType", element)
        else:
            _variables_plain(_add(base, "struct"), declaration.fields)


def _variables_plain(parent: ET.Element, variables: list[Variable]) -> None:
    for variable in variables:
        element = _add(parent, "variable", name=variable.name)
        _type(element, "type", variable.type)
        if variable.initial:
            _value(element, "initialValue", variable.initial)


def _pou(parent: ET.Element, block: Block, kind: str) -> None:
    pou = _add(parent, "pou", name=block.name, pouType=kind)
    interface = _add(pou, "interface")
    _variables(interface, "inputVars", block.inputs)
    _variables(interface, "outputVars", block.outputs)
    _variables(interface, "inOutVars", block.in_outs)
    _variables(interface, "externalVars", block.externals)
    _variables(interface, "localVars", block.locals)
    if block.actions:
        actions = _add(pou, "actions")
        for action in block.actions:
            _text(_add(_add(actions, "action", name=action.name), "body"), "ST", action.body)
    body = _add(pou, "body")
    if block.steps:
        _network(_add(body, "SFC"), block)
    else:
        _text(body, "ST", block.body)
    ET.SubElement(_add(pou, "documentation"), f"{{{XHTML}}}p").text = block.comment


def _network(sfc: ET.Element, block: Block) -> None:
    """Steps in columns; ways out through a divergence, each transition ending in a jump.
    Orthogonal regions: a simultaneous divergence after the transition that starts them,
    and a simultaneous convergence of their last steps before the transition that joins them
    (drawn after every step, since it gathers steps of several columns)."""
    ids = count(1)
    steps: dict[str, int] = {}
    for column, step in enumerate(block.steps):
        x = column * COLUMN
        step_id = next(ids)
        steps[step.name] = step_id
        element = _add(sfc, "step", localId=step_id, name=step.name)
        if step.initial:
            element.set("initialStep", "true")
        _position(element, x, 0)
        _add(element, "connectionPointOut", formalParameter="")
        if step.actions:
            _add(element, "connectionPointOutAction", formalParameter="")
            actions = _add(sfc, "actionBlock", localId=next(ids))
            _position(actions, x + COLUMN // 2, 0)
            _add(_add(actions, "connectionPointIn"), "connection", refLocalId=step_id)
            for index, (name, qualifier) in enumerate(step.actions):
                action = _add(actions, "action", localId=next(ids), qualifier=qualifier)
                _position(action, 0, index * 20, "relPosition")
                _add(action, "reference", name=name)
        leaving = [t for t in block.transitions if t.source == step.name and not t.sources]
        source = step_id
        if len(leaving) > 1:
            divergence = _add(sfc, "selectionDivergence", localId=next(ids))
            _position(divergence, x, ROW)
            _add(_add(divergence, "connectionPointIn"), "connection", refLocalId=step_id)
            for _ in leaving:
                _add(divergence, "connectionPointOut", formalParameter="")
            source = int(divergence.get("localId"))
        for row, transition in enumerate(leaving):
            _transition(sfc, ids, transition, [source], x, 2 * ROW + 2 * ROW * row)
    column = len(block.steps)
    for transition in block.transitions:
        if not transition.sources:
            continue
        x = column * COLUMN
        column += 1
        convergence = _add(sfc, "simultaneousConvergence", localId=next(ids))
        _position(convergence, x, ROW)
        for name in transition.sources:
            _add(_add(convergence, "connectionPointIn"), "connection", refLocalId=steps[name])
        _add(convergence, "connectionPointOut")
        _transition(sfc, ids, transition, [int(convergence.get("localId"))], x, 2 * ROW)


def _transition(
    sfc: ET.Element, ids, transition: Transition, sources: list[int], x: int, y: int
) -> None:
    """A transition under ``sources``, then a jump to its target, or a simultaneous
    divergence with a jump to each of its targets."""
    transition_id = next(ids)
    element = _add(sfc, "transition", localId=transition_id)
    if transition.priority is not None:
        element.set("priority", str(transition.priority))
    _position(element, x, y)
    connected = _add(element, "connectionPointIn")
    for source in sources:
        _add(connected, "connection", refLocalId=source)
    _add(element, "connectionPointOut")
    condition = _add(_add(element, "condition"), "inline", name=transition.name)
    _text(condition, "ST", [transition.condition])
    origin = transition_id
    if transition.targets:
        divergence = _add(sfc, "simultaneousDivergence", localId=next(ids))
        _position(divergence, x, y + ROW)
        _add(_add(divergence, "connectionPointIn"), "connection", refLocalId=transition_id)
        for _ in transition.targets:
            _add(divergence, "connectionPointOut", formalParameter="")
        origin = int(divergence.get("localId"))
    for offset, target in enumerate(transition.targets or [transition.target]):
        jump = _add(sfc, "jumpStep", localId=next(ids), targetName=target)
        _position(jump, x + offset * COLUMN // 2, y + 2 * ROW if transition.targets else y + ROW)
        _add(_add(jump, "connectionPointIn"), "connection", refLocalId=origin)


def _configuration(parent: ET.Element, unit: Unit, interval: str) -> None:
    configuration = _add(parent, "configuration", name=unit.configuration)
    resource = _add(configuration, "resource", name=unit.resource)
    task = _add(resource, "task", name=unit.task, interval=interval, priority=1)
    _add(task, "pouInstance", name=unit.instance, typeName=unit.program.name)
    if unit.globals:  # an empty section is "no variable declared" to MatIEC
        _variables_plain(_add(configuration, "globalVars"), unit.globals)
