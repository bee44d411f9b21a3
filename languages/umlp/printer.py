"""Canonical text of UML/P statecharts (``.sc``), the inverse of :mod:`languages.umlp.syntax`:
for every syntax tree the parser produces, parsing the printed text gives an equal tree.

The Java parts are printed as they were read: brackets and literal texts are part of the
tree, only spacing and line breaks are the printer's. Layout: two-space indentation, one
element per line, a blank line between groups of different kinds, ``};`` after a state body
as MontiCore writes it; the comments of the source are re-attached by
:class:`metamodel.printer.Writer`.
"""

from __future__ import annotations

from collections.abc import Sequence

from lightrocks.languages.umlp import nodes as n
from lightrocks.metamodel.comments import Comments
from lightrocks.metamodel.printer import INDENT, Writer

# --- Java -------------------------------------------------------------------------------


def type_text(node: n.MCType) -> str:
    arguments = f"<{', '.join(type_text(a) for a in node.arguments)}>" if node.arguments else ""
    return node.name + arguments + "[]" * node.dimensions


def expression(node: n.JExpression) -> str:
    """A Java expression as written (its brackets are nodes of their own)."""
    match node:
        case n.JLiteral(text=text):
            return text
        case n.JName(name=name):
            return name
        case n.JFieldAccess(target=target, name=name):
            return f"{expression(target)}.{name}"
        case n.JCall(target=target, arguments=arguments):
            return f"{expression(target)}({', '.join(expression(a) for a in arguments)})"
        case n.JArrayAccess(target=target, index=index):
            return f"{expression(target)}[{expression(index)}]"
        case n.JPostfix(operator=operator, operand=operand):
            return expression(operand) + operator
        case n.JPrefix(operator=operator, operand=operand):
            text = expression(operand)
            # ``- -x`` must not become ``--x``, nor ``+ +x`` ``++x``
            return operator + (" " if text[:1] in "+-" and operator in ("+", "-") else "") + text
        case n.JBinary(operator=operator, left=left, right=right):
            return f"{expression(left)} {operator} {expression(right)}"
        case n.JConditional(condition=condition, then=then, otherwise=otherwise):
            return f"{expression(condition)} ? {expression(then)} : {expression(otherwise)}"
        case n.JAssignment(operator=operator, target=target, value=value):
            return f"{expression(target)} {operator} {expression(value)}"
        case n.JBracket(expression=inner):
            return f"({expression(inner)})"
    raise TypeError(f"not a Java expression: {node!r}")


def _initializer(node: n.JExpression | n.JArrayInit) -> str:
    if isinstance(node, n.JArrayInit):
        values = ", ".join(_initializer(v) for v in node.values)
        return "{" + values + ("," if node.trailing_comma else "") + "}"
    return expression(node)


def local_variable(node: n.JLocalVariable) -> str:
    """``final Type a = 1, b`` without the ``;``."""
    declarators = []
    for declarator in node.declarators:
        text = declarator.name + "[]" * declarator.dimensions
        if declarator.init is not None:
            text += f" = {_initializer(declarator.init)}"
        declarators.append(text)
    modifiers = "".join(f"{m} " for m in node.modifiers)
    return f"{modifiers}{type_text(node.type)} {', '.join(declarators)}"


def _indented(lines: Sequence[str]) -> list[str]:
    return [INDENT + line for line in lines]


def _attached(head: str, body: n.JStatement) -> list[str]:
    """``head`` followed by a statement: a block opens on the head's line."""
    if isinstance(body, n.JBlock):
        return [f"{head} {{", *_indented(block_lines(body.statements)), "}"]
    lines = statement_lines(body)
    if len(lines) == 1:
        return [f"{head} {lines[0]}"]
    return [head, *_indented(lines)]


def block_lines(statements: Sequence[n.JStatement]) -> list[str]:
    return [line for s in statements for line in statement_lines(s)]


def statement_lines(node: n.JStatement) -> list[str]:
    """A Java statement as lines, nested blocks indented by two spaces."""
    match node:
        case n.JBlock(statements=statements):
            if not statements:
                return ["{}"]
            return ["{", *_indented(block_lines(statements)), "}"]
        case n.JLocalVariable():
            return [local_variable(node) + ";"]
        case n.JExpressionStatement(expression=value):
            return [expression(value) + ";"]
        case n.JIf(condition=condition, then=then, otherwise=otherwise):
            lines = _attached(f"if ({expression(condition)})", then)
            if otherwise is None:
                return lines
            if lines[-1] == "}":
                rest = _attached("else", otherwise)
                return [*lines[:-1], "} " + rest[0], *rest[1:]]
            return [*lines, *_attached("else", otherwise)]
        case n.JWhile(condition=condition, body=body):
            return _attached(f"while ({expression(condition)})", body)
        case n.JDoWhile(body=body, condition=condition):
            lines = _attached("do", body)
            tail = f"while ({expression(condition)});"
            if lines[-1] == "}":
                return [*lines[:-1], "} " + tail]
            return [*lines, tail]
        case n.JFor(init=init, condition=condition, updates=updates, body=body):
            if init is None:
                first = ""
            elif isinstance(init, n.JLocalVariable):
                first = local_variable(init)
            else:
                first = ", ".join(expression(e) for e in init)
            middle = f" {expression(condition)}" if condition is not None else ""
            last = (" " + ", ".join(expression(e) for e in updates)) if updates else ""
            return _attached(f"for ({first};{middle};{last})", body)
        case n.JForEach(modifiers=modifiers, type=kind, name=name, iterable=iterable, body=body):
            declared = "".join(f"{m} " for m in modifiers) + f"{type_text(kind)} {name}"
            return _attached(f"for ({declared} : {expression(iterable)})", body)
        case n.JSwitch(value=value, groups=groups, labels=labels):
            lines = [f"switch ({expression(value)}) {{"]
            for group in groups:
                lines += _indented([_label(label) for label in group.labels])
                lines += _indented(_indented(block_lines(group.statements)))
            lines += _indented([_label(label) for label in labels])
            return [*lines, "}"]
        case n.JJump(keyword=keyword):
            return [f"{keyword};"]
        case n.JReturn(value=value):
            return ["return;" if value is None else f"return {expression(value)};"]
        case n.JEmpty():
            return [";"]
    raise TypeError(f"not a Java statement: {node!r}")


def _label(label: n.JSwitchLabel) -> str:
    return "default:" if label.value is None else f"case {expression(label.value)}:"


def inline(node: n.JStatement) -> str:
    """A statement on one line: its lines joined (blocks and ``;`` delimit Java's
    statements, so the joined text means the same)."""
    if isinstance(node, n.JBlock):
        if not node.statements:
            return "{}"
        return "{ " + " ".join(line.strip() for line in block_lines(node.statements)) + " }"
    return " ".join(line.strip() for line in statement_lines(node))


# --- statecharts --------------------------------------------------------------------------


def stereotype(values: Sequence[n.StereoValue]) -> str:
    """``<<a, b="c">>`` or the empty string."""
    if not values:
        return ""
    texts = [v.name if v.content is None else f"{v.name}={v.content}" for v in values]
    return f"<<{', '.join(texts)}>>"


def event(node: n.SCEvent) -> str:
    if node.arguments is None:
        return node.name
    return f"{node.name}({', '.join(expression(a) for a in node.arguments)})"


def event_definition(node: n.SCFuncEventDef) -> str:
    returns = f"{type_text(node.return_type)} " if node.return_type is not None else ""
    parameters = ", ".join(f"{type_text(p.type)} {p.name}" for p in node.parameters)
    return f"event {returns}{node.name}({parameters});"


def format_sc_text(text: str, file: str) -> str:
    """The canonical text of a ``.sc`` file with its comments; raises ``SyntaxProblem``."""
    from lightrocks.languages.umlp.syntax import parse_sc

    return print_sc(parse_sc(text, file), Comments(text))


def print_sc(unit: n.SCArtifact, comments: Comments | None = None) -> str:
    """The canonical text of ``unit``; ``comments`` those of the text it was parsed from."""
    writer = Writer(comments)
    if unit.package:
        writer.item(unit.package_position, "package")
        writer.line([f"package {unit.package};"], unit.package_position.line)
    for item in unit.type_imports:
        writer.item(item.position, "import")
        writer.line([f"import {item.name}{'.*' if item.star else ''};"], item.position.line)
    chart = unit.statechart
    writer.item(chart.position, "statechart")
    head = _joined(stereotype(chart.stereotype), chart.keyword, chart.name)
    if not chart.elements and not writer.comments_within(chart.position):
        writer.line([head + " { }"], chart.position.line)
    else:
        writer.open([head + " {"], chart.position.line)
        for element in chart.elements:
            _element(writer, element)
        writer.close(chart.position)
    return writer.finish()


def _joined(*parts: str) -> str:
    return " ".join(p for p in parts if p)


def _element(writer: Writer, node: n.SCElement) -> None:
    where = node.position
    match node:
        case n.SCFuncEventDef():
            writer.item(where, "event")
            writer.line([event_definition(node)], where.line)
        case n.SCCompleteness(complete=complete):
            writer.item(where, "completeness")
            writer.line(["(c)" if complete else "(...)"], where.line)
        case n.SCState():
            _state(writer, node)
        case n.SCTransition():
            head = f"{node.source} -> {node.target}"
            writer.item(where, "transition")
            _transition(writer, _joined(stereotype(node.stereotype), head), node)
        case n.SCInternTransition():
            writer.item(where, "transition")
            _transition(writer, _joined(stereotype(node.stereotype), "->"), node)
        case n.SCAction(kind=kind, body=body):
            writer.item(where, "action")
            _action(writer, f"{kind} /", body, "", where)
        case _:
            raise TypeError(f"not a statechart element: {node!r}")


def _state(writer: Writer, node: n.SCState) -> None:
    spaced = node.body is not None and bool(node.body)
    writer.item(node.position, "state", spaced=spaced)
    modifiers = ("initial",) * node.initial + ("final",) * node.final
    ante = inline(n.JBlock(node.ante)) if node.ante is not None else ""
    head = _joined(stereotype(node.stereotype), *modifiers, ante, "state", node.name)
    if node.invariant is not None:
        head += f" [{expression(node.invariant)}]"
    if node.body is None:
        writer.line([head + ";"], node.position.line)
    elif not node.body and not writer.comments_within(node.body_position):
        writer.line([head + " { };"], node.position.line)
    else:
        writer.open([head + " {"], node.position.line)
        for element in node.body:
            _element(writer, element)
        writer.close(node.body_position, ";")


def _transition(writer: Writer, head: str, node: n.SCTransition | n.SCInternTransition) -> None:
    if node.pre is not None:
        head += f" [{expression(node.pre)}]"
    if node.event is not None:
        head += f" {event(node.event)}"
    if node.action is None:
        writer.line([head + ";"], node.position.line)
        return
    _action(writer, head + " /", node.action, ";", node.position)


def _action(writer: Writer, head: str, body: n.SCActionBody, end: str, where: n.Position) -> None:
    """``head statement [post]`` and ``end``: a block of several statements, or one that
    does not fit or holds comments, on lines of its own."""
    post = f" [{expression(body.post)}]" if body.post is not None else ""
    statement = body.statement
    if statement is None:
        text = head + post
        writer.line([text + (" " + end if end and text.endswith("/") else end)], where.line)
        return
    one_line = f"{head} {inline(statement)}{post}{end}"
    if not isinstance(statement, n.JBlock):
        writer.line([one_line], where.line)
        return
    short = len(statement.statements) <= 1 and len(one_line) <= writer.width
    if short and not writer.comments_within(statement.position):
        writer.line([one_line], where.line)
        return
    writer.open([f"{head} {{"], where.line)
    for item in statement.statements:
        writer.item(item.position, "statement")
        writer.line(statement_lines(item), item.position.line)
    writer.close(statement.position, post + end)
